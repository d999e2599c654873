"""Plan search on the bundled PDDL domains: ethasp next to Fast Downward.

Each instance is solved by a whole process, timed from outside:

* ``python -m ethasp.interfaces.cli plan DOMAIN PROBLEM --json`` (shortest plans), and
* Fast Downward (``astar(lmcut())``, also optimal) from the PyPI package
  ``up-fast-downward``, through its driver script ``fast-downward.py``.

Instances are the bundled problems plus larger ones of the bundled blocks
world and gripper domains, generated here (plans of up to about 20 steps).
For each instance it prints the plan length and seconds of both planners and
the ratio ethasp/Fast Downward.  Without ``up-fast-downward`` installed it
says that the baseline is unavailable and prints the ethasp figures alone.

Usage: python benchmarks/pddl_vs_fast_downward.py [--time-limit SECONDS] [--quick]
"""

from __future__ import annotations

import argparse
import itertools
import json
import random
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from fast_downward import ethasp_plan, fast_downward_driver, run_fast_downward

ROOT = Path(__file__).resolve().parent.parent
PDDL = ROOT / "asp" / "pddl"


@dataclass
class Instance:
    name: str
    domain: Path
    problem: Path


@dataclass
class Run:
    length: int | None
    seconds: float
    note: str = ""


# -- generated problems -------------------------------------------------------------


def gripper_problem(balls: int) -> str:
    names = " ".join(f"ball-{i}" for i in range(1, balls + 1))
    init = " ".join(f"(ball-at ball-{i} a)" for i in range(1, balls + 1))
    goal = " ".join(f"(ball-at ball-{i} b)" for i in range(1, balls + 1))
    return (
        f"(define (problem gripper-{balls}) (:domain gripper)\n"
        f"  (:objects a b - room left right - gripper {names} - ball)\n"
        f"  (:init (robot-at a) (free left) (free right) (occupied b) {init})\n"
        f"  (:goal (and {goal})))\n"
    )


def _towers(blocks: list[str], rng: random.Random) -> list[list[str]]:
    blocks = blocks[:]
    rng.shuffle(blocks)
    towers: list[list[str]] = []
    for block in blocks:
        if towers and rng.random() < 0.7:
            rng.choice(towers).append(block)
        else:
            towers.append([block])
    return towers


def blocksworld_problem(size: int, seed: int) -> str:
    rng = random.Random(seed)
    blocks = [f"b{i}" for i in range(1, size + 1)]
    init = []
    for tower in _towers(blocks, rng):
        init.append(f"(on-table {tower[0]})")
        init += [f"(on {upper} {lower})" for lower, upper in itertools.pairwise(tower)]
        init.append(f"(clear {tower[-1]})")
    goal = [
        f"(on {upper} {lower})"
        for tower in _towers(blocks, rng)
        for lower, upper in itertools.pairwise(tower)
    ]
    return (
        f"(define (problem blocks-{size}-{seed}) (:domain blocksworld)\n"
        f"  (:objects {' '.join(blocks)} - block)\n"
        f"  (:init {' '.join(init)} (fragile b1))\n"
        f"  (:goal (and {' '.join(goal)})))\n"
    )


def instances(folder: Path, quick: bool) -> list[Instance]:
    result = [
        Instance(name, PDDL / f"{name}-domain.pddl", PDDL / f"{name}-problem.pddl")
        for name in ("trolley", "care", "blocksworld", "gripper")
    ]
    generated = {f"gripper-{n}": gripper_problem(n) for n in ((2, 3) if quick else (2, 3, 5, 6))}
    blocks = [(6, 1), (7, 2)] if quick else [(6, 1), (7, 2), (8, 6), (10, 5), (9, 4)]
    generated |= {f"blocks-{n}-{seed}": blocksworld_problem(n, seed) for n, seed in blocks}
    for name, text in generated.items():
        path = folder / f"{name}.pddl"
        path.write_text(text)
        domain = "gripper" if name.startswith("gripper") else "blocksworld"
        result.append(Instance(name, PDDL / f"{domain}-domain.pddl", path))
    return result


# -- the planners -------------------------------------------------------------------


def run_ethasp(instance: Instance, time_limit: float) -> Run:
    done, seconds = ethasp_plan(instance.domain, instance.problem, time_limit)
    if done.returncode != 0:
        return Run(None, seconds, done.stderr.strip())
    data = json.loads(done.stdout)
    if data["status"] != "found":
        return Run(None, seconds, data["status"])
    return Run(len(data["plan"]), seconds)


def fast_downward(driver: Path, instance: Instance, time_limit: float) -> Run:
    run = run_fast_downward(driver, instance.domain, instance.problem, time_limit)
    return Run(len(run.steps) if run.steps is not None else None, run.seconds, run.note)


# -- the table ----------------------------------------------------------------------


def show(run: Run | None) -> tuple[str, str]:
    if run is None:
        return "-", "-"
    return (str(run.length) if run.length is not None else run.note[:12]), f"{run.seconds:.2f}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--time-limit",
        type=float,
        default=60.0,
        help="seconds per planner and instance (default 60)",
    )
    parser.add_argument("--quick", action="store_true", help="small instances only")
    args = parser.parse_args()
    driver = fast_downward_driver()
    if driver is None:
        print(
            "Fast Downward baseline unavailable (pip install up-fast-downward); ethasp figures only"
        )
    header = (
        f"{'instance':16} {'ethasp len':>10} {'ethasp s':>9} {'FD len':>7} {'FD s':>7} {'ratio':>6}"
    )
    print(header)
    print("-" * len(header))
    ratios = []
    with tempfile.TemporaryDirectory() as folder:
        for instance in instances(Path(folder), args.quick):
            ours = run_ethasp(instance, args.time_limit)
            theirs = fast_downward(driver, instance, args.time_limit) if driver else None
            ratio = "-"
            if theirs is not None and ours.length is not None and theirs.length is not None:
                ratios.append(ours.seconds / theirs.seconds)
                ratio = f"{ratios[-1]:.1f}"
            (our_length, our_seconds), (their_length, their_seconds) = show(ours), show(theirs)
            print(
                f"{instance.name:16} {our_length:>10} {our_seconds:>9} {their_length:>7} "
                f"{their_seconds:>7} {ratio:>6}",
                flush=True,
            )
    if ratios:
        ratios.sort()
        print(
            f"median ratio ethasp/FD: {ratios[len(ratios) // 2]:.1f} "
            f"(instances solved by both: {len(ratios)})"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
