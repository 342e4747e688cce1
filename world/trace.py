"""One line of a run's trace (trace.jsonl), the same from `teleo launch` (the world process)
and `teleo simulate`: nothing in it depends on timing, so two lockstep runs of one scenario
and seed, or a launch and a simulate of it, give the same file (docs/scenarios.md, "Run
files").

    {"cycle": t, "actions": {agent: [[name, arg...]...]}, "counters": {agent: {name: n}},
     "digest": "<16 hex>", "events": [outcome...], "memory": {agent: memory},
     "control": {"programs": {agent: {"name", "text"}}, "set": [{"key", "value"}]}}

`counters` and `digest` are those of the world state of cycle t (before its actions);
`actions` are the actions applied to each agent for t (what it sent, or the world's safe
action when they did not arrive); `events` the outcomes of the events injected at the start
of t (only when some were); `memory` each agent memory that changed with t's actions (only
when one did: docs/bus.md, "Agent memory"); `control` what changed at the start of t (only
when something did: a program swapped in, a `teleo set`; world/changes.py). A restarted
world replays this file
(world/resume.py).
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping, Sequence
from typing import Any


def digest(snapshot: dict[str, Any]) -> str:
    """A short hash of the whole world state (canonical JSON)."""
    text = json.dumps(snapshot, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def trace_line(cycle: int, snapshot: dict[str, Any], actions: Mapping[str, Sequence],
               injected: Sequence[dict[str, Any]] = (),
               memory: Mapping[str, Any] | None = None, state_digest: str = "",
               control: Mapping[str, Any] | None = None) -> str:
    """The trace line of one cycle, JSON with sorted keys and a newline. ``state_digest``:
    ``digest(snapshot)`` when the caller already has it."""
    line: dict[str, Any] = {
        "cycle": cycle,
        "actions": {a: [list(x) for x in acts] for a, acts in sorted(actions.items())},
        "counters": snapshot["counters"], "digest": state_digest or digest(snapshot)}
    if injected:
        line["events"] = list(injected)
    if memory:
        line["memory"] = dict(memory)
    if control:
        line["control"] = dict(control)
    return json.dumps(line, sort_keys=True) + "\n"
