; A robot with two grippers moves balls between rooms, written for ethasp.
; Besides carrying a ball, it can throw it through the doorway into another
; room, which is quicker but dangerous when someone is in that room.  The
; moral annotations are in gripper-utility.lp.

(define (domain gripper)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types room ball gripper)
  (:predicates
    (robot-at ?r - room)
    (ball-at ?b - ball ?r - room)
    (free ?g - gripper)
    (carry ?b - ball ?g - gripper)
    (occupied ?r - room)
    (thrown ?b - ball))

  (:action move
    :parameters (?from ?to - room)
    :precondition (and (robot-at ?from) (not (= ?from ?to)))
    :effect (and (robot-at ?to) (not (robot-at ?from))))

  (:action pick
    :parameters (?b - ball ?r - room ?g - gripper)
    :precondition (and (ball-at ?b ?r) (robot-at ?r) (free ?g))
    :effect (and (carry ?b ?g) (not (ball-at ?b ?r)) (not (free ?g))))

  (:action drop
    :parameters (?b - ball ?r - room ?g - gripper)
    :precondition (and (carry ?b ?g) (robot-at ?r))
    :effect (and (ball-at ?b ?r) (free ?g) (not (carry ?b ?g))))

  (:action throw
    :parameters (?b - ball ?from ?to - room ?g - gripper)
    :precondition (and (carry ?b ?g) (robot-at ?from) (not (= ?from ?to)))
    :effect (and (ball-at ?b ?to) (free ?g) (not (carry ?b ?g)) (thrown ?b))))
