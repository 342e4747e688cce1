"""Merging head-plans (agents/lang/planning/merge.py; seed 003, section 4): the next step is
the one of least expected total travel, not the nearest; an action two plans need is done
once; no order carries more than the robot can; ties go to a step where the robot is, then
to the request(s) the last action served, then to the newest request; many plans are merged
by a beam search that stays close to the exact order."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang.core.store import PerceptIndex
from agents.lang.planning.domain import Metric
from agents.lang.planning.merge import (
    MAX_STATES,
    Carry,
    Load,
    Planner,
    choose,
    detour,
    fcfs,
    visit_loads,
    visits,
)
from agents.lang.planning.state import PlanStep

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


def test_many_plans_are_merged_by_a_beam_search():
    many = [("A", "B")] * 16
    assert not Planner(line(0.0), many).exact and 3 ** 16 > MAX_STATES
    assert Planner(line(0.0), many).total() == 14.0      # every A, then the B's at once


def order_length(p: Planner) -> tuple[float, list[int]]:
    """The length of the order a Planner follows from the robot, and the order."""
    idx, cur, total, out = tuple(0 for _ in p.plans), None, 0.0, []
    while True:
        k = p._best(idx, cur)[1]
        if k < 0:
            return total, out
        total += p.metric.move(cur, p.plans[k][idx[k]])
        cur = p.plans[k][idx[k]]
        idx = idx[:k] + (idx[k] + 1,) + idx[k + 1:]
        out.append(k)


plan_sets = st.lists(st.lists(st.sampled_from(sorted(POS)), min_size=1, max_size=3)
                     .map(tuple), min_size=1, max_size=6)


@settings(max_examples=60, deadline=None)
@given(plans=plan_sets, robot=st.sampled_from(sorted(POS.values())))
def test_the_beam_follows_an_order_it_can_do_and_no_better_than_the_exact_one(plans, robot):
    exact = Planner(line(robot), plans)
    beam = Planner(line(robot), plans)
    beam.exact = False
    length, order = order_length(beam)
    assert sorted(order) == sorted(k for k, p in enumerate(plans) for _ in p)
    assert abs(length - beam.total()) < 1e-6
    assert beam.total() >= exact.total() - 1e-6
    assert abs(order_length(exact)[0] - exact.total()) < 1e-6


def carry_step(name: str, place: str, delta: int) -> PlanStep:
    held = "(holding x)" if delta > 0 else "(not (holding x))" if delta < 0 else "(seen x)"
    return PlanStep(name, (place,), 0, (), "", "", (), (held,), (("*go", place),), (), place)


def one_way(s: PlanStep) -> int:
    return 1 if "(holding x)" in s.effects else -1 if "(not (holding x))" in s.effects else 0


def test_no_order_carries_more_than_the_capacity():
    # two pickups at A, their drops at E; a third pickup at B, its drop at D. With room for
    # two things the robot must drop at D before taking the third (or the first two at E)
    plans = {t: (carry_step("take", a, 1), carry_step("drop", b, -1))
             for t, (a, b) in {"p": ("A", "E"), "q": ("A", "E"), "r": ("B", "D")}.items()}
    assert visit_loads(plans["p"], one_way) == (1, -1)
    free = choose(line(0.0), plans, {"p": 0, "q": 1, "r": 2}, ())
    tight = choose(line(0.0), plans, {"p": 0, "q": 1, "r": 2}, (), Carry(0, 2, one_way))
    assert free.expected == 50.0 and tight.expected > free.expected
    load = Load(0, 2, tuple(visit_loads(p, one_way) for p in plans.values()))
    p = Planner(line(0.0), [visits(s) for s in plans.values()], load)
    _, order = order_length(p)
    held, most, done = 0, 0, [0, 0, 0]
    for k in order:
        held += load.deltas[k][done[k]]
        done[k] += 1
        most = max(most, held)
    assert most == 2
    full = choose(line(0.0), plans, {"p": 0, "q": 1, "r": 2}, (), Carry(2, 2, one_way))
    assert full is not None       # nothing fits: chosen as if there were no limit


def test_a_step_where_the_robot_is_comes_first_among_equals():
    # at E: m's drop at E costs nothing now; j's goes to D and comes back to E anyway
    plans = {"m": (step("drop-m", "E", "*drop-m"),),
             "j": (step("go-j", "D"), step("end-j", "E"))}
    got = choose(line(50.0), plans, {"m": 0, "j": 1}, ())
    assert (got.step.text, got.expected) == ("<drop-m E>", 40.0)


def test_a_shared_goto_serves_the_requests_whose_visit_is_made_there_now():
    # p, q and r all begin with the goto to A; with room for two things, the order takes
    # two of them there now and comes back for the third: the goto is done for those two
    plans = {t: (step("goto", "A"), carry_step(f"take-{t}", "A", 1),
                 carry_step(f"drop-{t}", b, -1))
             for t, b in (("p", "E"), ("q", "E"), ("r", "B"))}
    got = choose(line(30.0), plans, {"p": 0, "q": 1, "r": 2}, (), Carry(0, 2, one_way))
    assert got.step.text == "<goto A>" and len(got.tasks) == 2
