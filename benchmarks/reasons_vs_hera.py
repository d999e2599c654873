"""Reasons for judgements, ethasp against a model-enumeration baseline.

Side by side in one run: the sufficient and necessary reasons (at most 10 of
each) of deontology and do-no-harm judgements as the plan and its final state
grow, computed by ``ethasp judge`` (whole process, as a user runs it), and by
``ethics.explanations.compute_primes`` of the HERA toolbox (PyPI package
``ethics``), which enumerates the models of the formula and computes prime
implicants by hitting sets.  The baseline is not a dependency of ethasp;
install it to compare (``pip install ethics==0.22.3``).  Each baseline run
is a subprocess with a time cap; sizes stop at the first one that exceeds it
(or fails).  ethasp's times are of the whole process (start-up, model
checking, judgement and reasons); the baseline's are of compute_primes alone.

The model has n variables x(i) and n actions a(i); a(i) makes x(i) true;
every tenth action and its fact are bad.  The plan a(0) ... a(n-1) ends in a
state of n facts, all caused, so both principles find it impermissible:
deontology because of the bad actions, do-no-harm because of the bad facts
it causes.

    python benchmarks/reasons_vs_hera.py [--sizes 10 100 1000]
        [--baseline-sizes 2 4 6 8 10 12 100 1000] [--cap SECONDS]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PRINCIPLES = ("deontology", "do-no-harm")


def model_text(n: int) -> str:
    lines = [f"variable(x({i})). action(a({i})). eff(a({i}),x({i}),true)." for i in range(n)]
    lines.append(f"goal(x({n - 1}),true).")
    lines += [f"utility(a({i}),-1). utility(x({i}),true,-2)." for i in range(0, n, 10)]
    return "\n".join(lines) + "\n"


def plan_text(n: int) -> str:
    return " ".join(f"a({i})" for i in range(n)) + "\n"


def run_ethasp(n: int, principle: str, folder: Path) -> tuple[float, dict]:
    """Seconds for the whole ``ethasp judge`` process, and its judgement."""
    model, plan = folder / f"model{n}.lp", folder / f"plan{n}.txt"
    model.write_text(model_text(n))
    plan.write_text(plan_text(n))
    command = [
        sys.executable,
        "-m",
        "ethasp.interfaces.cli",
        "judge",
        str(model),
        "--plan-file",
        str(plan),
        "--principle",
        principle,
        "--json",
        "--reasons-limit",
        "10",
    ]
    start = time.perf_counter()
    run = subprocess.run(command, capture_output=True, text=True, cwd=ROOT)
    seconds = time.perf_counter() - start
    if run.returncode != 0:
        raise SystemExit(f"ethasp failed: {run.stderr.strip()}")
    return seconds, json.loads(run.stdout)["judgements"][0]


# The baseline runs in a subprocess (it cannot be interrupted otherwise); the
# formula is the principle's formula for the benchmark's plan, in the syntax
# of the ethics package, negated for an impermissible plan (whose reasons
# entail the negation).  The baseline's own work is compute_primes; the
# reasons that hold are then picked from its prime implicants.
BASELINE = r"""
import sys, time
from ethics.language import And, Bad, Caused, Impl, Not
from ethics.explanations import compute_primes
n, principle = int(sys.argv[1]), sys.argv[2]
if principle == "deontology":
    parts = [Not(Bad(f"a{i}")) for i in range(n)]
else:
    parts = [Impl(Bad(f"x{i}"), Not(Caused(f"x{i}"))) for i in range(n)]
def conjunction(items):  # balanced, so that deep nesting does not hit Python's recursion limit
    if len(items) == 1:
        return items[0]
    middle = len(items) // 2
    return And(conjunction(items[:middle]), conjunction(items[middle:]))
formula = conjunction(parts)
start = time.perf_counter()
implicants, _ = compute_primes(Not(formula))
print(time.perf_counter() - start, len(implicants))
"""


def baseline_available() -> bool:
    check = subprocess.run(
        [sys.executable, "-c", "import ethics.explanations"], capture_output=True
    )
    return check.returncode == 0


def run_baseline(n: int, principle: str, cap: float) -> float | str:
    """Seconds of compute_primes, or why there are none (over the cap, failed)."""
    try:
        run = subprocess.run(
            [sys.executable, "-c", BASELINE, str(n), principle],
            capture_output=True,
            text=True,
            timeout=cap,
        )
    except subprocess.TimeoutExpired:
        return f"> {cap:g}"
    if run.returncode != 0:
        last = (run.stderr.strip().splitlines() or ["?"])[-1]
        return "failed: " + last.split(":")[0]
    return float(run.stdout.split()[0])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[10, 100, 1000])
    parser.add_argument(
        "--baseline-sizes", type=int, nargs="+", default=[2, 4, 6, 8, 10, 12, 100, 1000]
    )
    parser.add_argument(
        "--cap",
        type=float,
        default=120.0,
        help="time cap of one baseline run in seconds (default 120)",
    )
    args = parser.parse_args()

    available = baseline_available()
    if not available:
        print("baseline unavailable (pip install ethics==0.22.3 to compare)")
    sizes = sorted(set(args.sizes) | (set(args.baseline_sizes) if available else set()))
    print(
        f"{'facts':>6} {'principle':<11} {'ethasp judge (s)':>17} {'reasons':>9} "
        f"{'baseline (s)':>13}"
    )
    largest: dict[str, tuple[int, float, float]] = {}
    with tempfile.TemporaryDirectory() as folder:
        for principle in PRINCIPLES:
            over_cap = False
            for n in sizes:
                seconds, judgement = run_ethasp(n, principle, Path(folder))
                counts = (
                    f"{len(judgement['sufficient_reasons'])}/"
                    f"{len(judgement['necessary_reasons'])}"
                    + ("+" if judgement["reasons_truncated"] else "")
                )
                base = "-"
                if available and n in args.baseline_sizes:
                    if over_cap:
                        base = "skipped"
                    else:
                        spent = run_baseline(n, principle, args.cap)
                        if isinstance(spent, str):
                            over_cap = True
                            base = spent
                        else:
                            base = f"{spent:.3f}"
                            largest[principle] = (n, spent, seconds)
                print(f"{n:>6} {principle:<11} {seconds:>17.3f} {counts:>9} {base:>13}", flush=True)
    print(
        "reasons: sufficient/necessary found (at most 10 each; + = limit reached); "
        "ethasp: whole process; baseline: compute_primes alone"
    )
    for principle, (n, spent, seconds) in largest.items():
        print(
            f"{principle}: at {n} facts, the largest size the baseline finishes, "
            f"baseline / ethasp judge = {spent / seconds:.1f}"
        )


if __name__ == "__main__":
    main()
