"""What a process derives from each object it is handed, kept for the same objects next cycle.

The bus hands a row seen last cycle over as the very same list (bus/rows.py) and the engine
keeps a belief that still holds as the very same Belief, so what was made from them last cycle
(a Belief from a list, a list from a Belief) can be reused. By identity, never by equality:
`(v 3)` and `(v 3.0)` are equal, yet print differently.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any


class PerObject:
    """``make(x)`` for each ``x``, remembered from one call of ``of`` to the next for the
    objects given again (each kept alive meanwhile, so its id cannot be reused)."""

    def __init__(self, make: Callable[[Any], Any]) -> None:
        self.make = make
        self.last: dict[int, tuple[Any, Any]] = {}  # id(x) -> (x, make(x))

    def of(self, items: Iterable) -> list:
        last, now, out = self.last, {}, []
        for x in items:
            hit = last.get(id(x))
            value = hit[1] if hit is not None and hit[0] is x else self.make(x)
            now[id(x)] = (x, value)
            out.append(value)
        self.last = now
        return out
