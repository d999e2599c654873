"""Ctrl-C: a real SIGINT to an ethasp process gives one line and exit code 130;
a dialogue is saved first."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import threading
import time

import pytest
from conftest import MODELS

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

# A guard against a hang, not a measure of speed: a process that ignores the
# interrupt is killed after this many seconds and the test fails.
HANG = 60


def _as_at_a_terminal() -> None:
    # A shell without job control starts background jobs with SIGINT ignored,
    # and a child inherits that: a test run so would test nothing.
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def start(*arguments: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "ethasp.interfaces.cli", *arguments],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=_as_at_a_terminal,
    )


def wait_for_line(process: subprocess.Popen, fragment: str) -> list[str]:
    """Read standard output until a line holding ``fragment`` (killing a hung process)."""
    timer = threading.Timer(HANG, process.kill)
    timer.start()
    lines = []
    try:
        for line in process.stdout:
            lines.append(line)
            if fragment in line:
                return lines
    finally:
        timer.cancel()
    raise AssertionError(f"no line with {fragment!r}: {lines}")


def interrupt(process: subprocess.Popen) -> tuple[int, str, str]:
    """Send SIGINT (standard input stays open, as at a terminal); the exit code and
    what the process wrote after that."""
    process.send_signal(signal.SIGINT)
    try:
        process.wait(timeout=HANG)
    except subprocess.TimeoutExpired:
        process.kill()
        process.communicate()
        raise AssertionError("the process did not stop on Ctrl-C") from None
    out, err = process.stdout.read(), process.stderr.read()
    process.stdin.close()
    return process.returncode, out, err


def assert_one_line(err: str, fragment: str) -> None:
    assert "Traceback" not in err
    # Warnings of lenient PDDL reading come first, each a line of its own.
    lines = [line for line in err.splitlines() if ": warning: " not in line]
    assert len(lines) == 1 and fragment in lines[0], err


def test_dialogue_waiting_for_input_is_saved_then_exits_130(tmp_path):
    saved = tmp_path / "dialogue.json"
    process = start(
        "dialogue", str(MODELS / "trolley.lp"), "--principle", "do-no-harm", "--save", str(saved)
    )
    wait_for_line(process, "next contrasts must satisfy")
    code, _, err = interrupt(process)
    assert code == 130
    assert_one_line(err, f"ethasp: interrupted; dialogue saved to {saved}")
    data = json.loads(saved.read_text())
    assert data["format"] == "ethasp-dialogue" and data["plan"] == ["refrain"]


def test_dialogue_after_a_question_keeps_the_question(tmp_path):
    saved = tmp_path / "dialogue.json"
    process = start(
        "dialogue", str(MODELS / "trolley.lp"), "--principle", "do-no-harm", "--save", str(saved)
    )
    wait_for_line(process, "next contrasts must satisfy")
    process.stdin.write("why refrain rather than pull\n")
    process.stdin.flush()
    wait_for_line(process, "constraints:")
    code, _, err = interrupt(process)
    assert code == 130
    assert_one_line(err, "dialogue saved to")
    steps = json.loads(saved.read_text())["steps"]
    assert [step["question"]["action"] for step in steps] == ["refrain"]


def hard_gripper(tmp_path, balls: int = 14):
    """A gripper task whose shortest plan (about 3 steps a ball) takes long to prove."""
    names = " ".join(f"ball-{i}" for i in range(1, balls + 1))
    at = " ".join(f"(ball-at ball-{i} a)" for i in range(1, balls + 1))
    goal = " ".join(f"(ball-at ball-{i} b)" for i in range(1, balls + 1))
    problem = tmp_path / "many-problem.pddl"
    problem.write_text(f"""(define (problem many) (:domain gripper)
  (:objects a b - room left right - gripper {names} - ball)
  (:init (robot-at a) (free left) (free right) (occupied b) {at})
  (:goal (and {goal})))
""")
    return [str(MODELS / "pddl" / "gripper-domain.pddl"), str(problem)]


@pytest.mark.slow
def test_long_plan_search_stops_at_once(tmp_path):
    # (Exact reachability solves gripper with a few dozen balls in seconds.)
    process = start("plan", *hard_gripper(tmp_path, balls=100), "--max-horizon", "1000")
    time.sleep(5)  # loading done, deep in the search
    assert process.poll() is None, "the search ended before the interrupt"
    code, out, err = interrupt(process)
    assert code == 130 and out == ""
    assert_one_line(err, "ethasp: interrupted")


@pytest.mark.slow
def test_permissible_plan_search_stops_at_once(tmp_path):
    process = start("plan", *hard_gripper(tmp_path, balls=40), "--principle", "utilitarianism")
    time.sleep(5)
    assert process.poll() is None, "the search ended before the interrupt"
    code, out, err = interrupt(process)
    assert code == 130 and out == ""
    assert_one_line(err, "ethasp: interrupted")


# -- the watchdog of commands that overrun their time limit ---------------------------


def test_the_server_and_the_dialogue_outlive_the_time_limit(monkeypatch):
    """The watchdog ends a command that gives one answer and is stuck long after
    its time limit; a server or a dialogue runs jobs, each under its own limit,
    and is never ended by it."""
    import time as clock

    import ethasp.interfaces.web.server as server
    from ethasp.interfaces import cli
    from ethasp.interfaces.cli import execution

    monkeypatch.setattr(execution, "OVERRUN_GRACE", 0.0)
    served = []

    def serve(workspace, host, port, open_page, **options):
        clock.sleep(1.0)  # up ten times longer than the limit
        served.append(port)
        return 0

    monkeypatch.setattr(server, "serve", serve)
    assert cli.main(["serve", "trolley", "--time-limit", "0.05", "--port", "0"]) == 0
    assert served == [0]
    parser = cli.build_parser()
    assert not parser.parse_args(["dialogue", "trolley"]).one_answer
    for command in ("plan", "judge", "ask", "validate", "query"):
        arguments = {"ask": ["--question", "why pull"], "query": ["Bad(pull)"]}
        assert parser.parse_args([command, "trolley", *arguments.get(command, [])]).one_answer


def test_a_command_stuck_after_its_time_limit_ends_in_one_line(monkeypatch, capsys):
    import time as clock

    from ethasp.interfaces import cli
    from ethasp.interfaces.cli import execution, plan

    monkeypatch.setattr(execution, "OVERRUN_GRACE", 0.0)
    monkeypatch.setattr(plan, "find_plan", lambda *args, **kwargs: clock.sleep(5.0))
    assert cli.main(["plan", "trolley", "--time-limit", "0.05"]) == 2
    assert "no answer within the time limit" in capsys.readouterr().err


def test_the_memory_limit_stops_the_search_and_then_the_command(monkeypatch, capsys):
    """Beyond --memory-limit the command's budget is cancelled with the reason
    (its searches answer bounded); beyond 1.5 times it the command ends with
    one line (where clingo cannot be stopped)."""
    import time as clock

    from ethasp.interfaces import cli
    from ethasp.interfaces.cli import execution, plan
    from ethasp.planning.search import BOUNDED, SearchResult

    def waits_for_its_budget(model, *args, budget=None, **kwargs):
        while not budget.expired():
            clock.sleep(0.01)
        return SearchResult(BOUNDED, proof=budget.why_stopped())

    assert 2**20 < execution._memory() < 2**40  # the real reading: a plausible size
    monkeypatch.setattr(plan, "find_plan", waits_for_its_budget)
    monkeypatch.setattr(execution, "_memory", lambda: int(1.2 * 2**30))
    assert cli.main(["plan", "trolley", "--memory-limit", "1", "--json"]) == 0
    out = capsys.readouterr().out
    assert "the memory limit of 1 GB was reached" in out and '"bounded"' in out
    monkeypatch.setattr(plan, "find_plan", lambda *args, **kwargs: clock.sleep(5.0))
    monkeypatch.setattr(execution, "_memory", lambda: 2 * 2**30)
    assert cli.main(["plan", "trolley", "--memory-limit", "1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ethasp: error: out of memory: 2.0 GB in use") and err.count("\n") == 1
