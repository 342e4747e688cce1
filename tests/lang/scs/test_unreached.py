"""Steps of a body after the assert that achieves its goal never run (issue 31, N19): the
body ends once its goal holds, and `teleo check` says which steps are cut off."""

from __future__ import annotations

from agents.lang import Engine, load_program_text
from tests.lang.scs.drive import PRELUDE, Driver

BODY = ("(do (*a) (do-first ((flag f) (do (*b) (assert (done ?x)))) "
        "(() (do (*c) (assert (done ?x))))) (*d) (*e))")


def program(body: str, extra: str = ""):
    return load_program_text(PRELUDE + extra + f"(skills ((done ?x) :percepts ((self ?x))\n"
                             f" :body {body}))\n(goals (done ME))\n", "t.tlp")


def test_the_steps_cut_off_by_an_assert_of_the_goal_are_named_and_indeed_never_run():
    prog = program(BODY)
    warned = [str(w) for w in prog.warnings]
    assert len(warned) == 2   # one per assert of (done ?x)
    assert all("steps after it never run: (*e) " in w and "(done ?x)" in w for w in warned)
    d = Driver(Engine(prog, solver=None))
    assert d.run(5) == ["a", "c", "d", "-", "-"]   # (*d) in the assert's cycle, (*e) never
    assert "bodies ended: goal achieved 1" in d.result.decision.explain()


def test_no_warning_where_nothing_follows_or_another_fact_is_asserted():
    assert program("(do (*a) (assert (done ?x)) (*b))").warnings == ()
    assert program("(do (*a) (assert (seen ?x)) (*b) (*c))",
                   "(concepts ((done ?x) :percepts ((done ?x))))").warnings == ()
    found = [str(w) for w in program("(do (atomic (*a) (assert (done ?x))) (*b))").warnings]
    assert len(found) == 1 and "never run: (*b) " in found[0]
