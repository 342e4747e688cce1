"""Reading a TOML file within bounds: what every scenario read goes through.

tomllib alone turns hostile input into Python exceptions: a file that is not UTF-8 raises
UnicodeDecodeError, `a = [[[[...` nested a few thousand deep raises RecursionError, and
`nan`, `inf`, a 100-digit integer or a date are values the bus cannot carry. `read_toml`
reads at most MAX_TOML_BYTES, names the line and column of a bad byte or of nesting deeper
than MAX_TOML_DEPTH, and refuses non-finite floats, integers beyond 64 bits and dates, naming
the key. Every failure is a TomlTextError whose message starts with `file:line:col` or
`file: key`.
"""

from __future__ import annotations

import datetime
import math
import re
import sys
import tomllib
from pathlib import Path
from typing import Any

from world.errors import WorldError

MAX_TOML_BYTES = 1024 * 1024
"""[bytes] of one scenario file (the largest shipped scenario has about 3,000)."""
MAX_TOML_DEPTH = 32
"""[levels] of nested arrays and inline tables (scenarios use 3)."""
INT_MIN, INT_MAX = -(2**63), 2**63 - 1
"""Integers are signed 64-bit: what msgpack carries on the bus."""


class TomlTextError(WorldError):
    """A TOML file that cannot be read as a scenario; the message names file:line:col or key."""


def read_toml(path: Path) -> dict[str, Any]:
    """The TOML document in ``path``; raises TomlTextError (see the module doc)."""
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_TOML_BYTES + 1)
    except FileNotFoundError:
        raise TomlTextError(f"{path}: file not found") from None
    except OSError as exc:
        raise TomlTextError(f"{path}: cannot read: {exc.strerror or exc}") from None
    if len(data) > MAX_TOML_BYTES:
        raise TomlTextError(f"{path}: longer than the limit of {MAX_TOML_BYTES} bytes")
    text = _decode(data, path)
    _check_depth(text, path)
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise TomlTextError(f"{path}: not valid TOML: {exc}") from None
    except ValueError:  # an integer of more digits than Python converts (4300)
        raise TomlTextError(f"{path}: an integer of more than {sys.get_int_max_str_digits()} "
                            "digits; no setting takes a number that large") from None
    except RecursionError:  # not reached: _check_depth bounds the nesting first
        raise TomlTextError(f"{path}: nested too deeply") from None
    _check_values(doc, str(path), ())
    return doc


NOT_A_VALUE = object()
"""What ``toml_value`` returns for text that spells no TOML value."""


def toml_value(text: str, where: str, key: tuple[str | int, ...]) -> Any:
    """The one TOML value ``text`` spells (`20`, `2.5`, `true`, `"x"`, `[3, 4]`,
    `{ agent = "ME" }`), or NOT_A_VALUE when it spells none (`programs/x.tlp`, `a = 1` over
    two lines); within the bounds of ``read_toml``: nesting deeper than MAX_TOML_DEPTH or a
    value no message can carry raises TomlTextError naming ``where`` and ``key``."""
    if len(text) > MAX_TOML_BYTES:
        raise TomlTextError(f"{where}: longer than the limit of {MAX_TOML_BYTES} bytes")
    _check_depth(text, Path(where))
    try:
        doc = tomllib.loads(f"v = {text}")
    except (tomllib.TOMLDecodeError, ValueError, RecursionError):
        return NOT_A_VALUE
    if set(doc) != {"v"}:
        return NOT_A_VALUE
    _check_values(doc["v"], where, key)
    return doc["v"]


def _decode(data: bytes, path: Path) -> str:
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        start = data.rfind(b"\n", 0, exc.start) + 1
        col = len(data[start:exc.start].decode("utf-8", errors="replace")) + 1
        raise TomlTextError(f"{path}:{line}:{col}: not UTF-8: byte "
                            f"0x{data[exc.start]:02x} ({exc.reason}); save the file as UTF-8")\
            from None


# Strings (multi-line first), comments and the brackets that nest. Table headers ([a],
# [[a]]) count as brackets too, at most two deep.
_TOKEN = re.compile(r'"""(?:[^\\]|\\.)*?"""|\'\'\'.*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\''
                    r"|#[^\n]*|[\[\]{}]", re.DOTALL)


def _check_depth(text: str, path: Path) -> None:
    """Refuse nesting deeper than MAX_TOML_DEPTH before tomllib recurses into it."""
    depth = 0
    for match in _TOKEN.finditer(text):
        token = match.group()
        if token in ("[", "{"):
            depth += 1
            if depth > MAX_TOML_DEPTH:
                line = text.count("\n", 0, match.start()) + 1
                col = match.start() - text.rfind("\n", 0, match.start())
                raise TomlTextError(f"{path}:{line}:{col}: arrays or inline tables nested "
                                    f"deeper than {MAX_TOML_DEPTH} levels")
        elif token in ("]", "}"):
            depth = max(0, depth - 1)


def _check_values(value: Any, path: str, where: tuple[str | int, ...]) -> None:
    """Refuse values no message can carry: NaN and infinities, integers beyond 64 bits,
    dates and times (TOML has them; JSON and msgpack as teleo uses them do not)."""
    if isinstance(value, dict):
        for k, v in value.items():
            _check_values(v, path, (*where, str(k)))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            _check_values(v, path, (*where, i))
    elif isinstance(value, float) and not math.isfinite(value):
        raise TomlTextError(f"{path}: {_key(where)}: expected a finite number, got {value}")
    elif isinstance(value, int) and not isinstance(value, bool) and \
            not INT_MIN <= value <= INT_MAX:
        raise TomlTextError(f"{path}: {_key(where)}: integer out of range (signed 64-bit), "
                            f"got {str(value)[:30]}...")
    elif isinstance(value, datetime.date | datetime.time):
        raise TomlTextError(f"{path}: {_key(where)}: expected a string, number or boolean, "
                            f"got the date/time {value.isoformat()}; quote it")


def _key(where: tuple[str | int, ...]) -> str:
    """A value's place as the scenario messages write it: [run].deadline,
    [[events]] #2.speed, [world].cars[0].along."""
    if len(where) >= 2 and isinstance(where[1], int):
        head, rest = f"[[{where[0]}]] #{where[1] + 1}", where[2:]
    elif len(where) >= 2:
        head, rest = f"[{where[0]}]", where[1:]
    else:
        return str(where[0]) if where else "top level"
    return head + "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in rest)
