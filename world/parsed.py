"""A parse of plain data remembered by the data's exact value: every snapshot a world publishes
carries the same config, and reading it again for each snapshot (each agent, each cycle) cost
the office's perception half its time."""

from __future__ import annotations

import marshal
from collections.abc import Callable
from functools import lru_cache
from typing import Any, TypeVar

T = TypeVar("T")


def parsed_by_value(parse: Callable[[Any], T], size: int = 4) -> Callable[[Any], T]:
    """``parse`` remembering its last ``size`` results by the argument's exact value (its
    marshal bytes, which tell 3 from 3.0 and 0.0 from -0.0); a value marshal cannot write is
    parsed every time. ``parse`` must be pure and its results immutable; what it raises is not
    remembered."""
    @lru_cache(maxsize=size)
    def by_bytes(data: bytes) -> T:
        return parse(marshal.loads(data))

    def remembered(value: Any) -> T:
        try:
            data = marshal.dumps(value)
        except ValueError:  # not plain data: nothing to key it by
            return parse(value)
        return by_bytes(data)

    remembered.__doc__ = parse.__doc__
    return remembered
