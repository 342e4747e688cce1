"""A config read from each snapshot is parsed once per distinct value (world/parsed.py)."""

from __future__ import annotations

import pytest

from world.parsed import parsed_by_value


def test_the_same_value_is_parsed_once_and_another_type_is_another_value():
    calls = []

    def parse(d):
        calls.append(d)
        if not isinstance(d["n"], int):
            raise ValueError(f"n: expected an integer, got {d['n']!r}")
        return ("parsed", d["n"])

    read = parsed_by_value(parse)
    first = read({"n": 3, "rooms": [1, 2]})
    assert read({"n": 3, "rooms": [1, 2]}) is first  # a new dict of the same value
    assert len(calls) == 1
    with pytest.raises(ValueError, match="expected an integer"):
        read({"n": 3.0, "rooms": [1, 2]})  # equal to == but not the same value
    with pytest.raises(ValueError):  # an error is not remembered: parsed again
        read({"n": 3.0, "rooms": [1, 2]})
    assert len(calls) == 3


def test_a_value_marshal_cannot_write_is_parsed_every_time():
    read = parsed_by_value(lambda d: object())
    value = {"f": object()}
    assert read(value) is not read(value)
