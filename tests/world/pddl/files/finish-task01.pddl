; A blue varnished piece to be glazed white.
(define (problem finish-1) (:domain finish)
  (:objects p - piece black blue white - colour)
  (:init (varnished p) (colour p blue))
  (:goal (and (colour p white) (glazed p))))
