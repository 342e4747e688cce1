"""A STRIPS simulator of the four Blocks World operators (pick-up, put-down, stack, unstack, as
in bench/planning/bw_pddl.py's DOMAIN), written apart from teleo's world and engine so that it can
check their runs: a plan replayed from the start state, each action's preconditions checked, the
goal checked on the result. Also a breadth-first search for a shortest plan on small problems (the
check of A* with LM-cut in the tests).

teleo's actions map onto the operators: (*pickup B T) is pick-up B, (*putdown B T) put-down B,
(*stack B C) stack B C, (*unstack B C) unstack B C; (*wait) does nothing.

    >>> s = initial((("B1", "B2"),))
    >>> s = apply(s, ("unstack", "B2", "B1"))
    >>> try:
    ...     apply(s, ("stack", "B1", "B2"))
    ... except Illegal as exc:
    ...     print(exc)
    (stack B1 B2): precondition (holding B1) is false
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable

from bench.planning.bw_problems import Towers

State = frozenset[tuple[str, ...]]
"""STRIPS facts: ("on", X, Y), ("ontable", X), ("clear", X), ("holding", X), ("handempty",)."""

OPERATORS = {"pick-up": 1, "put-down": 1, "stack": 2, "unstack": 2}
TELEO = {"*pickup": "pick-up", "*putdown": "put-down", "*stack": "stack",
         "*unstack": "unstack"}


class Illegal(Exception):
    """An action whose preconditions do not hold, or that is not one of the operators."""


def initial(towers: Towers) -> State:
    """The facts of a state given as towers (bottom first), the hand empty."""
    facts: set[tuple[str, ...]] = {("handempty",)}
    for t in towers:
        if t:
            facts |= {("ontable", t[0]), ("clear", t[-1])}
            facts |= {("on", t[i + 1], t[i]) for i in range(len(t) - 1)}
    return frozenset(facts)


def _effects(step: tuple[str, ...]) -> tuple[list, list, list]:
    """(preconditions, deletes, adds) of one ground operator."""
    name, *args = step
    if name not in OPERATORS or len(args) != OPERATORS[name]:
        raise Illegal(f"({' '.join(step)}): not an operator; expected one of "
                      f"{', '.join(f'{o}/{k}' for o, k in OPERATORS.items())}")
    x = args[0]
    if name == "pick-up":
        pre = [("clear", x), ("ontable", x), ("handempty",)]
        return pre, pre, [("holding", x)]
    if name == "put-down":
        return [("holding", x)], [("holding", x)], [("clear", x), ("handempty",),
                                                     ("ontable", x)]
    y = args[1]
    if name == "stack":
        return ([("holding", x), ("clear", y)], [("holding", x), ("clear", y)],
                [("clear", x), ("handempty",), ("on", x, y)])
    pre = [("on", x, y), ("clear", x), ("handempty",)]
    return pre, pre, [("holding", x), ("clear", y)]


def apply(state: State, step: tuple[str, ...]) -> State:
    """The state after ``step`` (an operator and its blocks); raises Illegal naming the false
    precondition."""
    pre, dels, adds = _effects(step)
    for fact in pre:
        if fact not in state:
            raise Illegal(f"({' '.join(step)}): precondition ({' '.join(fact)}) is false")
    return (state - frozenset(dels)) | frozenset(adds)


def from_teleo(action: list | tuple, table: str = "T") -> tuple[str, ...] | None:
    """A teleo action as an operator step; None for (*wait). Raises Illegal for another
    action, or a table argument that is not the table."""
    name, *args = action
    if name == "*wait" and not args:
        return None
    if name not in TELEO or len(args) != 2:
        raise Illegal(f"({' '.join(map(str, action))}): not a Blocks World action "
                      f"(*pickup, *putdown, *stack, *unstack with two arguments)")
    op = TELEO[name]
    if OPERATORS[op] == 1:
        if args[1] != table:
            raise Illegal(f"({' '.join(map(str, action))}): {args[1]} is not the table {table}")
        return (op, args[0])
    return (op, *args)


def replay(towers: Towers, steps: Iterable[tuple[str, ...]]) -> State:
    """The state after ``steps`` from the start ``towers``; raises Illegal at the first step
    whose preconditions do not hold, saying which step (1-based)."""
    state = initial(towers)
    for k, step in enumerate(steps, 1):
        try:
            state = apply(state, step)
        except Illegal as exc:
            raise Illegal(f"step {k}: {exc}") from None
    return state


def holds(state: State, goal: Iterable[tuple[str, str]]) -> list[tuple[str, str]]:
    """The goal's `on` pairs that do not hold in ``state`` (empty: the goal holds)."""
    return [(a, b) for a, b in goal if ("on", a, b) not in state]


def successors(state: State, blocks: list[str]) -> Iterable[tuple[tuple[str, ...], State]]:
    """Every (step, next state) the operators allow from ``state``."""
    for x in blocks:
        candidates = [("pick-up", x), ("put-down", x)]
        candidates += [(op, x, y) for y in blocks if y != x for op in ("stack", "unstack")]
        for step in candidates:
            try:
                yield step, apply(state, step)
            except Illegal:
                continue


def to_teleo(step: tuple[str, ...], table: str = "T") -> list[str]:
    """An operator step as the teleo action that does it (the inverse of from_teleo)."""
    name = {v: k for k, v in TELEO.items()}[step[0]]
    return [name, step[1], table] if OPERATORS[step[0]] == 1 else [name, *step[1:]]


def shortest_plan(towers: Towers, goal: list[tuple[str, str]]) -> list[tuple[str, ...]]:
    """A shortest plan, by breadth-first search (small problems only)."""
    start = initial(towers)
    blocks = sorted({b for t in towers for b in t})
    parent: dict[State, tuple[State, tuple[str, ...]] | None] = {start: None}
    todo = deque([start])
    while todo:
        state = todo.popleft()
        if not holds(state, goal):
            steps = []
            while parent[state] is not None:
                state, step = parent[state]
                steps.append(step)
            return steps[::-1]
        for step, nxt in successors(state, blocks):
            if nxt not in parent:
                parent[nxt] = (state, step)
                todo.append(nxt)
    raise Illegal(f"shortest_plan: no plan reaches {goal} from {towers}")
