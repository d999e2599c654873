"""Long requests of the page run as jobs: a move made by a worker process
(:mod:`ethasp.interfaces.web.workers`) under the server's limits, watched
by a thread of the server, with a state the page polls.

Cancelling a job ends its worker process at once (with every process below
it) and frees its session: the dialogue stays as it was.  A job whose worker
passed the time limit (plus a grace) or the memory limit is ended the same
way and says so (state ``time`` or ``memory``).
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ethasp.execution import worker as execution
from ethasp.execution.limits import Limits
from ethasp.planning.budget import Progress

RUNNING, DONE, FAILED, CANCELLED = "running", "done", "failed", "cancelled"
TIME, MEMORY = execution.TIME, execution.MEMORY  # ended at a limit

UNCHANGED = "the dialogue is unchanged"


@dataclass
class Job:
    """One long request: what it does, how it goes, and how it ended."""

    id: str
    kind: str
    description: str
    limits: Limits = field(default_factory=Limits)
    started: float = field(default_factory=time.monotonic)
    state: str = RUNNING
    error: str = ""
    note: str = ""
    progress: list[str] = field(default_factory=list)
    ended: float | None = None
    process: int | None = None  # the worker process that makes the move
    thread: threading.Thread | None = None
    cancelled: threading.Event = field(default_factory=threading.Event)
    lock: threading.RLock = field(default_factory=threading.RLock)

    # -- from the worker ------------------------------------------------------------

    def record(self, progress: Progress) -> None:
        """The progress callback: keep the last few lines."""
        with self.lock:
            self.progress = ([*self.progress, progress.line()])[-5:]

    def finish(self, state: str, error: str = "", note: str = "") -> bool:
        """End the job, unless it has ended already (cancelled); True if it ended now."""
        with self.lock:
            if self.state != RUNNING:
                return False
            self.state, self.error, self.note = state, error, note
            self.ended = time.monotonic()
            return True

    # -- from the page ----------------------------------------------------------------

    def cancel(self) -> bool:
        """Cancel the job: its worker is ended; False if it had ended."""
        with self.lock:
            ended = self.finish(CANCELLED, note=f"cancelled: {UNCHANGED}")
            if ended:
                self.cancelled.set()
            return ended

    def wait(self, seconds: float) -> None:
        """Wait for the thread that watches the worker (at most ``seconds``)."""
        if self.thread is not None:
            self.thread.join(seconds)

    @property
    def running(self) -> bool:
        return self.state == RUNNING

    @property
    def alive(self) -> bool:
        """Its thread still watches the worker."""
        return self.thread is not None and self.thread.is_alive()

    def elapsed(self) -> float:
        return (self.ended or time.monotonic()) - self.started

    def to_json(self) -> dict:
        with self.lock:
            return {
                "id": self.id,
                "kind": self.kind,
                "description": self.description,
                "state": self.state,
                "elapsed": round(self.elapsed(), 1),
                "progress": self.progress[-1] if self.progress else "",
                "error": self.error,
                "note": self.note,
                "process": self.process,
            }


def start(
    job: Job,
    worker: execution.Worker,
    give_back: Callable[[execution.Worker], None],
    move: Callable[..., Any],
    args: tuple,
    commit: Callable[[Any], str],
) -> Job:
    """Make ``move(*args)`` in ``worker`` under the job's limits, in a thread
    that watches it; ``give_back`` returns the worker when the move ends.

    ``commit`` installs the move's value (and returns a note); it is called
    under the job's lock, only if the job was not cancelled, and must be quick.
    InputErrors end the job ``failed`` with their one-line message.
    """
    job.process = worker.pid

    def run() -> None:
        try:
            outcome = worker.call(
                move, *args, limits=job.limits, on_progress=job.record, cancel=job.cancelled
            )
        except Exception as error:  # the server is closing, or a bug
            outcome = execution.Outcome(
                execution.FAILED, message=f"{type(error).__name__}: {error}"
            )
            worker.kill()
        if outcome.limited:  # ended, or an allocation failed in it: a new one is safer
            worker.kill()
        give_back(worker)
        try:
            _ended(job, outcome, commit)
        except Exception as error:  # a bug: tell the page, keep the trace on the console
            print(f"ethasp: error in a job of the page: {error!r}", file=sys.stderr, flush=True)
            job.finish(FAILED, error=f"internal error: {type(error).__name__}: {error}")

    job.thread = threading.Thread(target=run, name=f"ethasp-job-{job.id}", daemon=True)
    job.thread.start()
    return job


def _ended(job: Job, outcome: execution.Outcome, commit: Callable[[Any], str]) -> None:
    """The job's state from how its move ended."""
    status = outcome.status
    if status == execution.DONE:
        with job.lock:  # a cancel waits for the commit, or the commit is skipped
            if job.state == RUNNING:
                job.finish(DONE, note=commit(outcome.value) or "")
    elif status == execution.INPUT_ERROR:
        job.finish(FAILED, error=outcome.message)
    elif outcome.limited:
        job.finish(status, error=f"{outcome.message}: the work was ended and {UNCHANGED}")
    elif status != execution.CANCELLED:  # a bug, or a worker that crashed
        detail = outcome.message.strip().splitlines()
        if outcome.message.strip():
            print(outcome.message.rstrip(), file=sys.stderr, flush=True)
        job.finish(
            FAILED,
            error=f"internal error: {detail[-1] if detail else status} (the server's "
            f"console shows more); {UNCHANGED}",
        )
