"""Every field of every world event is checked before use (issue 24, items 1 and 2; fault
drill N3): a value of the wrong type (a list or a map where a name goes), out of range, a
missing field or one the kind does not have fails the event with a reason naming the field;
the world never raises, and what it records stays plain data it can send and write."""

from __future__ import annotations

import importlib.util
import json
import math
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bus.codec import encode
from bus.messages import Envelope, EventReply
from world.domain import get_domain
from world.run_scenario import load_scenario

ROOT = Path(__file__).resolve().parents[2]
sys.path.append(str(ROOT / "bench" / "faults"))
from fuzz_events import EVENT_BASES  # noqa: E402

SCENARIOS = {"driving": "driving_demo.toml", "blocks": "blocks_mishaps.toml",
             "office": "office_errand.toml"}


def world(domain: str):
    sc = load_scenario(ROOT / "scenarios" / SCENARIOS[domain])
    return get_domain(sc.domain).create(sc.world_table, sc.run.seed, sc.agent_ids), \
        sc.agent_ids[0]


def sendable(outcome: dict) -> None:
    """What the world does with an outcome: answer a query with it, write it to the trace."""
    encode(EventReply(Envelope(1, "r", 0, "world", 0), outcome["status"] == "done",
                      outcome["reason"], outcome))
    json.dumps(outcome, allow_nan=False)


@pytest.mark.parametrize("owner", [[], [[]], {"k1": []}, [True, 24], ["S143", {}, 18]])
def test_a_package_whose_owner_is_a_list_or_a_map_is_refused_naming_the_owner(owner):
    """Drill N3: these owners raised TypeError (unhashable) in injection.py and killed the
    world, six times in 355 events."""
    sim, _ = world("driving")
    out = sim.inject({"kind": "package", "id": "P10", "address": 3, "street": "THIRD",
                      "owner": owner})
    assert out["status"] == "failed", out
    assert out["reason"].startswith("inject: owner: expected an agent's name, got "), out
    sendable(out)


def _cases() -> list[tuple[str, dict]]:
    out = []
    for domain in SCENARIOS:       # teleo's own worlds: the fuzzer's event bases are theirs
        sim, agent = world(domain)
        out += [(domain, e) for e in EVENT_BASES[domain](sim, agent)]
    return out


CASES = _cases()


@pytest.mark.parametrize("domain, event", CASES, ids=[f"{d}-{e['kind']}-{i}"
                                                      for i, (d, e) in enumerate(CASES)])
def test_an_unknown_field_is_refused_by_name_in_every_kind_of_every_world(domain, event):
    """Trial #10: `teleo event '{"kind": "pedestrian", ..., "colour": "red"}'` was applied,
    the key ignored; a scenario file refuses an unknown key, and so does every world."""
    sim, _ = world(domain)
    out = sim.inject({**event, "colour": "red"})
    assert out["status"] == "failed" and "unknown field 'colour'; known: kind" in out["reason"]
    assert get_domain(domain).check_event({**event, "colour": "red"}).startswith(
        "unknown field 'colour'")
    assert get_domain(domain).check_event(event) == ""   # the event itself is well formed


junk = st.recursive(
    st.one_of(st.none(), st.booleans(), st.integers(-(2**70), 2**70), st.floats(),
              st.text(max_size=8), st.binary(max_size=4)),
    lambda inner: st.one_of(st.lists(inner, max_size=3),
                            st.dictionaries(st.text(max_size=6), inner, max_size=3)),
    max_leaves=8)


@pytest.mark.parametrize("domain", tuple(SCENARIOS))
def test_any_value_in_any_field_is_applied_or_refused_naming_a_field(domain):
    sim, agent = world(domain)
    bases = EVENT_BASES[domain](sim, agent)

    @settings(max_examples=150, deadline=None, suppress_health_check=list(HealthCheck))
    @given(st.sampled_from(bases), st.data())
    def prop(base, data):
        name = data.draw(st.sampled_from([*base, "extra"]))
        event = {**base, name: data.draw(junk)}
        out = sim.inject(event)   # never raises
        sendable(out)
        if out["status"] == "failed":
            assert any(f in out["reason"] for f in (*event, "unknown kind")), out
        sim.step()

    prop()


def test_a_refused_event_that_is_not_plain_data_is_recorded_as_its_text():
    sim, _ = world("blocks")
    for event in ({"kind": "slip", "agent": b"\x00"}, {"kind": "remove", "block": math.nan},
                  {"kind": "knock", "block": [[[[[[[[[["x"]]]]]]]]]]}):
        out = sim.inject(event)
        assert out["status"] == "failed" and isinstance(out["event"], str), out
        sendable(out)


def load_fuzz():
    spec = importlib.util.spec_from_file_location("fuzz_drill",
                                                  ROOT / "bench" / "faults" / "fuzz.py")
    module = sys.modules["fuzz_drill"] = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("domain", tuple(SCENARIOS))
def test_a_world_stays_alive_through_100000_random_events(domain, tmp_path):
    """Drill d4e at full size, in-process, on a real pymunk world (bench/faults/fuzz.py's
    world-events reader: half the events come through the codec, the world steps every 50
    and its state and trace line are made); about 10 s per world on the 2-core machine."""
    fuzz = load_fuzz()
    from fuzz_bus import Pipeline, world_events_reader

    pipe = Pipeline(domain, tmp_path)
    reader = fuzz.bus_reader(lambda: world_events_reader(pipe))()
    tally = fuzz.fuzz(f"world-events-{domain}", reader, 100_000, seed=24, limit_s=10.0)
    assert tally.crashes == [], tally.crashes[0][1]
    assert tally.hangs == [] and tally.unnamed == [], (tally.hangs[:3], tally.unnamed[:3])
    assert tally.inputs == 100_000 and tally.accepted > 2_000 and tally.refused > 50_000
    before = pipe.world.snapshot_dict()["cycle"]
    pipe.world.step()   # and it goes on
    assert pipe.world.snapshot_dict()["cycle"] == before + 1
