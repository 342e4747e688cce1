"""Declarative checks of the messages teleo's processes read: a small schema per
message kind, kept in the package that owns the message (bus/codec.py for the bus messages'
fields, each world's events and snapshot records, the goal-entry process's view of an
intention), written with the specs here. A value that does not fit is refused with a
FieldError naming the field and showing the value, shortened:

    owner: expected a name (letters, digits, '_' or '-', a letter first, at most 32), got []
    unknown field 'colour'; known: kind, ahead_of, dist, lateral, speed, heading, id

Pure standard library: the bus, the worlds and the processes all use it (docs/architecture.md,
"Dependency rule").
"""

from bus.schema.brief import brief
from bus.schema.containers import AnyOf, ListOf, MapOf, Record, Tagged, TupleOf
from bus.schema.plain import Plain
from bus.schema.specs import INT64, Atom, Bool, FieldError, Int, Num, OneOf, Spec, Str

__all__ = ["INT64", "AnyOf", "Atom", "Bool", "FieldError", "Int", "ListOf", "MapOf", "Num", "OneOf",
           "Plain", "Record", "Spec", "Str", "Tagged", "TupleOf", "brief"]
