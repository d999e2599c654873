"""How long a search may run, whom it tells how it goes, and how to stop it.

Every search of ethasp (plans, HPlans, best reachable states, contrast plans)
runs under a :class:`Budget`: a time limit (None for none), a callback that
receives :class:`Progress` records while it runs, and a cancellation flag
that another thread may set (:meth:`Budget.cancel`).  A search that runs out
of time or is cancelled stops soon and answers ``bounded``, never a claim it
has not proven.

One budget covers one command (or one question of a dialogue): every search
made for it shares the same deadline.  A budget made while a worker process
runs a call for a front end (:mod:`ethasp.execution`) joins that call: it
expires by the call's soft deadline, is cancelled with it (for example when
the memory of the process tree nears its limit), and reports progress to the
front end unless it has a callback of its own.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

from ethasp.execution import context as execution_context

# The default time limit of a command line search, in seconds (``ethasp ...
# --time-limit 0`` for none; the Python API has no limit unless given one).
DEFAULT_TIME_LIMIT = 120.0

# How often a running solve checks the deadline and the cancellation flag.
POLL_SECONDS = 0.05


@dataclass(frozen=True)
class Progress:
    """How a search goes: what it searches (``task``), the horizon reached, and
    for optimisation the best utility found so far and the best upper bound
    proven (None where not known)."""

    task: str
    horizon: int | None = None
    best: int | None = None
    bound: int | None = None
    elapsed: float = 0.0

    def line(self) -> str:
        """One compact line, e.g. ``best reachable state: horizon 8, best 4, bound 7 (3.1 s)``."""
        parts = []
        if self.horizon is not None:
            parts.append(f"horizon {self.horizon}")
        if self.best is not None:
            parts.append(f"best {self.best}")
        if self.bound is not None:
            parts.append(f"bound {self.bound}")
        detail = ", ".join(parts)
        return (
            f"{self.task}: {detail} ({self.elapsed:.1f} s)"
            if detail
            else f"{self.task} ({self.elapsed:.1f} s)"
        )


class Budget:
    """A time limit, a progress callback and a cancellation flag for searches."""

    def __init__(
        self, time_limit: float | None = None, on_progress: Callable[[Progress], None] | None = None
    ):
        if time_limit is not None and not time_limit >= 0:
            raise ValueError("a time limit must be 0 seconds or more (None for none)")
        self.started = time.monotonic()
        self.time_limit = time_limit
        self.deadline = None if time_limit is None else self.started + time_limit
        self.on_progress = on_progress
        self._cancelled = threading.Event()
        self._reason: list[str] = []  # why it was cancelled, if a reason was given
        self._share = False
        running = execution_context.current()
        if running is not None:
            self._cancelled = running.cancelled
            self._reason = running.reasons
            soft = running.limits.soft_deadline()
            if soft is not None and (self.deadline is None or soft < self.deadline):
                self.deadline = soft
                self.time_limit = running.limits.time
            if self.on_progress is None:
                self.on_progress = running.progress

    def share(self, seconds: float) -> Budget:
        """A part of this budget: at most ``seconds`` more, cancelled with it,
        reporting to the same callback."""
        part = Budget(None, self.on_progress)
        part.started = self.started
        part._cancelled = self._cancelled
        part._reason = self._reason
        end = time.monotonic() + seconds
        part.deadline = end if self.deadline is None else min(end, self.deadline)
        part.time_limit = self.time_limit
        part._share = True
        return part

    def until(self, condition: Callable[[], bool]) -> Budget:
        """This budget, also expired as soon as ``condition()`` holds (for a
        search that another one may make pointless; the condition is polled
        while the search runs)."""
        return _Until(self, condition)

    # -- limits -------------------------------------------------------------------

    def cancel(self, reason: str = "") -> None:
        """Stop every search under this budget soon (thread-safe); ``reason``
        replaces "the search was cancelled" in what the searches say."""
        if reason:
            self._reason[:] = [reason]
        self._cancelled.set()

    @property
    def cancelled(self) -> bool:
        return self._cancelled.is_set()

    def elapsed(self) -> float:
        return time.monotonic() - self.started

    def remaining(self) -> float | None:
        """Seconds left (None: no limit); 0 once cancelled or expired."""
        if self.cancelled:
            return 0.0
        if self.deadline is None:
            return None
        return max(0.0, self.deadline - time.monotonic())

    def expired(self) -> bool:
        """Cancelled, or past the deadline."""
        remaining = self.remaining()
        return remaining is not None and remaining <= 0.0

    def why_stopped(self) -> str:
        """Words for a search cut short by this budget."""
        if self.cancelled:
            return self._reason[0] if self._reason else "the search was cancelled"
        if self._share:
            return "its share of the time was used"
        if self.time_limit is None:
            return "the search was stopped"
        return f"the time limit of {self.time_limit:g} s was reached"

    # -- progress -----------------------------------------------------------------

    def report(
        self,
        task: str,
        horizon: int | None = None,
        best: int | None = None,
        bound: int | None = None,
    ) -> None:
        """Tell the progress callback (if any) how a search goes."""
        if self.on_progress is not None:
            self.on_progress(Progress(task, horizon, best, bound, self.elapsed()))

    def wait_event(self, event: threading.Event) -> bool:
        """Wait for an event (work in another thread); False if the budget ran
        out first."""
        while True:
            remaining = self.remaining()
            step = POLL_SECONDS if remaining is None else min(POLL_SECONDS, remaining)
            if event.wait(step):
                return True
            if self.expired():
                return False

    def wait(self, handle) -> bool:
        """Wait for an asynchronous clingo solve handle; False if the budget ran out
        first (the solve is then cancelled)."""
        while True:
            remaining = self.remaining()
            step = POLL_SECONDS if remaining is None else min(POLL_SECONDS, remaining)
            if handle.wait(step):
                return True
            if self.expired():
                handle.cancel()
                handle.wait()
                return False


class _Until(Budget):
    """A budget that also expires when a condition holds (see :meth:`Budget.until`)."""

    def __init__(self, parent: Budget, condition: Callable[[], bool]):
        super().__init__(None, parent.on_progress)
        self.started = parent.started
        self.deadline = parent.deadline
        self.time_limit = parent.time_limit
        self._cancelled = parent._cancelled
        self._reason = parent._reason
        self._share = parent._share
        self.parent = parent
        self.condition = condition

    def expired(self) -> bool:
        return self.condition() or self.parent.expired()


def unlimited() -> Budget:
    """A budget without time limit or progress callback."""
    return Budget(None)
