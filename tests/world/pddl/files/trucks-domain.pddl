; A hand-written domain for the pddl world's tests: a type hierarchy, `either`, constants,
; equality and negative preconditions.
(define (domain trucks)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types vehicle place - object
          truck van - vehicle
          parcel)
  (:constants depot - place)
  (:predicates (at ?v - vehicle ?p - place)
               (parcel-at ?x - parcel ?p - place)
               (in ?x - parcel ?v - vehicle)
               (broken ?v - vehicle)
               (link ?a - place ?b - place)
               (ready))
  (:action drive
    :parameters (?v - vehicle ?from - place ?to - place)
    :precondition (and (at ?v ?from) (link ?from ?to) (not (= ?from ?to)) (not (broken ?v)))
    :effect (and (at ?v ?to) (not (at ?v ?from))))
  (:action load
    :parameters (?x - parcel ?v - (either truck van) ?p - place)
    :precondition (and (parcel-at ?x ?p) (at ?v ?p))
    :effect (and (in ?x ?v) (not (parcel-at ?x ?p))))
  (:action unload
    :parameters (?x - parcel ?v - vehicle ?p - place)
    :precondition (and (in ?x ?v) (at ?v ?p))
    :effect (and (parcel-at ?x ?p) (not (in ?x ?v))))
  (:action service
    :parameters (?v - vehicle)
    :precondition (and (at ?v depot) (broken ?v))
    :effect (and (not (broken ?v)) (ready)))
  (:action stay
    :parameters (?v - vehicle ?p - place)
    :precondition (and (at ?v ?p) (= ?p depot))
    :effect (ready)))
