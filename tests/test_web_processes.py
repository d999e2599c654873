"""``ethasp serve`` as a real process, asked over HTTP: a cancelled search
ends its worker process at once and the next question is answered by
another; the memory of the server's process tree returns near its idle size
after a cancel and stays within the memory limit over a long session; a
question past the time limit says so."""

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

import pytest
from busy_model import MAX_HORIZON, SLOW_QUESTION, busy_model
from conftest import ROOT

from ethasp.execution.limits import GB, GRACE, tree_resident

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(not Path("/proc/self/statm").exists(), reason="memory read from /proc"),
]

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


@pytest.fixture
def busy(tmp_path):
    return busy_model(tmp_path, 10)


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


def test_cancel_ends_the_worker_and_the_server_returns_to_its_idle_memory(busy):
    server = Served(busy)
    try:
        key = server.start()
        idle = server.settled()
        job = server.searching(key, SLOW_QUESTION)
        end = time.monotonic() + WAIT  # the search takes memory as it goes
        while server.memory() < idle + 150 * MB:
            assert time.monotonic() < end and server.job(key)["state"] == "running"
            time.sleep(0.05)
        grown = server.memory()
        cancelled = server.cancel(key)
        assert cancelled["state"] == "cancelled"
        assert cancelled["note"] == "cancelled: the dialogue is unchanged"
        assert ended(job["process"], 1.0), "the cancelled search's worker still runs"
        # The next question starts at once, in another worker.
        answered = server.ask(key, QUICK)
        assert answered["state"] == "done" and answered["process"] != job["process"]
        steps = server.call(f"api/sessions/{key}")[1]["steps"]
        assert [step["question"] for step in steps] == [QUICK]
        after = server.settled()
        assert after < idle + 64 * MB < grown, (idle // MB, grown // MB, after // MB)
    finally:
        server.stop()


def test_a_question_past_the_time_limit_says_so(busy):
    server = Served(busy, "--time-limit", "2")
    try:
        key = server.start()
        job = server.ask(key, SLOW_QUESTION)
        assert job["elapsed"] <= 2 + GRACE + 0.5, job
        # Ended in its worker at the limit, or stopped there by its search:
        # either way the page says that the time limit was reached.
        if job["state"] == "time":
            assert job["error"] == (
                "the time limit of 2 s was reached: the work was ended and the dialogue "
                "is unchanged"
            )
            assert ended(job["process"])
        else:
            assert job["state"] == "done", job
            answer = server.call(f"api/sessions/{key}")[1]["steps"][-1]["answer"]
            assert answer["status"] == "bounded" and "time limit of 2 s" in answer["proof"]
        assert server.ask(key, "why pull")["state"] == "done"
    finally:
        server.stop()


def test_a_session_of_300_questions_stays_within_the_memory_limit(busy):
    limit = 0.6  # GB: the idle server (its process and two warm workers) takes about a third
    server = Served(busy, "--memory-limit", str(limit))
    peak = [0]
    stop = threading.Event()

    def sample() -> None:
        while not stop.is_set():
            peak[0] = max(peak[0], server.memory())
            time.sleep(0.05)

    sampler = threading.Thread(target=sample, daemon=True)
    try:
        key = server.start()
        idle = server.settled()
        sampler.start()
        states: dict[str, int] = {}
        for number in range(1, 301):
            if number % 25 == 0:
                server.searching(key, SLOW_QUESTION)
                job = server.cancel(key)
            else:
                # Mostly questions a warm worker answers from what it keeps,
                # and now and then one that searches anew.
                question = (
                    f"why not press({number // 10 % 10 + 1}) at {number // 100 + 1}"
                    if number % 10 == 0
                    else ("why pull", "why not refrain", QUICK)[number % 3]
                )
                job = server.ask(key, question)
                if job["state"] == "done":
                    assert server.move(f"api/sessions/{key}/undo", {})["state"] == "done"
            states[job["state"]] = states.get(job["state"], 0) + 1
        assert states == {"done": 288, "cancelled": 12}
        after = server.settled()
    finally:
        stop.set()
        server.stop()
    assert peak[0] <= limit * GB, peak[0] // MB
    assert after < idle + 64 * MB, (idle // MB, after // MB)
