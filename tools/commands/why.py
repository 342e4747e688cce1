"""`teleo why RUN CONCEPT-INSTANCE [--cycle N]`: why an instance such as `(clear A)` is or is
not believed at a cycle of a recorded run (as Soar's `matches`), from the run record's
percepts and world model of that cycle, through the program's concepts
(tools/records/why.py).

    teleo why RUN '(clear A)' --cycle 3
    teleo why RUN '(on C B)' --agent ME --program programs/blocks.tlp --json

RUN is a run folder, a run id under the runs folder, or an .mcap file (as `teleo explain`).
"""

from __future__ import annotations

import json

import click

from tools.commands.explain import _of_cycle, _open, _program


def _load(program: str):
    from agents.lang import ProgramError, load_program

    try:
        return load_program(program)
    except ProgramError as exc:
        raise click.ClickException(str(exc.errors[0] if exc.errors else exc)) from None


def _instance(text: str, program) -> object:
    """``text`` read as one concept instance of ``program``; UsageError (one line) if not."""
    from agents.lang import GoalError, Literal
    from agents.lang.reading.goals import parse_goal

    try:
        lit = parse_goal(text, program)
    except GoalError as exc:
        raise click.ClickException(str(exc).replace("goal ", "concept instance ", 1)) from None
    if not isinstance(lit, Literal) or lit.negated:
        raise click.ClickException(f"concept instance {text!r}: expected one concept instance "
                               "such as (clear A), not a conjunction or a negation")
    return lit


def _prior_model(rec, agent: str, cycle: int) -> list:
    """The world model (SCS facts, seed 002) the agent held after the previous cycle's
    decision, what its inference read this cycle: a simulate record echoes no agent memory
    with the percepts (as the web view reads it, tools/view/model.py)."""
    decision = (rec.by_cycle("intention", agent).get(cycle - 1) or {}).get("decision")
    section = decision.get("scs") if isinstance(decision, dict) else None
    model = section.get("model") if isinstance(section, dict) else None
    return model if isinstance(model, list) else []


@click.command()
@click.argument("run", metavar="RUN")
@click.argument("instance", metavar="CONCEPT-INSTANCE")
@click.option("--cycle", type=int, default=None, help="Which cycle (default: the last).")
@click.option("--agent", default=None, help="Whose beliefs (default: the only agent).")
@click.option("--program", "program", type=click.Path(), default=None,
              help="The agent's program (default: the one the run's scenario names).")
@click.option("--json", "as_json", is_flag=True, help="One JSON object, for scripts.")
def why(run: str, instance: str, cycle: int | None, agent: str | None, program: str | None,
        as_json: bool) -> None:
    """Say why a concept instance is or is not believed at a cycle of a recorded run.

    For a believed instance, each clause that holds, with its bindings and the percept or
    belief that matched each condition; for one not believed, each clause's first
    condition that failed and what was there instead (as Soar's `matches`). RUN: a run
    folder, a run id or an .mcap file; CONCEPT-INSTANCE such as '(clear A)'."""
    from tools.records.why import why as explain_why
    from tools.records.why import why_text

    try:  # explain's words for a run, agent or cycle not there, as one line
        rec, agent = _open(run, agent)
        cycle, seen = _of_cycle(rec, "percepts", agent, cycle)
    except click.UsageError as exc:
        raise click.ClickException(exc.message) from None
    path = program or _program(rec, agent)
    if path == "PROGRAM":
        raise click.ClickException(f"run {rec.run}: the program of {agent} cannot be found "
                                   "from its scenario; name it with --program")
    prog = _load(path)
    lit = _instance(instance, prog)
    model = (seen.get("memory") or {}).get("model") or _prior_model(rec, agent, cycle)
    report = explain_why(prog, lit, seen["percepts"], model)
    recorded = rec.by_cycle("beliefs", agent).get(cycle)
    if recorded is not None and not lit.variables():  # what the run's own inference said
        report["recorded"] = [lit.pred, *lit.args] in recorded["beliefs"]
    where = f"at cycle {cycle} of run {rec.run} (agent {agent}, program {path})"
    if as_json:
        click.echo(json.dumps({"run": rec.run, "agent": agent, "cycle": cycle,
                               "program": path, **report}, indent=1))
        return
    click.echo(why_text(report, where))
    if report.get("recorded") is not None and report["recorded"] != report["believed"]:
        click.echo(f"  note: the run's recorded beliefs say "
                   f"{'believed' if report['recorded'] else 'not believed'}: the program "
                   "may have changed since the run")


commands = [why]
