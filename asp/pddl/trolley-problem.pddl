; The trolley dilemma: five will die unless someone acts.

(define (problem dilemma)
  (:domain trolley)
  (:init (five-will-die))
  (:goal (done)))
