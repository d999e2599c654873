"""Whole-process time of `ethasp judge` as the plan grows (a script, not a test).

The model has N switches on(0) ... on(N-1) and a done flag: switch_on(I)
needs on(I) false and makes it true, switch_off(I) the reverse, finish sets
done (the goal).  Some actions are bad, some facts good or bad.  The plan
sweeps over all switches again and again, so every step has a precondition
on a variable last touched N steps earlier, then finishes.

Run:  python benchmarks/judge_scaling.py [--variables 1000] [--steps 1000 2000 5000 10000]
Prints, per plan length, the wall-clock and CPU time of the whole `ethasp
judge ... --principle deontology --principle do-no-harm` process (best of
--repeat runs; CPU time is steadier on a busy machine) and the growth
ratios; the target is under 1 s for 10,000 steps on 1,000 variables.
"""

from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def model_text(variables: int) -> str:
    """The switches model as facts."""
    lines = ["variable(done).", "action(finish).", "eff(finish,done,true).", "goal(done,true)."]
    for i in range(variables):
        lines += [
            f"variable(on({i})).",
            f"action(switch_on({i})). pre(switch_on({i}),on({i}),false). "
            f"eff(switch_on({i}),on({i}),true).",
            f"action(switch_off({i})). pre(switch_off({i}),on({i}),true). "
            f"eff(switch_off({i}),on({i}),false).",
        ]
        if i % 7 == 0:
            lines.append(f"utility(switch_off({i}),-1).")
        if i % 5 == 0:
            lines.append(f"utility(on({i}),true,-2). utility(on({i}),false,1).")
        elif i % 3 == 0:
            lines.append(f"utility(on({i}),true,3).")
    return "\n".join(lines) + "\n"


def plan_text(variables: int, steps: int) -> str:
    """steps - 1 switching actions sweeping over all switches, then finish."""
    actions = []
    for step in range(steps - 1):
        sweep, i = divmod(step, variables)
        actions.append(f"switch_on({i})" if sweep % 2 == 0 else f"switch_off({i})")
    actions.append("finish")
    return " ".join(actions)


def run_once(model: Path, plan: Path, extra: list[str]) -> tuple[float, float]:
    """Wall-clock and CPU seconds of one `ethasp judge` process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "ethasp.interfaces.cli",
            "judge",
            str(model),
            "--plan-file",
            str(plan),
            "--principle",
            "deontology",
            "--principle",
            "do-no-harm",
            "--json",
            *extra,
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    elapsed = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if run.returncode != 0:
        raise SystemExit(f"ethasp judge failed: {run.stderr.strip()}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return elapsed, cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--variables", type=int, default=1000)
    parser.add_argument("--steps", type=int, nargs="+", default=[1000, 2000, 5000, 10000])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument(
        "--with-reasons",
        action="store_true",
        help="also compute reasons (by default --reasons-limit 0: verdicts only)",
    )
    args = parser.parse_args()
    extra = [] if args.with_reasons else ["--reasons-limit", "0"]
    with tempfile.TemporaryDirectory() as folder:
        model = Path(folder) / "switches.lp"
        model.write_text(model_text(args.variables))
        baseline = Path(folder) / "empty.lp"
        baseline.write_text(
            "variable(done). action(finish). eff(finish,done,true). goal(done,true).\n"
        )
        plan1 = Path(folder) / "plan1.txt"
        plan1.write_text("finish")
        startup = min(run_once(baseline, plan1, extra) for _ in range(args.repeat))
        print(
            f"start-up (one-variable model, one-step plan): {startup[0]:.3f} s "
            f"wall, {startup[1]:.3f} s CPU"
        )
        print(
            f"model: {args.variables} variables; principles: deontology, do-no-harm; "
            f"reasons: {'yes' if args.with_reasons else 'no'}"
        )
        print(f"{'steps':>8} {'wall s':>8} {'CPU s':>8} {'CPU ratio':>10} {'steps ratio':>12}")
        previous = None
        for steps in args.steps:
            plan = Path(folder) / f"plan{steps}.txt"
            plan.write_text(plan_text(args.variables, steps))
            wall, cpu = min(run_once(model, plan, extra) for _ in range(args.repeat))
            ratio = f"{cpu / previous[1]:.2f}" if previous else "-"
            steps_ratio = f"{steps / previous[0]:.2f}" if previous else "-"
            print(f"{steps:>8} {wall:>8.3f} {cpu:>8.3f} {ratio:>10} {steps_ratio:>12}")
            previous = (steps, cpu)


if __name__ == "__main__":
    main()
