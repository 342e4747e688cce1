"""Per-action resources: lower goals act in the same cycle through free resources (seed 000,
"Directions for Future Work": parallel skills; seed 003: compatible goals)."""

from __future__ import annotations

from agents.lang import GoalStatus, load_program_text

from .conftest import me

MAN_AHEAD = ["man", "M31", "angle", 5.0, "dist", 12.0]


def test_without_resources_one_goal_acts(minidrive):
    decision = minidrive.cycle(minidrive.initial_state(), [me(speed=30, heading=10.0),
                                                           MAN_AHEAD]).decision
    assert [a.to_list() for a in decision.actions] == [["*brake", 100]]
    assert len(decision.paths) == 1


def test_free_resources_let_a_lower_goal_steer_while_braking(minidrive_res):
    decision = minidrive_res.cycle(minidrive_res.initial_state(),
                                   [me(speed=30, heading=10.0), MAN_AHEAD]).decision
    assert [a.to_list() for a in decision.actions] == [["*brake", 100], ["*steer", -10.0]]
    assert [g.status for g in decision.goals] == [
        GoalStatus.ACTIVE, GoalStatus.PENDING, GoalStatus.ACTIVE]
    assert decision.goals[2].note == "acts in parallel through free resources"
    assert decision.goals[1].note == "no path with free resources"
    first, second = decision.paths
    assert (first.goal_id, first.resources, first.parallel) == ("p1", ("pedals",), False)
    assert (second.goal_id, second.resources, second.parallel) == ("p3", ("wheel",), True)
    assert any(w.goal_id == "p2" and w.reason == "resources taken: pedals (by p1)"
               for w in decision.why)
    d = decision.to_dict()
    assert d["parallel"][0]["goal_id"] == "p3" and d["resources"] == ["pedals"]


def test_undeclared_action_takes_every_resource():
    program = load_program_text("""
(concepts ((calm ?x) :percepts ((o ?x calm T))) ((tidy ?x) :percepts ((o ?x tidy T))))
(skills ((calm ?x) :percepts ((o ?x)) :actions ((*shout ?x)))
        ((tidy ?x) :percepts ((o ?x)) :actions ((*sweep ?x))))
(resources (*sweep broom))
(goals (calm A) (tidy A))""", "res.tlp")
    assert any("action *shout is not listed in (resources ...)" in str(w)
               for w in program.warnings)
    from agents.lang import Engine
    engine = Engine(program)
    decision = engine.cycle(engine.initial_state(), [["o", "A", "calm", "NIL", "tidy", "NIL"]]) \
        .decision
    assert [a.to_list() for a in decision.actions] == [["*shout", "A"]]
    assert decision.status_of("p2") is GoalStatus.PENDING
