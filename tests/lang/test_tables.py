"""Seed 000's Tables 1, 2, 3, 5 and 6 load verbatim (typos included) and run."""

from __future__ import annotations

import pytest

from agents.lang import Engine, Percept, ProgramError, load_program

from .conftest import FIX


def support(*names):
    return [FIX / n for n in names] + [FIX / "table2_concepts.tlp", FIX / "driving_support.tlp"]


@pytest.mark.parametrize("table", ["table1_skills.tlp", "table5_skills.tlp", "table6_skills.tlp"])
def test_skill_tables_load_with_the_concepts_they_use(table):
    program = load_program(*support(table))
    assert all(s.head.pred in program.arity for s in program.skills)
    own = [s for s in program.skills if s.loc.source.endswith(table)]
    assert own and {s.head.pred for s in own} <= {"at-desired-speed", "at-address"}


def test_table1_alone_reports_every_undefined_concept_with_its_location():
    with pytest.raises(ProgramError) as info:
        load_program(FIX / "table1_skills.tlp")
    text = str(info.value)
    assert "table1_skills.tlp:3:9: undefined concept 'stopped' in (stopped ?self)" in text
    for name in ("at-desired-speed", "address-behind", "address-in-front", "at-address"):
        assert f"undefined concept '{name}'" in text
    assert len(info.value.errors) == 6


def test_table6_typos_are_read_with_warnings():
    program = load_program(*support("table6_skills.tlp"))
    warnings = [str(w) for w in program.warnings]
    assert any("table6_skills.tlp:1:14: warning: '?self?ad' read as 2 variables ?self ?ad" in w
               for w in warnings)
    assert any("table6_skills.tlp:25:1: warning: ':require' read as ':requires'" in w
               for w in warnings)
    first, _, third = program.skills_for("at-address")
    assert [str(a) for a in first.head.args] == ["?self", "?ad", "?st"]
    assert [str(c) for c in third.requires] == ["(not-hitting-pedestrians ?self)"]


def test_table3_percepts_load_verbatim(table3):
    assert len(table3) == 9
    me = next(p for p in table3 if p.type == "self")
    assert me.to_list() == ["self", "ME", "speed", 20.0, "heading", -5.60023, "wheel-angle", 0,
                            "throttle", 0, "limit", 25, "breakthrottle", 100,
                            "segment", "S2724"]
    package = next(p for p in table3 if p.type == "package")
    assert package.get("delivered") == "NIL" and isinstance(me.get("limit"), int)
    assert Percept.from_list(["street", "B"]) in table3


def test_table2_concepts_infer_the_seeds_beliefs_from_table3(table3):
    engine = Engine(load_program(FIX / "table2_concepts.tlp", FIX / "driving_support.tlp"))
    beliefs = {str(b) for b in engine.infer(table3)}
    # seed 000: "the vehicle is in segment S2724 and segment S2724 is on street B ... the
    # vehicle is on street B"; speed 20 with limit 25 is the desired speed (Table 2 tests).
    assert {"(in-segment ME S2724)", "(segment-at-street S2724 B)", "(at-street ME B)",
            "(at-desired-speed ME)"} <= beliefs
    assert "(at-street ME SECOND)" not in beliefs


def test_table5_skill_switches_on_speed(table3):
    engine = Engine(load_program(*support("table5_skills.tlp")))
    state = engine.add_goal(engine.initial_state(), "(at-address ME 2 B)")
    behind = [p if p.type != "building" else Percept.from_list(
        ["building", "B2677", "address", 2, "street", "B", "c1angle", -149.5, "c1dist", 42.4])
        for p in table3]
    result = engine.cycle(state, behind)
    # speed is fine, the address is behind: the first skill (requires at-desired-speed) applies
    assert result.decision.path[0].skill == "at-address#1"
    assert str(result.decision.path[0].goal) == "(at-address ME 2 B)"
    assert [w.reason for w in result.decision.why if w.skill == "at-address#2"] == [
        "not tried: an earlier skill applies"]
