"""The [world] table of a scenario: defaults, keys, and errors that name the key."""

from __future__ import annotations

import tomllib

import pytest

from world.driving.city import build_city
from world.driving.config import WorldConfig, load_world_config
from world.errors import ConfigError

SCENARIO = """
[world]
grid = [5, 3]
block_length = 90.0
speed_limit = 12
pedestrians = 7
traffic = 2
perception_range = 80
dt = 0.05
packages = [{ id = "PACKET1", address = 5, street = "B", owner = "ME" }]
cars = [{ agent = "ME", street = "SECOND", from = "A", toward = "B", along = 15 }]
"""


def test_absent_keys_give_the_default_city() -> None:
    config = load_world_config({})
    assert config == WorldConfig()
    assert (config.dt, config.speed_limit, config.block_length) == (0.1, 15.0, 100.0)
    city = build_city(config)
    assert len(city.intersections) == 16 and len(city.segments) == 24
    assert len(city.buildings) == 96


def test_a_toml_world_table_is_read_and_round_trips() -> None:
    config = load_world_config(tomllib.loads(SCENARIO)["world"])
    assert config.ns_streets == ("A", "B", "C", "D", "E")
    assert config.ew_streets == ("FIRST", "SECOND", "THIRD")
    assert (config.block_length, config.speed_limit, config.dt) == (90.0, 12.0, 0.05)
    assert config.packages[0].street == "B" and config.cars[0].along == 15.0
    assert load_world_config(config.to_dict()) == config
    city = build_city(config)
    assert city.size == (360.0, 180.0)
    assert city.building("B", 5).street == "B"


@pytest.mark.parametrize(("table", "message"), [
    ({"speed_limit": -3}, "speed_limit"),
    ({"dt": "fast"}, "dt"),
    ({"grid": [1, 4]}, "grid"),
    ({"pedestrians": 2.5}, "pedestrians"),
    ({"colour": "red"}, "unknown keys"),
    ({"packages": [{"id": "P", "address": 99, "street": "A", "owner": "ME"}]}, "address 99"),
    ({"packages": [{"id": "P", "address": 1, "street": "Z", "owner": "ME"}]}, "'Z'"),
    ({"cars": [{"agent": "ME", "street": "A", "from": "B", "toward": "FIRST"}]}, "cross"),
])
def test_bad_tables_name_the_key(table: dict, message: str) -> None:
    with pytest.raises(ConfigError, match=message):
        build_city(load_world_config(table))
