"""The world model (seed 002, section 2, "World Model": 'additional facts can be either
asserted, retracted, or updated by the SCS program'): an asserted fact is a belief from the
next cycle on, joined with inferred beliefs (concepts may build on it), until retracted; it
is part of the engine state, so it survives a restart."""

from __future__ import annotations

import json

from agents.lang import EngineState
from tests.lang.scs.drive import Driver, body_program

EXTRA = """(concepts
  ((marked-twice ?x) :percepts ((self ?x)) :relations ((mark ?x) (mark2 ?x)))
  ((mark2 ?x) :percepts ((mark2 ?x))))"""
BODY = "(do (assert (mark ?x)) (*a) (assert (mark2 ?x)) (*b) (retract (mark ?x)) (*c))"


def beliefs(d: Driver) -> set[str]:
    return {str(b) for b in d.result.beliefs if b.pred in ("mark", "mark2", "marked-twice")}


def test_asserted_facts_are_beliefs_on_later_cycles_until_retracted():
    d = Driver(body_program(BODY, EXTRA))
    d.step()
    assert beliefs(d) == set()                            # asserted this cycle: not yet
    assert d.state.scs.model == (("mark", "ME"),)
    d.step()
    assert beliefs(d) == {"(mark ME)"}
    d.step()
    assert beliefs(d) == {"(mark ME)", "(mark2 ME)", "(marked-twice ME)"}   # a concept on top
    d.step()
    assert beliefs(d) == {"(mark2 ME)"}                   # retracted


def test_model_facts_join_perceived_instances_of_the_same_concept():
    d = Driver(body_program("(do (assert (mark2 ME)) (*a))",
                            "(concepts ((mark2 ?x) :percepts ((mark2 ?x))))"))
    d.step(extra=[["mark2", "YOU"]])
    d.step(extra=[["mark2", "YOU"]])
    assert beliefs(d) == {"(mark2 ME)", "(mark2 YOU)"}


def test_the_model_survives_a_restart_and_is_shown():
    d = Driver(body_program(BODY, EXTRA))
    d.step()
    d.step()
    again = Driver(body_program(BODY, EXTRA))
    again.state = EngineState.from_dict(json.loads(json.dumps(d.state.to_dict())))
    again.outcomes = d.outcomes
    again.step()
    assert beliefs(again) == {"(mark ME)", "(mark2 ME)", "(marked-twice ME)"}
    assert again.state.scs.model == (("mark2", "ME"),)    # (mark ME) retracted meanwhile
    assert "world model: (mark2 ME)" in again.result.decision.explain()


def test_engine_infer_takes_the_model_as_base_facts():
    engine = body_program(BODY, EXTRA)
    base = [["mark", "ME"], ["mark2", "ME"]]
    found = {str(b) for b in engine.infer([["self", "ME"]], base)}
    assert "(marked-twice ME)" in found
    assert "(marked-twice ME)" not in {str(b) for b in engine.infer([["self", "ME"]])}
