"""``ethasp serve`` as a real process, asked over HTTP: a cancelled search
ends its worker process at once and the next question is answered by
another; the memory of the server's process tree returns near its idle size
after a cancel and stays within the memory limit over a long session; a
question past the time limit says so."""

from __future__ import annotations

import time
from pathlib import Path

import pytest
from busy_model import SLOW_QUESTION, busy_model
from served import MB, QUICK, WAIT, Peak, Served, ended, long_session

from ethasp.execution.limits import GB, GRACE

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(not Path("/proc/self/statm").exists(), reason="memory read from /proc"),
]


@pytest.fixture
def busy(tmp_path):
    return busy_model(tmp_path, 10)


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
    try:
        key = server.start()
        idle = server.settled()
        with Peak(server) as peak:
            states = long_session(server, key, 300)
        assert states == {"done": 288, "cancelled": 12}
        after = server.settled()
    finally:
        server.stop()
    assert peak.bytes <= limit * GB, peak.bytes // MB
    assert after < idle + 64 * MB, (idle // MB, after // MB)
