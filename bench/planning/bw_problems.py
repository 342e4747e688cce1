"""Random Blocks World problems for bench/planning/planning.py: states drawn uniformly at random,
exactly, as Slaney and Thiebaux generate them ("Blocks World revisited", AIJ 125, 2001, section 4
and their program bwstates), and the goal literal orders the benchmark compares.

A state of n blocks is a set of towers (each a list of blocks, bottom first). Counting them:
build a state by taking the floating towers (towers whose base is not placed yet; at first
every block is one) one at a time and either putting the tower on the table (it is grounded)
or putting its base on the top of one of the other towers, grounded or floating. With m
floating towers and k grounded ones, the number of states that can still come out is

    g(0, k) = 1,    g(m, k) = g(m - 1, k + 1) + (m - 1 + k) g(m - 1, k)

(g(n, 0) = 1, 1, 3, 13, 73, 501, ... is the number of states: the sum of the Lah numbers
L(n, j) over j, OEIS A000262). Taking the table with probability g(m - 1, k + 1) / g(m, k)
and otherwise each of the m - 1 + k other towers alike gives every state the same chance:
each state comes from exactly one sequence of choices.

    >>> [states(n) for n in range(6)]
    [1, 1, 3, 13, 73, 501]
    >>> import random
    >>> random_state(4, random.Random(1))
    (('B4',), ('B3',), ('B1', 'B2'))
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from functools import cache

Towers = tuple[tuple[str, ...], ...]
"""A state: towers of block names, each bottom first (tower k stands in table column k)."""


@cache
def g(m: int, k: int) -> int:
    """States that can still be built from m floating towers and k grounded ones."""
    if m == 0:
        return 1
    return g(m - 1, k + 1) + (m - 1 + k) * g(m - 1, k)


def states(n: int) -> int:
    """The number of Blocks World states of n labelled blocks."""
    return g(n, 0)


def block_names(n: int) -> list[str]:
    """B1 .. Bn: symbols teleo's programs and PDDL both read."""
    return [f"B{i + 1}" for i in range(n)]


def random_state(n: int, rng: random.Random) -> Towers:
    """One of the states(n) states of blocks B1 .. Bn, each with probability 1 / states(n)."""
    floating = [[name] for name in block_names(n)]
    grounded: list[list[str]] = []
    while floating:
        tower = floating.pop()
        m, k = len(floating) + 1, len(grounded)
        r = rng.randrange(g(m, k))
        if r < g(m - 1, k + 1):
            grounded.append(tower)
            continue
        others = floating + grounded                   # m - 1 + k towers, one chosen alike
        others[(r - g(m - 1, k + 1)) // g(m - 1, k)].extend(tower)
    return tuple(tuple(t) for t in grounded)


def on_facts(towers: Towers) -> frozenset[tuple[str, str]]:
    """Every (upper, lower) pair of blocks in the state: its `on` facts."""
    return frozenset((t[i + 1], t[i]) for t in towers for i in range(len(t) - 1))


def canonical(towers: Towers) -> Towers:
    """The state with its towers in a fixed order (by base), for comparing states."""
    return tuple(sorted((t for t in towers if t), key=lambda t: t[0]))


@dataclass(frozen=True)
class Problem:
    """A benchmark problem: n blocks, the seed it was drawn from, its start and goal states.
    The goal is the goal state's `on` facts only, as the IPC-2000 Blocks World problems state
    theirs (probBLOCKS-4-0: (:goal (AND (ON D C) (ON C B) (ON B A)))): a tower's base is
    left free to stand anywhere."""

    n: int
    seed: int
    start: Towers
    goal_state: Towers

    @property
    def name(self) -> str:
        return f"bw-{self.n}-{self.seed}"

    def goal(self, order: str = "listed") -> list[tuple[str, str]]:
        """The goal's `on` pairs (upper, lower): ``listed`` as the IPC problems list them,
        each tower top-down; ``bottom-up``, each tower from its base."""
        out = []
        for t in self.goal_state:
            pairs = [(t[i + 1], t[i]) for i in range(len(t) - 1)]
            out += pairs if order == "bottom-up" else pairs[::-1]
        if order not in ("listed", "bottom-up"):
            raise ValueError(f"Problem.goal: order {order!r}: expected listed or bottom-up")
        return out


def problem(n: int, seed: int) -> Problem:
    """Problem ``seed`` of n blocks: start and goal drawn independently and uniformly."""
    rng = random.Random(f"blocks-world-{n}-{seed}")
    return Problem(n, seed, random_state(n, rng), random_state(n, rng))
