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
from busy_model import MAX_HORIZON, SLOW_QUESTION, busy_model
from conftest import MODELS

from ethasp.execution.limits import GRACE

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

# A guard against a hang, not a measure of speed: a process that ignores the
# interrupt is killed after this many seconds and the test fails.
HANG = 60
# Seconds a Python process takes to start and read the command line (a busy
# machine may take longer than an idle one).
STARTUP = 1.0


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


def descendants(pid: int) -> set[int]:
    from ethasp.execution.limits import descendants as below

    return set(below(pid))


def busy_dialogue(tmp_path, *options: str) -> subprocess.Popen:
    """A dialogue about the plan "pull" of a model with a slow question
    (tests/busy_model.py), once it shows the plan."""
    model = busy_model(tmp_path, 10)
    process = start(
        *("dialogue", str(model), "--plan", "pull", "--principle", "deontology"),
        *("--max-horizon", str(MAX_HORIZON), *options),
    )
    wait_for_line(process, "next contrasts must satisfy")
    return process


@pytest.mark.slow
def test_ctrl_c_during_a_question_ends_its_work_and_the_dialogue_goes_on(tmp_path):
    saved = tmp_path / "dialogue.json"
    process = busy_dialogue(tmp_path, "--save", str(saved))
    process.stdin.write(f"{SLOW_QUESTION}\n")
    process.stdin.flush()
    time.sleep(3)  # deep in the search (it takes about half a minute)
    working = descendants(process.pid)
    assert working, "the question has no worker process"
    process.send_signal(signal.SIGINT)
    lines = wait_for_line(process, "interrupted")
    assert lines[-1] == "interrupted: the work was ended and the dialogue is as it was\n"
    assert not working & descendants(process.pid), "the question's processes still run"
    process.stdin.write("why pull rather than refrain\nhistory\nquit\n")
    process.stdin.flush()
    lines = wait_for_line(process, "1. why pull rather than refrain")
    assert any(line.startswith("  contrast plan: refrain") for line in lines)
    process.stdin.close()
    assert process.wait(timeout=HANG) == 0, process.stderr.read()
    assert process.stderr.read() == ""
    steps = json.loads(saved.read_text())["steps"]
    assert [step["question"]["action"] for step in steps] == ["pull"]


@pytest.mark.slow
def test_a_question_of_a_dialogue_past_its_time_limit_says_so(tmp_path):
    process = busy_dialogue(tmp_path, "--time-limit", "2", "--save", "-")
    began = time.monotonic()
    process.stdin.write(f"{SLOW_QUESTION}\n")
    process.stdin.flush()
    lines = wait_for_line(process, "2 s was reached")
    assert time.monotonic() - began < 2 + GRACE + 1.0
    # Ended in its worker at the limit, or stopped there by its search.
    assert lines[-1] in (
        "no answer: the time limit of 2 s was reached; the work was ended and the "
        "dialogue is as it was\n",
    ) or lines[-1].startswith("  no contrast plan found (bounded): "), lines
    # (A bounded answer keeps its question: it is taken back first.)
    undo = "undo\n" if "bounded" in lines[-1] else ""
    process.stdin.write(f"{undo}why pull rather than refrain\nquit\n")
    process.stdin.flush()
    wait_for_line(process, "contrast plan: refrain")
    process.stdin.close()
    assert process.wait(timeout=HANG) == 0, process.stderr.read()


def hard_gripper(tmp_path, balls: int = 14):
    """A gripper task whose shortest plan (about 3 steps a ball) takes long to
    prove (by clingo: the tests below ask for it, as Fast Downward, where it is
    installed, could find the answers sooner)."""
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
    process = start(
        "plan", *hard_gripper(tmp_path, balls=100), "--max-horizon", "1000", "--planner", "clingo"
    )
    time.sleep(5)  # loading done, deep in the search
    assert process.poll() is None, "the search ended before the interrupt"
    code, out, err = interrupt(process)
    assert code == 130 and out == ""
    assert_one_line(err, "ethasp: interrupted")


@pytest.mark.slow
def test_permissible_plan_search_stops_at_once(tmp_path):
    process = start(
        "plan",
        *hard_gripper(tmp_path, balls=40),
        *("--principle", "utilitarianism", "--planner", "clingo"),
    )
    time.sleep(5)
    assert process.poll() is None, "the search ended before the interrupt"
    code, out, err = interrupt(process)
    assert code == 130 and out == ""
    assert_one_line(err, "ethasp: interrupted")


# -- commands that give one answer run in a worker process -------------------------------


def test_only_commands_that_give_one_answer_run_in_a_worker():
    """The dialogue, the page and the batch keep their process and run their
    searches in workers of their own; the other commands run in one."""
    from ethasp.interfaces import cli

    parser = cli.build_parser()
    for command in ("dialogue", "serve", "batch"):
        arguments = {"batch": ["asp", "--output", "out.jsonl"]}.get(command, ["trolley"])
        assert not parser.parse_args([command, *arguments]).one_answer
    for command in ("plan", "judge", "ask", "validate", "query"):
        arguments = {"ask": ["--question", "why pull"], "query": ["Bad(pull)"]}
        assert parser.parse_args([command, "trolley", *arguments.get(command, [])]).one_answer


@pytest.mark.slow
def test_a_command_stuck_in_a_grounding_answers_bounded_at_its_time_limit(tmp_path):
    """The model's own grounding cannot be interrupted: the command's worker is
    ended at the time limit and the command answers bounded, on time."""
    model = tmp_path / "big.lp"
    model.write_text(
        "variable(v). action(a). eff(a,v,true). goal(v,true).\n"
        "big(X,Y) :- X = 1..6000, Y = 1..6000.\n"
    )
    began = time.monotonic()
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "ethasp.interfaces.cli",
            "plan",
            str(model),
            "--time-limit",
            "2",
            "--json",
        ],
        capture_output=True,
        text=True,
        timeout=HANG,
    )
    assert time.monotonic() - began < 3.0 + STARTUP
    assert done.returncode == 0 and done.stderr == ""
    assert json.loads(done.stdout) == {
        "status": "bounded",
        "proof": "the time limit of 2 s was reached before an answer was found",
    }


DRIVER = """
import sys, time
import ethasp.reasons.reasons as reasons
judge = reasons.judge

def slow_reasons(*args, reasons_limit=0, **kwargs):
    if reasons_limit:
        time.sleep(60)  # as where clingo cannot be stopped
    return judge(*args, reasons_limit=reasons_limit, **kwargs)

reasons.judge = slow_reasons
from ethasp.interfaces.cli import main
sys.exit(main(sys.argv[1:], worker=True))
"""


SLOW_CONTRAST = """
import sys, time
import ethasp.questions.contrast as contrast

def slow_ask(*args, **kwargs):
    time.sleep(60)  # as where clingo cannot be stopped

contrast.ask = slow_ask
from ethasp.interfaces.cli import main
sys.exit(main(sys.argv[1:], worker=True))
"""


@pytest.mark.slow
def test_a_question_ended_before_its_contrast_answers_bounded_with_the_plan_judged():
    """The plan asked about is judged, the contrast is not found: the JSON
    answer says bounded like every answer without a contrast (its status and
    proof), with the verdict on the plan asked about and why it is bounded."""
    arguments = ["ask", "trolley", "--plan", "pull", "--question", "why pull"]
    done = subprocess.run(
        # (a limit far beyond the judgement of the plan asked about, on a busy machine too)
        [sys.executable, "-c", SLOW_CONTRAST, *arguments, "--time-limit", "8", "--json"],
        capture_output=True,
        text=True,
        timeout=HANG,
    )
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    assert data["status"] == "bounded" and data["contrast"] is None
    assert data["original"]["plan"] == ["pull"] and data["original"]["status"] == "proven"
    assert (
        data["bounded"]
        == data["proof"]
        == ("the time limit of 8 s was reached before the contrast plan was found and explained")
    )


@pytest.mark.slow
def test_a_command_ended_at_its_time_limit_answers_with_what_it_found():
    """The verdicts are found, their reasons are not: the answer is the
    verdicts, bounded, in words and in JSON."""
    arguments = ["judge", "trolley", "--plan", "pull", "--principle", "do-no-harm"]
    began = time.monotonic()
    words = subprocess.run(
        [sys.executable, "-c", DRIVER, *arguments, "--time-limit", "3"],
        capture_output=True,
        text=True,
        timeout=HANG,
    )
    assert time.monotonic() - began < 4.0 + STARTUP
    assert words.returncode == 0, words.stderr
    assert "do-no-harm: impermissible (proven)" in words.stdout
    assert words.stdout.rstrip().endswith(
        "bounded: the time limit of 3 s was reached before the reasons were found"
    )
    data = json.loads(
        subprocess.run(
            [sys.executable, "-c", DRIVER, *arguments, "--time-limit", "3", "--json"],
            capture_output=True,
            text=True,
            timeout=HANG,
        ).stdout
    )
    assert data["bounded"] == "the time limit of 3 s was reached before the reasons were found"
    assert [(j["principle"], j["permissible"]) for j in data["judgements"]] == [
        ("do-no-harm", False)
    ]
