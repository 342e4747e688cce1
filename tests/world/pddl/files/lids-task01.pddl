; Crate a under crate b on pallet p1, the bin shut; a is to go on pallet p2, b anywhere.
(define (problem lids-1) (:domain lids)
  (:objects h - hoist a b - crate p1 p2 - surface bin1 - bin)
  (:init (available h) (on a p1) (on b a) (clear b) (clear p2))
  (:goal (and (on a p2))))
