"""Asking the world of a running launch on its control key, teleo/<run>/world/control
(bus/pause.py): `teleo pause`, `step-run`, `resume`, `program load`, `set` and the web view's
pause, step and resume buttons go this one way, and each hears the world's verdict (docs/bus.md,
"Pausing and stepping a launch", "Changing a running launch")."""

from __future__ import annotations

from typing import Any


class ControlError(Exception):
    """The world refused, did not answer, or answered with something else; one line that
    names the run."""


def ask_world(node: Any, run: str, event: dict[str, Any], timeout: float
              ) -> tuple[dict[str, Any], str]:
    """Ask the world of ``run`` ``event`` through ``node`` (an open bus node); returns its
    outcome and note, or raises ControlError."""
    from bus import keys
    from bus.errors import BusError, NobodyServing, QueryFailed
    from bus.messages import EventReply, WorldEvent

    try:
        reply = node.query(keys.world_control(run), WorldEvent(node.envelope(), event), timeout)
    except NobodyServing as exc:
        raise ControlError(
            f"run {run}: no answer from the world within {timeout:g} s: it answers between "
            "two cycles; is the run stalled, over, or started by an older teleo? "
            "(teleo inspect)") from exc
    except QueryFailed as exc:  # the world's refusal, in its words
        raise ControlError(f"run {run}: the world refused: {exc.reason}") from exc
    except BusError as exc:
        raise ControlError(f"run {run}: {exc}") from exc
    if not isinstance(reply, EventReply):
        raise ControlError(f"run {run}: the world answered with a {reply.KIND}")
    return dict(reply.outcome), reply.reason


def ask_once(info: Any, event: dict[str, Any], timeout: float) -> tuple[dict[str, Any], str]:
    """``ask_world`` through a node of its own on the launch of ``info`` (runfile.RunInfo)."""
    from tools.runs import runfile

    return ask_via(runfile.bus_config(info), info.run, event, timeout)


def ask_via(cfg: Any, run: str, event: dict[str, Any], timeout: float,
            process: str = "control-cli") -> tuple[dict[str, Any], str]:
    """``ask_world`` through a node of its own on the bus ``cfg`` (bus.config.BusConfig)."""
    from bus.errors import BusError
    from bus.node import open_node

    try:
        with open_node(cfg, run, process) as node:
            return ask_world(node, run, event, timeout)
    except BusError as exc:
        raise ControlError(f"run {run}: {exc}") from exc


def verdict_line(outcome: dict[str, Any], note: str = "") -> str:
    """The world's verdict on a pause, step or resume, as `teleo pause` prints it after the
    run: "paused at cycle 120 after 3 cycles (already paused)"."""
    where = "paused" if outcome.get("paused") else "running"
    line = f"{where} at cycle {outcome.get('cycle')}"
    if outcome.get("op") == "step":
        line += f" after {outcome.get('stepped')} cycles"
    return line + (f" ({note})" if note else "")
