"""The local pool: warm worker processes on this machine's cores.

Each case runs in a :class:`~ethasp.execution.worker.Worker` (the one
mechanism every front end of ethasp runs its searches in): a process that
imported ethasp and read the principles' encodings once
(:func:`ethasp.batch.task.warm`), then computes cases one after the other,
each under the batch's limits per case.  A thread of the batch's process
feeds each worker from the queue of cases.

A case's time limit holds as for the command line: its searches stop at the
limit and answer ``bounded``; where clingo cannot be stopped (a grounding
that does not end), the worker is ended at the limit plus a fraction of a
second and the case gets an error line saying so.  Its memory limit holds
for the worker's processes.  A worker that dies while computing a case (a
crash in a library) is replaced and the case retried once, on a fresh
worker; if it dies again, the case becomes an error line.
"""

from __future__ import annotations

import os
import threading
from collections import deque
from collections.abc import Iterable, Iterator
from dataclasses import replace
from queue import Queue

import ethasp.batch.task as task
from ethasp.batch.task import Settings, Work, case_lines
from ethasp.execution.limits import GRACE, Limits
from ethasp.execution.worker import Worker


def default_workers() -> int:
    """The cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


class LocalPool:
    """Worker processes that compute :class:`Work` items (see the module docstring)."""

    def __init__(
        self,
        workers: int,
        settings: Settings,
        memory_limit: float | None = None,
        grace: float = GRACE,
    ):
        self.workers = workers
        self.settings = settings
        self.grace = grace
        self.memory_limit = memory_limit
        self._pool = [
            Worker(task.warm, "ethasp-batch-worker", own_tree=True) for _ in range(workers)
        ]
        self._busy: set[Worker] = set()
        self._closed = threading.Event()
        self._lock = threading.Lock()

    def busy_pids(self) -> list[int]:
        """The process ids of the workers computing a case now."""
        with self._lock:
            return [worker.pid for worker in self._busy if worker.pid is not None]

    def close(self) -> None:
        """End every worker now (also from another thread, e.g. on Ctrl-C)."""
        self._closed.set()
        for worker in self._pool:
            worker.kill()

    def run(self, works: Iterable[Work]) -> Iterator[tuple[Work, list[dict]]]:
        """Compute the works, yielding each with its lines as it finishes."""
        queue = deque(works)
        left = len(queue)
        results: Queue = Queue()
        wake = threading.Condition(self._lock)
        counts = {"left": left}

        def serve(worker: Worker) -> None:
            while True:
                with wake:
                    while not queue and counts["left"] and not self._closed.is_set():
                        wake.wait(0.2)
                    if not queue or self._closed.is_set():
                        return
                    work = queue.popleft()
                    self._busy.add(worker)
                try:
                    worker.ready()  # a case's limits count the case, not the warm-up
                    limits = Limits.of(
                        self.settings.time_limit, self.memory_limit, grace=self.grace
                    )
                    outcome = worker.call(task.run, work, self.settings, limits=limits)
                finally:
                    with wake:
                        self._busy.discard(worker)
                results.put((work, outcome))

        threads = [
            threading.Thread(target=serve, args=(worker,), name="ethasp-batch-feed", daemon=True)
            for worker in self._pool[: max(1, min(self.workers, left))]
        ]
        for thread in threads:
            thread.start()
        try:
            while counts["left"]:
                work, outcome = results.get()
                lines = case_lines(work, outcome)
                if lines is None:
                    with wake:
                        queue.appendleft(replace(work, attempt=work.attempt + 1))
                        wake.notify_all()
                    continue
                with wake:
                    counts["left"] -= 1
                    wake.notify_all()
                yield work, lines
        finally:
            self.close()
            for thread in threads:
                thread.join(1.0)
