"""Fast Downward for the benchmarks: its driver script, from the PyPI package
``up-fast-downward`` (a benchmark extra, never a dependency of ethasp), and
the commands the benchmarks run beside it (``ethasp plan`` of a task)."""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def fast_downward_command(
    driver: Path, domain: Path, problem: Path, plan_file: Path, search: str
) -> list[str]:
    """Fast Downward's driver on a task, writing its plan to ``plan_file``."""
    return [
        sys.executable,
        str(driver),
        "--plan-file",
        str(plan_file),
        str(domain),
        str(problem),
        "--search",
        search,
    ]


def ethasp_plan(
    domain: Path, problem: Path, time_limit: float
) -> tuple[subprocess.CompletedProcess, float]:
    """``ethasp plan DOMAIN PROBLEM --json`` of this checkout, as a whole
    process timed from outside: the process and its seconds."""
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    command = [
        sys.executable,
        "-m",
        "ethasp.interfaces.cli",
        "plan",
        str(domain),
        str(problem),
        "--json",
        "--time-limit",
        str(time_limit),
    ]
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, env=env, cwd=ROOT)
    return done, time.perf_counter() - start


def fast_downward_driver() -> Path | None:
    """The driver script of the up-fast-downward package, if it is installed."""
    spec = importlib.util.find_spec("up_fast_downward")
    if spec is None or not spec.submodule_search_locations:
        return None
    for location in spec.submodule_search_locations:
        driver = Path(location) / "downward" / "fast-downward.py"
        if driver.is_file():
            return driver
    return None


@dataclass
class FastDownwardPlan:
    """What one run of Fast Downward gave: the plan's steps and cost (None
    without a plan), the seconds it took, and why there is no plan."""

    steps: list[str] | None
    cost: int | None
    seconds: float
    note: str = ""


def run_fast_downward(
    driver: Path, domain: Path, problem: Path, time_limit: float, search: str = "astar(lmcut())"
) -> FastDownwardPlan:
    """Fast Downward on a task, as a whole process timed from outside."""
    with tempfile.TemporaryDirectory() as work:
        plan_file = Path(work) / "plan"
        command = fast_downward_command(driver, domain, problem, plan_file, search)
        start = time.perf_counter()
        try:
            subprocess.run(command, capture_output=True, text=True, cwd=work, timeout=time_limit)
        except subprocess.TimeoutExpired:
            return FastDownwardPlan(None, None, time.perf_counter() - start, "time limit")
        seconds = time.perf_counter() - start
        if not plan_file.is_file():
            return FastDownwardPlan(None, None, seconds, "no plan")
        text = plan_file.read_text()
        cost = re.search(r"; cost = (\d+)", text)
        steps = [line for line in text.splitlines() if line.strip() and not line.startswith(";")]
        return FastDownwardPlan(steps, int(cost.group(1)) if cost else None, seconds)
