; Blocks world with one hand, written for ethasp, with a moral twist: besides
; the four classic actions, the robot can knock a block off the block below
; it onto the table, which saves a step but damages the block.  Some blocks
; are fragile.  The moral annotations are in blocksworld-utility.lp.

(define (domain blocksworld)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types block)
  (:predicates
    (on ?x ?y - block)
    (on-table ?x - block)
    (clear ?x - block)
    (holding ?x - block)
    (hand-busy)
    (fragile ?x - block)
    (damaged ?x - block))

  (:action pick-up
    :parameters (?x - block)
    :precondition (and (clear ?x) (on-table ?x) (not (hand-busy)))
    :effect (and (not (on-table ?x)) (not (clear ?x)) (holding ?x) (hand-busy)))

  (:action put-down
    :parameters (?x - block)
    :precondition (holding ?x)
    :effect (and (not (holding ?x)) (not (hand-busy)) (on-table ?x) (clear ?x)))

  (:action unstack
    :parameters (?x ?y - block)
    :precondition (and (on ?x ?y) (clear ?x) (not (hand-busy)))
    :effect (and (not (on ?x ?y)) (not (clear ?x)) (clear ?y) (holding ?x) (hand-busy)))

  (:action stack
    :parameters (?x ?y - block)
    :precondition (and (holding ?x) (clear ?y) (not (= ?x ?y)))
    :effect (and (not (holding ?x)) (not (hand-busy)) (not (clear ?y)) (on ?x ?y) (clear ?x)))

  (:action knock-off
    :parameters (?x ?y - block)
    :precondition (and (on ?x ?y) (clear ?x) (not (hand-busy)))
    :effect (and (not (on ?x ?y)) (clear ?y) (on-table ?x) (damaged ?x))))
