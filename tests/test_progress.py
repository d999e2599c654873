"""Searches never hang silently: budgets report progress, a live line shows it
on a terminal after a delay, commands have a default time limit, and a
cancelled or expired budget makes searches answer bounded."""

from __future__ import annotations

import io

import pytest
from conftest import MODELS

from ethasp import Model
from ethasp.interfaces import cli, progress
from ethasp.planning.budget import DEFAULT_TIME_LIMIT, Budget, Progress
from ethasp.principles.restriction import plan_with_principles


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_progress_records_read_as_one_line():
    assert (
        Progress("best reachable state", 8, 4, 7, 3.14).line()
        == "best reachable state: horizon 8, best 4, bound 7 (3.1 s)"
    )
    assert Progress("plan search", elapsed=0.5).line() == "plan search (0.5 s)"


def test_the_live_line_waits_then_shows_and_clears(monkeypatch):
    stream = Terminal()
    line = progress.ProgressLine(stream)
    line(Progress("plan search", horizon=3))
    assert stream.getvalue() == ""  # nothing in the first seconds
    monkeypatch.setattr(progress, "DELAY", 0.0)
    line = progress.ProgressLine(stream)
    line(Progress("plan search", horizon=3))
    assert stream.getvalue().startswith("\rethasp: plan search: horizon 3")
    line.clear()
    assert stream.getvalue().endswith("\r")
    quiet = progress.ProgressLine(io.StringIO())  # not a terminal: nothing
    quiet(Progress("plan search", horizon=3))
    assert quiet.width == 0


def test_searches_report_to_the_budget():
    seen: list[Progress] = []
    budget = Budget(None, seen.append)
    result = plan_with_principles(
        Model.load([MODELS / "rescue.lp"]), ["utilitarianism"], budget=budget
    )
    assert result.status == "found"
    assert any(record.task == "best reachable state" for record in seen)
    assert all(record.elapsed >= 0 for record in seen)


def test_commands_have_a_default_time_limit():
    parser = cli.build_parser()
    for command in (
        ["plan", "m.lp"],
        ["judge", "m.lp", "--plan", "a"],
        ["ask", "m.lp", "--question", "why a"],
        ["dialogue", "m.lp"],
    ):
        assert parser.parse_args(command).time_limit == DEFAULT_TIME_LIMIT
    assert parser.parse_args(["plan", "m.lp", "--time-limit", "0"]).time_limit is None
    assert "0 for no limit" in parser._subparsers._group_actions[0].choices["plan"].format_help()


def test_a_cancelled_budget_answers_bounded():
    budget = Budget()
    budget.cancel()
    result = plan_with_principles(
        Model.load([MODELS / "rescue.lp"]), ["utilitarianism"], budget=budget
    )
    assert result.status == "bounded" and "cancelled" in result.proof


def test_a_budget_until_a_condition_ends_with_its_parent():
    parent = Budget(100)
    part = parent.until(lambda: False)
    assert not part.expired() and part.remaining() <= 100
    parent.cancel()
    assert part.expired() and part.why_stopped() == "the search was cancelled"
    with pytest.raises(ValueError):
        Budget(-1)
