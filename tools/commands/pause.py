"""`teleo pause`, `teleo step-run [N]`, `teleo resume`: hold a running lockstep launch between
two cycles, run N cycles of it and hold it again, let it go on (as Soar's `run 1` or a
behaviour tree ticked by hand).

Each asks the world process on teleo/<run>/world/control; the world answers at a cycle
boundary with where the run is ("paused at cycle 120": cycle 120 is the next to run), so what
is printed is the world's verdict, not that something was sent (bus/pause.py). While the run
is held every stage stays up and no deadline counts; its trace is byte for byte that of the
same run never paused (docs/bus.md, "Pausing and stepping a launch"). A realtime run refuses.
Exit status: 0 when the world did it, 1 when it refused, did not answer, or nothing runs.
"""

from __future__ import annotations

import json

import click

from tools.runs import runfile

VERDICT_TIMEOUT = 30.0  # [s] for the world to reach a cycle boundary and answer
STEP_SECONDS = 5.0      # [s] more per cycle of a step-run (a loaded machine, a slow program)


def _timeout_option(f):
    return click.option("--timeout", type=click.FloatRange(min=0.1), default=None,
                        help=f"Seconds to wait for the world's verdict [default: "
                             f"{VERDICT_TIMEOUT:g}, plus {STEP_SECONDS:g} per stepped "
                             "cycle].")(f)


def _json_option(f):
    return click.option("--json", "as_json", is_flag=True,
                        help='One JSON object: {"run", "op", "paused", "cycle", "stepped", '
                             '"note"}.')(f)


def ask(run_id: str | None, event: dict, timeout: float) -> tuple[str, dict, str]:
    """Ask the world of the running launch `event` on its control key; returns (run, the
    world's outcome, its note); ClickException for no launch, no answer or a refusal."""
    from tools.runs.control import ControlError, ask_once

    info = runfile.locate(run_id)
    try:
        outcome, note = ask_once(info, event, timeout)
    except ControlError as exc:
        raise click.ClickException(str(exc)) from exc
    return info.run, outcome, note


def _report(run: str, outcome: dict, note: str, as_json: bool) -> None:
    if as_json:
        click.echo(json.dumps({"run": run, **outcome, "note": note}))
        return
    from tools.runs.control import verdict_line

    click.echo(f"run {run}: {verdict_line(outcome, note)}")


@click.command("pause")
@_timeout_option
@_json_option
@runfile.run_option
@runfile.quiet_option
def pause(timeout: float | None, as_json: bool, run_id: str | None) -> None:
    """Hold the running lockstep launch before its next cycle; print where it is held.

    Every stage stays up and no deadline counts while it is held; `teleo step-run` runs
    cycles of it, `teleo resume` lets it go on."""
    _report(*ask(run_id, {"op": "pause"}, timeout or VERDICT_TIMEOUT), as_json)


@click.command("step-run")
@click.argument("cycles", type=click.IntRange(1, 1_000_000), default=1, required=False)
@_timeout_option
@_json_option
@runfile.run_option
@runfile.quiet_option
def step_run(cycles: int, timeout: float | None, as_json: bool, run_id: str | None) -> None:
    """Run CYCLES cycles (default 1) of the launch, then hold it again; print where.

    A run that was not paused is held after them too. (`teleo step` is the language
    engine's step, over files.)"""
    wait = timeout or VERDICT_TIMEOUT + STEP_SECONDS * cycles
    _report(*ask(run_id, {"op": "step", "cycles": cycles}, wait), as_json)


@click.command("resume")
@_timeout_option
@_json_option
@runfile.run_option
@runfile.quiet_option
def resume(timeout: float | None, as_json: bool, run_id: str | None) -> None:
    """Let a paused launch go on; print the cycle it goes on from."""
    _report(*ask(run_id, {"op": "resume"}, timeout or VERDICT_TIMEOUT), as_json)


commands = [pause, step_run, resume]
