"""The executive's use of the loop watch (agents/lang/execution/loops.py), one cycle at a time: the
situation digest (made when first asked), the circles found, the goal each is blamed on, and
the watches for the next cycle.

A circle found while pursuing a goal is blamed on the least important goal that acted in it
(seed 000's priorities: the lower goal gives way), which backs off the next time it is pursued
(agents/lang/execution/executive.py): the skill its remembered path began with is not used again
for it
in the episode, and the impasse handler backtracks; after MAX_LOOPS circles it fails."""

from __future__ import annotations

from dataclasses import replace

from ..core.store import FactStore, PerceptIndex
from .loops import LoopState, Watch, combined, world


class Watcher:
    """One cycle's loop watch: ``texts`` and ``ranks`` give each goal id its text and its
    place in the goal list (0 most important); ``intends`` is the intention part of the
    situation (loops.intention)."""

    def __init__(self, state: LoopState, pidx: PerceptIndex, store: FactStore, cycle: int,
                 texts: dict[str, str], ranks: dict[str, int], intends: str = ""):
        self.pidx, self.store, self.cycle = pidx, store, cycle
        self.texts, self.ranks, self.intends = texts, ranks, intends
        self._world = ""
        self._digest = ""
        self.old = {w.goal_id: w.observed(store, self.world) for w in state.watches}
        self.new: dict[str, Watch] = {}
        self.pursued: set[str] = set()

    @property
    def world(self) -> str:
        if not self._world:
            self._world = world(self.pidx, self.store)
        return self._world

    @property
    def digest(self) -> str:
        if not self._digest:
            self._digest = combined(self.world, self.intends)
        return self._digest

    def watch(self, goal_id: str) -> Watch:
        """The watch of ``goal_id`` as it stands now (a new episode if it had none)."""
        return self.new.get(goal_id) or self.old.get(goal_id) or Watch(goal_id, self.cycle)

    def banned(self, goal_id: str) -> frozenset:
        return frozenset(self.watch(goal_id).banned)

    def check(self, goal_id: str) -> None:
        """Look for a circle while pursuing ``goal_id`` now; one found is blamed on the least
        important goal that acted in it (``take`` hands it over)."""
        back = self.watch(goal_id).returned(self.digest)
        if back is None:
            return
        fight = list(self.watch(goal_id).since_visit(back)) or [goal_id]
        if goal_id not in fight:
            fight.insert(0, goal_id)
        names = " and ".join(f"{g} {self.texts.get(g, '')}".strip() for g in fight)
        why = (f"loop: back in the situation of cycle {back.cycle} while pursuing {goal_id} "
               f"{self.texts.get(goal_id, '')}, with no progress since; the goals that acted "
               f"in the circle: {names}")
        culprit = max(fight, key=lambda g: self.ranks.get(g, -1))
        w = self.watch(culprit)
        self.new[culprit] = replace(w, loops=w.loops + 1, circle=why, pending=True)

    def take(self, goal_id: str) -> str:
        """The circle ``goal_id`` is to back off from now ("" if none); taken once."""
        w = self.watch(goal_id)
        if not w.pending:
            return ""
        self.new[goal_id] = replace(w, pending=False)
        return w.circle

    def circle(self, goal_id: str) -> str:
        """Why the last circle blamed on ``goal_id`` in its episode was one ("" if none)."""
        return self.watch(goal_id).circle

    def loops(self, goal_id: str) -> int:
        return self.watch(goal_id).loops

    def ban(self, goal_id: str, key: tuple[str, int, tuple]) -> None:
        w = self.watch(goal_id)
        if key not in w.banned:
            self.new[goal_id] = replace(w, banned=w.banned + (key,))

    def state(self, goals: list[tuple[str, bool]], actor: str, expects: tuple[tuple, ...],
              paths: dict[str, tuple]) -> LoopState:
        """The watches for the next cycle: ``goals`` are (id, held this cycle) of the goal
        list; each goal's watch sees this situation, in which ``actor`` acted to achieve
        ``expects`` (by the path ``paths[actor]``), except that the episode of a goal holding
        for the second cycle in a row ends."""
        out = []
        for g, held in goals:
            w = self.watch(g)
            if held and (not w.visits or w.visits[-1].held):
                continue
            if g == actor and paths.get(g):
                top = paths[g][0]
                w = replace(w, last=(top.goal, top.skill, top.bindings))
            out.append(w.seen(self.digest, self.cycle, actor, g in self.pursued, expects,
                              self.world, held))
        return LoopState(tuple(sorted(out, key=lambda w: w.goal_id)))
