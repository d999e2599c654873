"""Causal agency models, ethasp against HERA: verdicts of every principle.

One run generates random causal agency models (CAMs) of 5 to 30 variables
with a fixed seed, and judges every action of each under the fifteen
principles HERA defines for CAMs, side by side:

* HERA: the HERA toolbox (PyPI package ``ethics`` 0.22.3, ``ethics.cam``;
  install it to compare) evaluating each principle for each action in this
  process, with the stand-in for its missing ``ethics.argumentation`` module
  that the tests register; where it fails or evaluates a formula to None it
  gives no verdict (always for minimize harm, minimax harm, discourse and
  universality);
* ethasp in this process: ``Model.load`` and
  ``ethasp.principles.judgement.judge`` of every action under the fifteen
  principles (the Python API, verdicts without reasons);
* ethasp as a user runs it: the whole process ``ethasp judge CAM --json
  --reasons-limit 0`` (start-up included), which judges every action under
  the group ``hera`` (the text output would explain each verdict, the JSON
  output with ``--reasons-limit 0`` gives the verdicts alone).

It checks that every verdict HERA gives is ethasp's, and prints per size the
median time per CAM of each, the ratio of HERA's in-process time to
ethasp's, the verdicts HERA gave and the disagreements (which must be 0).
The models come from the generator of the differential tests
(``tests/hera_cams.py``, driven by ``random.Random(seed)``): of n variables,
2 or 3 actions, n // 6 background variables, n // 10 events, the rest
consequences with random mechanisms over the variables before them, up to n
utilities, intentions, goals, two patients.

    python benchmarks/cams_vs_hera.py [--sizes 5 10 15 20 25 30] [--models N] [--seed S]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import random
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from hera_cams import PRINCIPLES, Choices, cam, hera_verdicts, write  # noqa: E402

from ethasp import Model, Plan  # noqa: E402
from ethasp.planning.readers.hera_data import name_term  # noqa: E402
from ethasp.principles.judgement import judge  # noqa: E402


def shape(n: int) -> tuple[int, int, int, int]:
    """Actions, background variables, events and consequences of n variables."""
    actions = 3 if n >= 10 else 2
    background, events = n // 6, n // 10
    return actions, background, events, n - actions - background - events


def hera_available() -> bool:
    try:
        import ethics.cam.semantics  # noqa: F401
    except ImportError:
        return False
    return True


def ethasp_verdicts(path: Path, actions: list[str]) -> dict[tuple[str, str], bool]:
    """ethasp's verdicts through the Python API (verdicts without reasons):
    (action, principle) -> permissible."""
    model = Model.load([path])
    verdicts = {}
    for action in actions:
        report = judge(model, Plan((name_term(action),)), list(PRINCIPLES))
        for judgement in report.judgements:
            assert judgement.status == "proven", (path, action, judgement.principle)
            verdicts[(action, judgement.principle)] = judgement.permissible
    return verdicts


def ethasp_process(path: Path) -> tuple[float, dict[tuple[str, str], bool]]:
    """Seconds of the whole ``ethasp judge`` process, and its verdicts."""
    command = [sys.executable, "-m", "ethasp.interfaces.cli", "judge", str(path)]
    start = time.perf_counter()
    run = subprocess.run(
        [*command, "--json", "--reasons-limit", "0"], capture_output=True, text=True
    )
    seconds = time.perf_counter() - start
    if run.returncode != 0:
        raise SystemExit(f"ethasp failed on {path}: {run.stderr.strip()}")
    verdicts = {}
    for choice in json.loads(run.stdout)["choices"]:
        for judgement in choice["judgements"]:
            verdicts[(choice["plan"][0], judgement["principle"])] = judgement["permissible"]
    return seconds, verdicts


def timed(function, *args):
    """Seconds of the call, and its result; what it prints is dropped (HERA
    prints a line for each dialogue its discourse principles lack)."""
    start = time.perf_counter()
    with contextlib.redirect_stdout(io.StringIO()):
        result = function(*args)
    return time.perf_counter() - start, result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[5, 10, 15, 20, 25, 30])
    parser.add_argument("--models", type=int, default=5, help="random CAMs per size")
    parser.add_argument("--seed", type=int, default=29)
    args = parser.parse_args()
    baseline = hera_available()
    if not baseline:
        print("baseline unavailable (pip install ethics==0.22.3 to compare with HERA)")
    print(
        f"{'vars':>4} {'CAMs':>4} {'HERA verdicts':>13} {'disagree':>8} "
        f"{'HERA s':>8} {'ethasp s':>8} {'ratio':>6} {'ethasp process s':>16}"
    )
    rng = random.Random(args.seed)
    with tempfile.TemporaryDirectory() as folder:
        for n in args.sizes:
            hera_times, ours_times, process_times = [], [], []
            compared = disagreements = 0
            for index in range(args.models):
                data, world = cam(Choices(rng=rng), *shape(n), spaces=False, utilities=n)
                path = write(data, Path(folder) / f"cam{n}-{index}.json", world)
                seconds, ours = timed(ethasp_verdicts, path, data["actions"])
                ours_times.append(seconds)
                seconds, theirs_process = ethasp_process(path)
                process_times.append(seconds)
                assert theirs_process == ours, f"the CLI and the API differ on {path}"
                if not baseline:
                    continue
                seconds, theirs = timed(hera_verdicts, path, data, world)
                hera_times.append(seconds)
                for key, verdict in theirs.items():
                    if verdict is None:
                        continue
                    compared += 1
                    if ours[key] != verdict:
                        disagreements += 1
                        print(f"  disagreement on {key}: HERA {verdict}, ethasp {ours[key]}")
                        print(f"  {json.dumps(dict(data, world=world))}")
            ours_median = statistics.median(ours_times)
            hera = f"{statistics.median(hera_times):8.3f}" if hera_times else f"{'-':>8}"
            ratio = (
                f"{statistics.median(hera_times) / ours_median:6.1f}" if hera_times else f"{'-':>6}"
            )
            print(
                f"{n:>4} {args.models:>4} {compared:>13} {disagreements:>8} {hera} "
                f"{ours_median:8.3f} {ratio} {statistics.median(process_times):16.3f}",
                flush=True,
            )


if __name__ == "__main__":
    main()
