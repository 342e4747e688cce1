"""Each agent's goals' status changes, as a run record tells them (tools/records/run_record.py
keeps them in its metadata `teleo.goals`; `teleo explain` and the summaries read them)."""

from __future__ import annotations

import json
from collections import defaultdict
from collections.abc import Callable
from typing import Any

__all__ = ["GoalHistory"]


class GoalHistory:
    """Each agent's goals' status changes, fed with intention and goal-list records: agent ->
    goal id -> [{"cycle", "status", "goal", "priority", "note"}] (one entry per change, first
    sighting included). A user goal that leaves the agent's goal list without having failed
    was cancelled: the executive never reports that, as it no longer has the goal.

    The records are kept by cycle and the changes worked out from them in cycle order (the
    goal list of a cycle before the intention decided from it), so the history is the same
    whatever order the records arrived in (the goal list of cycle t+1
    reaching the recorder before the intention of t that said "failed" must not turn the
    failure into "cancelled", nor a failed run into a completed one).

    A change seen after a gap in the record (cycles whose world state it lacks, between the
    agent's previous intention and this one) happened at some cycle of the gap or at the one
    seen: its entry has "after", the last cycle known before it, so that nobody takes the
    cycle after a gap for the cycle of the change (not the cycle the gap ended at)."""

    FINAL = frozenset({"failed", "cancelled"})

    def __init__(self) -> None:
        # agent -> cycle -> that cycle's goals (a tuple shared between equal cycles: a run of
        # 65,000 cycles keeps one reference per cycle)
        self._lists: dict[str, dict[int, tuple]] = defaultdict(dict)
        self._intents: dict[str, dict[int, tuple]] = defaultdict(dict)
        self._shared: dict[tuple, tuple] = {}
        self._has_state: Callable[[int], bool] | None = None
        self._ended: dict[str, dict[str, dict[str, Any]]] = defaultdict(dict)  # ended_before
        self._cache: dict[str, dict[str, list[dict[str, Any]]]] | None = None

    def feed(self, record: dict[str, Any], has_state: Callable[[int], bool] | None = None
             ) -> None:
        """Take one intention or goal-list record; `has_state(cycle)`: whether the record
        holds that cycle's world state (None: no gaps are looked for), asked when the
        changes are worked out. A record of another shape (a hostile peer's) is passed over:
        only goals with a string id are kept, their other fields as plain values."""
        env = record.get("env")
        cycle = env.get("cycle") if isinstance(env, dict) else None
        if not isinstance(cycle, int) or isinstance(cycle, bool):
            return
        agent = str(record.get("agent", ""))
        self._has_state, self._cache = has_state, None
        if record.get("kind") == "GoalList":
            self._lists[agent][cycle] = self._share(tuple(
                (g["id"], _text(g.get("goal", "")), _priority(g.get("priority")))
                for g in _goals(record.get("goals"))))
            return
        decision = record.get("decision")
        self._intents[agent][cycle] = self._share(tuple(
            (g["id"], g["status"] if isinstance(g.get("status"), str) else None,
             _text(g.get("goal", "")),
             _priority(g.get("priority")), _text(g.get("note", "")))
            for g in _goals(decision.get("goals") if isinstance(decision, dict) else ())))

    def ended_before(self, agent: str, record: dict[str, Any]) -> None:
        """A user goal the goal store says failed or was cancelled (a record of its list:
        id, goal, priority, status, updated_cycle, note), taken as one change when nothing
        of it was fed: a view opened after it ended saw no message of it."""
        gid, status = record.get("id"), record.get("status")
        if status in self.FINAL and isinstance(gid, str):
            self._ended[agent][gid] = record
            self._cache = None

    def _share(self, item: tuple) -> tuple:
        return self._shared.setdefault(item, item)

    @property
    def changes(self) -> dict[str, dict[str, list[dict[str, Any]]]]:
        """agent -> goal id -> its changes, worked out from every record fed so far."""
        if self._cache is not None:   # a live view asks often; work it out once a change
            return self._cache
        out: dict[str, dict[str, list[dict[str, Any]]]] = defaultdict(dict)
        for agent in sorted({*self._lists, *self._intents, *self._ended}):
            self._changes_of(agent, out[agent])
            for gid, record in self._ended.get(agent, {}).items():
                if gid not in out[agent]:
                    cycle = record.get("updated_cycle")
                    out[agent][gid] = [{
                        "cycle": cycle if isinstance(cycle, int) else 0,
                        "status": record["status"], "goal": _text(record.get("goal", "")),
                        "priority": _priority(record.get("priority")),
                        "note": _text(record.get("note", ""))}]
        self._cache = out
        return out

    def _changes_of(self, agent: str, out: dict[str, list[dict[str, Any]]]) -> None:
        lists, intents, has_state = self._lists[agent], self._intents[agent], self._has_state
        last: dict[str, str] = {}
        listed: dict[str, tuple] = {}
        seen = -1   # the cycle of the agent's previous intention

        def add(gid: str, cycle: int, status: str, goal: str, priority: Any, note: str,
                after: int | None = None) -> None:
            last[gid] = status
            change = {"cycle": cycle, "status": status, "goal": goal, "priority": priority,
                      "note": note}
            if after is not None:
                change["after"] = after
            out.setdefault(gid, []).append(change)

        for cycle in sorted({*lists, *intents}):
            if cycle in lists:   # the goal list of a cycle comes before its decision
                now = {g[0]: g for g in lists[cycle]}
                for gid, (_, goal, priority) in listed.items():
                    if gid not in now and last.get(gid) not in self.FINAL:
                        add(gid, cycle, "cancelled", goal, priority,
                            "withdrawn from the goal list")
                listed = now
            if cycle not in intents:
                continue
            after = None
            if has_state is not None and not all(has_state(c) for c in range(seen + 1, cycle)):
                after = seen
            seen = cycle
            for gid, status, goal, priority, note in intents[cycle]:
                if last.get(gid) not in (status, "cancelled"):
                    add(gid, cycle, status, goal, priority, note, after)

    def to_meta(self) -> dict[str, str]:
        return {agent: json.dumps(goals) for agent, goals in self.changes.items()}


def _goals(goals: Any) -> list[dict[str, Any]]:
    """The goal records of a list that have a string id."""
    if not isinstance(goals, list | tuple):
        return []
    return [g for g in goals if isinstance(g, dict) and isinstance(g.get("id"), str)]


def _text(value: Any) -> str:
    return value if isinstance(value, str) else str(value)


def _priority(value: Any) -> int | None:
    return value if isinstance(value, int) and not isinstance(value, bool) else None
