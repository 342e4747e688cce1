"""Loose variables (agents/lang/solving/loose.py): a skill's variable that its head leaves
open and that one condition of its start names beside static relations, such as a lift's
count of passengers when boarding (elevators, IPC 2008). Which variables are loose, and a
chosen way bound afresh to the count that holds now rather than the one it was chosen with."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Engine, as_percepts, load_program_text
from agents.lang.core.store import PerceptIndex, store_of
from agents.lang.solving.loose import loose, loose_vars, rebind, rebound_vars
from agents.lang.solving.state import StackEntry
from agents.lang.solving.task import Task

COUNTS = ("n0", "n1", "n2", "n3")

# the shape `teleo pddl program` writes for elevators' board, plus a skill whose loose-looking
# variable a static relation ties to the head (miconic's board: the floor is the passenger's
# origin) and one whose open variable no static relation names (the block B is on)
PROGRAM = """
(concepts
  ((lift-at ?lift ?floor) :percepts ((lift-at _ arg1 ?lift arg2 ?floor)))
  ((passenger-at ?p ?floor) :percepts ((passenger-at _ arg1 ?p arg2 ?floor)))
  ((boarded ?p ?lift) :percepts ((boarded _ arg1 ?p arg2 ?lift)))
  ((passengers ?lift ?n) :percepts ((passengers _ arg1 ?lift arg2 ?n)))
  ((next ?a ?b) :percepts ((next _ arg1 ?a arg2 ?b)))
  ((can-hold ?lift ?n) :percepts ((can-hold _ arg1 ?lift arg2 ?n)))
  ((origin ?p ?f) :percepts ((origin _ arg1 ?p arg2 ?f)))
  ((on ?a ?b) :percepts ((on _ arg1 ?a arg2 ?b))))
(skills
  ((boarded ?p ?lift)
   :percepts ((next _ arg1 ?n1 arg2 ?n2) (object ?p type passenger) (object ?lift type lift)
              (object ?f type count) (object ?n1 type count) (object ?n2 type count))
   :start ((lift-at ?lift ?f) (passenger-at ?p ?f) (passengers ?lift ?n1) (next ?n1 ?n2)
           (can-hold ?lift ?n2))
   :actions ((*board ?p ?lift ?f ?n1 ?n2))
   :effects ((passengers ?lift ?n2) (not (passenger-at ?p ?f)) (not (passengers ?lift ?n1))))
  ((passenger-at ?p ?f)
   :percepts ((object ?p type passenger) (object ?lift type lift) (object ?f type count))
   :start ((lift-at ?lift ?f) (boarded ?p ?lift))
   :actions ((*leave ?p ?lift ?f))
   :effects ((not (boarded ?p ?lift))))
  ((lift-at ?lift ?f)
   :percepts ((object ?lift type lift) (object ?f type count) (object ?g type count))
   :start ((lift-at ?lift ?g))
   :actions ((*move ?lift ?g ?f))
   :effects ((not (lift-at ?lift ?g))))
  ((boarded ?p ?lift)
   :percepts ((object ?p type passenger) (object ?lift type lift) (object ?f type count))
   :start ((lift-at ?lift ?f) (origin ?p ?f))
   :actions ((*step-in ?p ?lift ?f)))
  ((on ?a ?c)
   :percepts ((object ?a type passenger) (object ?b type passenger)
              (object ?c type passenger))
   :start ((on ?a ?b))
   :actions ((*shift ?a ?b ?c))
   :effects ((not (on ?a ?b)))))
(goals (boarded p1 lift1))
"""
ENGINE = Engine(load_program_text(PROGRAM, "loose.tlp"))
BOARD, LEAVE, MOVE, STEP_IN, SHIFT = (s for s in ENGINE.program.skills
                                      if s.kind == "primitive")


def atom(*args: str) -> list[str]:
    out = [args[0], "_"]
    for k, a in enumerate(args[1:], start=1):
        out += [f"arg{k}", a]
    return out


def task_with(count: str) -> Task:
    """Lift1 at floor f2 with ``count`` passengers (capacity n3), p1 waiting at f1."""
    objects = [["object", x, "type", t] for x, t in
               [("p1", "passenger"), ("p2", "passenger"), ("lift1", "lift"),
                ("f1", "count"), ("f2", "count"), *((c, "count") for c in COUNTS)]]
    atoms = [atom("lift-at", "lift1", "f2"), atom("passenger-at", "p1", "f1"),
             atom("passengers", "lift1", count), atom("origin", "p1", "f1"),
             atom("on", "p1", "p2")]
    atoms += [atom("next", a, b) for a, b in zip(COUNTS, COUNTS[1:], strict=False)]
    atoms += [atom("can-hold", "lift1", c) for c in COUNTS[1:]]
    index = PerceptIndex(as_percepts(objects + atoms))
    return Task(ENGINE.program, index, store_of(ENGINE.infer(index)))


def test_the_count_of_boarding_is_loose_and_a_floor_or_a_tied_variable_is_not():
    task = task_with("n0")
    names = {v.name for v in loose_vars(task, BOARD.number)}
    assert names == {"n1"}   # ?n2: no fluent condition names it; it is bound afresh too
    assert {v.name for v in rebound_vars(task, BOARD.number)} == {"n1", "n2"}
    assert not loose_vars(task, LEAVE.number)     # ?lift: named by two fluent conditions
    assert not loose_vars(task, MOVE.number)      # ?g: no static relation names it
    assert not loose_vars(task, STEP_IN.number)   # ?f: (origin ?p ?f) ties it to the head
    assert not loose_vars(task, SHIFT.number)     # the block ?a is on


def _board_way(task: Task, chosen: str):
    """The way boarding p1 into lift1 with the count ``chosen`` (whatever holds now)."""
    ways = task.alternatives(task.subgoal("(boarded p1 lift1)"))
    return next(w for w in ways if w.clause == BOARD.number and
                f"(passengers lift1 {chosen})" in w.conditions)


@settings(max_examples=25, deadline=None)
@given(now=st.sampled_from(COUNTS[:3]), then=st.sampled_from(COUNTS[:3]))
def test_a_chosen_way_takes_the_count_that_holds_now_and_keeps_the_rest(now, then):
    way = _board_way(task_with(then), then)   # chosen when the lift held ``then``
    task = task_with(now)
    entry = StackEntry("(boarded p1 lift1)", alternatives=(way,), chosen=0,
                       initial=tuple(c for c in way.conditions if task.holds(c)))
    new = rebind(task, entry).decision
    assert [c for c in new.conditions if not task.holds(c)] == ["(lift-at lift1 f1)"]
    assert {k: v for k, v in new.bindings if k in ("p", "lift", "f")} == \
        {"p": "p1", "lift": "lift1", "f": "f1"}
    assert (now == then) == (new == way)   # unchanged where its count still holds
    assert loose(task, new) == loose(task, way)
