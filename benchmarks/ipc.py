"""Plan search on IPC domains: ethasp next to Fast Downward, in one run.

For every domain folder (a ``domain.pddl`` and problem files ``*.pddl``) under
the folder given (for instance a copy of IPC domains) and every problem, four
whole processes are timed from outside, each capped (``--time-limit``,
default 60 s):

* ``ethasp plan DOMAIN PROBLEM --json --planner clingo`` (a shortest plan,
  proven, by the encodings and the engines beside them: mode ``opt``);
* the same with ``--satisficing`` (some plan: ``sat``);
* both with ``--planner fast-downward`` (Fast Downward as ethasp's engine,
  on the task written from ethasp's grounding: ``opt-fd``, ``sat-fd``);
* Fast Downward ``astar(lmcut())`` (optimal) and
* Fast Downward ``lazy_greedy([ff()])`` (satisficing), both from the PyPI
  package ``up-fast-downward`` (``pip install '.[benchmark]'``), through its
  driver script.

It prints per instance and mode the plan length, the seconds and ethasp's
status, and the ratios ethasp/Fast Downward (optimal against astar,
satisficing against greedy); then how many instances meet the targets, on
every instance Fast Downward solves within 10 s: with clingo, an optimal plan
of Fast Downward's length within 2x its time and a satisficing plan within
3x; with Fast Downward as the engine, both within 1.5x.
ethasp's modules are compiled to bytecode first, as a wheel installation has
them.  ``--repeat N`` runs each process N times and keeps the fastest (the
machine may be shared).  ``--cpu`` prints (and compares) processor seconds
instead, user and system time of each process and its children: on a busy
machine they vary far less than the seconds on the clock, but they count
every core ethasp's engines use.  ``--json FILE`` writes every run (seconds
and processor seconds).  Without ``up-fast-downward`` it prints ethasp's
figures alone.

Usage: python benchmarks/ipc.py FOLDER [--time-limit S] [--repeat N] [--only TEXT]
                                [--modes opt,sat,opt-fd,sat-fd,fd-opt,fd-sat] [--cpu] [--json FILE]
"""

from __future__ import annotations

import argparse
import compileall
import contextlib
import json
import math
import os
import re
import resource
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import asdict, dataclass
from pathlib import Path

from fast_downward import fast_downward_command, fast_downward_driver

ROOT = Path(__file__).resolve().parent.parent
FD_SEARCH = {"fd-opt": "astar(lmcut())", "fd-sat": "lazy_greedy([ff()])"}
# ethasp's modes: (any plan, its --planner).
ETHASP = {
    "opt": (False, "clingo"),
    "sat": (True, "clingo"),
    "opt-fd": (False, "fast-downward"),
    "sat-fd": (True, "fast-downward"),
}
MODES = ("opt", "sat", "opt-fd", "sat-fd", "fd-opt", "fd-sat")
# What each of ethasp's modes is compared with.
BASELINE = {"opt": "fd-opt", "sat": "fd-sat", "opt-fd": "fd-opt", "sat-fd": "fd-sat"}
# Targets: Fast Downward solves within this many seconds, ethasp within a factor.
TARGET_SECONDS = 10.0
TARGET_FACTOR = {"opt": 2.0, "sat": 3.0, "opt-fd": 1.5, "sat-fd": 1.5}


@dataclass
class Instance:
    domain_name: str
    name: str
    domain: Path
    problem: Path


@dataclass
class Run:
    length: int | None
    seconds: float
    status: str
    cpu: float = 0.0  # processor seconds (user and system, the process's children too)


def instances(folder: Path, only: str | None) -> list[Instance]:
    """Every problem of every domain folder (sorted, p2 before p10)."""

    def natural(path: Path):
        return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", path.name)]

    result = []
    for domain in sorted(folder.glob("*/domain.pddl")):
        for problem in sorted(domain.parent.glob("*.pddl"), key=natural):
            if problem.name == "domain.pddl":
                continue
            instance = Instance(domain.parent.name, problem.stem, domain, problem)
            if only is None or only in f"{instance.domain_name}/{instance.name}":
                result.append(instance)
    return result


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _tree_cpu(root: int, seen: dict[int, float]) -> None:
    """Record the processor seconds (user and system, its own) of ``root`` and of
    every process below it, as last seen (``seen``: by process id)."""
    try:
        pids = [int(name) for name in os.listdir("/proc") if name.isdigit()]
    except OSError:
        return
    parents: dict[int, int] = {}
    stats: dict[int, list[str]] = {}
    for pid in pids:
        try:
            fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        parents[pid] = int(fields[1])
        stats[pid] = fields
    tree, frontier = {root}, [root]
    while frontier:
        parent = frontier.pop()
        for pid, ppid in parents.items():
            if ppid == parent and pid not in tree:
                tree.add(pid)
                frontier.append(pid)
    for pid in tree:
        if pid in stats:
            fields = stats[pid]
            seen[pid] = (int(fields[11]) + int(fields[12])) / TICKS


TICKS = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100


def timed(
    command: list[str], cap: float, cwd: Path
) -> tuple[subprocess.CompletedProcess | None, float, float]:
    """Run a command (in a session of its own), at most ``cap`` seconds; its
    result (None on timeout, its processes then killed), the seconds taken and
    the processor seconds of the process and of every process below it.

    Those are read from ``/proc`` every 10 ms (each process's own time, as
    last seen): ethasp's engines and planners run in processes whose parent
    does not wait for them (their times would be missing from the
    resource usage of the children waited for).  Where ``/proc`` cannot be
    read, the resource usage of the children waited for is taken."""
    cpu = _children_cpu()
    start = time.perf_counter()
    process = subprocess.Popen(
        command,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=cwd,
        start_new_session=True,
    )
    seen: dict[int, float] = {}
    output: dict[str, str] = {}

    def communicate() -> None:
        output["stdout"], output["stderr"] = process.communicate()

    reader = threading.Thread(target=communicate, daemon=True)
    reader.start()
    while reader.is_alive():
        _tree_cpu(process.pid, seen)
        reader.join(0.01)
        if time.perf_counter() - start > cap:
            os.killpg(process.pid, signal.SIGKILL)  # the planner's children too
            reader.join()
            return None, time.perf_counter() - start, sum(seen.values())
    seconds = time.perf_counter() - start
    waited = _children_cpu() - cpu
    return (
        subprocess.CompletedProcess(
            command, process.returncode, output.get("stdout", ""), output.get("stderr", "")
        ),
        seconds,
        max(waited, sum(seen.values())),
    )


def run_ethasp(instance: Instance, satisficing: bool, cap: float, planner: str) -> Run:
    command = [
        sys.executable,
        "-m",
        "ethasp.interfaces.cli",
        "plan",
        str(instance.domain),
        str(instance.problem),
        "--json",
        "--time-limit",
        "0",
        "--planner",
        planner,
    ]
    if satisficing:
        command.append("--satisficing")
    done, seconds, cpu = timed(command, cap, ROOT)
    if done is None:
        return Run(None, seconds, "timeout", cpu)
    if done.returncode != 0:
        return Run(None, seconds, f"error {done.returncode}", cpu)
    data = json.loads(done.stdout)
    length = len(data["plan"]) if data.get("plan") is not None else None
    return Run(length, seconds, data["status"], cpu)


def _fast_downward_outcome(code: int) -> str:
    """What a Fast Downward exit code without a plan means (its driver's codes):
    proven unsolvable, an incomplete search that gave up, or input it refused
    (a feature its translator or the search does not support)."""
    if code in (10, 11):
        return "no plan"
    if code == 12:
        return "gave up"
    if code in (31, 33, 34, 36, 37):
        return "refused"
    return f"error {code}"


def run_fast_downward(driver: Path, instance: Instance, search: str, cap: float) -> Run:
    with tempfile.TemporaryDirectory() as work:
        plan_file = Path(work) / "plan"
        command = fast_downward_command(
            driver, instance.domain, instance.problem, plan_file, search
        )
        done, seconds, cpu = timed(command, cap, Path(work))
        if done is None:
            return Run(None, seconds, "timeout", cpu)
        if not plan_file.is_file():
            return Run(None, seconds, _fast_downward_outcome(done.returncode), cpu)
        steps = [
            line
            for line in plan_file.read_text().splitlines()
            if line.strip() and not line.startswith(";")
        ]
        return Run(len(steps), seconds, "found", cpu)


# What is compared: seconds on the clock, or processor seconds (--cpu).
CPU = False


def taken(run: Run) -> float:
    return run.cpu if CPU else run.seconds


def best_of(runs: list[Run]) -> Run:
    """The fastest of repeated runs (a run that found a plan beats one that did not)."""
    return min(runs, key=lambda run: (run.length is None, taken(run)))


def cell(run: Run | None) -> str:
    if run is None:
        return f"{'-':>4} {'-':>6}"
    length = str(run.length) if run.length is not None else run.status[:7]
    return f"{length:>4} {taken(run):6.2f}"


def ratio(ours: Run | None, theirs: Run | None) -> float | None:
    if ours is None or theirs is None or ours.length is None or theirs.length is None:
        return None
    return taken(ours) / taken(theirs)


def meets(mode: str, ours: Run | None, theirs: Run | None) -> bool | None:
    """Whether a target applies (None if not) and is met."""
    if theirs is None or theirs.length is None or taken(theirs) > TARGET_SECONDS:
        return None
    if ours is None or ours.length is None or ours.status != "found":
        return False
    if mode.startswith("opt") and ours.length != theirs.length:
        return False
    return taken(ours) <= TARGET_FACTOR[mode] * taken(theirs)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "folder", type=Path, help="a folder of domain folders, each with domain.pddl and problems"
    )
    parser.add_argument(
        "--time-limit", type=float, default=60.0, help="seconds per process (default 60)"
    )
    parser.add_argument(
        "--repeat", type=int, default=1, help="runs per process, the fastest kept (default 1)"
    )
    parser.add_argument("--only", help="instances whose DOMAIN/PROBLEM contains this text")
    parser.add_argument(
        "--modes",
        default=",".join(MODES),
        help=f"comma-separated, of {','.join(MODES)} (default all)",
    )
    parser.add_argument(
        "--cpu",
        action="store_true",
        help="print and compare processor seconds (user and system, children "
        "included) instead of seconds on the clock",
    )
    parser.add_argument("--json", type=Path, help="also write every run to this JSON file")
    args = parser.parse_args()
    global CPU
    CPU = args.cpu
    modes = [mode for mode in args.modes.split(",") if mode]
    unknown = set(modes) - set(MODES)
    if unknown:
        parser.error(f"unknown modes: {', '.join(sorted(unknown))}")
    driver = fast_downward_driver()
    if driver is None:
        print("Fast Downward unavailable (pip install up-fast-downward); ethasp figures only")
        modes = [mode for mode in modes if not mode.startswith("fd-") and not mode.endswith("-fd")]
    chosen = instances(args.folder, args.only)
    if not chosen:
        print(f"no instances in {args.folder} (domain folders with domain.pddl)")
        return 1
    # ethasp's modules compiled to bytecode once, as an installation from a
    # wheel does (Fast Downward's driver is installed so): where bytecode is
    # not written (PYTHONDONTWRITEBYTECODE), every process would otherwise
    # compile them anew, about 0.04 s each.
    compileall.compile_dir(ROOT / "ethasp", quiet=1)
    try:
        load = os.getloadavg()[0]
        print(
            f"load average at start: {load:.2f}; "
            f"{'processor seconds' if CPU else 'seconds'} ({time.strftime('%Y-%m-%d %H:%M')})"
        )
    except OSError:
        pass
    shown = [mode for mode in ETHASP if mode in modes]
    print(
        f"{'instance':24}"
        + "".join(f" {mode:>11} {BASELINE[mode]:>11} {'ratio':>5}  " for mode in shown)
    )
    print(f"{'':24}" + f" {'len':>4} {'s':>6} {'len':>4} {'s':>6} {'':>5}  " * len(shown))
    results: dict[str, list] = {mode: [] for mode in shown}
    for instance in chosen:
        runs: dict[str, Run | None] = {}
        for mode in MODES:
            if mode not in modes:
                runs[mode] = None
                continue
            attempts = []
            for _ in range(max(1, args.repeat)):
                if mode.startswith("fd-"):
                    attempts.append(
                        run_fast_downward(driver, instance, FD_SEARCH[mode], args.time_limit)
                    )
                else:
                    satisficing, planner = ETHASP[mode]
                    attempts.append(run_ethasp(instance, satisficing, args.time_limit, planner))
            runs[mode] = best_of(attempts)
        line = f"{instance.domain_name[:18] + '/' + instance.name:24}"
        for mode in shown:
            theirs = BASELINE[mode]
            found = ratio(runs[mode], runs[theirs])
            status = runs[mode].status if runs[mode] is not None else ""
            mark = {True: "", False: "*", None: ""}[meets(mode, runs[mode], runs[theirs])]
            line += (
                f" {cell(runs[mode])} {cell(runs[theirs])} "
                f"{(f'{found:.1f}' if found is not None else '-'):>5}{mark:1}"
                f"{'' if status in ('found', '') else ' ' + status:>2} "
            )
            results[mode].append((instance, runs[mode], runs[theirs]))
        print(line.rstrip(), flush=True)
    print(
        "* a target missed (Fast Downward within 10 s; ethasp not within its factor of it: "
        + ", ".join(f"{mode} {factor:g}x" for mode, factor in TARGET_FACTOR.items())
        + "; shortest plans of the same length)"
    )
    for mode in shown:
        verdicts = [meets(mode, ours, theirs) for _, ours, theirs in results[mode]]
        applicable = [verdict for verdict in verdicts if verdict is not None]
        ratios = sorted(
            r for r in (ratio(ours, theirs) for _, ours, theirs in results[mode]) if r is not None
        )
        if not applicable:
            continue
        median = f", median ratio {ratios[len(ratios) // 2]:.1f}" if ratios else ""
        geometric = (
            f", geometric mean {math.exp(sum(map(math.log, ratios)) / len(ratios)):.2f}"
            if ratios
            else ""
        )
        print(
            f"{mode} (--planner {ETHASP[mode][1]}): target met on "
            f"{sum(applicable)} of {len(applicable)} instances{median}{geometric}"
        )
    with contextlib.suppress(OSError):
        print(f"load average at end: {os.getloadavg()[0]:.2f}")
    if args.json:
        args.json.write_text(
            json.dumps(
                [
                    {
                        "instance": f"{instance.domain_name}/{instance.name}",
                        "mode": mode,
                        "ethasp": asdict(ours) if ours is not None else None,
                        "fast_downward": asdict(theirs) if theirs is not None else None,
                    }
                    for mode in shown
                    for instance, ours, theirs in results[mode]
                ],
                indent=1,
            )
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
