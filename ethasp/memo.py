"""Results kept per model, outside the layers below.

The layers above plan search (judgements, best reachable states, HModels,
reasons) compute each answer once per model and keep it here, keyed by the
object they are about (a model or its planner), for as long as that object
lives: the planner, a lower layer, holds no result of theirs.
"""

from __future__ import annotations

import threading
import weakref


class Registry:
    """Dictionaries of results, one per owner (kept while the owner lives;
    owners are told apart by identity, so models, which compare by value, may
    own one too)."""

    def __init__(self):
        # Reentrant: the garbage collector may run a weak reference's callback
        # (_forget) in the thread that holds the lock, inside of().
        self.lock = threading.RLock()
        self.by_owner: dict[int, tuple[weakref.ref, dict]] = {}

    def of(self, owner) -> dict:
        key = id(owner)
        with self.lock:
            entry = self.by_owner.get(key)
            if entry is None or entry[0]() is not owner:
                entry = (weakref.ref(owner, lambda ref, key=key: self._forget(key, ref)), {})
                self.by_owner[key] = entry
            return entry[1]

    def _forget(self, key: int, ref: weakref.ref) -> None:
        """Drop the results of a dead owner (not those of a later owner that
        got its identity)."""
        with self.lock:
            entry = self.by_owner.get(key)
            if entry is not None and entry[0] is ref:
                del self.by_owner[key]


_RESULTS = Registry()


def results(owner) -> dict:
    """The results kept for an owner (a model's planner, or a model)."""
    return _RESULTS.of(owner)
