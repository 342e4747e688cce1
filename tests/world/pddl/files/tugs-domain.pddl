; A hand-written domain for the problem solver's tests: a plane leaves its gate pushed back
; by a tug (engine off), then starts its engine, which ends the pushing for good, and taxis
; under its own power. Driving is written before pushing, so in program order every place
; is reached by driving; the cheaper way to the apron, from the gate, is being pushed there.
(define (domain tugs)
  (:requirements :strips :typing)
  (:types place)
  (:predicates (at ?p - place) (road ?a ?b - place) (tow ?a ?b - place)
               (pushing) (running) (departed))
  (:action drive
    :parameters (?a ?b - place)
    :precondition (and (at ?a) (road ?a ?b) (running))
    :effect (and (at ?b) (not (at ?a))))
  (:action push
    :parameters (?a ?b - place)
    :precondition (and (pushing) (at ?a) (tow ?a ?b))
    :effect (and (at ?b) (not (at ?a))))
  (:action start
    :parameters ()
    :precondition (and (pushing))
    :effect (and (running) (not (pushing))))
  (:action depart
    :parameters (?p - place)
    :precondition (and (running) (at ?p) (road ?p ?p))
    :effect (and (departed))))
