"""Shared test helpers: run encodings through clingo and read answer sets."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import clingo
import pytest
from hypothesis import HealthCheck, settings

ROOT = Path(__file__).resolve().parent.parent
ENCODINGS = ROOT / "encodings"
MODELS = ROOT / "asp"

# The Hypothesis profiles of the property tests.  ``ci`` (continuous
# integration, .ci/run): derandomised, so that every run draws the same
# examples and a failure is the code's, never the draw's; no example
# database, no deadline (a shared machine is slow at times), and a failing
# example printed so that it can be replayed (@reproduce_failure).  ``dev``,
# the default elsewhere: new random examples on every run, failures kept in
# the local example database and tried first next time.  Each test sets its
# own number of examples; HYPOTHESIS_PROFILE chooses the profile (``ci`` by
# default where the variable CI is set, as CI services do).
settings.register_profile(
    "ci",
    derandomize=True,
    database=None,
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile("dev", deadline=None)
PROFILE = os.environ.get("HYPOTHESIS_PROFILE") or ("ci" if os.environ.get("CI") else "dev")
settings.load_profile(PROFILE)


def ethasp_process(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    """``python -m ethasp.interfaces.cli ARGS`` as a process, run from ``cwd``
    with the checkout's ethasp, its output captured as text."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
    )


def answer_sets(files, program: str = "", arguments=("0",)) -> list[set[str]]:
    """All answer sets (shown atoms, as strings) of encodings plus a program."""
    ctl = clingo.Control(list(arguments), logger=lambda code, message: None)
    for name in files:
        ctl.load(str(ENCODINGS / name) if not Path(name).is_absolute() else str(name))
    if program:
        ctl.add("base", [], program)
    ctl.ground([("base", [])])
    result: list[set[str]] = []
    ctl.solve(on_model=lambda model: result.append({str(s) for s in model.symbols(shown=True)}))
    return result


def only_answer(files, program: str = "") -> set[str]:
    answers = answer_sets(files, program)
    assert len(answers) == 1, answers
    return answers[0]


@pytest.fixture
def trolley_path() -> Path:
    return MODELS / "trolley.lp"
