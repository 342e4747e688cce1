"""The modifiers of seed 002, Appendix C, and the condition stack: ':while K0 specifies the
energizing condition ... if the energizing condition is not satisfied, the step does not
fail, but just becomes deactivated'; ':until K0 is shorthand for while not K0'; ':when K0 ...
is only checked before execution'; ':unless K0 is shorthand for when not K0'; nested
conditions 'are dynamically stacked ... checked from top to bottom (top conditions are the
outmost conditions in the nested constructs)'."""

from __future__ import annotations

from tests.lang.scs.drive import Driver, body_program, failing


def run(body: str, flags: list, policy=None, extra: str = "") -> tuple[list, Driver]:
    d = Driver(body_program(body, extra), **({"policy": policy} if policy else {}))
    return d.run(len(flags), lambda k: flags[k]), d


def test_while_false_deactivates_the_step_which_continues_where_it_was():
    t, d = run("(do :while ((flag go)) (*a) (*b) (*c))",
               [["go"], ["go"], [], [], ["go"], ["go"]])
    assert t == ["a", "b", "-", "-", "c", "a"]
    assert "bodies failed" not in d.scs["tally"]               # inactive is not failure


def test_an_inactive_thread_shows_why_and_its_goal_waits():
    _, d = run("(do :while ((flag go)) (*a) (*b))", [["go"], []])
    thread = d.scs["threads"][0]
    assert thread["status"] == "inactive"
    assert thread["note"] == "(do :while ((flag go))) is false: inactive"
    assert d.result.decision.goals[0].status.value == "suspended"


def test_until_is_while_not():
    t, _ = run("(do :until ((flag stop)) (*a) (*b) (*c))", [[], ["stop"], ["stop"], [], []])
    assert t == ["a", "-", "-", "b", "c"]


def test_when_is_checked_only_before_the_step_starts():
    body = "(do (do :when ((flag go)) (*a) (*b)) (*e))"
    t, d = run(body, [["go"], [], [], []])
    assert t == ["a", "b", "e", "-"]                          # go vanished after the start
    assert any(":when ((flag go))) is false" in w for w in d.why())


def test_when_false_before_the_start_fails_the_step_and_do_star_retries_it():
    t, _ = run("(do (do :when ((flag go)) (*a)) (*e))", [[], []])
    assert t == ["-", "-"]
    t, _ = run("(do* (do :when ((flag go)) (*a)) (*e))", [[], [], ["go"], ["go"]])
    assert t == ["-", "-", "a", "e"]


def test_unless_is_when_not():
    t, _ = run("(do (do :unless ((flag busy)) (*a)) (*e))", [["busy"], [], []])
    assert t == ["-", "a", "e"]


def test_when_binds_variables_for_the_steps_inside():
    extra = "(concepts ((target ?t) :percepts ((target ?t))))"
    d = Driver(body_program("(do :when ((target ?t)) (*a ?t) (*b ?t))", extra))
    assert d.step(extra=[["target", "T1"]]) == [["*a", "T1"]]
    assert d.step(extra=[["target", "T2"]]) == [["*b", "T1"]]   # kept once started


def test_conditions_are_checked_outermost_first():
    """The outer :while deactivates the body although the inner do-first could choose."""
    body = "(do :while ((flag go)) (do-first (((flag x)) (*a)) (() (*b))))"
    t, d = run(body, [["go", "x"], ["x"], ["go"]])
    assert t == ["a", "-", "b"]


def test_a_failing_inner_condition_makes_new_choices_at_its_level_and_below_only():
    """Inside (repeat ...), the do-first switches branch when its first true condition
    changes, abandoning the inner do (which would go on with (*c)), while the outer repeat
    keeps its round and position. When x comes back, (*d) has just been done: that ends
    the do-first (a finished step's result comes first), so the repeat goes on to (*e)."""
    body = "(repeat (*e) (do-first (((flag x)) (do (*a) (*b) (*c))) (() (*d))))"
    t, d = run(body, [["x"]] * 3 + [[]] + [["x"]] * 4)
    assert t == ["e", "a", "b", "d", "e", "a", "b", "c"]


def test_while_on_a_starred_construct_with_failures():
    """do* :while K: persistent while K holds, inactive (not retried) while it does not."""
    t, _ = run("(do* :while ((flag go)) (*a) (*b))",
               [["go"], ["go"], [], ["go"], ["go"]], failing("a", times=1))
    assert t == ["a", "a", "-", "b", "a"]
