"""Long requests of the page run as jobs: a worker thread, a budget (time
limit, progress records, cancellation) and a state the page polls.

Every search a job makes goes through :func:`searching`, with the job's
:class:`~ethasp.planning.budget.Budget`.  Cancelling a job cancels its budget
and frees its session at once: the job's result, if it still comes, is
thrown away, and the dialogue stays as it was.
"""

from __future__ import annotations

import threading
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ethasp.errors import InputError
from ethasp.planning.budget import Budget, Progress

RUNNING, DONE, FAILED, CANCELLED = "running", "done", "failed", "cancelled"


def searching(call: Callable[..., Any], budget: Budget, *args: Any, **kwargs: Any) -> Any:
    """Run one search call of a job (plan search, a question, a judgement)
    under the job's budget: cancelling the job stops its searches soon."""
    return call(*args, budget=budget, **kwargs)


@dataclass
class Job:
    """One long request: what it does, how it goes, and how it ended."""

    id: str
    kind: str
    description: str
    budget: Budget
    started: float = field(default_factory=time.monotonic)
    state: str = RUNNING
    error: str = ""
    note: str = ""
    progress: list[str] = field(default_factory=list)
    ended: float | None = None
    thread: threading.Thread | None = None
    lock: threading.RLock = field(default_factory=threading.RLock)

    # -- from the worker ------------------------------------------------------------

    def record(self, progress: Progress) -> None:
        """The budget's progress callback: keep the last few lines."""
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
        """Cancel the job (its budget too); False if it had ended."""
        self.budget.cancel()
        return self.finish(CANCELLED, note="cancelled: the dialogue is unchanged")

    @property
    def running(self) -> bool:
        return self.state == RUNNING

    @property
    def alive(self) -> bool:
        """Its thread still works (a cancelled job's search may still be finishing)."""
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
            }


def start(job: Job, work: Callable[[Budget], Callable[[], str]]) -> Job:
    """Run ``work(budget)`` in a worker thread.

    ``work`` does the searches and returns a commit function that installs
    its result (and returns a note); it is called under the job's lock, only
    if the job was not cancelled, and must be quick.  InputErrors end the job ``failed``
    with their one-line message.
    """

    def run() -> None:
        try:
            commit = work(job.budget)
        except InputError as error:
            job.finish(FAILED, error=str(error))
        except Exception as error:  # a bug: tell the page, keep the trace on the console
            traceback.print_exc()
            job.finish(FAILED, error=f"internal error: {type(error).__name__}: {error}")
        else:
            with job.lock:  # a cancel waits for the commit, or the commit is skipped
                if job.state == RUNNING:
                    job.finish(DONE, note=commit() or "")

    job.thread = threading.Thread(target=run, name=f"ethasp-job-{job.id}", daemon=True)
    job.thread.start()
    return job
