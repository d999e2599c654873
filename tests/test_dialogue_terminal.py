"""The dialogue at a terminal: Tab completion of commands, actions, facts and
principles, a history kept across runs (never an error when it cannot be
kept), Ctrl-C; run in a real pseudo-terminal where one exists."""

from __future__ import annotations

import os
import select
import sys
import time
from pathlib import Path

import pytest
from conftest import ROOT

from ethasp.interfaces.editing import Completer, history_path

WAIT = 120  # seconds a step may take on a busy machine (no timing is asserted)


# -- completion --------------------------------------------------------------------------

ASP = Completer(
    ["pull", "refrain", "move(r1,r2)", "move(r2,r3)"],
    ["five_will_die", "at(r1)"],
    ["deontology", "do-no-harm", "utilitarianism"],
)
PDDL = Completer(
    ["(move kitchen hall)", "(move kitchen store-room)", "(pick-up pills-ann store-room)"],
    ["(robot-at hall)"],
    ["deontology"],
)


@pytest.mark.parametrize(
    "line, expected",
    [
        (
            "",
            [
                "why ",
                "principle ",
                "plan ",
                "history ",
                "undo ",
                "save ",
                "load ",
                "help ",
                "quit ",
            ],
        ),
        ("un", ["undo "]),
        ("why p", ["pull "]),
        (
            "why ",
            [
                "move(r1,r2) ",
                "move(r2,r3) ",
                "pull ",
                "refrain ",
                "at(r1) ",
                "five_will_die ",
                "not ",
            ],
        ),
        ("why n", ["not "]),
        ("why not f", ["five_will_die "]),
        ("why move(r", ["move(r1,r2) ", "move(r2,r3) "]),
        ("why pull ", ["rather ", "before "]),
        ("why pull rather ", ["than "]),
        ("why pull rather than re", ["refrain "]),
        ("why pull rather than f", []),  # a fact cannot be the contrast's action
        ("why move(r1,r2) before m", ["move(r1,r2) ", "move(r2,r3) "]),
        ("why not pull ", []),
        ("principle d", ["deontology ", "do-no-harm "]),
        ("principle do-no-harm ", []),
        ("history ", []),
    ],
)
def test_completion_of_asp_names(line, expected):
    assert ASP.candidates(line) == expected


@pytest.mark.parametrize(
    "line, expected",
    [
        ("why (m", ["(move kitchen hall) ", "(move kitchen store-room) "]),
        ("why (move k", ["kitchen hall) ", "kitchen store-room) "]),  # word by word
        ("why (move kitchen s", ["store-room) "]),
        ("why (move kitchen hall) ", ["rather ", "before "]),
        ("why (move kitchen hall) before (p", ["(pick-up pills-ann store-room) "]),
        ("why not (r", ["(robot-at hall) "]),
    ],
)
def test_completion_of_pddl_names(line, expected):
    assert PDDL.candidates(line) == expected


def test_completion_of_file_names(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "saved.json").write_text("{}")
    (tmp_path / "sub").mkdir()
    assert ASP.candidates("load s") == ["saved.json", "sub/"]
    assert ASP.candidates("save sub/") == []


def test_where_the_history_is_kept(tmp_path):
    assert history_path({"ETHASP_HISTORY": str(tmp_path / "h")}) == tmp_path / "h"
    assert history_path({"ETHASP_HISTORY": ""}) is None
    assert history_path({"XDG_STATE_HOME": "/state"}) == Path("/state/ethasp/history")
    assert history_path({"HOME": "/home/someone"}) == Path(
        "/home/someone/.local/state/ethasp/history"
    )


# -- at a real terminal --------------------------------------------------------------------

pty = pytest.importorskip("pty")
pytest.importorskip("readline")


class Terminal:
    """``ethasp dialogue`` in a pseudo-terminal, typed at as a person would."""

    def __init__(self, *args: str, env: dict):
        environment = {**os.environ, "PYTHONPATH": str(ROOT), "TERM": "xterm", **env}
        self.pid, self.fd = pty.fork()
        if self.pid == 0:  # the child: the dialogue
            os.execve(
                sys.executable,
                [sys.executable, "-m", "ethasp.interfaces.cli", "dialogue", *args],
                environment,
            )
        self.output = b""

    def read(self, seconds: float) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            ready, _, _ = select.select([self.fd], [], [], 0.05)
            if ready:
                try:
                    data = os.read(self.fd, 65536)
                except OSError:
                    return
                if not data:
                    return
                self.output += data

    def wait_for(self, text: str, after: int = 0) -> None:
        end = time.monotonic() + WAIT
        while text.encode() not in self.output[after:]:
            assert time.monotonic() < end, f"no {text!r} in {self.text()!r}"
            self.read(0.1)

    def type(self, keys: str) -> int:
        mark = len(self.output)
        os.write(self.fd, keys.encode())
        return mark

    def text(self) -> str:
        return self.output.decode("utf-8", "replace").replace("\r", "")

    def end(self) -> int:
        end = time.monotonic() + WAIT
        while True:
            self.read(0.1)
            done, status = os.waitpid(self.pid, os.WNOHANG)
            if done:
                self.read(0.2)
                return os.waitstatus_to_exitcode(status)
            assert time.monotonic() < end, "the dialogue did not end"


def test_tab_completion_and_a_history_across_runs(tmp_path):
    history = tmp_path / "state" / "history"
    env = {"ETHASP_HISTORY": str(history)}
    first = Terminal("trolley", "--save", "-", env=env)
    first.wait_for("ethasp> ")
    mark = first.type("why pu\trather than re\t\n")  # completion adds the spaces
    first.wait_for("Alternatively, the man could refrain from action.", mark)
    mark = first.type("princ\tutil\t\n")
    first.wait_for("next contrasts must satisfy: utilitarianism", mark)
    first.type("quit\n")
    assert first.end() == 0
    assert history.read_text().splitlines() == [
        "why pull rather than refrain ",
        "principle utilitarianism ",
        "quit",
    ]

    # The next run recalls the question with the up arrow (three lines back).
    second = Terminal("trolley", "--save", "-", env=env)
    second.wait_for("ethasp> ")
    mark = second.type("\x1b[A\x1b[A\x1b[A\n")
    second.wait_for("Alternatively, the man could refrain from action.", mark)
    second.type("quit\n")
    assert second.end() == 0


def test_a_history_that_cannot_be_kept_is_no_error(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    terminal = Terminal("trolley", "--save", "-", env={"ETHASP_HISTORY": str(blocker / "history")})
    terminal.wait_for("ethasp> ")
    mark = terminal.type("why pull\n")
    terminal.wait_for("contrast plan", mark)
    terminal.type("quit\n")
    assert terminal.end() == 0
    assert "error" not in terminal.text().lower()


def test_ctrl_c_at_the_prompt_saves_and_ends(tmp_path):
    saved = tmp_path / "dialogue.json"
    terminal = Terminal("trolley", "--save", str(saved), env={"ETHASP_HISTORY": ""})
    terminal.wait_for("ethasp> ")
    terminal.type("why ref")
    terminal.read(0.3)
    terminal.type("\x03")
    assert terminal.end() == 130
    assert f"ethasp: interrupted; dialogue saved to {saved}" in terminal.text()
    assert saved.is_file()
