"""Merging head-plans (agents/lang/planning/merge.py; seed 003, section 4): the next step is
the one of least expected total travel, not the nearest; an action two plans need is done
once; ties go to the request(s) the last action served, then to the newest request."""

from __future__ import annotations

from agents.lang.planning.domain import Metric
from agents.lang.planning.merge import MAX_STATES, Planner, choose, detour, fcfs, visits
from agents.lang.planning.state import PlanStep
from agents.lang.store import PerceptIndex

POS = {"A": 0.0, "B": 14.0, "C": 100.0, "D": 30.0, "E": 50.0}


def line(robot: float) -> Metric:
    """Places on a line at POS [m]; the robot at ``robot``."""
    m = Metric(None, PerceptIndex([]))
    m.here = {p: abs(x - robot) for p, x in POS.items()}
    m.pairs = {(p, q): abs(x - y) for p, x in POS.items() for q, y in POS.items() if p < q}
    return m


def step(name: str, place: str, command: str = "*go") -> PlanStep:
    return PlanStep(name, (place,), 0, (), "", "", (), (), ((command, place),), (), place)


def test_the_step_of_least_expected_travel_not_the_nearest():
    # from 10 m: B (4 m) is nearest, but A first then B then C is 110 m, B first 118 m
    plans = {"t1": (step("fetch", "A"),), "t2": (step("fetch", "B"), step("bring", "C"))}
    got = choose(line(10.0), plans, {"t1": 0, "t2": 1}, ())
    assert (got.step.text, got.tasks, got.expected, got.order) == \
        ("<fetch A>", ("t1",), 110.0, ("t1 A", "t2 B", "t2 C"))


def test_an_action_two_plans_need_is_done_once_named_for_the_older_request():
    plans = {"m": (step("goto-deliver-loc-m", "E"), step("deliver-m", "E", "*drop")),
             "j": (step("goto-deliver-loc-j", "E"), step("deliver-j", "E", "*drop"))}
    got = choose(line(30.0), plans, {"m": 0, "j": 1}, ("m",))
    assert (got.step.text, got.tasks, got.expected) == ("<goto-deliver-loc-m E>",
                                                        ("m", "j"), 20.0)


def test_ties_go_to_the_last_served_request_then_to_the_newest():
    plans = {"m": (step("deliver-m", "E", "*drop-m"),), "j": (step("deliver-j", "E", "*drop-j"),)}
    at_e = line(50.0)
    assert choose(at_e, plans, {"m": 0, "j": 1}, ("m", "j")).tasks == ("j",)   # newest
    assert choose(at_e, plans, {"m": 0, "j": 1}, ("m",)).tasks == ("m",)       # last served
    assert choose(at_e, {}, {}, ()) is None


def test_visits_merge_consecutive_steps_at_one_place():
    steps = (step("a", "A"), step("b", "A"), step("c", "B"), step("d", ""), step("e", "A"))
    assert visits(steps) == ("A", "B", "A")


def test_detour_and_first_come_first_served():
    m = line(0.0)
    assert detour(m, [("D", "E")], ("B",)) == 0.0       # on the way
    assert detour(m, [("D", "E")], ("C",)) == 50.0      # beyond the end
    assert fcfs(m, "A", [("D", "A"), ("E", "A")]) == 160.0   # 30+30, then 50+50


def test_many_plans_are_merged_nearest_first():
    many = [("A", "B")] * 16
    assert not Planner(line(0.0), many).exact and 3 ** 16 > MAX_STATES
    assert Planner(line(0.0), many).total() == 14.0
