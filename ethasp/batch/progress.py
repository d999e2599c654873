"""How a batch goes, on standard error: a bar on a terminal, plain lines otherwise.

On a terminal one line is redrawn in place (at most ten times a second)::

    [##########..........]  512/1000 cases, 3 failed, 0:41 left

Elsewhere (a log file, a pipe) a plain line is written every
:data:`EVERY` seconds, and one at the end.  Time left is estimated from the
cases finished in this run.
"""

from __future__ import annotations

import sys
import time
from typing import TextIO

# Seconds between the plain lines (not on a terminal).
EVERY = 10.0
# Redraws a second at most (on a terminal).
RATE = 10.0
WIDTH = 24


def clock(seconds: float) -> str:
    """``0:41``, ``12:05``, ``3:02:10``."""
    seconds = round(seconds)
    hours, rest = divmod(seconds, 3600)
    minutes, seconds = divmod(rest, 60)
    return f"{hours}:{minutes:02d}:{seconds:02d}" if hours else f"{minutes}:{seconds:02d}"


class BatchProgress:
    """The progress of a batch of ``total`` cases, ``before`` of them done in an earlier run."""

    def __init__(
        self,
        total: int,
        before: int = 0,
        failed_before: int = 0,
        stream: TextIO | None = None,
        terminal: bool | None = None,
        enabled: bool = True,
    ):
        self.stream = stream or sys.stderr
        self.terminal = self.stream.isatty() if terminal is None else terminal
        self.enabled = enabled
        self.total, self.before = total, before
        self.done, self.failed = before, failed_before
        self.started = time.monotonic()
        # A plain line comes after EVERY seconds; the bar at once.
        self.last = self.started if not self.terminal else 0.0
        self.width = 0

    def update(self, done: int, failed: int) -> None:
        """``done`` cases of the total finished (counting earlier runs),
        ``failed`` of them failed."""
        changed = (done, failed) != (self.done, self.failed)
        self.done, self.failed = done, failed
        if not self.enabled or not changed:
            return
        now = time.monotonic()
        if now - self.last < (1.0 / RATE if self.terminal else EVERY):
            return
        self.last = now
        self._show(self.text())

    def left(self) -> str:
        finished = self.done - self.before
        if finished <= 0:
            return "time left unknown"
        rate = (time.monotonic() - self.started) / finished
        return f"{clock(rate * (self.total - self.done))} left"

    def text(self) -> str:
        failed = f", {self.failed} failed" if self.failed else ", none failed"
        counts = f"{self.done}/{self.total} cases{failed}, {self.left()}"
        if not self.terminal:
            return f"ethasp batch: {counts}"
        filled = int(WIDTH * self.done / self.total) if self.total else WIDTH
        return f"[{'#' * filled}{'.' * (WIDTH - filled)}] {counts}"

    def _show(self, text: str) -> None:
        if self.terminal:
            padding = " " * max(0, self.width - len(text))
            self.stream.write(f"\r{text}{padding}")
            self.width = len(text)
        else:
            self.stream.write(text + "\n")
        self.stream.flush()

    def clear(self) -> None:
        """Remove the bar (before other lines are written)."""
        if self.terminal and self.width:
            self.stream.write("\r" + " " * self.width + "\r")
            self.stream.flush()
            self.width = 0

    def finish(self, summary: str) -> None:
        """The last line: the summary of the run."""
        self.clear()
        if self.enabled:
            self.stream.write(summary + "\n")
            self.stream.flush()
