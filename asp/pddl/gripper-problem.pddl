; Four balls from room a to room b, where a child is playing.

(define (problem four-balls)
  (:domain gripper)
  (:objects a b - room left right - gripper ball-1 ball-2 ball-3 ball-4 - ball)
  (:init (robot-at a) (free left) (free right) (occupied b)
         (ball-at ball-1 a) (ball-at ball-2 a) (ball-at ball-3 a) (ball-at ball-4 a))
  (:goal (and (ball-at ball-1 b) (ball-at ball-2 b) (ball-at ball-3 b) (ball-at ball-4 b))))
