; A care robot in a home brings a patient her medicine.  Her own pills are in
; the store room, far away; the short way there passes a bedroom where
; someone sleeps, and entering it wakes the sleeper.  Another patient's pills
; of the same drug are close at hand, but giving them away leaves him without.
; The moral annotations are in care-utility.lp.

(define (domain care)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types room person medicine)
  (:predicates
    (robot-at ?r - room)
    (door ?a ?b - room)
    (sleeping-in ?r - room)          ; someone sleeps in room ?r
    (sleeps ?p - person ?r - room)
    (woken ?p - person)
    (medicine-at ?m - medicine ?r - room)
    (holding ?m - medicine)
    (hands-full)
    (person-at ?p - person ?r - room)
    (prescribed ?m - medicine ?p - person)
    (same-drug ?m ?n - medicine)
    (treated ?p - person)
    (deprived ?p - person))

  ; Moving between rooms; the robot does not enter a room where someone sleeps.
  (:action move
    :parameters (?from ?to - room)
    :precondition (and (robot-at ?from) (door ?from ?to) (not (= ?from ?to))
                       (not (sleeping-in ?to)))
    :effect (and (not (robot-at ?from)) (robot-at ?to)))

  ; Entering a bedroom anyway wakes the sleeper.
  (:action enter-bedroom
    :parameters (?from ?to - room ?p - person)
    :precondition (and (robot-at ?from) (door ?from ?to) (sleeps ?p ?to))
    :effect (and (not (robot-at ?from)) (robot-at ?to) (woken ?p)))

  (:action pick-up
    :parameters (?m - medicine ?r - room)
    :precondition (and (robot-at ?r) (medicine-at ?m ?r) (not (hands-full)))
    :effect (and (not (medicine-at ?m ?r)) (holding ?m) (hands-full)))

  (:action give
    :parameters (?m - medicine ?p - person ?r - room)
    :precondition (and (robot-at ?r) (person-at ?p ?r) (holding ?m) (prescribed ?m ?p))
    :effect (and (not (holding ?m)) (not (hands-full)) (treated ?p)))

  ; Giving a patient the pills prescribed to someone else.
  (:action give-other-medicine
    :parameters (?m - medicine ?p ?owner - person ?r - room ?own - medicine)
    :precondition (and (robot-at ?r) (person-at ?p ?r) (holding ?m)
                       (prescribed ?m ?owner) (not (= ?p ?owner))
                       (prescribed ?own ?p) (same-drug ?own ?m))
    :effect (and (not (holding ?m)) (not (hands-full)) (treated ?p) (deprived ?owner))))
