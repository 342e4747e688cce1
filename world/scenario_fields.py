"""Reading the fields of a scenario's tables while keeping every error: each
reader records what is wrong with its field, naming the field and its value
(`[run].cycles: expected >= 0, got -5`), and returns the field's default, so that the rest of
the file is read and checked too and `teleo check` reports every error at once."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

REQUIRED = object()
"""The default of a field that must be given."""


class Errors:
    """The errors found in one scenario file, each a line `FILE: where: what`."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.lines: list[str] = []

    def add(self, message: str) -> None:
        self.lines.append(f"{self.path}: {message}")

    def __len__(self) -> int:
        return len(self.lines)


def only(table: dict[str, Any], allowed: set[str], where: str, errors: Errors) -> None:
    """Record the fields of ``table`` not in ``allowed``."""
    unknown = sorted(set(table) - allowed)
    if unknown:
        errors.add(f"{where}: unknown field(s) {unknown}; expected {sorted(allowed)}")


def is_table(value: Any, where: str, errors: Errors) -> bool:
    """Whether ``value`` is a table; records the error when not."""
    if isinstance(value, dict):
        return True
    errors.add(f"{where}: expected a table, got {shown(value)}")
    return False


def field(table: dict[str, Any], key: str, kind: type | tuple, default: Any, where: str,
          errors: Errors, check: tuple[Callable[[Any], bool], str] | None = None) -> Any:
    """``table[key]`` if it is of ``kind`` (a bool is never a number) and, with ``check``
    (test, "what is expected"), passes the test; else records the error and returns
    ``default`` (None for a REQUIRED field)."""
    if key not in table and default is REQUIRED:
        errors.add(f"{where}.{key}: required, expected {_kind_name(kind)}")
        return None
    value = table.get(key, default)
    if isinstance(value, bool) and kind is not bool or not isinstance(value, kind):
        expected = "true or false" if kind is bool else _kind_name(kind)
        errors.add(f"{where}.{key}: expected {expected}, got {shown(value)}")
        return None if default is REQUIRED else default
    if check is not None and not check[0](value):
        errors.add(f"{where}.{key}: expected {check[1]}, got {shown(value)}")
        return None if default is REQUIRED else default
    return value


def shown(value: Any, most: int = 60) -> str:
    """``value`` as a message shows it: its repr, cut to ``most`` characters with "..."."""
    text = repr(value)
    return text if len(text) <= most else text[:most - 3] + "..."


def _kind_name(kind: type | tuple) -> str:
    kinds = kind if isinstance(kind, tuple) else (kind,)
    return " or ".join(k.__name__ for k in kinds)


def at_least(low: int | float, strict: bool = False, unit: str = ""
             ) -> tuple[Callable[[Any], bool], str]:
    """A ``check`` for ``field``: >= low (> low when strict), "[unit]" in the message."""
    text = f"{'>' if strict else '>='} {low}" + (f" [{unit}]" if unit else "")
    return ((lambda v: v > low) if strict else (lambda v: v >= low)), text
