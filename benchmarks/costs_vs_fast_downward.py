"""Cheapest plans on IPC domains with action costs: ethasp next to Fast Downward.

Each instance is solved by a whole process, timed from outside:

* ``python -m ethasp.interfaces.cli plan DOMAIN PROBLEM --json`` (a cheapest
  plan, its cost proven least), and
* Fast Downward (``astar(lmcut())``, also cost-optimal) from the PyPI package
  ``up-fast-downward``, through its driver script ``fast-downward.py``.

Instances are the folders of a folder (by default ``tests/data/ipc-costs``):
each has ``domain.pddl`` (or one ``domain-pN.pddl`` per problem, as some
competitions publish them) and problems ``p1.pddl``, ``p2.pddl``, ...  For
each instance it prints the cost and seconds of both planners, which of
ethasp's proofs settled it (uniform-cost search, or the solver's horizons)
and whether the costs agree; a cost that differs from Fast Downward's is a
failure, and the script then ends with exit code 1.  Without
``up-fast-downward`` installed it says that the baseline is unavailable and
prints the ethasp figures alone.

Usage: python benchmarks/costs_vs_fast_downward.py [--folder DIR] [--time-limit SECONDS]
       [--problems p1,p2]
"""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import dataclass
from pathlib import Path

from fast_downward import ethasp_plan, fast_downward_driver, run_fast_downward

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data" / "ipc-costs"


@dataclass
class Instance:
    name: str
    domain: Path
    problem: Path


@dataclass
class Run:
    cost: int | None
    seconds: float
    note: str = ""
    length: int | None = None


def instances(folder: Path, problems: list[str]) -> list[Instance]:
    found = []
    for domain_folder in sorted(path for path in folder.iterdir() if path.is_dir()):
        for problem in sorted(domain_folder.glob("p*.pddl"), key=lambda p: int(p.stem[1:])):
            if problems and problem.stem not in problems:
                continue
            domain = domain_folder / f"domain-{problem.stem}.pddl"
            if not domain.is_file():
                domain = domain_folder / "domain.pddl"
            found.append(Instance(f"{domain_folder.name} {problem.stem}", domain, problem))
    return found


def run_ethasp(instance: Instance, time_limit: float) -> Run:
    done, seconds = ethasp_plan(instance.domain, instance.problem, time_limit)
    if done.returncode != 0:
        return Run(None, seconds, done.stderr.strip().splitlines()[-1][:40] if done.stderr else "")
    data = json.loads(done.stdout)
    if data["status"] != "found":
        return Run(None, seconds, data["status"])
    how = "ucs" if "uniform-cost" in data["proof"] else "solver"
    return Run(data.get("cost"), seconds, how, len(data["plan"]))


def fast_downward(driver: Path, instance: Instance, time_limit: float) -> Run:
    run = run_fast_downward(driver, instance.domain, instance.problem, time_limit)
    return Run(run.cost, run.seconds, run.note, len(run.steps) if run.steps is not None else None)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--folder", type=Path, default=DATA, help=f"default {DATA}")
    parser.add_argument(
        "--time-limit", type=float, default=60.0, help="seconds per planner and instance"
    )
    parser.add_argument(
        "--problems", default="", help="problems to run, e.g. p1,p2 (default: every one)"
    )
    args = parser.parse_args()
    driver = fast_downward_driver()
    if driver is None:
        print(
            "Fast Downward baseline unavailable (pip install up-fast-downward); ethasp figures only"
        )
    header = (
        f"{'instance':44} {'ethasp cost':>11} {'steps':>5} {'s':>6} {'proof':>6} "
        f"{'FD cost':>7} {'steps':>5} {'s':>6} {'same':>5}"
    )
    print(header)
    print("-" * len(header))
    problems = [p for p in args.problems.split(",") if p]
    solved = agreed = differ = 0
    for instance in instances(args.folder, problems):
        ours = run_ethasp(instance, args.time_limit)
        theirs = fast_downward(driver, instance, args.time_limit) if driver else None
        same = "-"
        if ours.cost is not None:
            solved += 1
        if theirs is not None and ours.cost is not None and theirs.cost is not None:
            same = "yes" if ours.cost == theirs.cost else "NO"
            agreed += ours.cost == theirs.cost
            differ += ours.cost != theirs.cost
        our_cost = str(ours.cost) if ours.cost is not None else ours.note[:11]
        their_cost = (
            "-"
            if theirs is None
            else (str(theirs.cost) if theirs.cost is not None else theirs.note[:7])
        )
        print(
            f"{instance.name:44} {our_cost:>11} {ours.length or '-':>5} {ours.seconds:>6.1f} "
            f"{ours.note if ours.cost is not None else '-':>6} {their_cost:>7} "
            f"{(theirs.length or '-') if theirs else '-':>5} "
            f"{theirs.seconds if theirs else 0:>6.1f} {same:>5}",
            flush=True,
        )
    print(
        f"ethasp proved a cheapest plan for {solved} instances; the cost agrees with Fast "
        f"Downward's on {agreed}, differs on {differ}"
    )
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
