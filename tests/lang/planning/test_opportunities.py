"""Opportunistic steps (seed 003, section 4, issue 23 item 2): before the robot leaves a
room, a step of any selected or waiting request that is done right there is taken when it
delays no more important request beyond what it would wait anyway (no travel added to the
selected requests, room left for what they still carry). The burst case of the issue, in the
office world: rich's mail is taken on the first visit to r-5301, though a priority-1 request
came first. And random request sets, run through the planner: every request done once, the
travel never above first-come-first-served."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from agents.lang import Engine, load_program_text
from agents.lang.core.store import PerceptIndex
from agents.lang.engine import as_percepts
from agents.lang.planning.backchain import build
from agents.lang.planning.control import Control
from agents.lang.planning.domain import Domain, with_facts
from agents.lang.planning.merge import choose
from agents.lang.planning.monitor import Env
from agents.lang.planning.opportunity import opportunity
from agents.lang.planning.state import Task
from agents.lang.solving.state import literal
from bench.office.office_sets import (
    PEOPLE,
    ROOMS,
    Request,
    RequestSet,
    fcfs,
    measure,
    metric,
    run_set,
)

from .office_runs import run
from .toy import TOY, percepts

CARRY = TOY.replace(":detour 5))",
                    ":detour 5 :carrying (has ?x) :capacity (self ?r capacity ?c)))")


def toy_env(capacity: int, at: str = "C") -> tuple[Env, Control]:
    program = load_program_text(CARRY, "carry.tlp")
    raw = percepts(at, {"key": "C", "box": "E"})
    raw[0] = [*raw[0], "capacity", capacity]
    store = Engine(program, solver=None).infer(raw).store
    return Env(Domain(program), PerceptIndex(as_percepts(raw)), store, 5), \
        Control(Domain(program).rules)


def toy_task(env: Env, control: Control, goal_id: str, goal: str, priority: int,
             status: str) -> Task:
    lit = literal(goal)
    knowledge = (f"(wanted {lit.args[0]} {lit.args[1]})",)
    built = build(env.domain, lit, with_facts(env.store, knowledge), env.pidx, control,
                  env.metric)
    return Task(goal_id, goal, priority, int(goal_id[1:]), 0, knowledge, built.steps, status)


def test_a_waiting_requests_step_here_is_taken_before_leaving_when_it_costs_nothing():
    env, control = toy_env(capacity=2)
    top = toy_task(env, control, "t1", "(lies box A)", 1, "selected")   # walk E, take, walk A
    low = toy_task(env, control, "t2", "(lies key B)", 5, "waiting")    # take the key here
    assert [s.text for s in low.plan] == ["<take key C>", "<walk B>", "<drop key B>"]
    leaving = choose(env.metric, {"t1": top.plan}, {"t1": 1, "t2": 2}, ())
    assert leaving.step.text == "<walk E>"
    events: list[str] = []
    got = opportunity([top, low], leaving, env, events)
    assert (got.step.text, got.tasks) == ("<take key C>", ("t2",))
    assert events == ["cycle 5: t2 <take key C> taken in C before leaving it (waiting): no "
                      "travel, and the selected requests' travel stays 60.0 m"]


def test_not_when_it_would_take_room_a_more_important_request_needs():
    env, control = toy_env(capacity=1)        # the key would leave no hand for the box
    top = toy_task(env, control, "t1", "(lies box A)", 1, "selected")
    low = toy_task(env, control, "t2", "(lies key B)", 5, "waiting")
    leaving = choose(env.metric, {"t1": top.plan}, {"t1": 1, "t2": 2}, ())
    assert opportunity([top, low], leaving, env, []) is None


def test_not_for_a_blocked_request_nor_when_the_robot_stays():
    env, control = toy_env(capacity=2)
    top = toy_task(env, control, "t1", "(lies box A)", 1, "selected")
    low = toy_task(env, control, "t2", "(lies key B)", 5, "blocked")
    leaving = choose(env.metric, {"t1": top.plan}, {"t1": 1, "t2": 2}, ())
    assert opportunity([top, low], leaving, env, []) is None
    here = toy_task(env, control, "t3", "(lies key C)", 1, "selected")   # take, drop, at C
    staying = choose(env.metric, {"t3": here.plan}, {"t3": 3}, ())
    assert opportunity([here, low], staying, env, []) is None


@pytest.fixture(scope="module")
def burst():
    return run("office_burst")


def test_the_burst_takes_richs_mail_on_the_first_visit(burst):
    steps = burst.executed()
    assert steps.count("<goto-pickup-loc rich r-5301>") == 1
    k = steps.index("<goto-pickup-loc rich r-5301>")
    assert steps[k + 1] == "<acquire-item r-5301 rich mail-rich>"
    # it was waiting then: the priority-1 request, posted meanwhile, went first
    assert any(e.endswith("g1 <acquire-item r-5301 rich mail-rich> taken in r-5301 before "
                          "leaving it (waiting): no travel, and the selected requests' "
                          "travel stays 123.0 m") for e in burst.log())
    assert set(burst.statuses().values()) == {"achieved"} and len(burst.statuses()) == 10
    rich = next(f for f in burst.planner.finished if f.goal_id == "g1")
    assert rich.places == ("r-5301", "r-5302")
    p1 = [s for s in steps if "memo-reid" in s or "reid r-5310" in s]
    assert p1 == ["<acquire-item r-5315 reid memo-reid>", "<goto-deliver-loc reid r-5310>",
                  "<deliver-item r-5310 reid memo-reid>"]


requests = st.builds(
    lambda holder, to, arrival, kind: Request("", kind, holder, to, arrival),
    st.sampled_from(sorted(PEOPLE)), st.sampled_from([*ROOMS, *sorted(PEOPLE)]),
    st.integers(0, 200), st.sampled_from(["mail", "fax", "memo"])).filter(
        lambda r: r.to not in (r.holder, PEOPLE[r.holder]))


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(start=st.sampled_from(ROOMS), drawn=st.lists(requests, min_size=1, max_size=4))
def test_random_request_sets_are_each_done_once_and_never_travel_more_than_fcfs(start, drawn):
    """At most 4 requests: the robot's capacity (4) never makes it come back for one."""
    first = min(r.arrival for r in drawn)
    reqs = tuple(Request(f"{r.kind}-{r.holder}-{k}", r.kind, r.holder, r.to, r.arrival - first)
                 for k, r in enumerate(drawn))
    s = RequestSet(0, start, tuple(sorted(reqs, key=lambda r: r.arrival)))
    got = measure(s, run_set(s), metric(), optimum=False)
    assert got.done_once == got.requests
    assert got.teleo <= fcfs(s, metric()) + 1e-6
