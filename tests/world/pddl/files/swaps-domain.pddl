; A hand-written domain for the problem solver's tests: items sit on bays; two items on linked
; bays swap places, and swapping them at an inspection link also checks the first. Every item
; is to be checked and back on its own bay, so each check moves items that other conjuncts
; want where they are (the livelock the solver's agenda once fell into: every conjunct it
; orders first given up after a circle, the search fell back on one the agenda leaves out,
; which the agenda then dropped, every cycle, acting never).
(define (domain swaps)
  (:requirements :strips :typing)
  (:types item bay)
  (:predicates (on ?x - item ?b - bay)
               (checked ?x - item)
               (link ?a ?b - bay)
               (inspection ?a ?b - bay))
  (:action inspect
    :parameters (?a ?b - bay ?x ?y - item)
    :precondition (and (inspection ?a ?b) (on ?x ?a) (on ?y ?b))
    :effect (and (not (on ?x ?a)) (not (on ?y ?b)) (on ?x ?b) (on ?y ?a) (checked ?x)))
  (:action swap
    :parameters (?a ?b - bay ?x ?y - item)
    :precondition (and (link ?a ?b) (on ?x ?a) (on ?y ?b))
    :effect (and (not (on ?x ?a)) (not (on ?y ?b)) (on ?x ?b) (on ?y ?a))))
