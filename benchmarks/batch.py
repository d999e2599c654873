"""ethasp batch: many HERA situations on all cores, on a Dask cluster, and the alternatives.

One run writes N (default 1,000) seeded random HERA-style situations to a
temporary folder and judges them under HERA's ten principles, timing whole
processes:

* ``ethasp batch`` on the local pool with 2 workers and with 1 worker
  (target: 2 workers at least 1.8x faster on 2 cores);
* a Python loop over the same situations calling the API directly in one
  process (``Model.load`` and ``judge``), the time of the solving alone, so
  that ``(1-worker batch - direct loop) / N`` is the batch's overhead per case
  (target: under 10 ms); the same again on trivially small cases (a one-action
  model under one principle), where the overhead is nearly all there is;
* a shell-style loop of single ``ethasp judge SITUATION --principle hera``
  processes, on a sample of the situations, extrapolated to N (stated so);
* HERA's own Python loop (the ``ethics`` package, ``ethics.plans``) over the
  same situations, the ten principles each;
* a local Dask cluster (``dask scheduler`` and two ``dask worker --nthreads 1``
  on 127.0.0.1, started here), ``ethasp batch --scheduler``
  (target: within 1.2x of the local pool).

    python benchmarks/batch.py [--cases N] [--sample K] [--seed S] [--hera-cap SECONDS]

It prints the load of the machine (uptime) before and after, then every
figure and ratio side by side.  The situations: 2 to 4 variables, 1 to 3
actions with intrinsic values, preconditions and conditional effects, 0 to 2
events at time points, utilities of facts, 1 to 2 moral patients, a goal and
a plan of up to 3 actions.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ETHASP = [sys.executable, "-m", "ethasp.interfaces.cli"]

HERA_LOOP = """
import sys, time
from pathlib import Path
from ethics.plans.semantics import Situation
from ethics.plans import principles as p
PRINCIPLES = [(p.Deontology, ()), (p.GoalDeontology, ()), (p.AvoidAnyHarm, ()),
              (p.AvoidAvoidableHarm, ()), (p.DoNoHarm, ()), (p.DoNoInstrumentalHarm, ()),
              (p.KantianHumanity, ()), (p.KantianHumanity, (2,)),
              (p.DoubleEffectPrinciple, ()), (p.Utilitarianism, ())]
cap = float(sys.argv[2])
start = time.perf_counter()
done = 0
for path in sorted(Path(sys.argv[1]).glob("*.json")):
    for principle, args in PRINCIPLES:
        situation = Situation(str(path))
        try:
            situation.evaluate(principle, *args)
        except Exception:      # HERA gives no verdict on some inputs (see the tests)
            pass
    done += 1
    if time.perf_counter() - start > cap:
        break
print(done)
"""

DIRECT_LOOP = """
import sys
from pathlib import Path
from ethasp import Model, judge
principles = sys.argv[2].split(",")
for path in sorted(Path(sys.argv[1]).glob("*.*")):
    model = Model.load([path])
    plan = model.own_plan()
    judge(model, plan, principles, reasons_limit=0)
"""

TRIVIAL = """variable(done).
action(finish).
eff(finish,done,true).
goal(done,true).
plan_length(1).
plan_step(1,finish).
"""


def situation(rng: random.Random) -> dict:
    """A random HERA situation (see the module docstring)."""
    variables = ["a", "b", "c", "d"][: rng.randint(2, 4)]

    def partial(low: int, high: int) -> dict:
        chosen = rng.sample(variables, rng.randint(low, min(high, len(variables))))
        return {v: rng.random() < 0.5 for v in chosen}

    # The goal is a value of the first variable that the first action sets
    # unconditionally and no event touches: a plan of one step reaches it, so that
    # HERA's planner (every sequence of up to ten actions) stops early.
    goal = (variables[0], rng.random() < 0.5)
    actions = []
    for index in range(rng.randint(1, 3)):
        effects = [
            {"condition": partial(0, 2), "effect": partial(1, 2)} for _ in range(rng.randint(1, 3))
        ]
        if index == 0:
            effects[0] = {"condition": {}, "effect": {**effects[0]["effect"], goal[0]: goal[1]}}
        actions.append(
            {
                "name": f"act{index}",
                "intrinsicvalue": rng.choice(["good", "bad", "neutral"]),
                "preconditions": partial(0, 1) if index else {},
                "effects": effects,
            }
        )
    plan = [rng.choice(actions)["name"] for _ in range(rng.randint(1, 3))]
    others = variables[1:]

    def other(low: int, high: int) -> dict:
        chosen = rng.sample(others, rng.randint(low, min(high, len(others))))
        return {v: rng.random() < 0.5 for v in chosen}

    events = [
        {
            "name": f"ev{index}",
            "preconditions": partial(0, 1),
            "effects": [
                {"condition": partial(0, 2), "effect": other(1, 2)}
                for _ in range(rng.randint(1, 2))
            ],
            "timepoints": sorted(rng.sample(range(len(plan) + 2), rng.randint(1, 2))),
        }
        for index in range(rng.randint(0, 2))
    ]
    facts = {(v, b) for v in variables for b in (True, False)}
    utilities = [
        {"fact": {v: b}, "utility": rng.choice([-3, -2, -1, 1, 2, 3])}
        for v, b in rng.sample(sorted(facts), rng.randint(2, min(5, len(facts))))
    ]
    affects = {
        f"p{index}": {
            "pos": [dict([rng.choice(sorted(facts))])],
            "neg": [dict([rng.choice(sorted(facts))])],
        }
        for index in range(rng.randint(1, 2))
    }
    return {
        "actions": actions,
        "events": events,
        "utilities": utilities,
        "affects": affects,
        "plan": plan,
        "goal": dict([goal]),
        "initialState": {v: rng.random() < 0.5 for v in variables},
    }


CPU: list[float] = []  # the processor seconds of each timed command, with its descendants


def adopt_orphans() -> None:
    """Linux: processes left behind by a timed command (the batch's forkserver and its
    workers) become this process's children, so that their processor time is counted."""
    try:
        import ctypes

        ctypes.CDLL(None).prctl(36, 1, 0, 0, 0)  # PR_SET_CHILD_SUBREAPER
    except (OSError, AttributeError):
        pass


def reap(seconds: float = 10.0) -> None:
    """Wait for the adopted processes that end within ``seconds``."""
    deadline = time.monotonic() + seconds
    while True:
        try:
            pid, _ = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            if time.monotonic() > deadline:
                return
            time.sleep(0.05)


def cpu() -> float:
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    return used.ru_utime + used.ru_stime


def timed(command: list[str], **options) -> tuple[float, subprocess.CompletedProcess]:
    """Wall seconds of a command; its processor seconds (with every process it
    started) are appended to CPU."""
    before = cpu()
    start = time.perf_counter()
    run = subprocess.run(command, capture_output=True, text=True, **options)
    seconds = time.perf_counter() - start
    reap()
    CPU.append(cpu() - before)
    return seconds, run


def uptime() -> str:
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        return "load: unknown (no uptime)"


def batch(folder: Path, output: Path, *extra: str, principles: str = "hera") -> float:
    output.unlink(missing_ok=True)
    seconds, run = timed(
        [
            *ETHASP,
            "batch",
            str(folder),
            "--principle",
            principles,
            "-o",
            str(output),
            "--quiet",
            "--time-limit",
            "0",
            *extra,
        ]
    )
    if run.returncode not in (0, 1):
        sys.exit(f"ethasp batch failed: {run.stderr.strip()}")
    return seconds


BUSY = "x = 0\nfor i in range(8_000_000):\n    x += i\n"


def parallel_share() -> float:
    """What the machine offers now: the speed-up of two busy loops run side by
    side over one alone (2.0 on two free cores; less when others use them)."""
    alone, _ = timed([sys.executable, "-c", BUSY])
    start = time.perf_counter()
    loops = [subprocess.Popen([sys.executable, "-c", BUSY]) for _ in range(2)]
    for loop in loops:
        loop.wait()
    return 2 * alone / (time.perf_counter() - start)


def start_cluster(folder: Path) -> tuple[str, list[subprocess.Popen]]:
    """A scheduler and two single-threaded workers on 127.0.0.1, no dashboards."""
    environment = dict(os.environ, DASK_TEMPORARY_DIRECTORY=str(folder))
    address_file = folder / "scheduler.json"
    processes = [
        subprocess.Popen(
            [
                sys.executable,
                "-m",
                "dask",
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--no-dashboard",
                "--scheduler-file",
                str(address_file),
            ],
            cwd=folder,
            env=environment,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
    ]
    deadline = time.monotonic() + 120
    while not (address_file.is_file() and address_file.stat().st_size):
        if time.monotonic() > deadline:
            raise RuntimeError("the Dask scheduler did not start")
        time.sleep(0.2)
    time.sleep(0.2)
    address = json.loads(address_file.read_text())["address"]
    for name in ("one", "two"):
        home = folder / name
        home.mkdir()
        processes.append(
            subprocess.Popen(
                [
                    sys.executable,
                    "-m",
                    "dask",
                    "worker",
                    address,
                    "--name",
                    name,
                    "--nthreads",
                    "1",
                    "--no-dashboard",
                    "--host",
                    "127.0.0.1",
                    "--local-directory",
                    str(home),
                ],
                cwd=home,
                env=environment,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
        )
    from distributed import Client

    with Client(address, timeout=60, set_as_default=False) as client:
        client.wait_for_workers(2, timeout=120)
    return address, processes


def stop(processes: list[subprocess.Popen]) -> None:
    for process in reversed(processes):
        process.send_signal(signal.SIGTERM)
    for process in processes:
        try:
            process.wait(20)
        except subprocess.TimeoutExpired:
            process.kill()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=1000, help="situations (default 1000)")
    parser.add_argument(
        "--sample",
        type=int,
        default=40,
        help="situations judged by single ethasp judge processes (default 40)",
    )
    parser.add_argument("--seed", type=int, default=2021, help="random seed (default 2021)")
    parser.add_argument(
        "--hera-cap",
        type=float,
        default=600.0,
        help="seconds for HERA's loop before it is extrapolated (default 600)",
    )
    parser.add_argument("--no-cluster", action="store_true", help="leave out Dask")
    args = parser.parse_args()
    adopt_orphans()
    print(f"load before: {uptime()}")
    print(
        f"cores: {len(os.sched_getaffinity(0))}; {args.cases} situations, seed {args.seed}, "
        "HERA's ten principles, no reasons, no time limit",
        flush=True,
    )
    rng = random.Random(args.seed)
    rows: list[tuple[str, float, str, float | None]] = []
    with tempfile.TemporaryDirectory() as temporary:
        root = Path(temporary)
        folder = root / "situations"
        folder.mkdir()
        for index in range(args.cases):
            (folder / f"s{index:05d}.json").write_text(json.dumps(situation(rng)))
        trivial = root / "trivial"
        trivial.mkdir()
        for index in range(args.cases):
            (trivial / f"t{index:05d}.lp").write_text(TRIVIAL)

        share_before = parallel_share()
        print(f"  two busy loops side by side vs one: {share_before:.2f}x", flush=True)
        two = batch(folder, root / "two.jsonl", "--workers", "2")
        rows.append(("ethasp batch, local pool, 2 workers", two, "", CPU[-1]))
        print(f"  pool of 2: {two:.1f} s", flush=True)
        one = batch(folder, root / "one.jsonl", "--workers", "1")
        rows.append(("ethasp batch, local pool, 1 worker", one, "", CPU[-1]))
        print(f"  pool of 1: {one:.1f} s", flush=True)
        # The batch's time beyond its cases' own (the `seconds` of their lines), for
        # all cases and for one: the difference is the part that grows with the cases.
        case_seconds = {}
        for line in (root / "one.jsonl").read_text().splitlines():
            line = json.loads(line)
            case_seconds[line["case"]] = line["seconds"]
        beyond = one - sum(case_seconds.values())
        alone = root / "alone"
        alone.mkdir()
        shutil.copy(sorted(folder.glob("*.json"))[0], alone)
        single_case = batch(alone, root / "alone.jsonl", "--workers", "1")
        first = json.loads((root / "alone.jsonl").read_text().splitlines()[0])["seconds"]
        fixed = single_case - first
        print(
            f"  pool of 1 beyond its cases' own time: {beyond:.2f} s for {args.cases} cases, "
            f"{fixed:.2f} s for 1 case",
            flush=True,
        )
        share_after = parallel_share()
        print(f"  two busy loops side by side vs one: {share_after:.2f}x", flush=True)
        direct, run = timed(
            [
                sys.executable,
                "-c",
                DIRECT_LOOP,
                str(folder),
                "hera-deontology,goal-deontology,avoid-any-harm,"
                "avoid-avoidable-harm,hera-do-no-harm,do-no-instrumental-harm,"
                "kantian-humanity,kantian-humanity-2,double-effect,"
                "hera-utilitarianism",
            ]
        )
        if run.returncode:
            sys.exit(f"direct loop failed: {run.stderr.strip()[-500:]}")
        rows.append(("direct API loop in one process (solving alone)", direct, "", CPU[-1]))
        print(f"  direct loop: {direct:.1f} s", flush=True)
        trivial_one = batch(
            trivial, root / "trivial.jsonl", "--workers", "1", principles="deontology"
        )
        rows.append((f"{args.cases} trivial cases: batch, 1 worker", trivial_one, "", CPU[-1]))
        trivial_direct, run = timed([sys.executable, "-c", DIRECT_LOOP, str(trivial), "deontology"])
        rows.append((f"{args.cases} trivial cases: direct API loop", trivial_direct, "", CPU[-1]))

        sample = sorted(folder.glob("*.json"))[: args.sample]
        start, spent = time.perf_counter(), 0.0
        for path in sample:
            seconds, run = timed(
                [
                    *ETHASP,
                    "judge",
                    str(path),
                    "--principle",
                    "hera",
                    "--reasons-limit",
                    "0",
                    "--json",
                ]
            )
            spent += CPU[-1]
            if run.returncode:
                sys.exit(f"ethasp judge failed on {path.name}: {run.stderr.strip()}")
        scale = args.cases / len(sample)
        single = (time.perf_counter() - start) * scale
        rows.append(
            (
                "loop of single 'ethasp judge' processes",
                single,
                f"extrapolated from {len(sample)}",
                spent * scale,
            )
        )
        print(f"  single processes: {single:.1f} s (extrapolated)", flush=True)

        hera, run = timed([sys.executable, "-c", HERA_LOOP, str(folder), str(args.hera_cap)])
        if run.returncode:
            rows.append(
                (
                    "HERA's Python loop (ethics.plans)",
                    float("nan"),
                    (run.stderr.strip().splitlines() or ["failed"])[-1][:60],
                    None,
                )
            )
        else:
            done = int(run.stdout.split()[-1])
            note = "" if done == args.cases else f"extrapolated from {done}"
            rows.append(
                (
                    "HERA's Python loop (ethics.plans)",
                    hera * args.cases / done,
                    note,
                    CPU[-1] * args.cases / done,
                )
            )
        hera = rows[-1][1]
        print(f"  HERA: {rows[-1][1]:.1f} s {rows[-1][2]}", flush=True)

        dask = None
        if not args.no_cluster:
            cluster = root / "cluster"
            cluster.mkdir()
            address, processes = start_cluster(cluster)
            before = cpu()
            try:
                dask = batch(folder, root / "dask.jsonl", "--scheduler", address)
            finally:
                stop(processes)
            reap()
            rows.append(
                (
                    "ethasp batch, local Dask cluster, 2 workers",
                    dask,
                    "CPU: the cluster's whole life",
                    cpu() - before,
                )
            )
            print(f"  Dask: {dask:.1f} s", flush=True)
            same = sorted(
                json.loads(line)["hash"] for line in (root / "dask.jsonl").read_text().splitlines()
            ) == sorted(
                json.loads(line)["hash"] for line in (root / "two.jsonl").read_text().splitlines()
            )
            print(f"  Dask lines = local lines (by hash): {same}")
    print(f"load after: {uptime()}")
    print()
    print(f"{'configuration':50} {'seconds':>8} {'ms/case':>8} {'vs pool 2':>9} {'CPU s':>7}")
    for name, seconds, note, used in rows:
        shown = f"{used:7.1f}" if used is not None else "      -"
        print(
            f"{name:50} {seconds:8.1f} {1000 * seconds / args.cases:8.1f} "
            f"{seconds / two:8.2f}x {shown} {note}"
        )
    print("(CPU s: processor seconds of the command and every process it started)")
    print()
    print(
        f"speed-up of 2 workers over 1: {one / two:.2f}x (target >= 1.8x); the machine "
        f"offered {share_before:.2f}x before and {share_after:.2f}x after (two busy loops "
        "side by side vs one)"
    )
    print(
        f"overhead per case beyond solving (pool of 1 - direct loop) / N: wall "
        f"{1000 * (one - direct) / args.cases:.1f} ms, CPU "
        f"{1000 * (rows[1][3] - rows[2][3]) / args.cases:.1f} ms (target < 10 ms)"
    )
    print(
        f"  counted in the run (time beyond the cases' own, minus that of a 1-case batch) / N:"
        f" {1000 * (beyond - fixed) / max(1, args.cases - 1):.1f} ms"
    )
    print(
        f"  on trivial cases: wall {1000 * (trivial_one - trivial_direct) / args.cases:.1f} ms"
        f", CPU {1000 * (rows[3][3] - rows[4][3]) / args.cases:.1f} ms"
    )
    if dask is not None:
        print(f"Dask cluster of 2 vs local pool of 2: {dask / two:.2f}x (target <= 1.2x)")
    print(f"single processes vs pool of 2: {single / two:.1f}x slower (extrapolated)")
    print(f"HERA's loop vs pool of 2: {hera / two:.1f}x slower")


if __name__ == "__main__":
    main()
