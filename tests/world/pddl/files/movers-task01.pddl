; Crate a on pallet pa at place x, crate b on pallet pb at place y; a is to go on pb
; with b on top of it.
(define (problem movers-1) (:domain movers)
  (:objects x y - place t - truck hx hy - hoist pa pb - pallet a b - crate)
  (:init (at t x) (at hx x) (at hy y) (available hx) (available hy)
         (at pa x) (at pb y) (at a x) (at b y) (on a pa) (on b pb) (clear a) (clear b))
  (:goal (and (on b a) (on a pb))))
