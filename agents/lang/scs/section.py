"""The "scs" section of a decision (agents/lang/core/explanation.py, Section): every body thread
with its construct stack (what runs, where it was written, its position, choice, achieved
and failed substeps, retries, bindings, the action awaiting its outcome), the do-best
alternatives with their discount factors, the world model and the tally."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..core.program import Program
from ..core.terms import Action, fmt
from .state import Frame, ScsState, Thread
from .syntax import Construct, Kind, node_at

NAME = "scs"


@dataclass(frozen=True, slots=True)
class ScsSection:
    """SCS threads and records after one cycle."""

    scs: ScsState
    program: Program
    cycle: int
    name: str = NAME

    def to_dict(self) -> dict[str, Any]:
        return {"threads": [self._thread(t) for t in self.scs.threads],
                "choices": [c.to_dict() for c in self.scs.choices],
                "model": [list(f) for f in self.scs.model], "tally": dict(self.scs.tally)}

    def _thread(self, t: Thread) -> dict[str, Any]:
        return {"key": t.key, "goal_id": t.goal_id, "goal": t.goal, "skill": t.skill_name,
                "status": self.status(t), "note": t.note, "started": t.started,
                "stack": [self._frame(t, f) for f in (t.root.chain() if t.root else [])]}

    def status(self, t: Thread) -> str:
        """The thread's status; "suspended" when it did not run this cycle."""
        return t.status.value if t.last == self.cycle else "suspended"

    def _frame(self, t: Thread, f: Frame) -> dict[str, Any]:
        node = self._node(t, f)
        d: dict[str, Any] = {"step": _label(node), "where": str(getattr(node, "loc", "")),
                             "at": list(f.at)}
        if isinstance(node, Construct):
            d["state"] = _progress(node, f)
        if f.bind or f.alt:
            d["bindings"] = {k: v for k, v in (*f.bind, *f.alt)}
        if f.pending:
            d["pending"] = [list(a) for a in f.pending]
            d["outcome"] = f.outcome or "awaited"
        return d

    def _node(self, t: Thread, f: Frame) -> object:
        skills = self.program.skills
        if t.skill < len(skills) and skills[t.skill].body is not None:
            try:
                return node_at(skills[t.skill].body, f.at)
            except (IndexError, TypeError):
                pass
        return None

    def lines(self) -> list[str]:
        out = []
        if self.scs.threads:
            out.append("scs threads:")
        for t in self.scs.threads:
            out.append(f"  {t.goal_id} {t.goal} <- {t.skill_name}: {self.status(t)}"
                       f"{' -- ' + t.note if t.note else ''}")
            for depth, f in enumerate(t.root.chain() if t.root else []):
                d = self._frame(t, f)
                extra = f" {d['state']}" if d.get("state") else ""
                binds = d.get("bindings")
                if binds:
                    extra += " {" + ", ".join(f"?{k}={fmt(v)}" for k, v in binds.items()) + "}"
                if f.pending:
                    acts = " ".join(str(Action.from_list(a)) for a in f.pending)
                    extra += f" issued {acts}: {d['outcome']}"
                out.append(f"    {'  ' * depth}{d['step']}{extra}  ({d['where']})")
        if self.scs.choices:
            out.append("do-best discount factors:")
            for c in self.scs.choices:
                out.append(f"  {c.key}: {c.factor:.3f} (chosen {c.chosen}, succeeded "
                           f"{c.succeeded}, failed {c.failed})  {c.label}")
        if self.scs.model:
            out.append("world model: " + " ".join(
                "(" + " ".join(fmt(x) for x in f) + ")" for f in self.scs.model))
        if self.scs.tally:
            out.append("scs tally: " + ", ".join(f"{k} {v}" for k, v in self.scs.tally))
        return out


def _label(node: object) -> str:
    if isinstance(node, Construct):
        return f"({node.name})"
    return str(node) if node is not None else "(step not in this program)"


def _progress(node: Construct, f: Frame) -> str:
    n = len(node.steps)
    parts = []
    if node.kind in (Kind.DO, Kind.REPEAT):
        parts.append(f"step {f.cur + 1} of {n}" if f.cur >= 0 else "not started")
        if node.kind is Kind.REPEAT:
            parts.append(f"round {f.rounds + 1}")
    else:
        parts.append(f"alternative {f.cur + 1} of {n}" if f.cur >= 0 else "choosing")
    if f.done:
        parts.append("achieved " + ",".join(str(i + 1) for i in f.done))
    if f.failed:
        parts.append("failed " + ",".join(str(i + 1) for i in f.failed))
    if f.tries:
        parts.append(f"retries {f.tries}")
    return "[" + ", ".join(parts) + "]"
