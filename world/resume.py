"""How a restarted world process gets back to the cycle its predecessor had reached
(docs/faults.md, "The world dies").

The run folder holds the trace of every cycle run (world/recorder.py: actions applied, events
injected with their outcomes, a digest of the state) and a checkpoint of the simulation every
CHECKPOINT_EVERY cycles. `resume` restores the last checkpoint (or builds the world afresh
from the scenario when there is none, or the domain cannot restore) and replays the recorded
cycles after it: re-inject each cycle's events, check that the state's digest is the recorded
one, apply the recorded actions, step. The result is the world exactly as it was before the
first cycle not in the trace, with the outcomes the next world state must carry. Anything
that does not match raises CannotResume: the launcher then ends the run with that reason
instead of running on from a state that differs from the one the agents saw.
"""

from __future__ import annotations

import json
import logging
import pickle
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from world.domain import Domain, Restartable, World
from world.errors import WorldError
from world.recorder import CHECKPOINT, TRACE, complete_lines
from world.trace import digest

log = logging.getLogger(__name__)


class CannotResume(WorldError):
    """The world cannot be brought back to where the run was; the message says why."""


@dataclass
class Resumed:
    """A world ready to run cycle `cycle`, the outcomes and agent memories to publish with
    it, and how it got there (the checkpoint's cycle, or -1 for none, and the number of
    cycles replayed)."""

    world: World
    cycle: int
    outcomes: dict[str, list[dict[str, Any]]]
    checkpoint: int
    replayed: int
    memory: dict[str, Any]


def resume(domain: Domain, table: dict[str, Any], seed: int, agents: list[str],
           out: Path) -> Resumed:
    """The world of the run recorded in `out`, at the first cycle not in its trace."""
    lines = [_parse(line, n) for n, line in enumerate(complete_lines(out / TRACE))]
    world, start, outcomes = _start(domain, table, seed, agents, out, len(lines))
    for line in lines[start:]:
        outcomes = _replay(world, line, agents)
    memory: dict[str, Any] = {a: {} for a in agents}
    for line in lines:
        memory.update(line.get("memory", {}))
    return Resumed(world, len(lines), outcomes, start if start else -1, len(lines) - start,
                   memory)


def _start(domain: Domain, table: dict[str, Any], seed: int, agents: list[str], out: Path,
           recorded: int) -> tuple[World, int, dict[str, list]]:
    """From the checkpoint when there is a usable one, else a fresh world at cycle 0."""
    saved = _load_checkpoint(out / CHECKPOINT)
    if saved is not None and domain.restore is not None and saved["cycle"] <= recorded:
        try:
            return domain.restore(saved["world"]), saved["cycle"], saved["outcomes"]
        except WorldError as exc:
            log.warning("checkpoint of cycle %d not usable (%s): replaying from cycle 0",
                        saved["cycle"], exc)
    return domain.create(table, seed, agents), 0, {a: [] for a in agents}


def _load_checkpoint(path: Path) -> dict[str, Any] | None:
    try:
        with path.open("rb") as f:
            saved = pickle.load(f)
    except FileNotFoundError:
        return None
    except (pickle.UnpicklingError, EOFError, AttributeError, ImportError, TypeError,
            ValueError) as exc:
        log.warning("%s unreadable (%s): replaying from cycle 0", path, exc)
        return None
    if not isinstance(saved, dict) or saved.get("version") != 1:
        log.warning("%s: unknown checkpoint format: replaying from cycle 0", path)
        return None
    return saved


def _parse(text: str, n: int) -> dict[str, Any]:
    try:
        line = json.loads(text)
    except ValueError as exc:
        raise CannotResume(f"{TRACE} line {n + 1}: not JSON ({exc})") from exc
    if not isinstance(line, dict) or line.get("cycle") != n:
        raise CannotResume(f"{TRACE} line {n + 1}: expected cycle {n}, got "
                           f"{line.get('cycle') if isinstance(line, dict) else line!r}")
    return line


def _replay(world: World, line: dict[str, Any], agents: list[str]) -> dict[str, list]:
    """One recorded cycle again: its events, the digest check, its actions, a step."""
    for outcome in line.get("events", ()):
        world.inject(outcome.get("event"))
    found = digest(world.snapshot_dict())
    if found != line.get("digest"):
        raise CannotResume(f"{TRACE}: cycle {line['cycle']}: the replayed state differs from "
                           f"the recorded one (digest {found}, recorded {line.get('digest')}); "
                           "the domain is not deterministic or the files were changed")
    actions = line.get("actions", {})
    outcomes = {a: world.apply_actions(a, actions.get(a, [])) for a in agents}
    world.step()
    return outcomes


def can_checkpoint(world: World, domain: Domain) -> bool:
    """Whether this domain saves checkpoints (else a restart replays from cycle 0)."""
    return isinstance(world, Restartable) and domain.restore is not None
