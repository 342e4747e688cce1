"""A running agent's program swapped for another (agents/lang/swap.py, issue 34): the engine
state carries over where it still means something, and what is dropped is said."""

from __future__ import annotations

from agents.lang import Engine, load_program_text
from agents.lang.swap import carry_state, skill_map
from tests.lang.scs.drive import Driver

# the body of (never ?x) runs a, waits for (flag go), then b; (chores ?x) repeats c, d
OLD = """
(concepts ((flag ?f) :percepts ((flag ?f)))
          ((never ?x) :percepts ((never ?x)))
          ((chores ?x) :percepts ((chores ?x))))
(skills
  ((never ?x) :percepts ((self ?x)) :body (do (*a) (wait (flag go)) (*b)))
  ((chores ?x) :percepts ((self ?x)) :body (repeat (*c) (*d))))
(goals (never ME))
"""
# the same body of (never ?x), written further down after a new skill; chores is gone
NEW = """
; a comment moves every line
(concepts ((flag ?f) :percepts ((flag ?f)))
          ((never ?x) :percepts ((never ?x)))
          ((tidy ?x) :percepts ((tidy ?x))))
(skills
  ((tidy ?x) :percepts ((self ?x)) :actions ((*t)))
  ((never ?x) :percepts ((self ?x)) :body (do (*a) (wait (flag go)) (*b))))
(goals (never ME))
"""
CHANGED = NEW.replace("(*b))))", "(*e))))")   # the body of (never ?x) says something else


def _engine(text: str, name: str) -> Engine:
    return Engine(load_program_text(text, name), solver=None)


def _waiting(old: Engine) -> Driver:
    """p1's thread at its wait point, and a user goal (chores ME) g1 with its own thread."""
    d = Driver(old)
    d.state = old.add_goal(d.state, "(chores ME)", 5, "g1")
    assert d.run(2) == ["a", "c"]     # p1 acts, then waits for go: g1's thread runs
    return d


def test_a_thread_whose_body_is_still_there_goes_on_where_it_was():
    old, new = _engine(OLD, "old.tlp"), _engine(NEW, "new.tlp")
    d = _waiting(old)
    carried = carry_state(old, new, d.state)
    threads = {t.goal_id: t for t in carried.state.scs.threads}
    assert set(threads) == {"p1"}
    assert threads["p1"].skill == 1 and threads["p1"].key.endswith("|1")   # renumbered
    assert [e.id for e in carried.state.goals] == ["p1"]
    assert any(s.startswith("goal g1 (chores ME):") for s in carried.dropped), carried.dropped
    assert any(s.startswith("SCS thread of goal g1 (chores ME) (skill chores#1)")
               for s in carried.dropped), carried.dropped
    after = Driver(new)
    after.state = carried.state
    assert after.run(1, ["go"]) == ["b"]   # resumed at its wait point, not from (*a)


def test_a_changed_body_starts_again_and_is_said():
    old, changed = _engine(OLD, "old.tlp"), _engine(CHANGED, "changed.tlp")
    carried = carry_state(old, changed, _waiting(old).state)
    assert carried.state.scs.threads == ()
    assert any("SCS thread of goal p1 (never ME) (skill never#1): its body is not in the new "
               "program" == s for s in carried.dropped), carried.dropped
    after = Driver(changed)
    after.state = carried.state
    assert after.run(1, ["go"]) == ["a"]   # its new body from the start


def test_user_goals_the_new_program_can_pursue_keep_their_ids_and_priorities():
    old, new = _engine(OLD.replace("(goals (never ME))", ""), "old.tlp"), _engine(NEW, "n.tlp")
    state = old.add_goal(old.initial_state(), "(never YOU)", 7, "g4", once=True)
    carried = carry_state(old, new, state)
    goals = {e.id: e for e in carried.state.goals}
    assert set(goals) == {"p1", "g4"} and goals["g4"].priority == 7 and goals["g4"].once
    assert carried.dropped == ()
    assert carried.state.next_seq == state.next_seq


def test_the_same_program_carries_everything_and_drops_nothing():
    old = _engine(OLD, "old.tlp")
    state = _waiting(old).state
    carried = carry_state(old, _engine(OLD, "again.tlp"), state)
    assert carried.dropped == ()
    assert carried.state.scs == state.scs and carried.state.goals == state.goals
    assert carried.state.paths == state.paths


def test_the_skill_map_pairs_clauses_by_what_they_say_not_where():
    m = skill_map(_engine(OLD, "a").program, _engine(NEW, "b").program)
    assert dict(m.numbers) == {0: 1} and dict(m.names) == {"never#1": "never#1"}


def test_a_learned_skill_that_no_longer_reads_is_dropped_and_said():
    old = _engine(OLD, "old.tlp")
    state = old.initial_state(learned=("((chores ?x) :percepts ((self ?x)) :actions ((*c)))",))
    carried = carry_state(old, _engine(NEW, "new.tlp"), state)
    assert carried.state.learned == ()
    assert len(carried.dropped) == 1 and carried.dropped[0].startswith(
        "learned skill ((chores ?x) :percepts ((self ?x)) :actions ((*c))): it does not read "
        "against the new program ("), carried.dropped
    kept = carry_state(old, _engine(OLD, "o2.tlp"), state)
    assert kept.state.learned == state.learned and kept.dropped == ()
