; Reverse a tower of four blocks; the glass block b is fragile.

(define (problem reverse-four)
  (:domain blocksworld)
  (:objects a b c d - block)
  (:init (on-table a) (on b a) (on c b) (on d c) (clear d) (fragile b))
  (:goal (and (on a b) (on b c) (on c d))))
