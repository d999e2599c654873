"""Line editing for ``ethasp dialogue`` at a terminal: editing keys, a history
kept across runs, and completion with the Tab key.

It uses the standard library's :mod:`readline` (GNU readline or libedit);
where that is missing the dialogue reads plain lines.  Nothing here may stop
a dialogue: a history file that cannot be read or written is skipped.

* **History**: the lines typed, one per line, in ``$ETHASP_HISTORY`` if set
  (empty: no history), else ``$XDG_STATE_HOME/ethasp/history``, else
  ``~/.local/state/ethasp/history``; the last :data:`HISTORY_LENGTH` lines are
  kept.  Each line is appended as it is entered, so an interrupted dialogue
  keeps its history too.
* **Completion** (:class:`Completer`): the dialogue's commands; after ``why``,
  ``why not`` and the words that join two actions (``rather than``,
  ``before``), the model's actions and, after ``why`` and ``why not``, its
  state variables (as the model names them: ASP terms, or PDDL atoms such as
  ``(move kitchen hall)``, completed word by word); the principle names after
  ``principle``; file names after ``save`` and ``load``.
"""

from __future__ import annotations

import glob
import os
import sys
from collections.abc import Iterable, Sequence
from pathlib import Path

HISTORY_LENGTH = 1000
COMMANDS = ("why", "principle", "plan", "history", "undo", "save", "load", "help", "quit")
# Words that join the actions of a question ("why A rather than B").
JOINING = ("rather than", "before")


def history_path(environ: dict | None = None) -> Path | None:
    """Where the dialogue's history is kept (None: nowhere)."""
    environ = os.environ if environ is None else environ
    if "ETHASP_HISTORY" in environ:
        return Path(environ["ETHASP_HISTORY"]) if environ["ETHASP_HISTORY"] else None
    base = environ.get("XDG_STATE_HOME")
    if not base:
        try:
            home = Path(environ["HOME"]) if environ.get("HOME") else Path.home()
        except (RuntimeError, KeyError):  # no home directory
            return None
        base = str(home / ".local" / "state")
    return Path(base) / "ethasp" / "history"


def _operand_start(text: str) -> int:
    """Where the operand being typed at the end of ``text`` starts: after the
    last white space outside parentheses (a PDDL atom has spaces inside)."""
    depth, start = 0, 0
    for index, char in enumerate(text):
        if char == "(":
            depth += 1
        elif char == ")" and depth:
            depth -= 1
        elif char.isspace() and depth == 0:
            start = index + 1
    return start


class Completer:
    """What completes the word before the cursor, from the whole line before it.

    ``actions``, ``facts`` and ``principles`` are names as users type them
    (``pull``, ``move(a,b)``, ``(move a b)``).
    """

    def __init__(
        self,
        actions: Iterable[str],
        facts: Iterable[str],
        principles: Iterable[str],
        commands: Sequence[str] = COMMANDS,
    ):
        self.actions = sorted(set(actions))
        self.facts = sorted(set(facts))
        self.principles = sorted(set(principles))
        self.commands = list(commands)
        self._matches: list[str] = []

    def candidates(self, before: str) -> list[str]:
        """The completions of the line ``before`` the cursor, each to replace
        the text after its last space (readline's word); a complete word ends
        with a space (Python's readline adds none)."""
        word = before.split(" ")[-1]
        words = before[: len(before) - len(word)].split()
        if not words:
            return [command + " " for command in self.commands if command.startswith(word.lower())]
        command = words[0].lower()
        if command == "principle":
            return (
                [p + " " for p in self.principles if p.startswith(word)] if len(words) == 1 else []
            )
        if command in ("save", "load"):
            return self._files(word) if len(words) == 1 else []
        if command != "why":
            return []
        start = _operand_start(before)
        operand, head = before[start:], before[:start]
        kept = len(operand) - len(word)  # the operand's words before readline's word
        found = [name[kept:] + " " for name in self._names(head) if name.startswith(operand)]
        if kept == 0:
            found += [
                keyword for keyword in self._keywords(head) if keyword.startswith(word.lower())
            ]
        return found

    def _names(self, head: str) -> list[str]:
        """The names that may come after ``head`` (the line before the operand)."""
        text = " ".join(head.split()).lower()
        if text in ("why", "why not"):
            return self.actions + self.facts
        if any(text.endswith(" " + joining) for joining in JOINING):
            return self.actions
        return []

    @staticmethod
    def _keywords(head: str) -> list[str]:
        """``not`` after ``why``; the joining words after a first action."""
        text = " ".join(head.split()).lower()
        if text == "why":
            return ["not "]
        words = text.split()
        if len(words) < 2 or words[1] == "not":
            return []
        if text.endswith(" rather"):
            return ["than "]
        if (
            any(f" {joining} " in f"{text} " for joining in JOINING)
            or len(head) - _operand_start(head.rstrip()) == 0
        ):
            return []
        return [joining.split()[0] + " " for joining in JOINING]

    @staticmethod
    def _files(word: str) -> list[str]:
        found = []
        for name in sorted(glob.glob(glob.escape(os.path.expanduser(word)) + "*")):
            found.append(name + ("/" if os.path.isdir(name) else ""))
        return found

    def __call__(self, text: str, state: int) -> str | None:
        """readline's completer: the ``state``-th completion of ``text``."""
        if state == 0:
            try:
                import readline

                before = readline.get_line_buffer()[: readline.get_endidx()]
            except (ImportError, AttributeError):
                before = text
            try:
                self._matches = self.candidates(before)
            except Exception:
                self._matches = []
        return self._matches[state] if state < len(self._matches) else None


class LineEditor:
    """Reads the dialogue's lines with editing, history and completion when
    standard input is a terminal and readline is available."""

    def __init__(self, completer: Completer | None = None, path: Path | None = None):
        self.path = path
        self.readline = None
        self._terminal = None
        try:
            import readline
        except ImportError:  # a Python without readline: plain lines
            return
        self.readline = readline
        try:
            import termios

            self._terminal = termios.tcgetattr(sys.stdin.fileno())
        except (ImportError, OSError, ValueError):
            self._terminal = None
        readline.set_history_length(HISTORY_LENGTH)
        if completer is not None:
            readline.set_completer(completer)
            readline.set_completer_delims(" \t\n")
            if "libedit" in (getattr(readline, "__doc__", "") or ""):
                readline.parse_and_bind("bind ^I rl_complete")
            else:
                readline.parse_and_bind("tab: complete")
        if path is not None:
            try:
                readline.read_history_file(str(path))
                if readline.get_current_history_length() > HISTORY_LENGTH:
                    readline.write_history_file(str(path))  # keeps the last lines only
            except (OSError, ValueError):
                pass

    def read(self, prompt: str) -> str:
        """One line (EOFError at the end of input)."""
        line = input(prompt)
        if self.readline is not None and self.path is not None and line.strip():
            try:
                self.path.parent.mkdir(parents=True, exist_ok=True)
                if not self.path.exists():
                    self.path.touch(mode=0o600)
                self.readline.append_history_file(1, str(self.path))
            except (OSError, ValueError, AttributeError):
                pass  # the history is a convenience: never an error
        return line

    def restore(self) -> None:
        """Give the terminal back as it was (after an interrupt that ends the
        process while readline has it in its own mode)."""
        if self._terminal is None:
            return
        try:
            import termios

            termios.tcsetattr(sys.stdin.fileno(), termios.TCSADRAIN, self._terminal)
        except (ImportError, OSError, ValueError):
            pass
