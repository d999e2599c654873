"""clingo's messages, and how its errors reach the user (one line)."""

from __future__ import annotations

import clingo

from ethasp.errors import InputError


class Messages:
    """Collects clingo's messages; its errors become one-line InputErrors."""

    def __init__(self) -> None:
        self.errors: list[str] = []

    def __call__(self, code: clingo.MessageCode, message: str) -> None:
        first = message.split("\n", 1)[0]
        if code == clingo.MessageCode.RuntimeError or ": error:" in first:
            # "file:1:3-4: error: syntax error, ..." -> "file:1:3-4: syntax error, ..."
            self.errors.append(" ".join(message.replace(": error: ", ": ", 1).split()))

    def raise_first(self, fallback: str) -> None:
        raise InputError(self.errors[0] if self.errors else fallback)
