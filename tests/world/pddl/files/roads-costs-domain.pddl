; A small road domain written with action costs as the IPC since 2008 writes them
; (:action-costs, a cost function, (increase (total-cost) ...)), for tests/world/pddl/test_pddl_costs.py.
; honk changes nothing but the cost: an operator with no add effect, last in the file.
(define (domain roads)
  (:requirements :typing :action-costs)
  (:types place truck)
  (:predicates (at ?t - truck ?p - place) (road ?a ?b - place))
  (:functions (total-cost) - number
              (road-length ?a ?b - place) - number)
  (:action drive
    :parameters (?t - truck ?a ?b - place)
    :precondition (and (at ?t ?a) (road ?a ?b))
    :effect (and (not (at ?t ?a)) (at ?t ?b)
                 (increase (total-cost) (road-length ?a ?b))))
  (:action honk
    :parameters (?t - truck ?a - place)
    :precondition (at ?t ?a)
    :effect (increase (total-cost) 1)))
