; A hand-written domain for the problem solver's tests: one hoist stacks crates on surfaces
; (pallets and crates) and may put a crate away in a bin instead. To lift a crate from under
; another, the hoist lifts the top one and must put it down again to be free: anywhere but
; back on the crate it cleared (or on the pallet the lower crate is to go on), which would
; undo what the ways below that subgoal hold.
(define (domain hoists)
  (:requirements :strips :typing)
  (:types surface bin hoist - object
          crate - surface)
  (:predicates (on ?c - crate ?s - surface)
               (clear ?s - surface)
               (lifting ?h - hoist ?c - crate)
               (available ?h - hoist)
               (in ?c - crate ?b - bin))
  (:action lift
    :parameters (?h - hoist ?c - crate ?s - surface)
    :precondition (and (available ?h) (on ?c ?s) (clear ?c))
    :effect (and (lifting ?h ?c) (clear ?s) (not (on ?c ?s)) (not (clear ?c))
                 (not (available ?h))))
  (:action drop
    :parameters (?h - hoist ?c - crate ?s - surface)
    :precondition (and (lifting ?h ?c) (clear ?s))
    :effect (and (available ?h) (on ?c ?s) (clear ?c) (not (lifting ?h ?c))
                 (not (clear ?s))))
  (:action stow
    :parameters (?h - hoist ?c - crate ?b - bin)
    :precondition (and (lifting ?h ?c))
    :effect (and (available ?h) (in ?c ?b) (not (lifting ?h ?c)))))
