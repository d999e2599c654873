"""The page's worker processes: a few, each warm with the served model.

Every move of a dialogue that needs clingo runs in one of these workers
(:class:`ethasp.execution.worker.Worker`), one move per worker at a time, so
the server runs at most as many moves at once as it has workers.  A worker
is started as soon as the server starts and grounds the served model before
its first move (:func:`ethasp.interfaces.web.moves.warm`); it keeps the
grounding and what its moves computed (judgements, best reachable states,
HModels) for the moves after.

A worker is ended at once when its move is cancelled or passes a limit, and
a new one is started right away in its place, which grounds the model while
it waits for a move.  A worker that grew large (what it keeps grows with the
questions asked) is replaced after its move too, so that the server's memory
stays near its idle size.
"""

from __future__ import annotations

import contextlib
import functools
import threading

from ethasp.execution.limits import tree_resident
from ethasp.execution.worker import Worker
from ethasp.interfaces.web import moves
from ethasp.planning.model import Model

# A worker is replaced after a move when the memory of its processes passes
# this share of its part of the memory limit (the limit over the workers).
REPLACE = 0.5


class Workers:
    """At most ``size`` worker processes for the model; the memory limit
    (bytes, None: none) holds for the server's whole process tree."""

    def __init__(self, model: Model, size: int, memory: int | None = None):
        self.size = max(1, size)
        self.memory = memory
        warm = functools.partial(moves.warm, model)
        self._all = [Worker(warm, name=f"ethasp-page-{number}") for number in range(self.size)]
        self._idle = list(self._all)
        self._lock = threading.Lock()
        self._closed = False
        for worker in self._all:
            worker.start()

    def take(self) -> Worker | None:
        """An idle worker for a move (started, perhaps still warming), or None
        when every worker has a move."""
        with self._lock:
            if self._closed or not self._idle:
                return None
            worker = self._idle.pop(0)
        worker.start()  # unless it runs
        return worker

    def give_back(self, worker: Worker) -> None:
        """A worker whose move ended: one ended at a limit or on cancel is
        replaced at once by a new one (started in a thread of its own; it
        warms while it waits for a move); one that grew large is replaced too."""
        if worker.alive and self._large(worker):
            worker.kill()
        if worker.alive:
            self._idle_again(worker)
        else:
            threading.Thread(
                target=self._replace, args=(worker,), name="ethasp-page-replace", daemon=True
            ).start()

    def _replace(self, worker: Worker) -> None:
        with contextlib.suppress(OSError):
            worker.start()
        self._idle_again(worker)

    def _idle_again(self, worker: Worker) -> None:
        with self._lock:
            if not self._closed:
                self._idle.append(worker)
                return
        worker.kill()

    def _large(self, worker: Worker) -> bool:
        if self.memory is None or worker.pid is None:
            return False
        return tree_resident(worker.pid) > REPLACE * self.memory / self.size

    def busy(self) -> int:
        """Workers with a move."""
        with self._lock:
            return self.size - len(self._idle)

    def pids(self) -> list[int]:
        """The workers' processes (those started)."""
        return [worker.pid for worker in self._all if worker.pid is not None]

    def close(self) -> None:
        """End every worker (a move still running ends with it)."""
        with self._lock:
            self._closed = True
        for worker in self._all:
            with contextlib.suppress(OSError):
                worker.kill()
