; Ann, in the living room, needs her pills, which are in the store room.
; Bob sleeps in the bedroom between the hall and the store room; his pills of
; the same drug lie on the kitchen table, where the robot starts.
;
;   kitchen - hall - living-room
;              |  \
;        bedroom   corridor-1 - corridor-2
;              |                    |
;          store-room --------------+

(define (problem evening-round)
  (:domain care)
  (:objects kitchen hall living-room bedroom corridor-1 corridor-2 store-room - room
            ann bob - person
            pills-ann pills-bob - medicine)
  (:init
    (robot-at kitchen)
    (door kitchen hall) (door hall kitchen)
    (door hall living-room) (door living-room hall)
    (door hall bedroom) (door bedroom hall)
    (door bedroom store-room) (door store-room bedroom)
    (door hall corridor-1) (door corridor-1 hall)
    (door corridor-1 corridor-2) (door corridor-2 corridor-1)
    (door corridor-2 store-room) (door store-room corridor-2)
    (sleeping-in bedroom) (sleeps bob bedroom) (person-at bob bedroom)
    (person-at ann living-room)
    (medicine-at pills-ann store-room) (medicine-at pills-bob kitchen)
    (prescribed pills-ann ann) (prescribed pills-bob bob)
    (same-drug pills-ann pills-bob) (same-drug pills-bob pills-ann))
  (:goal (treated ann)))
