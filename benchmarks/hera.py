"""HERA vs ethasp: judging a situation under HERA's principles, whole processes.

One run prints, for situations of growing size (plan length, events, moral
patients), the time of a process that loads the situation with the HERA
toolbox (PyPI package ``ethics``, module ``ethics.plans``; install it to
compare) and evaluates its ten principles, and the time of ``ethasp judge
SITUATION --principle hera`` (the same ten verdicts, with and without
reasons), and their ratio.  HERA runs with a time cap; without the package
the script prints "baseline unavailable".

    python benchmarks/hera.py [--cap SECONDS] [--quick]

The situations (written to a temporary folder, HERA's format):  an agent works
through a chain of n tasks (``work_i`` needs ``done_{i-1}``); every task
helps one of P patients and harms another as a side effect; E events
(supervisors passing at time points 0..E-1) reward the patients whose tasks
are done by then.  The goal is the last task done; the plan does every task.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERA_SCRIPT = """
import sys
from ethics.plans.semantics import Situation
from ethics.plans import principles as p
for principle, args in [(p.Deontology, ()), (p.GoalDeontology, ()), (p.AvoidAnyHarm, ()),
                        (p.AvoidAvoidableHarm, ()), (p.DoNoHarm, ()), (p.DoNoInstrumentalHarm, ()),
                        (p.KantianHumanity, ()), (p.KantianHumanity, (2,)),
                        (p.DoubleEffectPrinciple, ()), (p.Utilitarianism, ())]:
    situation = Situation(sys.argv[1])
    print(principle.__name__, situation.evaluate(principle, *args))
"""


def situation(steps: int, events: int, patients: int) -> dict:
    """The chain of tasks (see the module docstring)."""
    actions = []
    for i in range(1, steps + 1):
        helped, harmed = f"well_p{i % patients}", f"hurt_p{(i + 1) % patients}"
        condition = {f"done_{i - 1}": True} if i > 1 else {}
        actions.append(
            {
                "name": f"work_{i}",
                "intrinsicvalue": "neutral",
                "preconditions": {},
                "effects": [
                    {"condition": condition, "effect": {f"done_{i}": True, helped: True}},
                    {"condition": condition, "effect": {harmed: True}},
                ],
            }
        )
    happenings = []
    for e in range(events):
        task = min(steps, e + 1)
        happenings.append(
            {
                "name": f"supervisor_{e}",
                "preconditions": {},
                "effects": [
                    {
                        "condition": {f"done_{task}": True},
                        "effect": {f"rewarded_p{e % patients}": True},
                    }
                ],
                "timepoints": [e],
            }
        )
    utilities, affects, initial = [], {}, {}
    for q in range(patients):
        utilities += [
            {"fact": {f"well_p{q}": True}, "utility": 2},
            {"fact": {f"hurt_p{q}": True}, "utility": -1},
            {"fact": {f"rewarded_p{q}": True}, "utility": 1},
        ]
        affects[f"p{q}"] = {
            "pos": [{f"well_p{q}": True}, {f"rewarded_p{q}": True}],
            "neg": [{f"hurt_p{q}": True}],
        }
        initial.update({f"well_p{q}": False, f"hurt_p{q}": False, f"rewarded_p{q}": False})
    initial.update({f"done_{i}": False for i in range(1, steps + 1)})
    return {
        "actions": actions,
        "events": happenings,
        "utilities": utilities,
        "affects": affects,
        "plan": [a["name"] for a in actions],
        "goal": {f"done_{steps}": True},
        "initialState": initial,
    }


def timed(command: list[str], cap: float | None) -> tuple[float | None, str]:
    start = time.perf_counter()
    try:
        run = subprocess.run(command, capture_output=True, text=True, timeout=cap)
    except subprocess.TimeoutExpired:
        return None, "timeout"
    seconds = time.perf_counter() - start
    if run.returncode != 0:
        return None, (run.stderr.strip().splitlines() or ["failed"])[-1][:60]
    return seconds, run.stdout


def hera_available() -> bool:
    return (
        subprocess.run(
            [sys.executable, "-c", "import ethics.plans.semantics"], capture_output=True
        ).returncode
        == 0
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cap", type=float, default=60.0, help="seconds per HERA run")
    parser.add_argument("--quick", action="store_true", help="the smallest sizes only")
    args = parser.parse_args()
    series = [
        ("plan length", [(n, 2, 2) for n in (2, 4, 5, 6, 8, 12, 16, 24)]),
        ("events", [(4, e, 2) for e in (1, 4, 8, 12, 16)]),
        ("patients", [(4, 2, p) for p in (1, 8, 16, 32, 64)]),
    ]
    if args.quick:
        series = [(name, sizes[:2]) for name, sizes in series]
    baseline = hera_available()
    if not baseline:
        print("baseline unavailable (pip install ethics to compare with HERA)")
    print(
        f"{'series':12} {'steps':>5} {'events':>6} {'patients':>8} {'HERA s':>8} "
        f"{'ethasp s':>9} {'ratio':>7} {'+reasons s':>10}"
    )
    with tempfile.TemporaryDirectory() as folder:
        for name, sizes in series:
            hera_failed = False
            for steps, events, patients in sizes:
                path = Path(folder) / f"s{steps}-e{events}-p{patients}.json"
                path.write_text(json.dumps(situation(steps, events, patients)))
                ours, out = timed(
                    [
                        sys.executable,
                        "-m",
                        "ethasp.interfaces.cli",
                        "judge",
                        str(path),
                        "--principle",
                        "hera",
                        "--reasons-limit",
                        "0",
                    ],
                    None,
                )
                if ours is None:
                    print(f"ethasp failed on {path.name}: {out}")
                    continue
                reasons, _ = timed(
                    [
                        sys.executable,
                        "-m",
                        "ethasp.interfaces.cli",
                        "judge",
                        str(path),
                        "--principle",
                        "hera",
                    ],
                    None,
                )
                hera, shown = None, "-"
                if baseline and not hera_failed:
                    hera, _detail = timed([sys.executable, "-c", HERA_SCRIPT, str(path)], args.cap)
                    shown = f"{hera:8.2f}" if hera is not None else f">{args.cap:.0f}"
                    hera_failed = hera is None  # larger sizes would take longer still
                elif hera_failed:
                    shown = f">{args.cap:.0f}"
                ratio = (
                    f"{hera / ours:7.1f}"
                    if hera is not None
                    else (f">{args.cap / ours:6.0f}" if shown.startswith(">") else "      -")
                )
                print(
                    f"{name:12} {steps:5} {events:6} {patients:8} {shown:>8} {ours:9.2f} "
                    f"{ratio} {reasons or 0:10.2f}",
                    flush=True,
                )


if __name__ == "__main__":
    main()
