"""Helpers for the planner's office tests: a scenario of seed 003 run in one process
(tools/commands/simulate.py: the pymunk office world, its perception and the engine with the ROGUE
planner), read back as the planner's state, the actions sent and the world's events."""

from __future__ import annotations

from dataclasses import dataclass, replace
from itertools import combinations
from pathlib import Path

from tools.commands.simulate import SimRun, simulate
from world.run_scenario import ScriptedEvent, load_scenario

ROOT = Path(__file__).resolve().parents[3]


@dataclass
class Office:
    """One run: ``run`` (records, final snapshot, engine states), ``planner`` (the ROGUE
    state at the end)."""

    run: SimRun

    @property
    def planner(self):
        return self.run.states["ME"].planner

    def executed(self) -> list[str]:
        """The head-plan: every operator applied, in order."""
        return [a.step for a in self.planner.head]

    def results(self) -> list[tuple[str, str]]:
        return [(a.step, a.result) for a in self.planner.head]

    def commands(self) -> list[list]:
        """Every command sent, in order; one sent again the next cycle (a running operation
        goes on) counts once."""
        out, last = [], []
        for r in self.run.records:
            now = r["ME"]["actions"]
            out += [a for a in now if a not in last]
            last = now
        return out

    def said(self) -> list[str]:
        return [" ".join(str(w) for w in a[1:]) for a in self.commands() if a[0] == "*say"]

    def log(self) -> list[str]:
        return list(self.planner.log)

    def statuses(self) -> dict[str, str]:
        return {f.goal: f.status for f in self.planner.finished}

    def counters(self) -> dict[str, int]:
        return self.run.final["counters"]["ME"]


def run(name: str, events: tuple = (), cycles: int | None = None) -> Office:
    """Simulate scenarios/``name``.toml, with extra (at_cycle, event) pairs."""
    scenario = load_scenario(ROOT / "scenarios" / f"{name}.toml")
    if events:
        scenario = replace(scenario, events=scenario.events + tuple(
            ScriptedEvent(c, e) for c, e in events))
    return Office(simulate(scenario, cycles))


def prefer_only(folder: Path) -> Path:
    """programs/office_rogue.tlp without its AVOID-OCCUPIED-CONF-ROOMS reject rule (Figure 7
    with the seed's prefer rule alone), written into ``folder``."""
    text = (ROOT / "programs" / "office_rogue.tlp").read_text()
    start = text.index("  ; an optional refinement: the planner's failure memory")
    end = text.index("  ; where the robot is and how far")
    path = folder / "office_prefer_only.tlp"
    path.write_text(text[:start] + text[end:])
    return path


FIGURE_7 = [
    ("<goto-room r-5309>", "verified"), ("<select-conference-room r-5309>", "applied"),
    ("<observe-conference-room r-5309>", "not-achieved"),
    ("<goto-room r-5311>", "verified"), ("<select-conference-room r-5311>", "applied"),
    ("<observe-conference-room r-5311>", "verified"), ("<schedule-meeting r-5311>", "verified")]
"""Seed 003, Figure 7: r-5309 first (the closest), found occupied; backtracking to r-5311."""


def interleavings(a: tuple, b: tuple) -> list[tuple]:
    """Every merge of sequences ``a`` and ``b`` that keeps each one's order."""
    n = len(a) + len(b)
    out = []
    for slots in combinations(range(n), len(a)):
        ia, ib, seq = iter(a), iter(b), []
        for k in range(n):
            seq.append(next(ia) if k in slots else next(ib))
        out.append(tuple(seq))
    return out


FIGURE_6 = [
    "<goto-pickup-loc mitchell r-5303>",
    "<acquire-item r-5303 mitchell mail-mitchell>",
    "<goto-pickup-loc jhm r-5311>",
    "<acquire-item r-5311 jhm fax-jhm>",
    "<goto-deliver-loc mitchell r-5313>",
    "<deliver-item r-5313 jhm fax-jhm>",
    "<deliver-item r-5313 mitchell mail-mitchell>"]
"""Seed 003, Figure 6, with the world's ids for the seed's items (delivermail, deliverfax)."""
