"""Threads of several goals (seed 002, section 3, "Multiple Threads of Execution": 'an
explicit wait-resume mechanism ... to switch among the threads only at designated points
of execution'). The prioritised goal list decides which thread acts; a thread at a wait
point lets the lower goals' threads run and resumes from the wait point, not from the
beginning; a preempted thread resumes where it was."""

from __future__ import annotations

import json

from agents.lang import Engine, EngineState, load_program_text
from tests.lang.scs.drive import Driver

# no (resources ...) section: one goal acts per cycle (seed 000)
TWO = """
(concepts ((flag ?f) :percepts ((flag ?f)))
          ((never ?x) :percepts ((never ?x)))
          ((chores ?x) :percepts ((chores ?x)))
          ((calm ?x) :percepts ((self ?x)) :relations ((not (flag alarm)))))
(skills
  ((calm ?x) :percepts ((self ?x)) :actions ((*e)))
  ((never ?x) :percepts ((self ?x)) :body (do (*a) (wait (flag go)) (*b)))
  ((chores ?x) :percepts ((self ?x)) :body (repeat (*c) (*d))))
(goals (calm ME) (never ME) (chores ME))
"""


def engine() -> Engine:
    return Engine(load_program_text(TWO, "two.tlp"), solver=None)


def test_a_waiting_thread_lets_lower_threads_run_and_resumes_at_its_wait_point():
    d = Driver(engine())
    flags = [[], [], [], ["go"], ["go"], ["go"]]
    assert d.run(6, lambda k: flags[k]) == ["a", "c", "d", "b", "a", "b"]
    statuses = {t["goal_id"]: t["status"] for t in d.scs["threads"]}
    assert statuses == {"p2": "acting", "p3": "suspended"}   # p3 waits for p2 to wait


def test_a_preempted_thread_suspends_and_resumes_where_it_was():
    d = Driver(engine())
    flags = [[], ["alarm"], ["alarm"], [], [], ["go"], ["go"]]
    t = d.run(3, lambda k: flags[k])
    assert t == ["a", "e", "e"]                      # the alarm (a law) preempts the body
    shown = {x["goal_id"]: x["status"] for x in d.scs["threads"]}
    assert shown == {"p2": "suspended"}              # kept as it was, not run this cycle
    t += d.run(4, lambda k: flags[k + 3])
    assert t == ["a", "e", "e", "c", "d", "b", "a"]  # resumed at the wait, not at (*a)


def test_outcomes_of_a_preempted_threads_step_are_not_lost():
    """The step issued just before the preemption is settled by the report of the next
    cycle even though the thread does not run then: it continues after the law is done."""
    d = Driver(engine())
    d.run(1)
    d.run(1, ["alarm"])
    stack = d.scs["threads"][0]["stack"]
    assert stack[-1]["pending"] == [["*a"]] and stack[-1]["outcome"] == "done"


def test_the_threads_survive_a_restart_of_the_executive():
    """A new Engine given the saved state (as JSON) continues exactly as the original."""
    flags = [[], ["alarm"], [], [], ["go"], [], ["go"], ["go"], []]
    whole = Driver(engine()).run(9, lambda k: flags[k])
    first = Driver(engine())
    part = first.run(4, lambda k: flags[k])
    saved = json.loads(json.dumps(first.state.to_dict()))
    again = Driver(engine())
    again.state = EngineState.from_dict(saved)
    again.outcomes = first.outcomes
    assert part + again.run(5, lambda k: flags[k + 4]) == whole


def test_the_state_shows_every_thread_with_its_construct_stack():
    d = Driver(engine())
    d.run(2)
    threads = d.result.state.to_dict()["scs"]["threads"]
    assert [t["goal_id"] for t in threads] == ["p2", "p3"]
    shown = d.result.decision.to_dict()["scs"]["threads"][0]
    assert shown["stack"][0]["step"] == "(do)" and shown["stack"][0]["state"] == \
        "[step 2 of 3]"
    assert shown["stack"][1]["step"] == "(wait (flag go))"
    text = d.result.decision.explain()
    assert "scs threads:" in text and "p2 (never ME) <- never#1: waiting -- waits for " \
        "((flag go))" in text


def test_threads_of_achieved_goals_are_dropped():
    d = Driver(engine())
    d.run(2)
    d.step(extra=[["chores", "ME"]])
    assert [t["goal_id"] for t in d.scs["threads"]] == ["p2"]
    assert d.scs["tally"]["bodies ended: goal achieved"] == 1


def test_a_restarted_executive_given_only_its_scs_state_resumes_its_threads():
    """What the executive process gets back after a restart (docs/bus.md, "Agent memory"):
    the SCS state, but no remembered skill path. The threads resume where they were."""
    from dataclasses import replace

    from agents.lang.scs.state import from_memory, to_memory
    flags = [[], [], [], ["go"], ["go"]]
    whole = Driver(engine()).run(5, lambda k: flags[k])
    first = Driver(engine())
    part = first.run(3, lambda k: flags[k])
    again = Driver(engine())
    memory = json.loads(json.dumps(to_memory(first.state.scs)))
    again.state = replace(again.state, cycle=first.state.cycle, scs=from_memory(memory))
    again.outcomes = first.outcomes
    assert again.state.paths == () and part + again.run(2, lambda k: flags[k + 3]) == whole
