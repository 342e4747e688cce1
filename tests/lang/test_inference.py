"""Inference: percept patterns, tests, negation, recursion, several clauses (seed 000, Table 2)."""

from __future__ import annotations

import math

from agents.lang import Engine, load_program_text

OPS = """
(concepts
  ((cmp ?x ?op)
   :percepts ((n ?x v ?v))
   :tests ((< ?v 10) (<= ?v 9) (> ?v -10) (>= ?v -9) (<> ?v 3) (= (abs ?v) (max ?v (- ?v)))
           (= (min 1 2 3) 1) (= (mod 7 3) 1) (= (sqrt 16) 4) (= (* 2 3 4) 24) (= (/ 9 2) 4.5)
           (= (+ 1 2 3) 6) (= (- 10 1 2) 7) (or (= ?v 0) (not (= ?v 0))) (and T 1)))
  ((named ?x) :percepts ((n ?x kind ?k)) :tests ((= ?k FOO)))
  ((ratio ?x) :percepts ((n ?x v ?v)) :tests ((> (/ 1 ?v) 0))))
"""


def beliefs(text: str, percepts: list) -> set[str]:
    engine = Engine(load_program_text(text, "t.tlp"))
    return {str(b) for b in engine.infer(percepts)}


def test_every_operator_in_tests():
    got = beliefs(OPS.replace("?op", "ok"), [["n", "A", "v", 2], ["n", "B", "v", 3],
                                              ["n", "Z", "v", 0], ["n", "K", "kind", "FOO"],
                                              ["n", "L", "kind", "foo"]])
    # B fails (<> ?v 3); K/L have no v; symbols keep case (FOO matches, foo does not);
    # (/ 1 0) makes the ratio test fail instead of raising
    assert got == {"(cmp A ok)", "(cmp Z ok)", "(named K)", "(ratio A)", "(ratio B)"}


def test_negation_with_an_existential_variable(table3):
    text = """(concepts
  ((near ?self ?m) :percepts ((self ?self) (man ?m dist ?d)) :tests ((< ?d 100)))
  ((alone ?self) :percepts ((self ?self)) :relations ((not (near ?self ?anyone)))))"""
    assert "(alone ME)" not in beliefs(text, list(table3))
    assert "(alone ME)" in beliefs(text, [p for p in table3 if p.type != "man"])


def test_recursion_reaches_the_fixpoint():
    text = """(concepts
  ((edge ?a ?b) :percepts ((e ?id from ?a to ?b)))
  ((path ?a ?b) :relations ((edge ?a ?b)))
  ((path ?a ?c) :relations ((edge ?a ?b) (path ?b ?c)))
  ((cyclic ?a) :relations ((path ?a ?a)))
  ((acyclic-node ?a) :percepts ((node ?a)) :relations ((not (cyclic ?a)))))"""
    edges = [["e", f"E{i}", "from", a, "to", b] for i, (a, b) in
             enumerate([("A", "B"), ("B", "C"), ("C", "D"), ("D", "B"), ("X", "A")])]
    nodes = [["node", n] for n in "ABCDX"]
    got = beliefs(text, edges + nodes)
    assert {f"(path X {n})" for n in "ABCD"} <= got
    assert {b for b in got if b.startswith("(cyclic")} == {"(cyclic B)", "(cyclic C)",
                                                          "(cyclic D)"}
    assert {b for b in got if b.startswith("(acyclic")} == {"(acyclic-node A)",
                                                           "(acyclic-node X)"}


def test_clauses_are_alternatives_and_heads_may_hold_constants():
    text = """(concepts
  ((light ?x ON) :percepts ((lamp ?x state 1)))
  ((light ?x OFF) :percepts ((lamp ?x state 0)))
  ((same ?x ?x) :percepts ((lamp ?x))))"""
    got = beliefs(text, [["lamp", "L1", "state", 1], ["lamp", "L2", "state", 0]])
    assert got == {"(light L1 ON)", "(light L2 OFF)", "(same L1 L1)", "(same L2 L2)"}


def test_repeated_variable_in_a_pattern_and_numbers_compare_across_int_and_float():
    text = """(concepts ((square ?s) :percepts ((rect ?s w ?x h ?x))))"""
    got = beliefs(text, [["rect", "R1", "w", 2, "h", 2.0], ["rect", "R2", "w", 2, "h", 3]])
    assert got == {"(square R1)"}
    assert math.isclose(2, 2.0)


def test_beliefs_convert_to_neutral_lists(table3):
    from agents.lang import load_program

    from .conftest import FIX
    engine = Engine(load_program(FIX / "table2_concepts.tlp", FIX / "driving_support.tlp"))
    lists = sorted(b.to_list() for b in engine.infer([p.to_list() for p in table3]))
    assert ["at-street", "ME", "B"] in lists and ["at-desired-speed", "ME"] in lists
