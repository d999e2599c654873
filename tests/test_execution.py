"""Workers: calls under time and memory limits, ended at once at a limit or on
cancel, with every process below them (ethasp.execution)."""

from __future__ import annotations

import contextlib
import os
import subprocess
import threading
import time

import execution_work as work
import pytest

from ethasp.execution import limits, spawner
from ethasp.execution.limits import GB, GRACE, Limits, tree_resident
from ethasp.execution.worker import (
    CANCELLED,
    DONE,
    FAILED,
    INPUT_ERROR,
    MEMORY,
    TIME,
    Worker,
    run,
)


def gone(pid: int) -> bool:
    """Has the process ended (and been reaped, or left to init)?"""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().split(")")[-1].split()[0] in ("Z", "X")
    except OSError:
        return True


def wait_gone(pid: int, seconds: float = 5.0) -> bool:
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if gone(pid):
            return True
        time.sleep(0.01)
    return False


def test_a_worker_answers_and_keeps_what_its_calls_leave():
    worker = Worker()
    try:
        first = worker.call(work.count)
        second = worker.call(work.count)
        assert (first.status, first.value) == (DONE, 1)
        assert (second.status, second.value) == (DONE, 2)  # the same, warm process
        assert worker.pid != os.getpid()
    finally:
        worker.kill()


def test_bad_input_is_one_line_and_a_bug_its_trace():
    worker = Worker()
    try:
        outcome = worker.call(work.bad_input)
        assert (outcome.status, outcome.message) == (INPUT_ERROR, "model.lp:1: something is wrong")
        outcome = worker.call(work.bug)
        assert outcome.status == FAILED and "ZeroDivisionError: a bug" in outcome.message
        assert "Traceback" in outcome.message
        assert worker.call(work.count).status == DONE  # the worker lives on
    finally:
        worker.kill()


def test_a_grounding_is_ended_at_the_time_limit_with_the_answer_so_far():
    worker = Worker()
    try:
        began = time.monotonic()
        outcome = worker.call(work.ground_forever, limits=Limits.of(1.0, None))
        took = time.monotonic() - began
        assert outcome.status == TIME and outcome.limited
        assert outcome.message == "the time limit of 1 s was reached"
        assert outcome.partial == "the answer so far"
        assert 1.0 <= took < 1.0 + GRACE + 0.5
        assert not worker.alive
        # The next call starts a new worker: what the old one kept is gone.
        assert worker.call(work.count).value == 1
    finally:
        worker.kill()


def test_the_memory_of_the_tree_stays_below_the_limit():
    limit = 0.4
    peak = [0]
    stop = threading.Event()

    def sample() -> None:
        # The processes below this one (the worker and its children): this
        # process's own memory is what the tests before left in it.
        while not stop.is_set():
            below = tree_resident(os.getpid()) - limits.resident(os.getpid())
            peak[0] = max(peak[0], below)
            time.sleep(0.002)

    sampler = threading.Thread(target=sample)
    sampler.start()
    try:
        outcome = run(work.hog, limits=Limits.of(None, limit))
    finally:
        stop.set()
        sampler.join()
    assert outcome.status == MEMORY and outcome.limited
    assert outcome.message == "the memory limit of 0.4 GB was reached"
    assert 0 <= outcome.peak <= limit * GB  # (0: the limit struck before a reading)
    assert peak[0] <= limit * GB


def test_cancel_ends_the_worker_and_its_children_at_once():
    worker = Worker()
    cancel = threading.Event()
    reported = []
    threading.Timer(0.5, cancel.set).start()
    began = time.monotonic()
    outcome = worker.call(work.child_then_sleep, on_partial=reported.append, cancel=cancel)
    assert outcome.status == CANCELLED
    assert time.monotonic() - began < 1.5
    assert reported and outcome.partial == reported[-1]
    assert wait_gone(reported[-1]), "the engine's child process outlived its worker"


def test_budgets_made_in_a_call_join_its_limits():
    remaining, cancelled = run(work.budget_of_the_call, limits=Limits.of(5.0, None)).value
    assert remaining is not None and 3.0 < remaining < 5.0 and not cancelled
    assert run(work.budget_of_the_call).value == (None, False)


@pytest.mark.skipif(not hasattr(os, "fork"), reason="a spawner forks")
def test_a_spawner_starts_children_from_a_process_with_threads():
    stop = threading.Event()
    busy = threading.Thread(target=stop.wait)
    busy.start()
    try:
        assert spawner.threads() >= 2
        child = spawner.spawn(work.lines_child, (3,))
        assert list(child.lines()) == ["line 0\n", "line 1\n", "line 2\n"]
    finally:
        stop.set()
        busy.join()


def test_a_child_that_replaces_its_standard_input_lives_on(tmp_path):
    """A child started as a new Python process watches its parent's pipe for
    its end; a child that puts a file on standard input (Fast Downward's
    reads its task there) is not taken for orphaned when that file ends.
    (Where the watch began reading only after the replacement, a loaded
    machine's order, it read the file to its end and ended the child: the
    planner's searches then failed at random in processes with threads.)"""
    task = tmp_path / "task"
    task.write_text("a task\n")
    child = spawner.SubprocessSpawner().spawn(work.stdin_replaced_child, (str(task),))
    assert list(child.lines()) == ["still here\n"]


def test_symbols_mean_the_same_in_another_process():
    """clingo pickles a symbol as its address in this process; ethasp.execution
    makes it pickle as its text, which a fresh process reads back."""
    import pickle
    import subprocess
    import sys

    import clingo

    import ethasp.execution.symbols  # noqa: F401

    symbols = [clingo.parse_term(text) for text in ('move("a b",-1)', "(1,f(x))", "#sup")]
    data = pickle.dumps(symbols)
    program = "import pickle, sys; print(list(map(str, pickle.loads(sys.stdin.buffer.read()))))"
    read = subprocess.run(
        [sys.executable, "-c", program],
        input=data,
        capture_output=True,
        check=True,
    )
    assert read.stdout.decode().strip() == str([str(symbol) for symbol in symbols])


def test_the_processes_below_one_are_found_from_their_parents():
    """The tree of a process read from its threads' children files (where the
    kernel has them) is the tree read from every process's parent."""
    tree = subprocess.Popen(["sh", "-c", "sleep 60 & sleep 60 & (sleep 60 & wait) & wait"])
    below: list[int] = []
    try:
        deadline = time.monotonic() + 30  # (a busy machine may start them late)
        while len(limits.descendants(tree.pid)) < 4 and time.monotonic() < deadline:
            time.sleep(0.02)
        below = sorted(limits.descendants(tree.pid))
        assert len(below) == 4, below  # three sleeps and a subshell
        assert below == sorted(limits._descendants_by_scan(tree.pid))
        assert tree.pid in limits.descendants(os.getpid())
    finally:
        for pid in [*below, tree.pid]:  # (this tree only: the test's other children live on)
            with contextlib.suppress(OSError):
                os.kill(pid, 9)
        tree.wait()
