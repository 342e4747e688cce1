"""PRODIGY's Back-Chainer (agents/lang/planning/backchain.py) on the solver's chaining code:
first on the toy domain (tests/lang/planning/toy.py), then on the office of seed 003, where
the tail-plans of Figure 5 come out as printed."""

from __future__ import annotations

import pytest

from agents.lang.planning.backchain import build, check
from agents.lang.planning.control import Control
from agents.lang.solving.state import literal

from .toy import World


def plan(world: World, goal: str, *facts: str, control: Control | None = None):
    return build(world.domain, literal(goal), world.base(*facts), world.pidx,
                 control or world.control, world.metric)


def texts(built) -> list[str]:
    return [s.text for s in built.steps]


def test_a_tail_plan_is_built_ahead_of_execution_in_the_projected_state():
    built = plan(World(), "(lies key E)")
    # (has key) needs (at C): the robot walks there; then (at E) is judged where the plan
    # will be (at C, not at A): the second walk is needed although the robot is not at E
    assert texts(built) == ["<walk C>", "<take key C>", "<walk E>", "<drop key E>"]
    assert [s.place for s in built.steps] == ["C", "C", "E", "E"]
    assert built.steps[0].actions == (("*walk", "C"),)
    assert built.steps[2].effects == ("(at E)", "(not (at ?anywhere))")


def test_what_holds_already_is_not_planned_for():
    assert texts(plan(World(at="C"), "(lies key E)")) == [
        "<take key C>", "<walk E>", "<drop key E>"]
    assert texts(plan(World(at="E", things={"key": "R1"}), "(lies key E)")) == [
        "<drop key E>"]
    assert plan(World(things={"key": "E"}), "(lies key E)").steps == ()


def test_a_choice_that_cannot_be_completed_is_given_up_for_the_next_alternative():
    # (buy key) comes first in the program, but (rich) is a fact nothing achieves here
    # ((win-lottery) needs (lucky), which needs (rich): a loop): back to (take key C)
    world = World(extra="\n(operators ((rich) :operator (win-lottery) :start ((lucky)))"
                        " ((lucky) :operator (cross-fingers) :start ((rich))))")
    assert texts(plan(world, "(has key)")) == ["<walk C>", "<take key C>"]
    # with (rich) known to the planner, buying is applicable: no walk
    assert texts(plan(world, "(has key)", "(rich)")) == ["<buy key>"]


def test_a_request_that_cannot_be_achieved_fails_with_the_reason():
    built = plan(World(things={"box": "E"}), "(has key)")
    assert built.steps == ()
    assert built.failed.startswith("(has key) cannot be achieved: ")
    assert "rich" in built.failed


def test_the_reason_names_operators_not_skills():
    # the Back-Chainer chains on operators only (seed 003): its reasons speak of operators
    built = plan(World(), "(lies ghost E)")
    assert built.failed.endswith("(rich) cannot be achieved: nothing to chain off: no operator "
                                 "achieves rich))")
    assert "skill" not in built.failed


def test_a_control_rule_rejects_bindings_and_the_firing_is_recorded():
    world = World(extra="""
(control-rules
  (control-rule NEAR-FIRST
    (if (and (candidate-operator (walk ?a)) (candidate-operator (walk ?b)) (closer ?a ?b)))
    (then prefer bindings (walk ?a) (walk ?b)))
  (control-rule NOT-D
    (if (candidate-operator (walk D)))
    (then reject bindings (walk D))))
(operators ((at ?p) :operator (teleport ?p) :percepts ((place ?p)) :actions ((*beam ?p))))""")
    control = Control(world.domain.rules)
    built = plan(world, "(at D)", control=control)
    assert texts(built) == ["<teleport D>"]   # (walk D) rejected: the other operator
    assert control.firings == ["reject bindings NOT-D (walk D)"]


def test_a_plan_is_checked_against_the_state_step_by_step():
    world = World()
    built = plan(world, "(lies key E)")
    goal = literal("(lies key E)")
    assert check(world.domain, built.steps, goal, world.store, world.pidx) == ""
    # the world moved the robot to C: the first walk is no longer needed
    at_c = World(at="C")
    assert check(at_c.domain, built.steps, goal, at_c.store, at_c.pidx) == \
        "<walk C> is no longer needed: (at C) holds"
    # someone took the key to D: taking it at C no longer applies
    moved = World(things={"key": "D", "box": "E"})
    assert check(moved.domain, built.steps, goal, moved.store, moved.pidx) == \
        "<take key C> no longer applies (its percepts changed)"


@pytest.fixture(scope="module")
def office():
    """The office's start (the robot in the lab r-5306) with programs/office_rogue.tlp."""
    from agents.lang import Engine, load_program
    from agents.lang.core.store import PerceptIndex
    from agents.lang.engine import as_percepts
    from agents.lang.planning.domain import Domain, Metric
    from world.domain import get_domain

    domain = get_domain("office")
    raw = domain.perceive(domain.create({}, 1, ["ME"]).snapshot_dict(), "ME")
    world = World.__new__(World)
    world.program = load_program("programs/office_rogue.tlp")
    world.store = Engine(world.program, solver=None).infer(raw).store
    world.pidx = PerceptIndex(as_percepts(raw))
    world.domain = Domain(world.program)
    world.metric = Metric(world.domain.travel, world.pidx)
    world.control = Control(world.domain.rules)
    return world


@pytest.mark.parametrize("goal, person, room, item", [
    ("(delivered mail-mitchell r-5313)", "mitchell", "r-5303", "mail-mitchell"),
    ("(delivered fax-jhm r-5313)", "jhm", "r-5311", "fax-jhm")])
def test_figure_5_head_plans(office, goal, person, room, item):
    knowledge = office.domain.knowledge(literal(goal), office.pidx, office.store)
    assert knowledge == (f"(requester {item} {person})", f"(deliver-loc {person} r-5313)")
    assert texts(plan(office, goal, *knowledge)) == [
        f"<goto-pickup-loc {person} {room}>", f"<acquire-item {room} {person} {item}>",
        f"<goto-deliver-loc {person} r-5313>", f"<deliver-item r-5313 {person} {item}>"]


def test_figure_7_tail_plan_prefers_the_closest_conference_room(office):
    control = Control(office.domain.rules)
    assert texts(plan(office, "(mtg-scheduled)", control=control)) == [
        "<goto-room r-5309>", "<select-conference-room r-5309>",
        "<observe-conference-room r-5309>", "<schedule-meeting r-5309>"]
    assert control.firings == ["prefer bindings LOOK-AT-CLOSEST-CONF-ROOM-FIRST "
                               "(schedule-meeting r-5309) over (schedule-meeting r-5311)"]
