"""Bad programs get file:line:col messages naming the problem; several errors at once."""

from __future__ import annotations

import re

import pytest

from agents.lang import ProgramError, load_program_text, parse_percepts

GOOD = """
(concepts
  ((fast ?c) :percepts ((car ?c speed ?s)) :tests ((> ?s 10))))
"""


def errors(text: str) -> list[str]:
    with pytest.raises(ProgramError) as info:
        load_program_text(text, "bad.tlp")
    lines = str(info.value).splitlines()
    assert all(re.match(r"^bad\.tlp:\d+:\d+: ", line) for line in lines), lines
    return [line for line in lines if ": warning: " not in line]


def test_a_good_program_has_no_errors():
    program = load_program_text(GOOD, "good.tlp")
    assert program.arity == {"fast": 1} and program.warnings == ()


def test_unclosed_list_points_at_its_opening_parenthesis():
    assert errors("(concepts\n  ((fast ?c) :percepts ((car ?c)))\n") == [
        "bad.tlp:1:1: '(' is never closed (missing ')')"]


def test_unclosed_section_points_at_where_the_next_form_starts():
    text = "(concepts\n  ((fast ?c) :percepts ((car ?c)))\n\n(goals (fast ME))\n"
    assert errors(text) == [
        "bad.tlp:1:1: '(' is never closed (missing ')'; the form starting here seems to end "
        "before line 4, where a new top-level form starts)"]


def test_misspelt_variable_gets_a_suggestion():
    text = GOOD + "(skills ((fast ?c) :percepts ((car ?c speed ?speed)) :actions ((*brake ?sped))))"
    (msg,) = errors(text)
    assert "variable ?sped in action (*brake ?sped) is bound nowhere (did you mean ?speed?)" in msg


def test_stray_closing_parenthesis():
    assert errors(GOOD + ")") == ["bad.tlp:4:1: unexpected ')' with no list open"]


def test_undefined_concept_with_suggestion():
    text = GOOD + "(concepts ((slow ?c) :percepts ((car ?c)) :relations ((not (fsat ?c)))))"
    assert errors(text) == ["bad.tlp:4:60: undefined concept 'fsat' in (not (fsat ?c)) "
                            "(:relations of concept slow#1) (did you mean 'fast'?)"]


def test_arity_mismatch_names_the_definition():
    text = GOOD + "(goals (fast ME 3))"
    assert errors(text) == ["bad.tlp:4:8: (fast ME 3) (goal): concept fast takes 1 argument(s), "
                            "got 2 (defined at bad.tlp:3:4)"]


def test_unbound_variables_in_tests_heads_and_actions():
    text = """(concepts ((fast ?c ?x) :percepts ((car ?c)) :tests ((> ?s 10))))
(skills ((fast ?c ?x) :percepts ((car ?c)) :actions ((*gas ?amount))))"""
    found = errors(text)
    assert "bad.tlp:1:54: variable ?s in test (> ?s 10) of concept (fast ?c ?x) is bound " \
           "nowhere; bind it in :percepts or a positive :relations entry" in found
    assert any(e.startswith("bad.tlp:1:12: variable ?x in head (fast ?c ?x)") for e in found)
    assert any(e.startswith("bad.tlp:2:54: variable ?amount in action (*gas ?amount)")
               for e in found)
    assert len(found) == 3


def test_unstratified_negation_names_the_cycle():
    text = """(concepts
  ((a ?x) :percepts ((o ?x)) :relations ((not (b ?x))))
  ((b ?x) :percepts ((o ?x)) :relations ((c ?x)))
  ((c ?x) :percepts ((o ?x)) :relations ((a ?x))))"""
    (msg,) = errors(text)
    assert msg.startswith("bad.tlp:2:47: negation is not stratified: a -> b -> c -> a")


def test_keywords_operators_and_actions_are_checked_together():
    text = """(concepts ((fast ?c) :percept ((car ?c speed ?s)) :tests ((>> ?s 10))))
(skills ((fast ?c) :percepts ((car ?c)) :actions ((gas 3))))
(skils)"""
    found = errors(text)
    assert any("keyword :percept is not allowed in a concept (did you mean ':percepts'?)" in e
               for e in found)
    assert any("unknown operator '>>'" in e for e in found)
    assert any("action names start with '*' (such as *gas), got gas" in e for e in found)
    assert any("bad.tlp:3:2: unknown section 'skils' (did you mean 'skills'?)" in e
               for e in found)


def test_skill_needs_actions_or_subgoals_and_a_known_head():
    text = GOOD + "(skills ((fast ?c) :percepts ((car ?c))) ((quick ?c) :actions ((*gas 1))))"
    found = errors(text)
    assert any("needs :actions (primitive), :subgoals (nonprimitive) or :body" in e
               for e in found)
    assert any("undefined concept 'quick' in (quick ?c) (head of skill quick#1)" in e
               for e in found)



def test_bad_percepts_are_located():
    with pytest.raises(ProgramError) as info:
        parse_percepts("((street B)\n (self ME speed))", "p.txt")
    assert str(info.value) == "p.txt:2:2: percept (self ME speed): attribute speed has no value"
    with pytest.raises(ProgramError, match=r"p.json:1:1: item 0: percept \['self'\]"):
        parse_percepts('[["self"]]', "p.json")


def test_a_test_written_under_relations_is_explained():
    text = "(concepts ((fast ?c) :percepts ((car ?c speed ?s)) :relations ((> ?s 10))))"
    assert errors(text) == ["bad.tlp:1:64: (> ?s 10) is a test; write it under :tests, not "
                            ":relations"]


def test_inline_tests_in_start_including_negated_ones():
    program = load_program_text(GOOD + """(skills ((fast ?c) :percepts ((car ?c speed ?s))
        :start ((not (> ?s 10)) (< ?s 100)) :actions ((*gas (- 10 ?s)))))""", "ok.tlp")
    (skill,) = program.skills
    assert [str(c) for c in skill.start] == ["(not (> ?s 10))", "(< ?s 100)"]
