; Four bays on the left, three on the right, each left bay linked to each right one.
(define (problem swaps-4-3) (:domain swaps)
  (:objects xl1 xl2 xl3 xl4 xr1 xr2 xr3 - item l1 l2 l3 l4 r1 r2 r3 - bay)
  (:init (link l1 r1) (inspection l1 r1) (link l1 r2) (inspection l1 r2) (link l1 r3) (inspection l1 r3) (link l2 r1) (inspection l2 r1) (link l2 r2) (inspection l2 r2) (link l2 r3) (inspection l2 r3) (link l3 r1) (inspection l3 r1) (link l3 r2) (inspection l3 r2) (link l3 r3) (inspection l3 r3) (link l4 r1) (inspection l4 r1) (link l4 r2) (inspection l4 r2) (link l4 r3) (inspection l4 r3)
         (on xl1 l1) (on xl2 l2) (on xl3 l3) (on xl4 l4) (on xr1 r1) (on xr2 r2) (on xr3 r3))
  (:goal (and (checked xl1) (checked xl2) (checked xl3) (checked xl4) (checked xr1) (checked xr2) (checked xr3) (on xl1 l1) (on xl2 l2) (on xl3 l3) (on xl4 l4) (on xr1 r1) (on xr2 r2) (on xr3 r3))))
