"""The examples of the documentation run as shown.

An example in README.md or docs/**/*.md is runnable when the line before its
code fence is the comment ``<!-- runnable -->`` (invisible on the rendered
page):

* a ``console`` block holds shell commands, each on a line starting with
  ``$ `` (continued by a trailing backslash), and below each the output it
  shows (standard output and standard error together).  The commands of a
  block run one after the other with bash, in one scratch folder that sees the
  repository's files (so ``asp/trolley.lp`` works and files the example writes
  stay out of the repository), with the ``ethasp`` and ``python`` of this
  environment.  Each must exit with code 0, the last one with N if the
  comment says ``<!-- runnable exit=N -->``;
* a ``pycon`` block is a Python session (``>>>`` prompts), run as a doctest
  from the same kind of folder.

In the output shown, a line ``...`` stands for any number of lines, and
``...`` within a line for any text (times, figures that vary); trailing
spaces do not count.  Everything else must be printed exactly so.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
MARKER = re.compile(r"^<!--\s*runnable(?:\s+exit=(\d+))?\s*-->\s*$")
FENCE = re.compile(r"^```(\w+)\s*$")
LANGUAGES = {"console", "pycon"}
TIMEOUT = 300  # seconds for one block (a guard against hangs, not a measure of speed)


@dataclass
class Example:
    path: Path
    line: int  # of the fence, 1-based
    language: str
    text: str  # the block's lines
    exit_code: int  # of the block's last command

    @property
    def name(self) -> str:
        return f"{self.path.relative_to(ROOT).as_posix()}:{self.line}"


def documents() -> list[Path]:
    return [
        ROOT / "README.md",
        *sorted(path for path in (ROOT / "docs").rglob("*.md") if "hooks" not in path.parts),
    ]


def examples_of(path: Path) -> list[Example]:
    lines = path.read_text(encoding="utf-8").splitlines()
    found = []
    for index, line in enumerate(lines):
        marker = MARKER.match(line)
        if not marker:
            continue
        fence = FENCE.match(lines[index + 1]) if index + 1 < len(lines) else None
        where = f"{path.relative_to(ROOT)}:{index + 1}"
        if fence is None or fence.group(1) not in LANGUAGES:
            raise AssertionError(
                f"{where}: a runnable marker must stand right before a ```console or ```pycon block"
            )
        end = next((j for j in range(index + 2, len(lines)) if lines[j].startswith("```")), None)
        if end is None:
            raise AssertionError(f"{where}: the block does not end")
        found.append(
            Example(
                path,
                index + 2,
                fence.group(1),
                "\n".join(lines[index + 2 : end]),
                int(marker.group(1) or 0),
            )
        )
    return found


EXAMPLES = [example for path in documents() for example in examples_of(path)]


def commands_of(text: str) -> list[tuple[str, list[str]]]:
    """The commands of a console block, each with the output lines shown."""
    commands: list[tuple[str, list[str]]] = []
    lines = text.splitlines()
    index = 0
    while index < len(lines):
        line = lines[index]
        if not line.startswith("$ "):
            if not commands:
                raise AssertionError(f"output before the first command: {line!r}")
            commands[-1][1].append(line)
            index += 1
            continue
        command = line[2:]
        while command.endswith("\\") and index + 1 < len(lines):
            index += 1
            command = command + "\n" + lines[index]  # bash joins the lines
        commands.append((command, []))
        index += 1
    return commands


def pattern(shown: list[str]) -> re.Pattern:
    """The output shown as a pattern: ``...`` lines and ``...`` within lines elide."""
    while shown and not shown[-1].strip():
        shown = shown[:-1]
    parts = []
    for line in shown:
        line = line.rstrip()
        if line == "...":
            parts.append(r"(?:[^\n]*\n)*?")
        else:
            pieces = line.split("...")
            # (a space before an elision may be the line's trailing space)
            pieces = [piece.rstrip() for piece in pieces[:-1]] + pieces[-1:]
            parts.append(".*?".join(re.escape(piece) for piece in pieces) + r"\n")
    return re.compile("".join(parts), re.S)


def normalised(output: str) -> str:
    lines = [line.rstrip() for line in output.splitlines()]
    while lines and not lines[-1]:
        lines.pop()
    return "".join(line + "\n" for line in lines)


@pytest.fixture
def workdir(tmp_path: Path) -> Path:
    """A scratch folder that sees the repository's files."""
    for entry in ROOT.iterdir():
        if not entry.name.startswith("."):
            (tmp_path / entry.name).symlink_to(entry)
    return tmp_path


def environment() -> dict[str, str]:
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join([str(Path(sys.executable).parent), env.get("PATH", "")])
    env.pop("ETHASP_DEBUG", None)
    env["COLUMNS"] = "80"
    return env


def test_the_examples_are_found():
    assert len(EXAMPLES) >= 20
    shown = "\n".join(example.text for example in EXAMPLES if example.language == "console")
    for command in ("plan", "validate", "judge", "query", "ask", "dialogue"):
        assert re.search(rf"^\$ (?:.*\| )?ethasp {command} ", shown, re.M), command
    assert any(example.path.name == "README.md" for example in EXAMPLES)
    assert any(example.language == "pycon" for example in EXAMPLES)


def run_console(example: Example, workdir: Path) -> None:
    commands = commands_of(example.text)
    for number, (command, shown) in enumerate(commands, start=1):
        expected_code = example.exit_code if number == len(commands) else 0
        run = subprocess.run(
            ["bash", "-c", command],
            cwd=workdir,
            env=environment(),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            timeout=TIMEOUT,
        )
        output = normalised(run.stdout)
        where = f"{example.name}: $ {command}"
        assert run.returncode == expected_code, (
            f"{where}\nexit code {run.returncode}, expected {expected_code}\n{output}"
        )
        assert pattern(shown).fullmatch(output), (
            f"{where}\nthe output differs from the documentation's:\n--- shown\n"
            + "\n".join(shown)
            + "\n--- printed\n"
            + output
        )


# Runs a doctest given on standard input; prints the failures, exits with their count.
DOCTEST = """
import doctest, sys
text = sys.stdin.read()
test = doctest.DocTestParser().get_doctest(text, {}, sys.argv[1], sys.argv[1], 0)
runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
runner.run(test)
sys.exit(min(runner.failures, 100))
"""


def run_pycon(example: Example, workdir: Path) -> None:
    run = subprocess.run(
        [sys.executable, "-c", DOCTEST, example.name],
        input=example.text,
        cwd=workdir,
        env=environment(),
        capture_output=True,
        text=True,
        timeout=TIMEOUT,
    )
    assert run.returncode == 0, f"{example.name}\n{run.stdout}{run.stderr}"


@pytest.mark.slow  # one or more ethasp processes per example
@pytest.mark.parametrize("example", EXAMPLES, ids=[example.name for example in EXAMPLES])
def test_an_example_runs_as_shown(example: Example, workdir: Path):
    if example.language == "console":
        run_console(example, workdir)
    else:
        run_pycon(example, workdir)


def test_elisions_match_what_they_should():
    assert pattern(["a ... c", "...", "z"]).fullmatch("a b c\nx\ny\nz\n")
    assert pattern(["...", "z"]).fullmatch("z\n")
    assert not pattern(["a", "z"]).fullmatch("a\nb\nz\n")
    assert not pattern(["a (1.0 s)"]).fullmatch("a (1.05 s)\n")
    assert commands_of("$ echo a \\\n  b\na b\n$ true") == [
        ("echo a \\\n  b", ["a b"]),
        ("true", []),
    ]
