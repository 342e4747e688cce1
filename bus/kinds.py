"""How a bus message kind is declared, once: a class decorated with `@message`, each field
with its spec (bus/schema) in the field's metadata, and what the codec, the recorder and the
key layout need to know as class attributes. Every table about message kinds (the codec's
checks, the packed fields, the kinds allowed per key, the recorder's derived fields and JSON
Schemas) is derived from the declared classes (docs/bus.md, "Declaring a message kind"):

    @message
    class Heartbeat(MessageKind):
        KIND = "Heartbeat"
        KEYS = ("agent/*/heartbeat",)           # key tails below teleo/<run>/
        env: Envelope
        agent: str = spec(NAME)
        beats: int = spec(Int(0), default=0)
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import MISSING, Field, dataclass, field, fields
from typing import Any, ClassVar, NamedTuple

from bus.errors import BusError
from bus.schema import Spec


class DeclarationError(BusError):
    """A message class declared against the rules above (names the class and the rule)."""


class Derived(NamedTuple):
    """A field a record adds to a kind's wire map for viewers (bus/record.py), dropped again
    on the way back: ``make(wire_map) -> value`` and its JSON Schema."""

    make: Callable[[dict], Any]
    schema: dict


class MessageKind:
    """The class attributes of a message kind (override them in the declaration).

    KIND: the name written on the wire. KEYS: the key tails below ``teleo/<run>/`` it may
    travel on, ``*`` standing for one chunk (``agent/*/percepts``); none: any key.
    PACKED: the field whose rows travel packed (bus/rows.py), or "". DERIVED: the fields a
    record adds (name -> Derived).
    """

    KIND: ClassVar[str] = ""
    KEYS: ClassVar[tuple[str, ...]] = ()
    PACKED: ClassVar[str] = ""
    DERIVED: ClassVar[Mapping[str, Derived]] = {}


MESSAGE_TYPES: dict[str, type] = {}
"""Every declared kind: its KIND -> its class (filled by `message`, in declaration order)."""


def spec(check: Spec, default: Any = MISSING,
         default_factory: Callable[[], Any] | Any = MISSING) -> Any:
    """A message field checked with ``check`` by every reader before the message is made."""
    return field(default=default, default_factory=default_factory,
                 metadata={"spec": check})


def message(cls: type) -> type:
    """Declare ``cls`` (a MessageKind subclass) a bus message kind: made a frozen dataclass
    and registered; raises DeclarationError naming the class and what is wrong."""
    made = dataclass(frozen=True)(cls)
    _check_declaration(made)
    MESSAGE_TYPES[made.KIND] = made
    return made


def field_specs(cls: type) -> tuple[tuple[str, Spec, Any], ...]:
    """(name, spec, default) of every field of a declared kind but env; default is MISSING,
    a value, or a `Fresh` maker for a field declared with a default_factory."""
    return tuple((f.name, f.metadata["spec"], _default(f)) for f in fields(cls)
                 if f.name != "env")


class Fresh:
    """The default of a field declared with a default_factory (made anew per message)."""

    def __init__(self, make: Callable[[], Any]) -> None:
        self.make = make


def _default(f: Field) -> Any:
    return Fresh(f.default_factory) if f.default_factory is not MISSING else f.default


def _check_declaration(cls: type) -> None:
    name = cls.__name__
    if not issubclass(cls, MessageKind) or not isinstance(cls.KIND, str) or not cls.KIND:
        raise DeclarationError(f"message {name}: expected a MessageKind subclass with a KIND "
                               f"string, got KIND={getattr(cls, 'KIND', None)!r}")
    known = MESSAGE_TYPES.get(cls.KIND)
    if known is not None and known.__qualname__ != cls.__qualname__:
        raise DeclarationError(f"message {name}: KIND {cls.KIND!r} is already "
                               f"{known.__module__}.{known.__qualname__}'s")
    names = [f.name for f in fields(cls)]
    if not names or names[0] != "env":
        raise DeclarationError(f"message {name}: expected env as the first field, got {names}")
    for f in fields(cls)[1:]:
        if not isinstance(f.metadata.get("spec"), Spec):
            raise DeclarationError(f"message {name}.{f.name}: expected a field declared with "
                                   f"spec(...) (bus/kinds.py), got no spec")
    if cls.PACKED and cls.PACKED not in names:
        raise DeclarationError(f"message {name}: PACKED names {cls.PACKED!r}, not one of its "
                               f"fields {names}")
    clash = set(cls.DERIVED) & set(names)
    if clash:
        raise DeclarationError(f"message {name}: derived {sorted(clash)} clash with fields")
