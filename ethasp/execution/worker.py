"""Work in a child process that its front end can end at once.

clingo cannot interrupt a grounding, and a search may need more memory than
its user allows.  So every front end (the command line, a web job, a batch
case, the dialogue, the Python API when it is given limits) runs its work in a
:class:`Worker`: a child process that runs calls one at a time and reports
back over a pipe.  The front end watches each call (:meth:`Worker.call`):

* the call's work expires a little before the time limit
  (:meth:`~ethasp.execution.limits.Limits.soft_deadline`: every budget made
  during the call joins it, :mod:`ethasp.execution.context`) and answers
  ``bounded`` with what it found;
* at the time limit plus :data:`~ethasp.execution.limits.GRACE` seconds the
  front end kills the worker and the processes below it, and answers with the
  last partial result the work reported;
* when the resident memory of the front end and the worker's processes
  passes :data:`~ethasp.execution.limits.SOFT_MEMORY` of the memory limit,
  the work is asked to stop (it answers ``bounded``); past
  :data:`~ethasp.execution.limits.HARD_MEMORY` its processes are killed; the
  worker's own allocations fail beyond the limit (``RLIMIT_DATA``);
* cancelling a call kills the worker at once.

A worker keeps what its calls leave in the process (loaded models,
groundings) for the next call: a front end that asks many questions about one
model keeps a warm worker.  A killed worker is gone with what it kept; the
next call starts a new one.

A worker is forked directly where the front end has one thread (the command
line: the fork copies only what is already imported, in about a
millisecond); elsewhere it comes from ``multiprocessing``'s forkserver, a
clean process that imported ethasp, or from spawn.  A worker starts its own
spawner (:mod:`ethasp.execution.spawner`) before it has any thread, for the
engines' child processes.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import queue
import signal
import sys
import threading
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ethasp.errors import InputError
from ethasp.execution import context as context_module
from ethasp.execution import spawner
from ethasp.execution import symbols  # noqa: F401 (symbols pickle as text)
from ethasp.execution.limits import (
    HARD_MEMORY,
    POLL,
    SOFT_MEMORY,
    Limits,
    data_size,
    descendants,
    limit_data,
    resident,
    restore_data,
)

DONE = "done"  # the call returned a value
INPUT_ERROR = "input error"  # bad input: one line
FAILED = "failed"  # a bug: the exception and its trace
TIME = "time"  # ended at the time limit
MEMORY = "memory"  # ended at the memory limit
CANCELLED = "cancelled"  # ended by the front end
DIED = "died"  # the worker ended on its own (a crash)

# Modules a forkserver imports before it forks workers.
PRELOAD = ["ethasp.execution.worker", "ethasp.planning.model"]

NO_LIMITS = Limits()

# How often (in memory readings) the processes below a worker are listed anew.
RESCAN = 10


@dataclass
class Outcome:
    """How a call ended: its value (``done``), one line (``input error``,
    ``failed``: then ``message``), or the limit or cancellation that ended it
    (``partial`` is the last partial result the work reported); its wall time
    and the largest resident memory seen of the processes watched."""

    status: str
    value: Any = None
    message: str = ""
    partial: Any = None
    seconds: float = 0.0
    peak: int = 0

    @property
    def limited(self) -> bool:
        return self.status in (TIME, MEMORY)


class _TreeMemory:
    """The resident memory of a process tree (the front end's, with every
    worker and the processes below them; or one worker's), its processes
    listed anew every :data:`RESCAN` readings."""

    def __init__(self, root: int, worker: int):
        self.root = root
        self.worker = worker
        self.readings = 0
        self.below: list[int] = []

    def __call__(self) -> int:
        if self.readings % RESCAN == 0:
            self.below = descendants(self.root)
            if self.worker not in self.below and self.worker != self.root:
                self.below.append(self.worker)
        self.readings += 1
        return resident(self.root) + sum(resident(pid) for pid in self.below)


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


def _is_memory_error(error: BaseException) -> bool:
    return isinstance(error, MemoryError) or (
        isinstance(error, RuntimeError) and "bad_alloc" in str(error)
    )


def _serve(connection, warm: Callable[[], None] | None) -> None:
    """A worker process: calls in, outcomes out, until the pipe closes."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the front end decides
    spawner.end_with_parent()
    spawner.start()  # while this process has one thread
    lock = threading.Lock()

    def send(message: tuple) -> None:
        with lock:
            connection.send(message)

    calls: queue.Queue = queue.Queue()

    def listen() -> None:
        while True:
            try:
                message = connection.recv()
            except (EOFError, OSError):
                message = None
            if message is None:
                calls.put(None)
                return
            if message[0] == "cancel":
                running = context_module.current()
                if running is not None and running.call == message[1]:
                    running.cancel(message[2])
            else:
                calls.put(message)

    if warm is not None:
        warm()
    threading.Thread(target=listen, name="ethasp-worker-listener", daemon=True).start()
    send(("ready", os.getpid()))
    while True:
        message = calls.get()
        if message is None:
            return
        _, call, function, args, kwargs, limits, budget = message
        running = context_module.Context(limits, send, call)
        context_module.enter(running)
        original = limit_data(budget)
        try:
            result: tuple = (DONE, function(*args, **kwargs))
        except InputError as error:
            result = (INPUT_ERROR, str(error))
        except BaseException as error:
            if _is_memory_error(error):
                result = (MEMORY, f"{type(error).__name__}: {error}")
            else:
                result = (FAILED, "".join(traceback.format_exception(error)))
        finally:
            context_module.enter(None)
            restore_data(original)
        try:
            send(result)
        except Exception as error:  # a value that cannot be sent
            send((FAILED, f"the answer could not be sent: {type(error).__name__}: {error}"))


def _context() -> multiprocessing.context.BaseContext:
    if "forkserver" in multiprocessing.get_all_start_methods():
        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(PRELOAD)
        return ctx
    return multiprocessing.get_context("spawn")


class Worker:
    """A child process that runs calls one at a time (see the module docstring).

    ``warm`` runs once in each new worker before its first call (imports,
    encodings read); it must be a module-level function.  The memory limit of
    a call holds for the whole process tree of this process (every worker
    and the processes below them), or with ``own_tree`` for the worker's
    processes alone (a batch's workers, each with a limit of its own).
    """

    def __init__(
        self,
        warm: Callable[[], None] | None = None,
        name: str = "ethasp-worker",
        own_tree: bool = False,
    ):
        self.warm = warm
        self.name = name
        self.own_tree = own_tree
        self.pid: int | None = None
        self._connection = None
        self._process: multiprocessing.process.BaseProcess | None = None
        self._ready = False
        self._calls = 0
        self._lock = threading.Lock()  # one call at a time

    # -- the process ------------------------------------------------------------------

    @property
    def alive(self) -> bool:
        if self.pid is None:
            return False
        if self._process is not None:
            return self._process.is_alive()
        try:
            ended, _ = os.waitpid(self.pid, os.WNOHANG)
        except ChildProcessError:
            return False
        return ended == 0

    def start(self) -> None:
        """Start the worker process, unless it runs."""
        if self.alive:
            return
        self._forget()
        mine, theirs = multiprocessing.Pipe()
        forked = hasattr(os, "fork") and sys.platform.startswith("linux") and spawner.threads() == 1
        if forked:
            for stream in (sys.stdout, sys.stderr):
                with contextlib.suppress(OSError, ValueError):
                    stream.flush()
            pid = os.fork()
            if pid == 0:  # the worker
                code = 0
                try:
                    mine.close()
                    _serve(theirs, self.warm)
                except BaseException:
                    code = 1
                finally:
                    os._exit(code)
            self.pid = pid
        else:
            process = _context().Process(
                target=_serve, args=(theirs, self.warm), name=self.name, daemon=True
            )
            with _main_importable():
                process.start()
            self._process, self.pid = process, process.pid
        theirs.close()
        self._connection = mine
        self._ready = False

    def _forget(self) -> None:
        if self._connection is not None:
            with contextlib.suppress(OSError):
                self._connection.close()
        self._connection = None
        self._process = None
        self.pid = None

    def kill(self) -> None:
        """End the worker and every process below it at once."""
        pid = self.pid
        if pid is None:
            return
        below = descendants(pid)
        for victim in [pid, *below]:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.kill(victim, signal.SIGKILL)
        self._reap()
        self._forget()

    def _reap(self) -> None:
        if self._process is not None:
            self._process.join(5.0)
        elif self.pid is not None:
            with contextlib.suppress(ChildProcessError):
                os.waitpid(self.pid, 0)

    def close(self) -> None:
        """End the worker after its current call (at once if it does not end)."""
        if self.pid is None:
            return
        with contextlib.suppress(OSError, ValueError):
            self._connection.send(None)
        if self._process is not None:
            self._process.join(2.0)
        else:
            end = time.monotonic() + 2.0
            while time.monotonic() < end and self.alive:
                time.sleep(0.01)
        self.kill()

    # -- calls --------------------------------------------------------------------------

    def call(
        self,
        function: Callable[..., Any],
        *args: Any,
        limits: Limits = NO_LIMITS,
        on_progress: Callable[[Any], None] | None = None,
        on_partial: Callable[[Any], None] | None = None,
        on_stderr: Callable[[str], None] | None = None,
        cancel: threading.Event | None = None,
        **kwargs: Any,
    ) -> Outcome:
        """Run ``function(*args, **kwargs)`` in the worker under ``limits``
        (measured from ``limits.started``); ``cancel`` (set by another
        thread) ends it at once.  ``function`` and its arguments and value
        must pickle (a module-level function).  ``on_progress``,
        ``on_partial`` and ``on_stderr`` receive what the work reports
        (:mod:`ethasp.execution.context`) as it comes."""
        handlers = {"progress": on_progress, "partial": on_partial, "stderr": on_stderr}
        with self._lock:
            return self._call(function, args, kwargs, limits, handlers, cancel)

    def _call(self, function, args, kwargs, limits, handlers, cancel) -> Outcome:
        self.start()
        self._calls += 1
        call = self._calls
        memory = None
        if limits.memory is not None:
            memory = _TreeMemory(self.pid if self.own_tree else os.getpid(), self.pid)
        budget = None
        if memory is not None:
            # The worker's data may grow by what the tree has left below the limit.
            headroom = int(limits.memory * HARD_MEMORY) - memory()
            budget = data_size(self.pid) + max(16 * 2**20, headroom)
        outcome = Outcome(DONE)
        try:
            self._connection.send(("call", call, function, args, kwargs, limits, budget))
        except (OSError, ValueError):
            self.kill()
            outcome.status, outcome.message = DIED, "the worker process ended before the call"
            return outcome
        hard = limits.hard_deadline()
        asked = False
        while True:
            now = time.monotonic()
            wait = POLL if (memory is not None or cancel is not None) else 0.25
            if hard is not None:
                wait = max(0.0, min(wait, hard - now))
            try:
                ready = self._connection.poll(wait)
            except (OSError, ValueError):
                ready = False
            if ready:
                try:
                    kind, value = self._receive()
                except (EOFError, OSError):
                    kind, value = DIED, None
                if kind == "ready":
                    self._ready = True
                elif kind in handlers:
                    if kind == "partial":
                        outcome.partial = value
                    if handlers[kind] is not None:
                        handlers[kind](value)
                else:
                    return self._ended(outcome, kind, value, limits)
                continue
            if cancel is not None and cancel.is_set():
                self.kill()
                return self._ended(outcome, CANCELLED, "cancelled", limits)
            if hard is not None and time.monotonic() >= hard:
                self.kill()
                return self._ended(outcome, TIME, limits.time_words(), limits)
            if memory is not None:
                used = memory()
                outcome.peak = max(outcome.peak, used)
                if used > HARD_MEMORY * limits.memory:
                    self.kill()
                    return self._ended(outcome, MEMORY, limits.memory_words(), limits)
                if used > SOFT_MEMORY * limits.memory and not asked:
                    asked = True
                    with contextlib.suppress(OSError, ValueError):
                        self._connection.send(("cancel", call, limits.memory_words()))
            if not self.alive:
                # Its last words may still be in the pipe.
                while True:
                    try:
                        if not self._connection.poll(0):
                            break
                        kind, value = self._receive()
                    except (EOFError, OSError):
                        break
                    if kind in handlers:
                        if kind == "partial":
                            outcome.partial = value
                        if handlers[kind] is not None:
                            handlers[kind](value)
                    elif kind != "ready":
                        return self._ended(outcome, kind, value, limits)
                self.kill()
                near = limits.memory is not None and outcome.peak > SOFT_MEMORY * limits.memory
                return self._ended(
                    outcome,
                    MEMORY if near else DIED,
                    limits.memory_words() if near else "the worker process ended",
                    limits,
                )

    def _receive(self) -> tuple[str, Any]:
        message = self._connection.recv()
        return message[0], message[1]

    @staticmethod
    def _ended(outcome: Outcome, kind: str, value: Any, limits: Limits) -> Outcome:
        outcome.status = kind
        if kind == DONE:
            outcome.value = value
        elif kind == MEMORY and limits.memory is not None:
            outcome.message = limits.memory_words()  # an allocation beyond it failed
        else:
            outcome.message = "" if value is None else str(value)
        outcome.seconds = time.monotonic() - limits.started if limits.started else 0.0
        return outcome


def run(
    function: Callable[..., Any],
    *args: Any,
    limits: Limits = NO_LIMITS,
    warm: Callable[[], None] | None = None,
    **kwargs: Any,
) -> Outcome:
    """One call in a worker of its own, ended with it."""
    worker = Worker(warm)
    try:
        return worker.call(function, *args, limits=limits, **kwargs)
    finally:
        worker.kill()
