; The runway is reached by road from the apron (and the hangar); the apron by tow from the
; gate by way of the stand, or by road from the hangar, which only the runway leads to.
(define (problem tugs-1) (:domain tugs)
  (:objects gate stand apron hangar runway - place)
  (:init (at gate) (pushing) (tow gate stand) (tow stand apron) (road apron runway)
         (road runway hangar) (road hangar apron) (road hangar runway) (road runway runway))
  (:goal (and (departed))))
