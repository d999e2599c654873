"""Every command that an encoding's header shows (``python -m clingo ...``,
possibly fed by ``echo ... |`` or ``<<< '...'``) runs as written from the
repository's root and ends in an answer, not an error: a reader can run each
such encoding alone."""

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


def header_commands(path: Path) -> list[str]:
    """The commands of the comment lines of a file (continued by a trailing
    backslash), those with an elision (``...``) left out."""
    commands, current = [], None
    for line in path.read_text().splitlines():
        if not line.startswith("%"):
            current = None
            continue
        text = line[1:].strip()
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
            commands.append(joined)
        current = None
    return commands


EXAMPLES = [
    (path.relative_to(ROOT).as_posix(), command)
    for path in sorted((ROOT / "encodings").rglob("*.lp"))
    for command in header_commands(path)
]


def test_the_examples_are_found():
    assert len(EXAMPLES) >= 10
    assert {"encodings/planning/plan.lp", "encodings/reasons/necessary.lp"} <= {
        name for name, _ in EXAMPLES
    }


@pytest.mark.parametrize("name,command", EXAMPLES, ids=[name for name, _ in EXAMPLES])
def test_an_encoding_runs_as_its_header_shows(name, command):
    command = command.replace("python -m clingo", f"{shlex.quote(sys.executable)} -m clingo")
    run = subprocess.run(
        ["bash", "-c", command], cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    assert run.returncode in CLINGO_ANSWERS, (command, run.stdout[-2000:], run.stderr[-2000:])
    assert "ERROR" not in run.stderr and "error" not in run.stdout.lower(), run.stderr
    assert "SATISFIABLE" in run.stdout or "OPTIMUM FOUND" in run.stdout, run.stdout[-2000:]
