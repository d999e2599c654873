"""Work for the tests of ethasp.execution: module-level functions, so that a
worker process started by a forkserver can import them."""

from __future__ import annotations

import os
import time

from ethasp.errors import InputError
from ethasp.execution import context, spawner

CALLS = []


def count() -> int:
    """How many calls this process has counted (state a warm worker keeps)."""
    CALLS.append(1)
    return len(CALLS)


def bad_input() -> None:
    raise InputError("model.lp:1: something is wrong")


def bug() -> None:
    raise ZeroDivisionError("a bug")


def ground_forever() -> str:
    """Report a partial answer, then ground a program clingo cannot stop in time."""
    import clingo

    context.partial("the answer so far")
    control = clingo.Control()
    control.add("base", [], "p(X,Y,Z) :- X = 1..1000, Y = 1..1000, Z = 1..1000.")
    control.ground([("base", [])])
    return "grounded"


def hog() -> None:
    """Take memory until an allocation fails."""
    kept = []
    while True:
        kept.append(bytearray(20 * 2**20))


def budget_of_the_call() -> tuple[float | None, bool]:
    """What a budget made during the call sees: seconds left, cancelled."""
    from ethasp.planning.budget import Budget

    budget = Budget(None)
    return budget.remaining(), budget.cancelled


def sleeping_child(out) -> None:
    out.write(f"{os.getpid()}\n")
    out.flush()
    time.sleep(60)


def child_then_sleep() -> None:
    """Start an engine's child process, report its pid, and sleep."""
    child = spawner.spawn(sleeping_child, ())
    pid = int(next(iter(child.lines())))
    context.partial(pid)
    time.sleep(60)


def lines_child(count: int, out) -> None:
    for number in range(count):
        out.write(f"line {number}\n")


def stdin_replaced_child(path: str, out) -> None:
    """Put a file on standard input (as a planner's child does before it
    becomes the planner), then write a line after a while."""
    os.dup2(os.open(path, os.O_RDONLY), 0)
    time.sleep(0.5)
    out.write("still here\n")
