"""Shortest paths on a grid world for an agent with a heading (MiniGrid's moves), a pure
function of plain data: what perception computes so that a program's skills need only follow
an affordance ("the next step toward the red key is forward").

A state is (x, y, dir) with MiniGrid's directions (0 east +x, 1 south +y, 2 west, 3 north).
The moves are `left`, `right` (turn, 1 step each) and `forward`; a closed door ahead is opened
on the way (`toggle` then `forward`: 2 steps), a locked one too when the agent carries the key
of its colour. A locked door without its key, or an object that could be picked up and put
aside (key, ball, box), is crossed only at a PENALTY, so a target behind one is still found,
with that first obstacle named (`via`): what the program must deal with first. Walls, lava
and the grid's edge are never crossed; a moving obstacle's cell is never entered from the
agent's own cell, and further on costs MOVING more (it will have moved by then). Ties are
broken in a fixed order (forward, left, right), so the same grid gives the same answer.
"""

from __future__ import annotations

import heapq
from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass

DIRS = ((1, 0), (0, 1), (-1, 0), (0, -1))
PENALTY = 1000          # [steps] the price of crossing an obstacle that must be dealt with first
MOVING = 0              # [steps] the extra price of a cell a moving obstacle stands on now (it
#                         moves each step: 0 was the quickest of 0, 1, 2 on Dynamic-Obstacles-8x8)
OPEN_KINDS = frozenset({"empty", "floor", "goal", "door-open"})
MOVABLE = frozenset({"key", "ball", "box"})


@dataclass(frozen=True)
class Cell:
    """What stands on a cell: kind (wall, lava, floor, goal, door-open, door-closed,
    door-locked, key, ball, box, obstacle), colour, and the name of the object there ("")."""

    kind: str
    color: str = ""
    name: str = ""


@dataclass(frozen=True)
class Reach:
    """The best way to a target: `steps` [moves] (penalties left out), `next` (the move to
    make now; "here" when the agent is already there), `via` (the first obstacle the path
    crosses, "" when none), `reachable` (no obstacle on the way)."""

    steps: int
    next: str
    via: str

    @property
    def reachable(self) -> bool:
        return not self.via


State = tuple[int, int, int]


class Grid:
    """A grid's cells as plain data: `cells[(x, y)]` for every non-empty cell."""

    def __init__(self, width: int, height: int, cells: dict[tuple[int, int], Cell]) -> None:
        self.width, self.height, self.cells = width, height, cells

    def at(self, x: int, y: int) -> Cell:
        if not (0 <= x < self.width and 0 <= y < self.height):
            return Cell("wall")
        return self.cells.get((x, y), Cell("empty"))


def ahead(state: State) -> tuple[int, int]:
    """The cell in front of a state."""
    dx, dy = DIRS[state[2]]
    return state[0] + dx, state[1] + dy


def _forward(grid: Grid, state: State, key_color: str, first: bool) -> tuple[int, str, str] | None:
    """(cost, first action, obstacle) of moving forward from `state` (`first`: the agent's
    own state); None: never."""
    cell = grid.at(*ahead(state))
    if cell.kind == "obstacle":   # it will have moved by then; never into it from here
        return None if first else (1 + MOVING, "forward", "")
    if cell.kind in OPEN_KINDS:
        return 1, "forward", ""
    if cell.kind == "door-closed" or (cell.kind == "door-locked" and cell.color == key_color):
        return 2, "toggle", ""
    if cell.kind == "door-locked" or cell.kind in MOVABLE:
        return PENALTY + 2, "toggle" if cell.kind == "door-locked" else "pickup", cell.name
    return None


class Search:
    """Every state's cheapest path from `start` (Dijkstra), carrying a key of `key_color`
    ("" when none)."""

    def __init__(self, grid: Grid, start: State, key_color: str = "") -> None:
        self.grid, self.start = grid, start
        self.best: dict[State, tuple[int, str, str]] = {}
        best, push, pop = self.best, heapq.heappush, heapq.heappop
        forward: dict[State, tuple[int, str, str] | None] = {}   # a cell's entry, by heading
        heap: list[tuple[int, int, State, str, str]] = [(0, 0, start, "here", "")]
        seq = 1
        while heap:
            cost, _, state, first, via = pop(heap)
            if state in best:
                continue
            best[state] = (cost, first, via)
            x, y, d = state
            if state not in forward:
                forward[state] = _forward(grid, state, key_color, state == start)
            fwd = forward[state]
            moves = ((1, (x, y, (d - 1) % 4), "left", ""), (1, (x, y, (d + 1) % 4), "right", ""))
            if fwd is not None:
                dx, dy = DIRS[d]
                moves = ((fwd[0], (x + dx, y + dy, d), fwd[1], fwd[2]), *moves)
            for step, nxt, act, obstacle in moves:
                if nxt not in best:
                    push(heap, (cost + step, seq, nxt, act if state == start else first,
                                via or obstacle))
                    seq += 1

    def to_states(self, targets: Iterable[State]) -> Reach | None:
        """The best way to any of `targets`, or None when none can be reached at all."""
        found = [(self.best[t], i) for i, t in enumerate(targets) if t in self.best]
        if not found:
            return None
        (cost, first, via), _ = min(found, key=lambda f: (f[0][0], f[1]))
        return Reach(cost % PENALTY, first, via)

    def to_stand_on(self, x: int, y: int) -> Reach | None:
        """The best way onto cell (x, y), in any heading."""
        return self.to_states((x, y, d) for d in range(4))

    def to_face(self, x: int, y: int) -> Reach | None:
        """The best way to stand next to (x, y), facing it."""
        return self.to_states((x - dx, y - dy, d) for d, (dx, dy) in enumerate(DIRS))

    def to_drop(self, fits) -> Reach | None:
        """The best way to a state with no obstacle on the way whose cell ahead `fits(x, y)`
        (a rank, lower is better, or None: not there; the move at it: "drop"): the best rank
        first, then the nearest."""
        found = []
        for i, (state, (cost, first, _)) in enumerate(self.best.items()):
            rank = fits(*ahead(state)) if cost < PENALTY else None
            if rank is not None:
                found.append((rank, cost, i, first))
        if not found:
            return None
        _, cost, _, first = min(found)
        return Reach(cost, "drop" if first == "here" else first, "")


def walkable_region(grid: Grid, start: tuple[int, int] | None,
                    blocked: tuple[int, int] | None) -> set[tuple[int, int]]:
    """The cells that can be walked to from `start` (doors count as passable, objects and
    lava not), with the cell `blocked` filled."""
    if start is None:
        return set()
    seen, todo = {start}, deque([start])
    while todo:
        x, y = todo.popleft()
        for dx, dy in DIRS:
            n = (x + dx, y + dy)
            if n in seen or n == blocked:
                continue
            kind = grid.at(*n).kind
            if kind in OPEN_KINDS or kind.startswith("door"):
                seen.add(n)
                todo.append(n)
    return seen


def cut_cells(region: set[tuple[int, int]]) -> set[tuple[int, int]]:
    """The cells of a connected `region` whose filling would cut it in two (its articulation
    points: Hopcroft and Tarjan's depth-first search, without recursion)."""
    def around(c: tuple[int, int]) -> list[tuple[int, int]]:
        return [(c[0] + dx, c[1] + dy) for dx, dy in DIRS if (c[0] + dx, c[1] + dy) in region]

    cuts: set[tuple[int, int]] = set()
    disc: dict[tuple[int, int], int] = {}
    low: dict[tuple[int, int], int] = {}
    for root in sorted(region):
        if root in disc:
            continue
        disc[root] = low[root] = len(disc)
        children = 0
        stack = [(root, None, iter(around(root)))]
        while stack:
            v, parent, todo = stack[-1]
            for w in todo:
                if w not in disc:
                    disc[w] = low[w] = len(disc)
                    children += v == root
                    stack.append((w, v, iter(around(w))))
                    break
                if w != parent:
                    low[v] = min(low[v], disc[w])
            else:
                stack.pop()
                if parent is not None:
                    low[parent] = min(low[parent], low[v])
                    if parent != root and low[v] >= disc[parent]:
                        cuts.add(parent)
        if children > 1:
            cuts.add(root)
    return cuts
