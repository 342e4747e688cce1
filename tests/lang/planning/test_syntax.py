"""The planner's program sections (agents/lang/planning/syntax.py): operators, requests and
control rules load from the program, seed 003's Table 2 rule nearly verbatim (``?goal`` for
``<goal>``); a mistake is a file:line:col diagnostic naming it, all of them at once."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from agents.lang import ProgramError, load_program, load_program_text
from agents.lang.planning.syntax import ControlRule, OperatorSpec, Travel

from .toy import TOY

ROOT = Path(__file__).resolve().parents[3]
TABLE_2 = """
(control-rules
  (control-rule SELECT-TOP-PRIORITY-AND-COMPATIBLE-GOALS
    (if (and (candidate-goal ?goal)
             (or (ancestor-is-top-priority-goal ?goal)
                 (compatible-with-top-priority-goal ?goal))))
    (then select goal ?goal)))
"""


def errors(text: str) -> list[str]:
    with pytest.raises(ProgramError) as info:
        load_program_text(TOY + text, "bad.tlp")
    lines = [x for x in str(info.value).splitlines() if ": warning: " not in x]
    assert all(re.match(r"^bad\.tlp:\d+:\d+: ", line) for line in lines), lines
    return [line.split(": ", 1)[1] for line in lines]


def test_the_office_program_loads_with_its_operators_requests_and_rules():
    program = load_program(ROOT / "programs" / "office_rogue.tlp")
    ops = program.sections["operators"]
    assert [o.name for o in ops[:4]] == ["goto-pickup-loc", "acquire-item", "goto-deliver-loc",
                                         "deliver-item"]
    assert all(isinstance(o, OperatorSpec) for o in ops) and program.skills == ()
    assert str(ops[0].effects[0]) == "(robot-in-room ?room)"   # the head, first
    rules = program.sections["control-rules"]
    assert [r.name for r in rules if isinstance(r, ControlRule)] == [
        "SELECT-TOP-PRIORITY-AND-COMPATIBLE-GOALS", "LOOK-AT-CLOSEST-CONF-ROOM-FIRST",
        "AVOID-OCCUPIED-CONF-ROOMS"]
    assert [r.detour for r in rules if isinstance(r, Travel)] == [12.0]
    # the planner's own predicates are the program's: a request may name them
    assert {"requester", "deliver-loc", "mtg-scheduled", "room-selected"} <= \
        set(program.arity) - set(program.concepts)


def test_table_2_loads_as_printed_in_the_seed():
    rule = load_program_text(TOY + TABLE_2, "t2.tlp").sections["control-rules"][-1]
    assert (rule.name, rule.verb, rule.kind) == \
        ("SELECT-TOP-PRIORITY-AND-COMPATIBLE-GOALS", "select", "goal")
    assert rule.cond.name == "and" and [c.name for c in rule.cond.args] == ["candidate-goal",
                                                                            "or"]
    # PRODIGY's own variables, <goal>, as the seed prints them, read as ?goal
    angled = load_program_text(TOY + TABLE_2.replace("?goal", "<goal>"), "t2.tlp")
    assert angled.sections["control-rules"][-1] == rule


def test_teleo_check_accepts_the_office_program():
    teleo = str(Path(sys.executable).parent / "teleo")
    done = subprocess.run([teleo, "check", "programs/office_rogue.tlp"], cwd=ROOT,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("programs/office_rogue.tlp: ok")


def test_an_operator_needs_a_name_and_bound_effects():
    assert errors("(operators ((at ?p) :effects ((at ?p)) :actions ((*walk ?p))))") == [
        "operator (at ?p) needs :operator (name ?param ...)"]
    assert errors("(operators ((at ?p) :operator (fly ?p ?q) :effects ((has ?x)) "
                  ":actions ((*fly ?p))))") == [
        "variable ?q in the parameters of operator fly is bound nowhere; bind it in the "
        "head, :percepts or :start",
        "variable ?x in effect (has ?x) of operator fly is bound nowhere; bind it in the "
        "head, :percepts or :start (only a negated effect may leave a variable open: any "
        "value)"]


def test_effects_and_preconditions_must_name_what_exists():
    assert errors("(operators ((at ?p) :operator (fly ?p) :start ((winged)) "
                  ":effects ((at ?p ?p)) :actions ((*fly ?p))))") == [
        "undefined concept 'winged' in (winged) (:start of skill at#1)",
        "(at ?p ?p) (:effects of operator fly): concept at takes 1 argument(s), got 2 "
        "(defined at bad.tlp:3:4)"]


def test_control_rules_are_checked():
    assert errors("(control-rules (control-rule R (if (candidate-operator (fly ?p))) "
                  "(then select operator fly)))") == [
        "control rule R: no operator 'fly' (operators: buy drop take walk)",
        "control rule R: (candidate-operator (fly ?p)): no operator 'fly'"]
    assert errors("(control-rules (control-rule R (if (best-goal ?g)) (then select goal ?g)))")[0] \
        .startswith("expected a meta-predicate (candidate-goal ancestor-is-top-priority-goal")
    assert errors("(control-rules (control-rule R (if (candidate-goal ?g)) "
                  "(then prefer goal ?g)))") == ["control rule R: prefer goal takes 2 "
                                                 "argument(s), got 1"]
    assert errors("(control-rules (control-rule R (if (not (candidate-goal ?g))) "
                  "(then select goal ?g)))") == [
        "variable ?g in the (then ...) of control rule R is bound nowhere; bind it in a "
        "positive condition of (if ...)"]


def test_travel_and_requests_are_checked():
    assert errors("(control-rules (travel :location (at ?p) :between (road ?a to ?b) "
                  ":from-here (place ?p dist ?d)))") == [
        "(travel ...) :between (road ?a to ?b): expected 3 variables (places, then the "
        "distance), got 2"]
    travel = ("(control-rules (travel :location (at ?p) :between (road ?a to ?b length ?d) "
              ":from-here (place ?p dist ?d) {}))")
    assert errors(travel.format(":carrying (has ?x)")) == [
        "(travel ...) :carrying and :capacity go together (what the robot carries, and the "
        "percept that says how much it can)"]
    assert errors(travel.format(":carrying (hass ?x) :capacity (self ?r capacity ?c)")) == [
        "undefined concept 'hass' in (hass ?x) (the :carrying of (travel ...)) (did you mean "
        "'has'?)"]
    assert errors(travel.format(":carrying (has ?x) :capacity (self R1 capacity 4)")) == [
        "(travel ...) :capacity (self R1 capacity 4): expected a variable for how many the "
        "robot can carry (its last one)"]
    ok = load_program_text(TOY.replace(":detour 5))", ":detour 5 :carrying (has ?x) "
                                       ":capacity (self ?r capacity ?c)))"), "ok.tlp")
    rule = next(r for r in ok.sections["control-rules"] if isinstance(r, Travel))
    assert (str(rule.carrying), rule.capacity is not None) == ("(has ?x)", True)
    assert errors("(requests ((has ?x) :knowledge ((owner ?x ?who))))") == [
        "variable ?who in knowledge (owner ?x ?who) is bound nowhere; bind it in the head, "
        ":percepts or :start"]


def test_an_operator_without_commands_is_applied_in_the_planners_model():
    program = load_program_text(TOY + "(operators ((ready) :operator (get-ready)))", "ok.tlp")
    op = program.sections["operators"][-1]
    assert (op.name, op.skill.actions, op.skill.kind) == ("get-ready", (), "primitive")
    assert "ready" in program.arity and "ready" not in program.concepts
