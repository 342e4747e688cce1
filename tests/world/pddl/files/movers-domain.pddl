; A hand-written domain for the problem solver's tests: hoists at places stack crates on
; surfaces (pallets and crates) and load them into trucks that drive between places. A crate
; in a hoist is at no place; put down, it is at the hoist's place.
(define (domain movers)
  (:requirements :strips :typing)
  (:types place truck hoist surface - object
          pallet crate - surface)
  (:predicates (at ?x - object ?p - place)
               (on ?c - crate ?s - surface)
               (clear ?s - surface)
               (lifting ?h - hoist ?c - crate)
               (available ?h - hoist)
               (in ?c - crate ?t - truck))
  (:action drive
    :parameters (?t - truck ?from ?to - place)
    :precondition (and (at ?t ?from))
    :effect (and (at ?t ?to) (not (at ?t ?from))))
  (:action lift
    :parameters (?h - hoist ?c - crate ?s - surface ?p - place)
    :precondition (and (at ?h ?p) (available ?h) (at ?c ?p) (on ?c ?s) (clear ?c))
    :effect (and (lifting ?h ?c) (clear ?s) (not (at ?c ?p)) (not (on ?c ?s))
                 (not (clear ?c)) (not (available ?h))))
  (:action drop
    :parameters (?h - hoist ?c - crate ?s - surface ?p - place)
    :precondition (and (at ?h ?p) (at ?s ?p) (clear ?s) (lifting ?h ?c))
    :effect (and (available ?h) (at ?c ?p) (on ?c ?s) (clear ?c) (not (lifting ?h ?c))
                 (not (clear ?s))))
  (:action load
    :parameters (?h - hoist ?c - crate ?t - truck ?p - place)
    :precondition (and (at ?h ?p) (at ?t ?p) (lifting ?h ?c))
    :effect (and (in ?c ?t) (available ?h) (not (lifting ?h ?c))))
  (:action unload
    :parameters (?h - hoist ?c - crate ?t - truck ?p - place)
    :precondition (and (at ?h ?p) (at ?t ?p) (available ?h) (in ?c ?t))
    :effect (and (lifting ?h ?c) (not (in ?c ?t)) (not (available ?h)))))
