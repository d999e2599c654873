"""Limits in the Python API (no worker process to end): the budget stops the
reasons' programs and solves and the diagrams' transition relations while they
are built, and a grounding that a budget left running in the background does
not crash the interpreter when it shuts down."""

from __future__ import annotations

import subprocess
import sys
import textwrap

from conftest import MODELS

from ethasp import Model, Plan
from ethasp.planning.budget import Budget
from ethasp.reasons.reasons import explain, judge


def test_reasons_are_cut_short_once_the_budget_ran_out():
    model = Model.load([MODELS / "trolley.lp"])
    spent = Budget()
    spent.cancel()
    report = judge(model, Plan.parse("pull"), ["deontology", "do-no-harm"], budget=spent)
    assert [j.principle for j in report.judgements] == ["deontology", "do-no-harm"]
    for judgement in report.judgements:
        explanation = judgement.explanation
        assert explanation.cut and explanation.truncated and not explanation.sufficient_reasons
        assert "its reasons were cut short" in explanation.text
    # The same verdicts with reasons, where the budget allows them.
    again = judge(model, Plan.parse("pull"), ["deontology", "do-no-harm"])
    assert [j.permissible for j in again.judgements] == [j.permissible for j in report.judgements]
    assert all(not j.explanation.cut and j.explanation.sufficient_reasons for j in again.judgements)


def test_reasons_cut_by_the_budget_say_so_and_are_not_kept():
    model = Model.load([MODELS / "trolley.lp"])
    spent = Budget()
    spent.cancel()
    cut = explain(model, Plan.parse("pull"), "do-no-harm", budget=spent)
    assert cut.truncated and cut.sufficient_truncated and cut.inus_truncated
    assert cut.sufficient_reasons == [] and cut.cut and cut.cut in cut.text
    whole = explain(model, Plan.parse("pull"), "do-no-harm")
    assert not whole.truncated and whole.sufficient_reasons and not whole.cut
    assert whole.text != cut.text


def test_a_grounding_left_running_does_not_crash_the_interpreter_at_exit():
    # The budget stops the wait for a program's grounding, which clingo cannot
    # interrupt: it goes on in the background, and the interpreter waits for
    # it at exit (a thread still in clingo at shutdown ended the process with
    # a segmentation fault).
    script = textwrap.dedent(
        """
        from ethasp import Model
        from ethasp.planning.budget import Budget
        from ethasp.planning.driver.planner import GroundingStopped

        model = Model.from_string("variable(v). action(a). eff(a,v,true). goal(v,true).")
        spent = Budget()
        spent.cancel()  # (the wait ends at once, whatever the machine's speed)
        try:
            model.planner.program(
                [], "p(1..1500). q(X,Y) :- p(X), p(Y), X != Y.", model=False, budget=spent
            )
            print("grounded")
        except GroundingStopped:
            print("stopped")
        """
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, (done.returncode, done.stderr[-2000:])
    assert done.stdout.strip() == "stopped"
