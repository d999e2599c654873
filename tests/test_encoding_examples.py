"""Every command that an encoding's header shows (``python -m clingo ...``,
possibly fed by ``echo ... |`` or ``<<< '...'``) runs as written from the
repository's root and ends in an answer, without an error, a warning or an
info message, and prints what the header says it shows: the line ``shows:``
right after the command lists text that the output holds (atoms, or
``UNSATISFIABLE``).  A reader can run each such encoding alone."""

from __future__ import annotations

import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
# Exit codes of clingo for an answer (satisfiable, unsatisfiable, complete);
# `python -m clingo` may also end with 0.
CLINGO_ANSWERS = {0, 10, 20, 30}


def header_commands(path: Path) -> list[tuple[str, list[str]]]:
    """The commands of the comment lines of a file (continued by a trailing
    backslash), those with an elision (``...``) left out, each with what the
    ``shows:`` line right after it lists."""
    commands: list[tuple[str, list[str]]] = []
    current, finished = None, None
    for line in path.read_text().splitlines():
        text = line[1:].strip() if line.startswith("%") else None
        if finished is not None:  # the line after a command
            shows = (
                text.removeprefix("shows:").split() if text and text.startswith("shows:") else []
            )
            commands.append((finished, shows))
            finished = None
        if text is None:
            current = None
            continue
        if current is None:
            if not (text.startswith(("python -m clingo", "echo "))):
                continue
            current = []
        current.append(text[:-1].rstrip() if text.endswith("\\") else text)
        joined = " ".join(current)
        unfinished = (
            text.endswith("\\")
            or joined.count("'") % 2
            or (joined.startswith("echo ") and "python -m clingo" not in joined)
        )
        if unfinished:
            continue
        if "..." not in joined:
            finished = joined
        current = None
    return commands


EXAMPLES = [
    (path.relative_to(ROOT).as_posix(), command, shows)
    for path in sorted((ROOT / "encodings").rglob("*.lp"))
    for command, shows in header_commands(path)
]


def test_the_examples_are_found():
    assert len(EXAMPLES) >= 10
    assert {"encodings/planning/plan.lp", "encodings/reasons/necessary.lp"} <= {
        name for name, _, _ in EXAMPLES
    }
    # Each says what it shows.
    assert [name for name, _, shows in EXAMPLES if not shows] == []


@pytest.mark.parametrize("name,command,shows", EXAMPLES, ids=[name for name, _, _ in EXAMPLES])
def test_an_encoding_runs_as_its_header_shows(name, command, shows):
    command = command.replace("python -m clingo", f"{shlex.quote(sys.executable)} -m clingo")
    run = subprocess.run(
        ["bash", "-c", command], cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    assert run.returncode in CLINGO_ANSWERS, (command, run.stdout[-2000:], run.stderr[-2000:])
    assert "ERROR" not in run.stderr and "error" not in run.stdout.lower(), run.stderr
    assert "warning" not in run.stderr and "info:" not in run.stderr, run.stderr
    assert "SATISFIABLE" in run.stdout or "OPTIMUM FOUND" in run.stdout, run.stdout[-2000:]
    missing = [text for text in shows if text not in run.stdout]
    assert not missing, (missing, run.stdout[-2000:])
