; A hand-written domain for the problem solver's tests: a piece is finished by glazing or
; varnishing it in a colour, either of which needs it untreated; sanding strips a finish.
; Glazing it white makes it both white and glazed: its being untreated, which glazing it in
; another colour would need, is no longer needed once the way under way (glazing it white)
; is done, so that need is no reason to drop the way.
(define (domain finish)
  (:requirements :strips :typing)
  (:types piece colour)
  (:predicates (untreated ?x - piece) (glazed ?x - piece) (varnished ?x - piece)
               (colour ?x - piece ?c - colour))
  (:action sand-glazed
    :parameters (?x - piece ?c - colour)
    :precondition (and (glazed ?x) (colour ?x ?c))
    :effect (and (untreated ?x) (not (glazed ?x))))
  (:action sand-varnished
    :parameters (?x - piece ?c - colour)
    :precondition (and (varnished ?x) (colour ?x ?c))
    :effect (and (untreated ?x) (not (varnished ?x))))
  (:action glaze
    :parameters (?x - piece ?old ?new - colour)
    :precondition (and (untreated ?x) (colour ?x ?old))
    :effect (and (glazed ?x) (colour ?x ?new) (not (colour ?x ?old)) (not (untreated ?x))))
  (:action varnish
    :parameters (?x - piece ?old ?new - colour)
    :precondition (and (untreated ?x) (colour ?x ?old))
    :effect (and (varnished ?x) (colour ?x ?new) (not (colour ?x ?old))
                 (not (untreated ?x)))))
