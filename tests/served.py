"""``ethasp serve`` as a real process, driven over HTTP as the page drives it
(for the tests of the page's processes and ``benchmarks/web_cancel.py``)."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

from busy_model import MAX_HORIZON, SLOW_QUESTION

from ethasp.execution.limits import tree_resident

ROOT = Path(__file__).resolve().parent.parent
WAIT = 120  # seconds a step may take on a busy machine (a guard, not a measure)
MB = 2**20
QUICK = "why pull rather than refrain"  # about the plan "pull": answered at once


class Served:
    """A server process and its page's API."""

    def __init__(self, model: Path, *options: str):
        command = [sys.executable, "-m", "ethasp.interfaces.cli", "serve", str(model)]
        command += ["--port", "0", "--quiet", "--principle", "deontology"]
        command += ["--max-horizon", str(MAX_HORIZON), *options]
        self.process = subprocess.Popen(
            command,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            cwd=ROOT,
            env={**os.environ, "PYTHONPATH": str(ROOT)},
        )
        line = self.process.stdout.readline()
        match = re.search(r" at (http://\S+/)$", line.strip())
        assert match, line + self.process.stderr.read()
        self.url = match.group(1)
        self.pid = self.process.pid

    def call(self, path: str, body: dict | None = None) -> tuple[int, dict]:
        request = urllib.request.Request(
            self.url + path,
            data=None if body is None else json.dumps(body).encode(),
            headers={"Content-Type": "application/json"},
        )
        try:
            with urllib.request.urlopen(request, timeout=WAIT) as reply:
                return reply.status, json.load(reply)
        except urllib.error.HTTPError as error:
            return error.code, json.load(error)

    def job(self, key: str) -> dict:
        return self.call(f"api/sessions/{key}/job")[1]["job"]

    def move(self, path: str, body: dict) -> dict:
        """A move, followed until its job ends; the job (and its session)."""
        status, data = self.call(path, body)
        assert status == 202, data
        job, end = data["job"], time.monotonic() + WAIT
        while job["state"] == "running":
            assert time.monotonic() < end, f"the job did not end: {job}"
            time.sleep(0.02)
            job = self.job(data["session"])
        return {**job, "session": data["session"]}

    def start(self, plan: str = "pull") -> str:
        """A new dialogue about the plan; its session."""
        job = self.move("api/sessions", {"plan": plan})
        assert job["state"] == "done", job
        return job["session"]

    def ask(self, key: str, question: str) -> dict:
        return self.move(f"api/sessions/{key}/ask", {"question": question})

    def searching(self, key: str, question: str) -> dict:
        """Ask a question that searches long; its job once the search reports
        a horizon."""
        status, data = self.call(f"api/sessions/{key}/ask", {"question": question})
        assert status == 202, data
        job, end = data["job"], time.monotonic() + WAIT
        while "horizon" not in job["progress"]:
            assert job["state"] == "running" and time.monotonic() < end, job
            time.sleep(0.05)
            job = self.job(key)
        return job

    def cancel(self, key: str) -> dict:
        status, data = self.call(f"api/sessions/{key}/cancel", {})
        assert status == 200, data
        return data["job"]

    def memory(self) -> int:
        """The resident memory of the server and every process below it."""
        return tree_resident(self.pid)

    def settled(self) -> int:
        """The tree's memory once it stops changing (new workers warm)."""
        readings: list[int] = []
        end = time.monotonic() + WAIT
        while time.monotonic() < end:
            readings = [*readings, self.memory()][-10:]
            if len(readings) == 10 and max(readings) - min(readings) < 2 * MB:
                break
            time.sleep(0.1)
        return readings[-1]

    def stop(self) -> None:
        self.process.send_signal(signal.SIGINT)
        try:
            self.process.wait(timeout=WAIT)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        self.process.stdout.close()
        self.process.stderr.close()


def ended(pid: int, seconds: float = 5.0) -> bool:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        try:
            with open(f"/proc/{pid}/stat") as stat:
                if stat.read().rsplit(")", 1)[1].split()[0] in ("Z", "X"):
                    return True
        except OSError:
            return True
        time.sleep(0.01)
    return False


class Peak:
    """The largest memory of a server's process tree while it is used (read
    every 50 ms in a thread)."""

    def __init__(self, server: Served):
        self.server = server
        self.bytes = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._sample, daemon=True)

    def _sample(self) -> None:
        while not self._stop.is_set():
            self.bytes = max(self.bytes, self.server.memory())
            time.sleep(0.05)

    def __enter__(self) -> Peak:
        self._thread.start()
        return self

    def __exit__(self, *exception) -> None:
        self._stop.set()
        self._thread.join()


def long_session(server: Served, key: str, questions: int) -> dict[str, int]:
    """Ask ``questions`` questions about the plan "pull", each taken back
    after: mostly ones a warm worker answers from what it keeps, every 10th
    one that searches anew, and every 25th the slow question, cancelled once
    it searches.  How many jobs ended in each state."""
    states: dict[str, int] = {}
    for number in range(1, questions + 1):
        if number % 25 == 0:
            server.searching(key, SLOW_QUESTION)
            job = server.cancel(key)
        else:
            question = (
                f"why not press({number // 10 % 10 + 1}) at {number // 100 + 1}"
                if number % 10 == 0
                else ("why pull", "why not refrain", QUICK)[number % 3]
            )
            job = server.ask(key, question)
            if job["state"] == "done":
                assert server.move(f"api/sessions/{key}/undo", {})["state"] == "done"
        states[job["state"]] = states.get(job["state"], 0) + 1
    return states
