"""`teleo program load AGENT FILE`, `teleo set KEY=VALUE`: change a running launch at a cycle
boundary (as Soar's `source` loads rules into a running agent, `ros2 param set` a node's
parameter; docs/bus.md, "Changing a running launch").

`program load` checks FILE first exactly as `teleo check` does (every error as file:line:col,
exit 1, the running program untouched), then asks the world (teleo/<run>/world/control) to
hand it to AGENT's stages at the next cycle it runs (or `--at N`); its inference and executive
swap it in at that same cycle, the engine state carried over where it still means something,
and say so with their output of the cycle. What is printed is their verdict: the cycle, what
was dropped, or why they kept the program they ran. The world's trace and the run record hold
the program's text at that cycle, so the same swap at the same cycle gives the same run.

`set` changes a field of the scenario that can change while the run runs (world/changes.py
RUNTIME_KEYS; `agents.<id>.program=FILE` is a program load), checked as `launch --set` checks
it; any other key is refused with a sentence naming it. Exit status: 0 when done (or
scheduled on a paused run), 1 when refused, not answered, or nothing runs.
"""

from __future__ import annotations

import json
import time
from typing import Any

import click

from tools.runs import runfile

VERDICT_TIMEOUT = 30.0  # [s] for the world to reach a cycle boundary and the stages to answer


def _options(f):
    f = click.option("--json", "as_json", is_flag=True,
                     help="One JSON object: the run's verdict.")(f)
    f = click.option("--timeout", type=click.FloatRange(min=0.1), default=VERDICT_TIMEOUT,
                     show_default=True,
                     help="Seconds to wait for the verdict (more with a far --at).")(f)
    f = click.option("--at", type=click.IntRange(min=0), default=None, metavar="CYCLE",
                     help="The cycle to change at (default: the next the world runs); the "
                          "same change at the same cycle gives the same run.")(f)
    return runfile.quiet_option(runfile.run_option(f))


@click.group("program")
def program() -> None:
    """Change a running agent's program (`teleo program load AGENT FILE`)."""


@program.command("load")
@click.argument("agent")
@click.argument("file", type=click.Path(dir_okay=False))
@_options
def load(agent: str, file: str, at: int | None, timeout: float, as_json: bool,
         run_id: str | None) -> None:
    """Swap FILE in as AGENT's program at a cycle boundary; print the stages' verdict.

    FILE is checked first as `teleo check` checks it. The engine state carries over where
    it still means something (goals, learned skills, skill paths and SCS threads whose
    skills are still there); what is dropped is said."""
    _load(agent, file, at, timeout, as_json, run_id)


def _load(agent: str, file: str, at: int | None, timeout: float, as_json: bool,
          run_id: str | None, setting: str = "") -> None:
    from agents.lang.loader import read_text
    from tools.commands.check import echo_checked, program_checked

    result, _ = program_checked(file, ())
    if not result["ok"]:
        if as_json:
            click.echo(json.dumps({"ok": False, "agent": agent, "program": file,
                                   "errors": result["errors"]}))
        else:
            echo_checked(result)
        raise click.ClickException(f"{file}: not loaded: the running program is untouched")
    info = runfile.locate(run_id)
    if agent not in info.agents:
        raise click.ClickException(f"run {info.run} has no agent {agent!r}; agents: "
                                   f"{', '.join(info.agents)}")
    event = {"op": "load", "agent": agent, "name": file, "text": read_text(file)}
    outcome, acks = _ask(info, event, at, timeout, agent)
    verdict = _verdict(info.run, agent, file, outcome, acks, setting)
    _say(verdict, as_json)


def _ask(info: Any, event: dict, at: int | None, timeout: float, agent: str = ""
         ) -> tuple[dict, dict[str, dict]]:
    """Ask the world (scheduling `event` at `at`), then, for a program, wait for the
    stages' verdicts of that cycle: (the world's outcome, {"inference": swap, "executive":
    swap} as far as they came)."""
    from bus import keys
    from bus.errors import BusError
    from bus.node import open_node
    from tools.runs.control import ControlError, ask_world

    if at is not None:
        event["at"] = at
    try:
        with open_node(runfile.bus_config(info), info.run, "control-cli") as node:
            inbox = node.subscribe(keys.beliefs(info.run, agent)) if agent else None
            if inbox is not None:
                node.subscribe(keys.intention(info.run, agent), inbox)
            outcome, _ = ask_world(node, info.run, event, timeout)
            if inbox is None or outcome.get("paused"):
                return outcome, {}
            return outcome, _acks(inbox, int(outcome["cycle"]), timeout)
    except ControlError as exc:
        raise click.ClickException(str(exc)) from exc
    except BusError as exc:
        raise click.ClickException(f"run {info.run}: {exc}") from exc


def _acks(inbox: Any, cycle: int, timeout: float) -> dict[str, dict]:
    """The inference's and the executive's Beliefs.swap / Intention.swap of `cycle`."""
    from bus.messages import Beliefs, Intention

    got: dict[str, dict] = {}
    end = time.monotonic() + timeout
    while len(got) < 2 and (left := end - time.monotonic()) > 0:
        msg = inbox.get(left)
        if msg is None or msg.env.cycle < cycle:
            continue
        stage = "inference" if isinstance(msg, Beliefs) else \
            "executive" if isinstance(msg, Intention) else ""
        if stage and stage not in got:
            got[stage] = dict(msg.swap) if msg.env.cycle == cycle else \
                {"ok": False, "reason": f"it skipped cycle {cycle}"}
    return got


def _verdict(run: str, agent: str, file: str, outcome: dict, acks: dict[str, dict],
             setting: str) -> dict[str, Any]:
    cycle = outcome.get("cycle")
    verdict = {"run": run, "agent": agent, "program": file, "cycle": cycle,
               "paused": bool(outcome.get("paused")), "stages": acks, "dropped": []}
    if setting:
        verdict["set"] = setting
    if verdict["paused"]:
        return {**verdict, "ok": True, "state": "scheduled"}
    for stage in ("inference", "executive"):
        ack = acks.get(stage)
        if ack is None:
            raise click.ClickException(f"run {run}: no word from {agent}'s {stage} on the swap "
                                       f"at cycle {cycle}: is the run stalled or over? "
                                       "(teleo inspect)")
        if not ack:
            raise click.ClickException(f"run {run}: {agent}'s {stage} did not swap at cycle "
                                       f"{cycle}: started by an older teleo?")
        if not ack.get("ok"):
            raise click.ClickException(f"run {run}: {agent} kept its program at cycle {cycle}: "
                                       f"{stage}: {ack.get('reason')}")
    verdict["dropped"] = list(acks["executive"].get("dropped", []))
    return {**verdict, "ok": True, "state": "swapped"}


def _say(verdict: dict[str, Any], as_json: bool) -> None:
    if as_json:
        click.echo(json.dumps(verdict))
        return
    head = f"run {verdict['run']}: {verdict['agent']} "
    if verdict["state"] == "scheduled":
        click.echo(head + f"runs {verdict['program']} from cycle {verdict['cycle']}: the run is "
                   "paused there (teleo step-run or resume runs it)")
        return
    dropped = verdict["dropped"]
    click.echo(head + f"runs {verdict['program']} from cycle {verdict['cycle']} (inference "
               f"and executive); {'dropped:' if dropped else 'nothing dropped'}")
    for line in dropped:
        click.echo(f"  {line}")


@click.command("set", short_help="Change a field of the running launch at a cycle boundary "
                                  "(run.deadline, ...)")
@click.argument("assignment", metavar="KEY=VALUE")
@_options
def set_(assignment: str, at: int | None, timeout: float, as_json: bool,
         run_id: str | None) -> None:
    """Change KEY of the running launch's scenario at a cycle boundary; print the verdict.

    What can change while it runs: run.deadline (the realtime period), run.render_every,
    and agents.<id>.program (as `teleo program load`). VALUE is checked as `launch --set`
    checks it."""
    from world.changes import RUNTIME_KEYS, fixed_key
    from world.overrides import OverrideError, parse_override

    try:
        o = parse_override(assignment)
    except OverrideError as exc:
        raise click.ClickException(str(exc).replace("--set ", "set ", 1)) from exc
    key = ".".join(o.key)
    if o.key[0] == "agents" and len(o.key) == 3 and o.key[2] == "program":
        return _load(o.key[1], str(o.value), at, timeout, as_json, run_id, key)
    if o.key not in RUNTIME_KEYS:
        raise click.ClickException(fixed_key(key))
    info = runfile.locate(run_id)
    outcome, _ = _ask(info, {"op": "set", "text": assignment.strip()}, at, timeout)
    verdict = {"run": info.run, "ok": True, "key": outcome.get("key", key),
               "value": outcome.get("value"), "cycle": outcome.get("cycle"),
               "paused": bool(outcome.get("paused"))}
    if as_json:
        click.echo(json.dumps(verdict))
        return
    held = " (the run is paused there)" if verdict["paused"] else ""
    click.echo(f"run {info.run}: {verdict['key']} = {json.dumps(verdict['value'])} from cycle "
               f"{verdict['cycle']}{held}")


commands = [program, set_]
