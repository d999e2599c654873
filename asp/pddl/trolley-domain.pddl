; The trolley problem of Krarup, Lindner, Krivic and Long (IEEE CASE 2021) in
; PDDL.  A runaway trolley will kill five people on the main track; pulling
; the lever diverts it to a side track, where it will kill one person.
; The moral annotations are in trolley-utility.lp.

(define (domain trolley)
  (:requirements :strips)
  (:predicates (five-will-die) (one-will-die) (done))

  (:action pull
    :parameters ()
    :effect (and (not (five-will-die)) (one-will-die) (done)))

  (:action refrain
    :parameters ()
    :effect (done)))
