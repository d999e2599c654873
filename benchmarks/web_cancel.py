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
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from busy_model import MAX_HORIZON, SLOW_QUESTION, busy_model  # noqa: E402

from ethasp.execution.limits import tree_resident  # noqa: E402

MB = 2**20
QUICK = "why pull rather than refrain"


class Served:
    def __init__(self, model: Path, *options: str):
        command = [sys.executable, "-m", "ethasp.interfaces.cli", "serve", str(model)]
        command += ["--port", "0", "--quiet", "--principle", "deontology"]
        command += ["--max-horizon", str(MAX_HORIZON), *options]
        self.process = subprocess.Popen(
            command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, text=True
        )
        line = self.process.stdout.readline()
        match = re.search(r" at (http://\S+/)$", line.strip())
        if not match:
            raise SystemExit(f"the server did not start: {line}")
        self.url = match.group(1)

    def call(self, path: str, body: dict | None = None) -> dict:
        request = urllib.request.Request(
            self.url + path,
            data=None if body is None else json.dumps(body).encode(),
            headers={"Content-Type": "application/json"},
        )
        try:
            with urllib.request.urlopen(request, timeout=600) as reply:
                return json.load(reply)
        except urllib.error.HTTPError as error:
            return json.load(error)

    def move(self, path: str, body: dict) -> dict:
        data = self.call(path, body)
        job = data["job"]
        while job["state"] == "running":
            time.sleep(0.01)
            job = self.call(f"api/sessions/{data['session']}/job")["job"]
        return {**job, "session": data["session"]}

    def memory(self) -> int:
        return tree_resident(self.process.pid)

    def settled(self) -> int:
        readings: list[int] = []
        end = time.monotonic() + 120
        while time.monotonic() < end:
            readings = [*readings, self.memory()][-10:]
            if len(readings) == 10 and max(readings) - min(readings) < 2 * MB:
                break
            time.sleep(0.1)
        return readings[-1]

    def stop(self) -> None:
        self.process.send_signal(signal.SIGINT)
        self.process.wait(60)


def gone(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] in ("Z", "X")
    except OSError:
        return True


def quick(server: Served, key: str, question: str = QUICK) -> float:
    """The time of a question answered at once (it is taken back after)."""
    began = time.monotonic()
    job = server.move(f"api/sessions/{key}/ask", {"question": question})
    took = time.monotonic() - began
    assert job["state"] == "done", job
    server.move(f"api/sessions/{key}/undo", {})
    return took


def new_question(number: int) -> str:
    """A question about the lever that no worker has answered yet (it
    searches a contrast plan that starts with another button)."""
    return f"why not press({number}) at 1"


def cancel_round(server: Served, key: str, idle: int, grow: int, number: int) -> dict:
    data = server.call(f"api/sessions/{key}/ask", {"question": SLOW_QUESTION})
    began = time.monotonic()
    job = data["job"]
    while server.memory() < idle + grow * MB and job["state"] == "running":
        time.sleep(0.02)
        job = server.call(f"api/sessions/{key}/job")["job"]
    searched = time.monotonic() - began
    grown = server.memory()
    began = time.monotonic()
    server.call(f"api/sessions/{key}/cancel", {})
    answered = time.monotonic() - began
    while not gone(job["process"]):
        time.sleep(0.001)
    ended = time.monotonic() - began
    after = quick(server, key, new_question(number))
    return {
        "searched": searched,
        "grown": grown,
        "cancel": answered,
        "ended": ended,
        "next": after,
        "settled": server.settled(),
    }


def session(server: Served, key: str, questions: int) -> tuple[float, int]:
    peak = [0]
    stop = threading.Event()

    def sample() -> None:
        while not stop.is_set():
            peak[0] = max(peak[0], server.memory())
            time.sleep(0.05)

    sampler = threading.Thread(target=sample, daemon=True)
    sampler.start()
    began = time.monotonic()
    try:
        for number in range(1, questions + 1):
            if number % 25 == 0:
                data = server.call(f"api/sessions/{key}/ask", {"question": SLOW_QUESTION})
                job = data["job"]
                while "horizon" not in job["progress"] and job["state"] == "running":
                    time.sleep(0.02)
                    job = server.call(f"api/sessions/{key}/job")["job"]
                server.call(f"api/sessions/{key}/cancel", {})
                continue
            question = (
                f"why not press({number // 10 % 10 + 1}) at {number // 100 + 1}"
                if number % 10 == 0
                else ("why pull", "why not refrain", QUICK)[number % 3]
            )
            job = server.move(f"api/sessions/{key}/ask", {"question": question})
            if job["state"] == "done":
                server.move(f"api/sessions/{key}/undo", {})
    finally:
        stop.set()
        sampler.join()
    return time.monotonic() - began, peak[0]


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
        key = server.move("api/sessions", {"plan": "pull"})["session"]
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
        key = server.move("api/sessions", {"plan": "pull"})["session"]
        idle = server.settled()
        took, peak = session(server, key, args.questions)
        after = server.settled()
    finally:
        server.stop()
    print(
        f"session of {args.questions} questions ({args.questions // 25} cancelled): "
        f"{took:.0f} s; tree idle {idle / MB:.0f} MB, peak {peak / MB:.0f} MB "
        f"(limit {args.memory_limit * 1024:.0f} MB), after {after / MB:.0f} MB"
    )
    print(f"load after: {uptime()}")
    if os.environ.get("ETHASP_KEEP") is None:
        for path in folder.iterdir():
            path.unlink()
        folder.rmdir()


if __name__ == "__main__":
    main()
