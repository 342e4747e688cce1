"""A value shown in a message, cut to a few dozen characters however large or deep it is
(``repr`` of a 1,000-level list raises RecursionError, and a megabyte string would make a
refusal a megabyte long)."""

from __future__ import annotations

import reprlib
from typing import Any

_REPR = reprlib.Repr()
_REPR.maxlevel, _REPR.maxstring, _REPR.maxother, _REPR.maxlong = 3, 44, 44, 40
_REPR.maxlist = _REPR.maxtuple = _REPR.maxdict = _REPR.maxset = 5


def brief(value: Any, width: int = 60) -> str:
    """``repr(value)`` in at most about ``width`` characters, saying how long a cut string is."""
    if type(value) is str and len(value) > width:
        return f"{value[:width]!r}... ({len(value)} characters)"
    try:
        text = _REPR.repr(value)
    except Exception:  # noqa: BLE001 - a foreign object's own __repr__ failing: say what it is
        text = f"<{type(value).__name__}>"
    return text if len(text) <= width + 20 else f"{text[:width + 20]}..."
