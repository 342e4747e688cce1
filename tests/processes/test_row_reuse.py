"""The inference and executive processes reuse what did not change between cycles: a belief
held last cycle keeps its list (so the codec sends the same bytes and receivers the same
list), and the executive rebuilds its belief set only when a list is new; strictly, so a
belief whose value turns from 3 to 3.0 is sent and read anew."""

from __future__ import annotations

from agents.lang import Engine, SharedRows, load_program_text
from agents.processes.executive import BeliefReader
from agents.processes.inference import BeliefRows

PROGRAM = load_program_text("(concepts ((value ?x ?v) :percepts ((obj ?x v ?v)))"
                            " ((seen ?x) :percepts ((obj ?x))))", "reuse.tlp")


def test_beliefs_held_last_cycle_keep_their_lists_and_a_new_type_is_a_new_list():
    engine, rows = Engine(PROGRAM), BeliefRows()
    first = rows.of(engine.infer(SharedRows([["obj", "A", "v", 3], ["obj", "B", "v", 1]])))
    assert first == (["seen", "A"], ["seen", "B"], ["value", "A", 3], ["value", "B", 1])
    same = rows.of(engine.infer(SharedRows([["obj", "A", "v", 3], ["obj", "B", "v", 1]])))
    assert same is first
    third = rows.of(engine.infer(SharedRows([["obj", "A", "v", 3.0], ["obj", "B", "v", 1]])))
    assert [repr(r) for r in third] == ["['seen', 'A']", "['seen', 'B']", "['value', 'A', 3.0]",
                                        "['value', 'B', 1]"]
    assert third[0] is first[0] and third[3] is first[3] and third[2] is not first[2]


def test_the_executive_reads_a_belief_set_anew_only_when_a_list_is_new():
    reader = BeliefReader()
    lists = (["seen", "A"], ["value", "A", 3])
    first = reader.read(lists)
    assert reader.read(tuple(lists)) is first
    changed = reader.read((lists[0], ["value", "A", 3.0]))
    assert changed is not first and changed == first  # equal to ==, yet another value
    assert {str(b) for b in changed} == {"(seen A)", "(value A 3.0)"}
    assert {str(b) for b in first} == {"(seen A)", "(value A 3)"}
