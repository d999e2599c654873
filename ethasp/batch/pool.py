"""The local pool: warm worker processes on this machine's cores.

Each worker process imports ethasp and reads the principles' encodings once
(:func:`ethasp.batch.task.warm`), then computes cases one after the other,
each sent to it over its own pipe by the batch's process, which keeps the
queue of cases.  Processes are started by ``multiprocessing``'s forkserver
where there is one (a clean single-threaded process that imported ethasp
forks each worker: no clingo object is ever shared between processes, and a
worker starts in milliseconds), else by spawn.

A worker that dies while computing a case (out of memory, a crash in a
library) is replaced and the case retried once, on a fresh worker; if it
dies again, the case becomes an error line.  With a per-case time limit, a
case still running ``2 x limit + grace`` seconds after it started is stuck
where clingo cannot be interrupted (grounding that does not end): its worker
is killed and replaced, and the case becomes an error line.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
import sys
import time
from collections import deque
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, replace
from multiprocessing.connection import wait

import ethasp.batch.task as task
from ethasp.batch.task import Settings, Work, error_line

# Seconds a case may run beyond twice its time limit before its worker is
# killed (as for the command line, ethasp.interfaces.cli.execution.OVERRUN_GRACE).
OVERRUN_GRACE = 10.0
# How often the pool looks at the clock when nothing happens.
TICK = 0.5


def default_workers() -> int:
    """The cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def context() -> multiprocessing.context.BaseContext:
    """forkserver (with ethasp imported in the server) where available, else spawn."""
    if "forkserver" in multiprocessing.get_all_start_methods():
        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(["ethasp.batch.pool"])
        return ctx
    return multiprocessing.get_context("spawn")


def _end_with_parent() -> None:
    """Linux: this process is killed when the one that started it ends (even by SIGKILL)."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def worker_main(connection, settings: Settings) -> None:
    """A worker process: cases in, result lines out, until the pipe closes."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the batch's process decides
    _end_with_parent()
    task.warm()
    connection.send(("ready", os.getpid()))
    while True:
        try:
            work = connection.recv()
        except (EOFError, OSError):
            return
        if work is None:
            return
        connection.send(("done", task.run(work, settings)))


@contextlib.contextmanager
def _main_importable():
    """A new worker imports the main module of this process, as multiprocessing
    does, from its file; a main module read from standard input or typed in has
    no file to import, so it is not imported (the workers need only ethasp)."""
    main = sys.modules.get("__main__")
    path = getattr(main, "__file__", None)
    if path is None or os.path.isfile(path) or getattr(main, "__spec__", None) is not None:
        yield
        return
    del main.__file__
    try:
        yield
    finally:
        main.__file__ = path


@dataclass
class _Slot:
    process: multiprocessing.process.BaseProcess
    connection: object
    ready: bool = False
    work: Work | None = None
    started: float = 0.0


def _death(process) -> str:
    code = process.exitcode
    if code is not None and code < 0:
        try:
            return f"killed by signal {signal.Signals(-code).name}"
        except ValueError:
            return f"killed by signal {-code}"
    return f"exit code {code}"


class LocalPool:
    """Worker processes that compute :class:`Work` items (see the module docstring)."""

    def __init__(self, workers: int, settings: Settings, grace: float = OVERRUN_GRACE):
        self.workers = workers
        self.settings = settings
        self.grace = grace
        self.slots: list[_Slot] = []
        self.context = context()

    def pids(self) -> list[int]:
        """The process ids of the workers running now."""
        return [slot.process.pid for slot in self.slots if slot.process.pid is not None]

    def busy_pids(self) -> list[int]:
        """The process ids of the workers computing a case now."""
        return [slot.process.pid for slot in self.slots if slot.work is not None]

    def _start(self) -> _Slot:
        mine, theirs = self.context.Pipe()
        process = self.context.Process(
            target=worker_main,
            args=(theirs, self.settings),
            name="ethasp-batch-worker",
            daemon=True,
        )
        with _main_importable():
            process.start()
        theirs.close()
        slot = _Slot(process, mine)
        self.slots.append(slot)
        return slot

    def _stop(self, slot: _Slot, kill: bool) -> None:
        if slot in self.slots:
            self.slots.remove(slot)
        if kill:
            slot.process.kill()
        else:
            try:
                slot.connection.send(None)
            except (OSError, ValueError):
                slot.process.kill()
        slot.process.join(None if kill else 5.0)
        if slot.process.is_alive():
            slot.process.kill()
            slot.process.join()
        slot.connection.close()

    def close(self) -> None:
        """End every worker now (also from another thread, e.g. on Ctrl-C)."""
        for slot in list(self.slots):
            with contextlib.suppress(OSError, ValueError, AttributeError):
                slot.process.kill()
        for slot in list(self.slots):
            try:
                slot.process.join(5.0)
                slot.connection.close()
            except (OSError, ValueError, AssertionError):
                pass
        self.slots.clear()

    def _overrun(self) -> float | None:
        limit = self.settings.time_limit
        return None if not limit else 2 * limit + self.grace

    @staticmethod
    def _dispatch(slot: _Slot, queue: deque[Work]) -> None:
        """Send the next case to a worker that is ready and idle."""
        if slot.ready and slot.work is None and queue:
            slot.work = queue.popleft()
            slot.started = time.monotonic()
            slot.connection.send(slot.work)

    def run(self, works: Iterable[Work]) -> Iterator[tuple[Work, list[dict]]]:
        """Compute the works, yielding each with its lines as it finishes."""
        queue = deque(works)
        overrun = self._overrun()
        failed_starts = 0
        try:
            for _ in range(min(self.workers, len(queue))):
                self._start()
            while queue or any(slot.work is not None for slot in self.slots):
                for slot in self.slots:
                    self._dispatch(slot, queue)
                timeout = TICK
                if overrun is not None:
                    running = [
                        slot.started + overrun - time.monotonic()
                        for slot in self.slots
                        if slot.work is not None
                    ]
                    if running:
                        timeout = max(0.0, min(min(running) + 0.01, TICK))
                by_object = {}
                for slot in self.slots:
                    by_object[slot.connection] = slot
                    by_object[slot.process.sentinel] = slot
                ready = wait(list(by_object), timeout)
                ended: list[_Slot] = []
                for item in ready:
                    slot = by_object[item]
                    if item is slot.process.sentinel:
                        if slot not in ended:
                            ended.append(slot)
                        continue
                    try:
                        kind, value = slot.connection.recv()
                    except (EOFError, OSError):
                        if slot not in ended:
                            ended.append(slot)
                        continue
                    if kind == "ready":
                        slot.ready = True
                        failed_starts = 0
                    elif slot.work is not None:
                        work, slot.work = slot.work, None
                        # The worker gets its next case before the caller
                        # writes this one's lines: it need not wait for them.
                        self._dispatch(slot, queue)
                        yield work, value
                for slot in ended:
                    # Results already in the pipe were read above; what is left is lost.
                    while slot.work is not None and slot.connection.poll():
                        try:
                            kind, value = slot.connection.recv()
                        except (EOFError, OSError):
                            break
                        if kind == "done":
                            work, slot.work = slot.work, None
                            yield work, value
                    work, started = slot.work, slot.started
                    slot.process.join(1.0)
                    cause = _death(slot.process)
                    if not slot.ready:
                        failed_starts += 1
                        if failed_starts >= 3:
                            raise RuntimeError(f"worker processes cannot start ({cause})")
                    self._stop(slot, kill=True)
                    if work is not None:
                        if work.attempt < 2:
                            queue.appendleft(replace(work, attempt=work.attempt + 1))
                        else:
                            line = error_line(
                                work.case,
                                f"its worker process ended while computing it, "
                                f"twice ({cause}): out of memory, or a crash",
                            )
                            line["seconds"] = round(time.monotonic() - started, 6)
                            yield work, [line]
                    if queue and len(self.slots) < self.workers:
                        self._start()
                if overrun is not None:
                    now = time.monotonic()
                    for slot in [
                        s for s in self.slots if s.work is not None and now - s.started > overrun
                    ]:
                        work, seconds = slot.work, round(now - slot.started, 6)
                        self._stop(slot, kill=True)
                        limit = self.settings.time_limit
                        line = error_line(
                            work.case,
                            f"no answer within the time limit of {limit:g} s: still "
                            f"grounding or solving after {overrun:g} s (clingo "
                            "cannot stop grounding; does the model's grounding "
                            "end?)",
                        )
                        line["seconds"] = seconds
                        yield work, [line]
                        if queue and len(self.slots) < self.workers:
                            self._start()
                if queue and not self.slots:
                    self._start()
            for slot in list(self.slots):
                self._stop(slot, kill=False)
        finally:
            self.close()
