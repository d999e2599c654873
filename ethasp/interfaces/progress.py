"""A live progress line on standard error, for searches that take a while.

Searches report :class:`ethasp.planning.budget.Progress` records to their
budget's callback.  :class:`ProgressLine` shows the latest one as a single
line, rewritten in place, once a command has run for :data:`DELAY` seconds,
and only when standard error is a terminal (so scripts and pipes see
nothing); the line is cleared before the answer is printed.
"""

from __future__ import annotations

import sys
import time
from typing import TextIO

from ethasp.planning.budget import Progress

# Seconds of quiet before the first progress line.
DELAY = 2.0
# At most this many redraws a second.
RATE = 10.0


class ProgressLine:
    """Shows progress records as one live line on a terminal."""

    def __init__(self, stream: TextIO | None = None, enabled: bool | None = None):
        self.stream = stream or sys.stderr
        self.enabled = self.stream.isatty() if enabled is None else enabled
        self.started = time.monotonic()
        self.last = 0.0
        self.width = 0

    def __call__(self, progress: Progress) -> None:
        if not self.enabled:
            return
        now = time.monotonic()
        if now - self.started < DELAY or now - self.last < 1.0 / RATE:
            return
        self.last = now
        text = f"ethasp: {progress.line()}"
        padding = " " * max(0, self.width - len(text))
        self.stream.write(f"\r{text}{padding}")
        self.stream.flush()
        self.width = len(text)

    def clear(self) -> None:
        """Remove the line (before the answer is printed)."""
        if self.width:
            self.stream.write("\r" + " " * self.width + "\r")
            self.stream.flush()
            self.width = 0
