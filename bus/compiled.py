"""A message kind's field checks compiled once into one function (bus/codec.py calls it for
every message whose wire map holds every field, as every writer sends them).

The function reads the fields in their declared order; a field whose spec is a leaf (a
string, an integer, a flag, a name among a few, a number, a map left to its reader) is tested
inline by a condition that is sufficient for its spec to accept the value unchanged, and its
spec's own check runs only when that condition fails (to refuse it, with the spec's words, or
to convert it); any other spec's check is called directly. A FieldError becomes the same
CodecError, naming the key, the kind and the field's path, that the field-by-field walk
(`bus.codec.walk_fields`) gives: the two accept and refuse exactly the same payloads
(tests/bus/test_compiled_checks.py).
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any

from bus.errors import CodecError
from bus.fields import All
from bus.kinds import field_specs
from bus.schema import Bool, FieldError, Int, Num, OneOf, Plain, Record, Spec, Str

CheckFn = Callable[[str, dict, Callable[[str, Any], tuple]], "dict[str, Any] | None"]


class Compiled:
    """A declared kind's class, fields ((name, spec, default) but env), packed field and
    compiled check ``check(key, body, unpack) -> values``, or None when a field is absent
    (the walk fills in defaults or names the missing one)."""

    def __init__(self, cls: type) -> None:
        self.cls = cls
        self.fields = field_specs(cls)
        self.names = tuple(name for name, _, _ in self.fields)
        self.packed: str = cls.PACKED
        self.check: CheckFn = _build(cls.KIND, self.fields, self.packed)


def compile_kind(cls: type) -> Compiled:
    """The compiled checks of a declared message kind."""
    return Compiled(cls)


def _build(kind: str, specs: tuple[tuple[str, Spec, Any], ...], packed: str) -> CheckFn:
    scope: dict[str, Any] = {"FieldError": FieldError, "CodecError": CodecError,
                             "ALL": frozenset(name for name, _, _ in specs)}
    lines = ["def check(key, body, unpack):",
             "    if not body.keys() >= ALL:",
             "        return None",
             "    name = ''",
             "    try:"]
    for i, (name, spec, _) in enumerate(specs):
        v = f"v{i}"
        lines += [f"        name = {name!r}", f"        {v} = body[{name!r}]"]
        if name == packed:
            lines.append(f"        {v} = unpack(key, {v})")
            continue
        scope[f"c{i}"] = spec.check
        condition = _condition(spec, v, f"k{i}", scope)
        lines.append(f"        if not ({condition}): {v} = c{i}({v})" if condition else
                     f"        {v} = c{i}({v})")
    lines += ["    except FieldError as exc:",
              f"        raise CodecError(key, f'{kind}.{{exc.within(name)}}') from None",
              "    except TypeError as exc:",
              f"        raise CodecError(key, f'{kind}.{{name}}: {{exc}}') from None",
              "    return {" + ", ".join(f"{name!r}: v{i}" for i, (name, _, _) in
                                       enumerate(specs)) + "}"]
    exec(compile("\n".join(lines), f"<checks of {kind}>", "exec"), scope)  # noqa: S102
    return scope["check"]


def _condition(spec: Spec, v: str, const: str, scope: dict[str, Any]) -> str:
    """Python source of a condition on ``v`` under which ``spec.check(v)`` returns ``v``
    itself ("" where there is none cheaper than the check); constants go in ``scope``."""
    kind = type(spec)
    if kind is Str and spec.pattern is None:
        longest = "" if spec.max_len >= sys.maxsize else f" and len({v}) <= {spec.max_len}"
        shortest = f" and len({v}) >= {spec.min_len}" if spec.min_len else ""
        return f"type({v}) is str{longest}{shortest}"
    if kind is Int:
        scope[const] = (spec._lo, spec._hi)
        return f"type({v}) is int and {const}[0] <= {v} <= {const}[1]"
    if kind is Bool:
        return f"type({v}) is bool"
    if kind is Num:
        scope[const] = (spec._lo, spec._hi)
        types = "type({v}) is float" if spec.as_float else \
            "(type({v}) is float or type({v}) is int)"
        return types.format(v=v) + f" and {const}[0] <= {v} <= {const}[1]"
    if kind is OneOf:
        scope[const] = frozenset(c for c in spec.choices if type(c) is str)
        return f"type({v}) is str and {v} in {const}"
    if kind is Record and not spec.fields and spec.open:
        return f"type({v}) is dict"
    if isinstance(spec, (Plain, Record, All)) and _keeps_empty_map(spec):
        return f"type({v}) is dict and not {v}"   # the usual empty memory, program, swap
    return ""


def _keeps_empty_map(spec: Spec) -> bool:
    """Whether ``spec`` accepts the empty map as it is (then every empty map passes)."""
    empty: dict = {}
    try:
        return spec.check(empty) is empty
    except FieldError:
        return False
