"""The bad-input corpus (tests/bad_inputs/cases.jsonl): every bad input gets
exit code 2 and one line on standard error naming the problem, never a
traceback.  Plus one generated case for every reserved predicate."""

from __future__ import annotations

import contextlib
import io
import json
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import MODELS, ROOT

from ethasp.interfaces.cli import main
from ethasp.planning.driver.namespace import reserved, signature_text

CORPUS = Path(__file__).resolve().parent / "bad_inputs"
FIXTURES = CORPUS / "fixtures"

PLACEHOLDERS = {
    "f": str(FIXTURES),
    "pddl": str(MODELS / "pddl"),
    "deep_not": shlex.quote("not " * 10_001 + "Bad(pull)"),
    "deep_name": shlex.quote("Good(" + "f(" * 10_001 + "a" + ")" * 10_001 + ")"),
    "deep_question": shlex.quote("why " + "f(" * 10_001 + "a" + ")" * 10_001),
    "long": "a" * 5000,
    "undecodable": shlex.quote('"\udcff"'),  # a byte that is not UTF-8, as Python keeps it
}


def rows() -> list[dict]:
    lines = (CORPUS / "cases.jsonl").read_text().splitlines()
    return [json.loads(line) for line in lines if line.strip()]


def argv(row: dict) -> list[str]:
    command = row["command"]
    for key, value in PLACEHOLDERS.items():
        command = command.replace("{" + key + "}", value)
    return shlex.split(command)


def run_in_process(arguments: list[str], stdin: str = "") -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    saved_stdin = sys.stdin
    sys.stdin = io.StringIO(stdin)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(arguments)
    finally:
        sys.stdin = saved_stdin
    return code, out.getvalue(), err.getvalue()


def run_process(arguments: list[str]) -> tuple[int, str, str]:
    done = subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *arguments],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=300,
        cwd=ROOT,
    )
    return done.returncode, done.stdout, done.stderr


def assert_refused(code: int, out: str, err: str, fragment: str, expected: int = 2) -> None:
    assert "Traceback" not in err and "Traceback" not in out, err
    assert code == expected, (code, err)
    lines = err.splitlines()
    assert len(lines) == 1, f"expected one line on standard error, got: {err!r}"
    assert fragment in lines[0], f"{fragment!r} not in {lines[0]!r}"


CASES = rows()


def test_the_corpus_is_large_and_well_formed():
    assert len(CASES) >= 80
    for row in CASES:
        assert set(row) <= {"command", "fragment", "exit", "subprocess"}, row
        assert row["exit"] == 2 and row["fragment"]


@pytest.mark.parametrize("row", CASES, ids=[row["command"][:60] for row in CASES])
def test_bad_input_in_process(row, monkeypatch, tmp_path):
    monkeypatch.chdir(tmp_path)  # nothing is written beside the sources
    fragment = row["fragment"].replace("{f}", str(FIXTURES))
    assert_refused(*run_in_process(argv(row)), fragment, row["exit"])


SUBPROCESS = [row for row in CASES if row.get("subprocess")]


@pytest.mark.slow
@pytest.mark.parametrize("row", SUBPROCESS, ids=[row["command"][:60] for row in SUBPROCESS])
def test_bad_input_as_a_process(row):
    fragment = row["fragment"].replace("{f}", str(FIXTURES))
    assert_refused(*run_process(argv(row)), fragment, row["exit"])


# -- every reserved predicate, generated from the encodings -----------------------


def _fact(signature: tuple[str, int]) -> str:
    name, arity = signature
    return f"{name}({','.join(['x'] * arity)})." if arity else f"{name}."


RESERVED = sorted(reserved(pddl=False))


@pytest.mark.parametrize("signature", RESERVED, ids=[signature_text(s) for s in RESERVED])
def test_every_reserved_predicate_is_refused(signature, tmp_path):
    model = tmp_path / "model.lp"
    model.write_text((MODELS / "trolley.lp").read_text() + "\n" + _fact(signature) + "\n")
    assert_refused(
        *run_in_process(["plan", str(model)]),
        f"model.lp:{len((MODELS / 'trolley.lp').read_text().splitlines()) + 2}: "
        f"the model defines {signature_text(signature)}",
    )


@pytest.mark.parametrize("signature", sorted(set(reserved(pddl=True)) - set(RESERVED)))
def test_pddl_typing_is_reserved_for_pddl_tasks(signature, tmp_path):
    annotations = tmp_path / "annotations.lp"
    annotations.write_text(_fact(signature) + "\n")
    pddl = MODELS / "pddl"
    assert_refused(
        *run_in_process(
            [
                "plan",
                str(pddl / "trolley-domain.pddl"),
                str(pddl / "trolley-problem.pddl"),
                str(annotations),
            ]
        ),
        f"the model defines {signature_text(signature)}",
    )


def test_a_time_limit_of_zero_means_no_limit():
    code, out, err = run_in_process(["plan", "trolley", "--time-limit", "0"])
    assert code == 0 and err == "" and out.startswith("plan of 1 step")
