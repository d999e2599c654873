"""The call a worker process is running, as the work sees it.

Work that runs in a worker (:mod:`ethasp.execution.worker`) reaches its
front end through :func:`current`: it reports progress records and partial
results (the best found so far, which the front end shows if it has to end
the work at a limit), and it sees the call's limits and cancellation.  Every
:class:`~ethasp.planning.budget.Budget` made during a call joins it: the
budget expires at the call's soft deadline at the latest, and is cancelled
with it (for example when the memory of the process tree nears its limit).

Outside a worker :func:`current` is None and nothing changes.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from ethasp.execution.limits import Limits


class Context:
    """One call in a worker process: its limits, a cancellation flag, and a
    channel to the front end."""

    def __init__(self, limits: Limits, send: Callable[[tuple], None], call: int = 0):
        self.limits = limits
        self.call = call  # the front end's number for it
        self.cancelled = threading.Event()
        self.reasons: list[str] = []  # why it was cancelled (shared with budgets)
        self._send = send

    def cancel(self, reason: str = "") -> None:
        if reason:
            self.reasons[:] = [reason]
        self.cancelled.set()

    def send(self, message: tuple) -> None:
        """A message to the front end: ``(kind, value)``; besides progress
        records and partial results, ``("stderr", text)`` relays text written
        to standard error."""
        self._send(message)

    def progress(self, record: Any) -> None:
        """A progress record for the front end (its latest one is shown)."""
        self._send(("progress", record))

    def partial(self, result: Any) -> None:
        """The answer so far: what the front end shows if it ends the work at a
        limit (it replaces any partial result reported before)."""
        self._send(("partial", result))


_current: Context | None = None


def current() -> Context | None:
    """The call this process is running for a front end (None: none)."""
    return _current


def enter(context: Context | None) -> None:
    global _current
    _current = context


def partial(result: Any) -> None:
    """Report the answer so far to the front end, if there is one."""
    context = _current
    if context is not None:
        context.partial(result)
