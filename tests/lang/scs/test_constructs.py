"""Each construct of seed 002, Appendix C, driven cycle by cycle with forced outcomes. A trace
lists each cycle's actions ('-': none); one atomic step per cycle, and a step's success or
failure is known the cycle after it was issued, when the world reports its outcome."""

from __future__ import annotations

from collections import Counter

from tests.lang.scs.drive import Driver, body_program, failing


def trace(body: str, n: int, policy=None, seed: int = 0, flags=(), extra: str = "") -> list:
    d = Driver(body_program(body, extra), seed, **({"policy": policy} if policy else {}))
    return d.run(n, flags)


# -- atomic actions and atomic groups ------------------------------------------------------
def test_an_atomic_action_succeeds_when_the_world_reports_it_done():
    """'An action returns either success or failure and so does the step': a body that
    succeeds while its goal is still false starts again (as a T-R program keeps acting)."""
    assert trace("(do (*a) (*b))", 5) == ["a", "b", "a", "b", "a"]


def test_a_failed_action_fails_the_do_and_the_body_is_passed_over():
    d = Driver(body_program("(do (*a) (*b))"), policy=failing("a", times=1))
    assert d.run(2) == ["a", "-"]
    assert any("body failed: (*a) failed: forced failure" in w for w in d.why())
    assert d.result.decision.goals[0].status.value == "impasse"
    assert d.run(2) == ["a", "b"]   # given up, the skill is entered afresh


def test_an_atomic_group_acts_in_one_cycle_and_fails_if_any_action_fails():
    assert trace("(do (atomic (*a) (*b)) (*c))", 3) == ["a+b", "c", "a+b"]
    d = Driver(body_program("(do (atomic (*a) (*b)) (*c))"), policy=failing("b", times=1))
    assert d.run(2) == ["a+b", "-"]
    assert any("(*a) (*b) failed: forced failure" in w for w in d.why())


def test_an_action_argument_is_evaluated_under_the_bindings():
    assert trace("(do (*a (+ 1 2)) (*b ?x))", 2) == ["a 3", "b ME"]


# -- do and do* ----------------------------------------------------------------------------
def test_do_runs_its_steps_in_order_and_fails_as_soon_as_one_fails():
    assert trace("(do (*a) (*b) (*c))", 3) == ["a", "b", "c"]
    assert trace("(do (*a) (*b) (*c))", 4, failing("b", times=1)) == ["a", "b", "-", "a"]


def test_do_star_retries_a_failed_step_until_it_succeeds_and_never_fails():
    """'do* ... whenever a substep fails, it retries that substep until it succeeds'."""
    assert trace("(do* (*a) (*b) (*c))", 6, failing("b", times=2)) == \
        ["a", "b", "b", "b", "c", "a"]
    d = Driver(body_program("(do* (*a) (*b))"), policy=failing("b"))
    assert d.run(6) == ["a", "b", "b", "b", "b", "b"]
    assert d.scs["threads"][0]["stack"][0]["state"] == "[step 2 of 2, retries 4]"


# -- do-all and do*-all --------------------------------------------------------------------
def test_do_all_does_every_step_once_in_a_seeded_nondeterministic_order():
    orders = {tuple(trace("(do-all (*a) (*b) (*c))", 3, seed=s)) for s in range(12)}
    assert all(sorted(o) == ["a", "b", "c"] for o in orders)
    assert len(orders) > 1                                   # not a fixed order
    assert trace("(do-all (*a) (*b) (*c))", 3, seed=5) == \
        trace("(do-all (*a) (*b) (*c))", 3, seed=5)         # the same seed, the same order


def test_do_all_fails_immediately_when_one_step_fails():
    for seed in range(6):
        t = trace("(do-all (*a) (*b) (*c))", 4, failing("a", times=1), seed=seed)
        first_a = t.index("a")
        assert t[first_a + 1] == "-"                          # the do-all failed at once


def test_do_star_all_retries_failed_steps_until_all_have_succeeded():
    for seed in range(6):
        t = trace("(do*-all (*a) (*b) (*c))", 5, failing("a", times=2), seed=seed)
        assert Counter(t) == Counter({"a": 3, "b": 1, "c": 1})


# -- do-any and do*-any --------------------------------------------------------------------
def test_do_any_does_one_step_chosen_nondeterministically():
    firsts = {trace("(do-any (*a) (*b) (*c))", 1, seed=s)[0] for s in range(12)}
    assert firsts == {"a", "b", "c"}
    assert trace("(do (do-any (*a) (*b)) (*e))", 2, seed=1)[1] == "e"   # one is enough


def test_do_any_tries_the_others_after_a_failure_and_fails_when_all_failed():
    t = trace("(do (do-any (*a) (*b) (*c)) (*e))", 4, failing("a", "b", "c"), seed=3)
    assert sorted(t[:3]) == ["a", "b", "c"] and t[3] == "-"   # each once, then the do failed
    for seed in range(4):
        ok = trace("(do (do-any (*a) (*b)) (*e))", 3, failing("a"), seed=seed)
        assert ok[ok.index("b") + 1] == "e" and "-" not in ok


def test_do_star_any_keeps_trying_failed_steps_too():
    t = trace("(do (do*-any (*a) (*b)) (*e))", 12, failing("a", "b", times=3), seed=2)
    assert "e" in t and "-" not in t                          # never failed
    before = t[:t.index("e")]                                 # the 4th try of one succeeded
    assert before.count(before[-1]) == 4 and len(before) >= 4


# -- do-first and do*-first ----------------------------------------------------------------
FIRST = "(do-first (((flag x)) (*a)) (((flag y)) (*b)) (() (*c)))"


def test_do_first_runs_the_step_of_the_first_true_condition_like_a_tr_program():
    flags = [["x", "y"], ["y"], ["y"], [], ["x"]]
    assert trace(FIRST, 5, flags=lambda k: flags[k]) == ["a", "b", "b", "c", "a"]


def test_do_first_rechecks_its_conditions_and_switches_with_a_new_choice():
    """A change of the first true condition abandons the running step: 'new choices of
    action at that level and those below are made'."""
    body = "(do-first (((flag x)) (do (*a) (*b) (*c))) (() (*d)))"
    flags = [["x"], ["x"], [], ["x"], ["x"]]
    assert trace(body, 5, flags=lambda k: flags[k]) == ["a", "b", "d", "a", "b"]


def test_do_first_fails_when_its_step_fails_and_do_star_first_retries():
    assert trace("(do (do-first (() (*a))) (*e))", 3, failing("a", times=1)) == ["a", "-", "a"]
    assert trace("(do (do*-first (() (*a))) (*e))", 4, failing("a", times=2)) == \
        ["a", "a", "a", "e"]


def test_do_first_with_no_true_condition_is_inactive_not_failed():
    flags = [[], [], ["y"]]
    d = Driver(body_program("(do-first (((flag x)) (*a)) (((flag y)) (*b)))"))
    assert d.run(3, lambda k: flags[k]) == ["-", "-", "b"]


def test_do_first_binds_its_condition_variables_for_its_step():
    extra = "(concepts ((target ?t) :percepts ((target ?t))))"
    d = Driver(body_program("(do-first (((target ?t)) (*a ?t)))", extra))
    assert d.step(extra=[["target", "T7"]]) == [["*a", "T7"]]


# -- do-best and do*-best ------------------------------------------------------------------
BEST = "(do-best (() :utility 3 (*a)) (((flag y)) :utility 9 (*b)) (() :utility (+ 2 4) (*c)))"


def test_do_best_picks_the_true_alternative_with_the_highest_utility():
    assert trace(BEST, 1, flags=["y"]) == ["b"]
    assert trace(BEST, 1) == ["c"]                            # (flag y) false: not a bidder


def test_do_best_breaks_ties_by_do_any_rules():
    tie = "(do-best (() :utility 5 (*a)) (() :utility 5 (*b)) (() :utility 1 (*c)))"
    firsts = {trace(tie, 1, seed=s)[0] for s in range(12)}
    assert firsts == {"a", "b"}


def test_do_best_fails_over_like_do_any_and_do_star_best_persists():
    body = "(do (do-best (() :utility 9 (*a)) (() :utility 5 (*b))) (*e))"
    assert trace(body, 3, failing("a", times=1)) == ["a", "b", "e"]
    assert trace(body, 3, failing("a", "b")) == ["a", "b", "-"]
    star = "(do (do*-best (() :utility 9 (*a)) (() :utility 5 (*b))) (*e))"
    t = trace(star, 8, failing("a", "b", times=2))
    assert "-" not in t and t[-1] in ("e", "a")


def test_do_best_failure_is_decided_in_the_same_cycle_as_do_any():
    """Seed 002, Appendix C: do-best's "failure semantics is the same as that of the do any
    construct": when the chosen alternative fails, the next true alternative runs in that
    cycle; with no other true alternative the do-best fails in that cycle, so the construct
    around it goes on at once (it does not wait, inactive, for another condition)."""
    body = "(do (do-best (() :utility 9 (*a)) (((flag y)) :utility 5 (*b))) (*e))"
    assert trace(body, 3, failing("a", times=1), flags=["y"]) == ["a", "b", "e"]
    d = Driver(body_program(body), policy=failing("a", times=1))
    assert d.run(2) == ["a", "-"]                     # the do fails with it: nothing to send
    assert any("(*a) failed and no other alternative's condition holds" in w
               for w in d.why())
    around = "(do-any (do-best (() :utility 9 (*a)) (((flag y)) :utility 5 (*b))) (*e))"
    for seed in range(6):
        t = trace(around, 6, failing("a"), seed=seed)
        assert "-" not in t and "a" in t[:-1]
        assert all(t[k + 1] == "e" for k in range(5) if t[k] == "a")   # the same cycle
    star = "(do* (do-best (() :utility 9 (*a)) (((flag y)) :utility 5 (*b))) (*e))"
    assert trace(star, 3, failing("a", times=1)) == ["a", "a", "e"]


def test_do_best_utility_uses_the_alternative_bindings():
    extra = "(concepts ((cost ?c) :percepts ((cost ?c))))"
    body = "(do-best (((cost ?k)) :utility (- 10 ?k) (*a ?k)) (() :utility 6 (*b)))"
    d = Driver(body_program(body, extra))
    assert d.step(extra=[["cost", 3]]) == [["*a", 3]]
    d = Driver(body_program(body, extra))
    assert d.step(extra=[["cost", 5]]) == [["*b"]]


# -- repeat and repeat* --------------------------------------------------------------------
def test_repeat_executes_its_steps_again_and_again_until_one_fails():
    assert trace("(repeat (*a) (*b))", 5) == ["a", "b", "a", "b", "a"]
    d = Driver(body_program("(do (repeat (*a) (*b)) (*e))"), policy=failing("b", times=1))
    assert d.run(3) == ["a", "b", "-"]
    assert d.result.decision.to_dict()["scs"]["tally"]["bodies failed"] == 1


def test_repeat_star_retries_and_counts_rounds():
    d = Driver(body_program("(repeat* (*a) (*b))"), policy=failing("a", times=1))
    assert d.run(6) == ["a", "a", "b", "a", "b", "a"]
    assert d.scs["threads"][0]["stack"][0]["state"] == "[step 1 of 2, round 3, retries 1]"


def test_a_round_without_any_action_waits_for_the_next_cycle():
    d = Driver(body_program("(repeat (assert (tick ME)))"))
    assert d.run(3) == ["-", "-", "-"]
    assert d.scs["threads"][0]["note"].startswith("(repeat) round")


# -- subgoals --------------------------------------------------------------------------------
SUB = """(concepts ((raised ?f) :percepts ((flag ?f))))
(skills ((raised ?f) :start ((flag go)) :actions ((*d ?f))))"""


def test_a_subgoal_acts_through_the_skill_hierarchy_and_succeeds_when_it_holds():
    flags = [["go"], ["go"], ["go", "up"], ["go", "up"]]
    d = Driver(body_program("(do (raised up) (*e))", SUB))
    assert d.run(4, lambda k: flags[k]) == ["d up", "d up", "e", "e"]
    path = d.result.decision.paths
    assert path == () or path[0].steps[0].skill == "never#1"


def test_a_subgoal_with_no_executable_path_fails():
    d = Driver(body_program("(do (raised up) (*e))", SUB))
    assert d.run(1) == ["-"]                                  # (flag go) false: no path
    assert any("subgoal (raised up) has no executable path" in w for w in d.why())
    assert trace("(do* (raised up) (*e))", 3, extra=SUB, flags=lambda k: ["go"] * (k > 1)) \
        == ["-", "-", "d up"]                                 # do* retries it each cycle


def test_a_chosen_alternative_keeps_what_its_step_reads_and_rematches_the_rest():
    """The distance ?d changes every cycle; the step reads only ?t, so the alternative stays
    chosen while (near T1 ?d) holds for some ?d, and is abandoned when T1 is out of sight."""
    extra = "(concepts ((near ?t ?d) :percepts ((target ?t dist ?d))))"
    body = ("(do-best (((near ?t ?d)) :utility (- 100 ?d) (do (*a ?t) (*b ?t) (*e ?t)))"
            " (() :utility 1 (*c)))")
    d = Driver(body_program(body, extra))
    seen = [d.step(extra=[["target", "T1", "dist", 10 - k]]) for k in range(2)]
    seen.append(d.step())
    assert seen == [[["*a", "T1"]], [["*b", "T1"]], [["*c"]]]


def test_a_step_that_has_just_ended_ends_its_alternative_though_the_condition_failed():
    """'Whenever an atomic action is finished, the stack of conditions is checked': the
    finished action's result comes first. Delivering makes (carrying P) false; the do-best
    alternative ends with success (and the fact is asserted), it is not abandoned."""
    extra = "(concepts ((carrying ?p) :percepts ((parcel ?p))))"
    body = ("(do (do-best (((carrying ?p)) :utility 5 (do (*a ?p) (assert (served ?p)))))"
            " (*e))")
    d = Driver(body_program(body, extra))
    assert d.step(extra=[["parcel", "P1"]]) == [["*a", "P1"]]
    assert d.step() == [["*e"]]                    # P1 gone: the alternative ended
    assert d.state.scs.model == (("served", "P1"),)
    assert d.scs["choices"][0]["succeeded"] == 1


def test_a_program_lists_the_actions_its_bodies_can_send():
    # what `teleo check SCENARIO` holds against the world's actions
    # (tools/commands/scenario_check.py)
    engine = body_program("(do (atomic (*a 1) (assert (mark ?x))) (do-any (*b) (*c ?x)))")
    assert [str(a) for a in engine.program.actions()] == ["(*a 1)", "(*b)", "(*c ?x)"]


def test_an_action_that_lasts_several_cycles_is_sent_again_until_its_outcome_comes():
    """Seed 002, Appendix C: an atomic action "is guaranteed to terminate within a bounded
    time and cannot be interrupted". The office world reports an operation's outcome when
    it ends (a *goto lasts until arrival), and sending it again continues it: the body waits
    for each outcome instead of failing the action a cycle after it was sent."""
    engine = body_program("(do (*a) (*b))")
    state, outcomes, sent, running = engine.initial_state(seed=0), [], [], None
    for _ in range(7):
        result = engine.cycle(state, [["self", "ME"]], outcomes)
        state, acts = result.state, [a.to_list() for a in result.decision.actions]
        sent.append(acts[0][0] if acts else "-")
        outcomes = []
        if acts and acts[0] != (running or [None])[0]:
            running = [acts[0], 3]            # a new operation, three cycles long
        if running is not None:
            running[1] -= 1
            if running[1] == 0:
                outcomes, running = [{"action": running[0], "status": "done"}], None
    # a, b, then (the body succeeded, its goal still unmet) the skill entered afresh
    assert sent == ["*a", "*a", "*a", "*b", "*b", "*b", "*a"]
    tally = result.decision.section("scs").to_dict()["tally"]
    assert tally.get("actions done") == 2 and "actions failed" not in tally, tally
