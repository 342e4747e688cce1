; A hand-written domain for the problem solver's tests: hoists (hoists-domain.pddl) whose bin
; has a lid, to be opened before a crate is put away in it. To lift a crate from under
; another, the hoist lifts the top one and must put it down to be free: no one action does
; so without undoing what the ways below hold (back on the crate just cleared, or on the
; pallet the lower crate is to go on), so the subgoal is chained: open the bin, stow it.
(define (domain lids)
  (:requirements :strips :typing :equality)
  (:types surface bin hoist - object
          crate - surface)
  (:predicates (on ?c - crate ?s - surface)
               (clear ?s - surface)
               (lifting ?h - hoist ?c - crate)
               (available ?h - hoist)
               (open ?b - bin)
               (in ?c - crate ?b - bin))
  (:action lift
    :parameters (?h - hoist ?c - crate ?s - surface)
    :precondition (and (available ?h) (on ?c ?s) (clear ?c))
    :effect (and (lifting ?h ?c) (clear ?s) (not (on ?c ?s)) (not (clear ?c))
                 (not (available ?h))))
  (:action drop
    :parameters (?h - hoist ?c - crate ?s - surface)
    :precondition (and (lifting ?h ?c) (clear ?s) (not (= ?c ?s)))
    :effect (and (available ?h) (on ?c ?s) (clear ?c) (not (lifting ?h ?c))
                 (not (clear ?s))))
  (:action unlid
    :parameters (?b - bin)
    :precondition (and)
    :effect (and (open ?b)))
  (:action stow
    :parameters (?h - hoist ?c - crate ?b - bin)
    :precondition (and (lifting ?h ?c) (open ?b))
    :effect (and (available ?h) (in ?c ?b) (not (lifting ?h ?c)))))
