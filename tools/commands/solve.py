"""`teleo solve DOMAIN.pddl PROBLEM.pddl`: a PDDL problem solved by a teleo agent in one process.

The domain's program (world/pddl/program.py) and a scenario of the pddl world are written to a
temporary folder; the problem's goal is posted as the agent's one user goal, a conjunction; the
run is `teleo simulate`'s loop (tools.commands.simulate.simulate), stopped once the goal is
achieved or given up. The executed plan is the agent's actions that the world did: a cycle
whose `actions_done` counter grew (one action a cycle). `achieved` needs both the goal's
status and the world's final state to say so (docs/pddl.md, "teleo solve")."""

from __future__ import annotations

import json
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import click

from tools.alarm import raised_after
from tools.paths import OutputPath
from world.errors import WorldError

AGENT = "ME"


def default_cycles(objects: int, goal: int) -> int:
    """The cycles a problem gets by default [cycles]: 50 + 20 per object + 10 per goal literal."""
    return 50 + 20 * objects + 10 * goal


@dataclass
class Solved:
    """What `teleo solve` reports (``to_dict`` is its --json)."""

    domain: str
    problem: str
    status: str                     # achieved, failed or limit
    cycles: int
    actions: list[list[str]] = field(default_factory=list)
    learned: int = 0
    solving_cycles: int = 0
    reason: str = ""
    goal: str = ""
    elapsed_s: float = 0.0
    learned_file: str | None = None
    notes: tuple[str, ...] = ()     # what of the PDDL files the world ignores (action costs)

    def to_dict(self) -> dict[str, Any]:
        return {"domain": self.domain, "problem": self.problem, "status": self.status,
                "goal": self.goal, "cycles": self.cycles, "actions": self.actions,
                "plan_length": len(self.actions), "learned": self.learned,
                "solving_cycles": self.solving_cycles, "reason": self.reason,
                "elapsed_s": round(self.elapsed_s, 3), "learned_file": self.learned_file,
                "notes": list(self.notes)}


def _write_learned(out: Path, program: Path, skills: tuple[str, ...]) -> list[Path]:
    """The learned skills in ``out`` and, beside it, the program they were learned with
    (``<stem>-program.tlp``: the run's own is in a temporary folder), which the learned file
    names, so that `teleo check` finds it."""
    from agents.lang.registry import learned_text

    out.parent.mkdir(parents=True, exist_ok=True)
    kept = out.with_name(f"{out.stem}-program.tlp")
    kept.write_text(program.read_text())
    out.write_text(learned_text(skills, str(kept)))
    return [out, kept]


def _scenario_text(name: str, domain: Path, problem: Path, program: Path, goal: str,
                   cycles: int) -> str:
    return (f'[run]\nname = {json.dumps(name)}\nmode = "lockstep"\ncycles = {cycles}\n'
            f'seed = 0\n\n[world]\ndomain = "pddl"\ndomain_file = {json.dumps(str(domain))}\n'
            f'problem_file = {json.dumps(str(problem))}\n\n[[agents]]\nid = "{AGENT}"\n'
            f'program = {json.dumps(str(program))}\n\n[[goals]]\nagent = "{AGENT}"\n'
            f'goal = {json.dumps(goal)}\npriority = 1\n')


class OutOfTime(BaseException):
    """`teleo solve --time-limit` spent, raised by an alarm wherever its process is (a
    BaseException, so that no handler of the engine's takes it for a failure of its own)."""


class _Watch:
    """A recorder for simulate (SimRecorder's calls, tools/records/run_recorders.py) that keeps
    whether the goal is over (satisfied or failed in the agent's decision of the last cycle),
    the cycles begun and the actions done so far (for a run cut short by the time limit,
    whose ``run`` never comes back): an action counts once the next snapshot's
    `actions_done` grew."""

    def __init__(self) -> None:
        self.over = False
        self.cycles = 0
        self.actions: list[list[str]] = []
        self._decided: list[list[str]] = []
        self._done = 0
        self.names = ("", "", "", ())   # the domain's, the problem's, the goal, the notes

    def goal_list(self, *args: Any) -> None:
        pass

    def static(self, *args: Any) -> None:
        pass

    def world(self, cycle: int, moving: dict, *args: Any) -> None:
        self.cycles = cycle + 1
        done = moving.get("counters", {}).get(AGENT, {}).get("actions_done", self._done)
        self.actions += self._decided[:max(0, done - self._done)]
        self._done = done

    def world_stats(self, *args: Any) -> None:
        pass

    def agent(self, cycle: int, agent: str, seen: Any, *args: Any) -> None:
        self.over = any(g.status.value in ("satisfied", "failed")
                        for g in seen.decision.goals)
        self._decided = [[str(x).lstrip("*").lower() for x in a.to_list()]
                         for a in seen.decision.actions]


def executed(run: Any) -> list[list[str]]:
    """The actions the world did, in order, lower-case without the `*`: a cycle's action
    counts when the agent's `actions_done` grew from that cycle's trace line to the next."""
    done = [json.loads(line)["counters"].get(AGENT, {}).get("actions_done", 0)
            for line in run.trace]
    done.append(run.final.get("counters", {}).get(AGENT, {}).get("actions_done", 0))
    out = []
    for record, before, after in zip(run.records, done, done[1:], strict=False):
        if after > before:
            out += [[str(x).lstrip("*").lower() for x in a]
                    for a in record[AGENT]["actions"][:after - before]]
    return out


def solve(domain: Path, problem: Path, cycles: int | None = None, learned: Path | None = None,
          extra: str = "", learned_out: Path | None = None,
          time_limit: float | None = None) -> Solved:
    """Run the problem, within ``time_limit`` [s] if given (then status ``limit``, saying
    so); raises WorldError, ScenarioError or LangError for bad input."""
    watch = _Watch()
    try:
        with raised_after(time_limit, OutOfTime):
            return _solve(domain, problem, cycles, learned, extra, learned_out, watch)
    except OutOfTime:
        from world.pddl.files import reset_parsers

        reset_parsers()   # the alarm may have cut a parse short
        where = f"in cycle {watch.cycles}" if watch.cycles else "before the first cycle"
        name, task, goal, notes = watch.names
        return Solved(name or domain.stem, task or problem.stem, "limit", watch.cycles,
                      watch.actions, reason=f"the time limit of {time_limit:g} s ran out "
                      f"{where} (no skills written)", goal=goal,
                      elapsed_s=float(time_limit or 0), notes=notes)


def _solve(domain: Path, problem: Path, cycles: int | None, learned: Path | None, extra: str,
           learned_out: Path | None, watch: _Watch) -> Solved:
    from tools.commands.scenario_check import load_checked
    from tools.commands.simulate import simulate
    from tools.records import sim_summary
    from world.pddl.files import load_task
    from world.pddl.program import goal_text, program_text

    task = load_task(domain, problem)
    goal = goal_text(task)
    watch.names = (task.domain.name, task.name, goal, task.domain.notes)
    limit = cycles or default_cycles(len(task.objects), len(task.goal))
    with tempfile.TemporaryDirectory(prefix="teleo-solve-") as folder:
        program = Path(folder) / f"{task.domain.name}.tlp"
        program.write_text(program_text(task.domain, task, extra, str(domain), goals=False))
        path = Path(folder) / "solve.toml"
        name = f"solve-{task.name}"[:40].replace(".", "-")
        path.write_text(_scenario_text(name, domain.resolve(), problem.resolve(), program,
                                       goal, limit))
        scenario, _ = load_checked(path)
        if not task.goal:
            return Solved(task.domain.name, task.name, "achieved", 0, goal="(and)",
                          notes=task.domain.notes)
        run = simulate(scenario, limit, learned=learned, recorder=watch,
                       until=lambda states: watch.over)
        written = _write_learned(learned_out, program, run.learned[AGENT]) \
            if learned_out else []
    summary = sim_summary.build(run, scenario, 0, limit)
    g = next((x for x in summary["goals"] if x["id"] == "g1"), {})
    holds = bool(run.final.get("goal_holds"))
    status = g.get("status", "")
    if status == "achieved" and holds:
        verdict, reason = "achieved", ""
    elif status == "achieved":
        verdict, reason = "failed", "the agent believed the goal achieved; the world says not"
    elif status == "failed":
        verdict, reason = "failed", g.get("note", "")
    else:
        verdict, reason = "limit", f"{len(run.records)} cycles ran out with the goal {status}"
    sections = [r[AGENT].get("solver") or {} for r in run.records]
    new = sum(len(x.get("learned") or ()) for x in sections)
    solving = sum(bool(x.get("solving")) for x in sections)
    return Solved(task.domain.name, task.name, verdict, len(run.records), executed(run), new,
                  solving, reason, goal, run.elapsed_s,
                  str(written[0]) if written else None, task.domain.notes)


@click.command("solve")
@click.argument("domain", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.argument("problem", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--cycles", type=click.IntRange(min=1), default=None,
              help="Cycles at most (default: 50 + 20 per object + 10 per goal literal).")
@click.option("--learned", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              default=None, help="Start from the skills in this learned file.")
@click.option("--learned-out", type=OutputPath(path_type=Path), default=None,
              help="Write the skills learned (those started from, then the new ones) here, "
                   "and the program they fit beside it (STEM-program.tlp).")
@click.option("--extra", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              default=None, help="Add this file of your own concepts and skills to the "
                                 "domain's program.")
@click.option("--time-limit", type=click.FloatRange(min=0, min_open=True), default=None,
              help="Stop after this many seconds with status limit (default: none).")
@click.option("--json", "as_json", is_flag=True, help="Print the result as one JSON object.")
def solve_command(domain: Path, problem: Path, cycles: int | None, learned: Path | None,
                  learned_out: Path | None, extra: Path | None, time_limit: float | None,
                  as_json: bool) -> None:
    """Solve PROBLEM of DOMAIN (PDDL files) with a teleo agent, in one process.

    Prints the outcome and the executed plan; exit 0 when the goal was achieved (and the
    world's state satisfies it), 1 otherwise (failed, or the cycles ran out)."""
    from agents.lang import LangError

    try:
        text = extra.read_text() if extra else ""
        result = solve(domain, problem, cycles, learned, text, learned_out, time_limit)
    except (WorldError, LangError) as exc:
        raise click.ClickException(" ".join(str(exc).split("\n")[:1])
                                   if isinstance(exc, WorldError) else str(exc)) from None
    if as_json:
        click.echo(json.dumps(result.to_dict(), indent=1))
    else:
        _echo(result)
    raise SystemExit(0 if result.status == "achieved" else 1)


def _echo(r: Solved) -> None:
    click.echo(f"{r.domain} {r.problem}: {r.status} in {r.cycles} cycles, "
               f"{len(r.actions)} actions, {r.solving_cycles} problem-solving cycles, "
               f"{r.learned} skills learned ({r.elapsed_s:.2f} s)")
    click.echo(f"  goal {r.goal}")
    if r.reason:
        click.echo(f"  why: {r.reason}")
    for note in r.notes:
        click.echo(f"  note: {note}")
    for k, a in enumerate(r.actions, start=1):
        click.echo(f"  {k:3d} ({' '.join(a)})")
    if r.learned_file:
        click.echo(f"learned skills written to {r.learned_file} (with the program beside it, "
                   f"-program.tlp)")


commands = [solve_command]
