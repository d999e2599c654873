"""ethasp serve: what Cancel costs, and what it gives back.

One run starts ``ethasp serve`` (a real process, on a free port) on a model
whose question "why not refrain at 200" searches for about half a minute
and takes hundreds of megabytes, while questions about its lever are
answered at once (``tests/busy_model.py``), and, over HTTP as the page does:

* measures the resident memory of the server's process tree (the server,
  its two warm workers and the processes below them) when idle;
* times a new question about the lever on a warm worker (the baseline: the
  fastest and the median of ``--repeat`` questions no worker has answered
  before, each taken back after);
* ``--rounds`` times: asks the slow question, cancels it once the tree has
  grown by ``--grow`` MB, and reports how long the cancel request took,
  when the worker's process was gone, a new question right after the cancel
  (answered by the other worker), and the tree's memory once the new worker
  has warmed;
* then a session of ``--questions`` questions (a cancelled slow one every
  25th), with the peak of the tree's memory against ``--memory-limit``.

    python benchmarks/web_cancel.py [--size 10] [--rounds 3] [--grow 200] [--repeat 5]
                                    [--questions 300] [--memory-limit 0.6]

It prints the load of the machine (uptime) before and after, then the
figures side by side.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from busy_model import SLOW_QUESTION, busy_model  # noqa: E402
from served import MB, QUICK, Peak, Served, ended, long_session  # noqa: E402


def quick(server: Served, key: str, question: str = QUICK) -> float:
    """The time of a question answered at once (it is taken back after)."""
    began = time.monotonic()
    job = server.ask(key, question)
    took = time.monotonic() - began
    assert job["state"] == "done", job
    server.move(f"api/sessions/{key}/undo", {})
    return took


def new_question(number: int) -> str:
    """A question about the lever that no worker has answered yet (it
    searches a contrast plan that starts with another button)."""
    return f"why not press({number}) at 1"


def cancel_round(server: Served, key: str, idle: int, grow: int, number: int) -> dict:
    began = time.monotonic()
    job = server.searching(key, SLOW_QUESTION)
    while server.memory() < idle + grow * MB and job["state"] == "running":
        time.sleep(0.02)
        job = server.job(key)
    searched = time.monotonic() - began
    grown = server.memory()
    began = time.monotonic()
    server.cancel(key)
    answered = time.monotonic() - began
    assert ended(job["process"], 60.0)
    gone = time.monotonic() - began
    after = quick(server, key, new_question(number))
    return {
        "searched": searched,
        "grown": grown,
        "cancel": answered,
        "ended": gone,
        "next": after,
        "settled": server.settled(),
    }


def uptime() -> str:
    return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--size", type=int, default=10, help="buttons and lamps of the model (at least 10)"
    )
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--grow", type=int, default=200, help="MB the search takes before Cancel")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--questions", type=int, default=300)
    parser.add_argument("--memory-limit", type=float, default=0.6, help="GB, of the session")
    args = parser.parse_args()
    print(f"load before: {uptime()}")
    folder = Path(tempfile.mkdtemp(prefix="ethasp-web-cancel-"))
    model = busy_model(folder, args.size)

    server = Served(model)
    try:
        key = server.start()
        quick(server, key)  # the first question of a worker grounds its parts
        baseline = sorted(quick(server, key, new_question(k)) for k in range(1, args.repeat + 1))
        idle = server.settled()
        rounds = [
            cancel_round(server, key, idle, args.grow, args.repeat + number)
            for number in range(1, args.rounds + 1)
        ]
    finally:
        server.stop()
    print(f"idle server tree: {idle / MB:.0f} MB")
    print(
        f"a new question on a warm worker: {baseline[0]:.2f} s fastest, "
        f"{baseline[len(baseline) // 2]:.2f} s median (of {args.repeat})"
    )
    print(
        "round  searched s  tree at cancel MB  cancel answered s  worker gone s  "
        "next question s  tree after MB"
    )
    for number, figures in enumerate(rounds, start=1):
        print(
            f"{number:5}  {figures['searched']:10.1f}  {figures['grown'] / MB:17.0f}  "
            f"{figures['cancel']:17.3f}  {figures['ended']:13.3f}  {figures['next']:15.2f}  "
            f"{figures['settled'] / MB:13.0f}"
        )

    server = Served(model, "--memory-limit", str(args.memory_limit))
    try:
        key = server.start()
        idle = server.settled()
        began = time.monotonic()
        with Peak(server) as peak:
            long_session(server, key, args.questions)
        took = time.monotonic() - began
        after = server.settled()
    finally:
        server.stop()
    print(
        f"session of {args.questions} questions ({args.questions // 25} cancelled): "
        f"{took:.0f} s; tree idle {idle / MB:.0f} MB, peak {peak.bytes / MB:.0f} MB "
        f"(limit {args.memory_limit * 1024:.0f} MB), after {after / MB:.0f} MB"
    )
    print(f"load after: {uptime()}")
    if os.environ.get("ETHASP_KEEP") is None:
        for path in folder.iterdir():
            path.unlink()
        folder.rmdir()


if __name__ == "__main__":
    main()
