"""Results kept per owner (ethasp.memo): kept while the owner lives, forgotten
after, and never a deadlock when the collector frees an owner while the
registry is in use."""

from __future__ import annotations

import gc
import threading

from ethasp.memo import Registry


class Owner:
    """An owner in a reference cycle, as a planner is: freed by the collector."""

    def __init__(self):
        self.cycle = self


def test_results_live_as_long_as_their_owner():
    registry = Registry()
    owner = Owner()
    registry.of(owner)["answer"] = 42
    assert registry.of(owner) == {"answer": 42}
    del owner
    gc.collect()
    assert registry.by_owner == {}


def test_an_owner_freed_while_the_registry_is_locked_is_forgotten_without_a_deadlock():
    """The collector runs whenever Python allocates, so it may free an owner
    (and call back into the registry) while the same thread holds the
    registry's lock: that must neither deadlock nor forget a living owner."""
    registry = Registry()
    done = []

    def work() -> None:
        living = Owner()
        registry.of(living)["kept"] = True
        dead = Owner()
        registry.of(dead)
        del dead
        with registry.lock:  # as inside Registry.of
            gc.collect()
        done.append(registry.of(living) == {"kept": True} and len(registry.by_owner) == 1)

    thread = threading.Thread(target=work, daemon=True)
    thread.start()
    thread.join(30)
    assert done == [True], "the registry deadlocked" if thread.is_alive() else done
