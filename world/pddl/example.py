"""The problem a pddl scenario runs when its `[world]` names no files: the Sussman anomaly in
the four-operator Blocks World of the IPC (C on A, A and B on the table; the goal A on B on
C), so that `[world] domain = "pddl"` alone is a world (docs/pddl.md)."""

from __future__ import annotations

DOMAIN_NAME = "<example blocks domain>"
PROBLEM_NAME = "<example sussman problem>"

DOMAIN = """\
(define (domain blocks)
  (:requirements :strips :typing)
  (:types block)
  (:predicates (on ?x - block ?y - block) (ontable ?x - block) (clear ?x - block)
               (handempty) (holding ?x - block))
  (:action pick-up :parameters (?x - block)
    :precondition (and (clear ?x) (ontable ?x) (handempty))
    :effect (and (not (ontable ?x)) (not (clear ?x)) (not (handempty)) (holding ?x)))
  (:action put-down :parameters (?x - block)
    :precondition (holding ?x)
    :effect (and (not (holding ?x)) (clear ?x) (handempty) (ontable ?x)))
  (:action stack :parameters (?x - block ?y - block)
    :precondition (and (holding ?x) (clear ?y))
    :effect (and (not (holding ?x)) (not (clear ?y)) (clear ?x) (handempty) (on ?x ?y)))
  (:action unstack :parameters (?x - block ?y - block)
    :precondition (and (on ?x ?y) (clear ?x) (handempty))
    :effect (and (holding ?x) (clear ?y) (not (clear ?x)) (not (handempty))
                 (not (on ?x ?y)))))
"""

PROBLEM = """\
(define (problem sussman) (:domain blocks)
  (:objects a b c - block)
  (:init (clear c) (clear b) (on c a) (ontable a) (ontable b) (handempty))
  (:goal (and (on a b) (on b c))))
"""
