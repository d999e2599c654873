"""Every proof and status message says exactly what was proven (one test per
kind of message: plans, HPlans, contrasts, utilitarian judgements)."""

from __future__ import annotations

import re

import pytest
from conftest import MODELS

from ethasp import Model, Plan, find_plan
from ethasp.planning import search as search_module
from ethasp.planning.budget import Budget
from ethasp.principles.judgement import judge
from ethasp.principles.restriction import plan_with_principles
from ethasp.questions.contrast import ask

TROLLEY = MODELS / "trolley.lp"
LOOP = """variable(a). variable(b). action(flip). eff(flip,a,true).
action(flop). eff(flop,a,false). goal(b,true)."""
UNREACHABLE = "variable(a). action(x). pre(x,a,true). eff(x,a,false). goal(a,true)."


def cancelled() -> Budget:
    budget = Budget()
    budget.cancel()
    return budget


def test_plan_messages(monkeypatch):
    # The exact layers start once the solver has worked a while, which on a busy
    # machine may come before the proofs these messages describe: keep them out.
    monkeypatch.setattr(search_module, "LAYERS_AFTER", float("inf"))
    found = find_plan(Model.load([TROLLEY]))
    assert found.proof in (
        "no plan has fewer than 1 step (every smaller horizon refuted)",
        "no plan has fewer than 1 step: exact reachability found no goal state within 0 steps",
    )  # whichever proves it first
    empty = find_plan(Model.from_string("variable(a). init(a). goal(a,true)."))
    assert empty.proof == "the goal holds in the initial state"
    relaxed = find_plan(Model.from_string(UNREACHABLE))
    assert relaxed.status == "none"
    assert relaxed.proof == "the goal is unreachable even ignoring delete effects"
    horizon = find_plan(
        Model.from_string(
            LOOP + " action(set). pre(set,a,true). pre(set,a,false). eff(set,b,true)."
        )
    )
    assert horizon.status == "none"
    # Proven by the loop-free threshold, or by the exact layers if they finish
    # first (they race with the solver; either proof is exact).
    match = re.match(
        r"no plan up to horizon (\d+), and no path of (\d+) steps? without a "
        r"repeated state: every reachable state was searched$",
        horizon.proof,
    )
    assert (match and int(match.group(2)) == int(match.group(1)) + 1) or horizon.proof == (
        "exact reachability layers ran out of new states without meeting a goal state: no "
        "goal state is reachable"
    ), horizon.proof
    cut = find_plan(Model.load([MODELS / "rescue.lp"]), max_horizon=2)
    assert cut.status == "bounded"
    # (by the solver's refutations, or by the exact layers if they are ahead)
    assert re.fullmatch(
        r"no plan up to horizon 2 \(the maximal horizon\)|every plan has more "
        r"than 2 steps \(exact reachability .*\), the maximal horizon",
        cut.proof,
    ), cut.proof
    stopped = find_plan(Model.load([MODELS / "rescue.lp"]), budget=cancelled())
    assert stopped.status == "bounded" and stopped.proof.startswith("the search was cancelled")


def test_hplan_messages_say_under_which_principles():
    model = Model.load([TROLLEY])
    found = plan_with_principles(model, ["do-no-harm"])
    assert found.proof.startswith("a shortest plan permissible under do-no-harm: ")
    none = plan_with_principles(model, ["do-no-harm", "utilitarianism"])
    assert none.status == "none"
    assert none.proof.startswith("no plan is permissible under do-no-harm and utilitarianism: ")
    utilitarian = plan_with_principles(model, ["utilitarianism"])
    assert utilitarian.proof.startswith(
        "a shortest plan permissible under utilitarianism: no plan has fewer than 1 step"
    )


def test_contrast_messages_speak_of_the_question():
    trolley = Model.load([TROLLEY])
    answer = ask(trolley, "why refrain rather than pull", principle="do-no-harm")
    # refrain is permissible under do-no-harm: what no plan is, is one that meets
    # the question (uses pull, not refrain) and is permissible.
    assert answer.principle_dropped
    assert answer.dropped_because.startswith(
        "no plan meeting the question is permissible under do-no-harm: "
    )
    assert answer.proof.startswith("a shortest plan meeting the question: ")
    model = Model.from_string(
        "variable(a). action(x). pre(x,a,true). eff(x,a,false). goal(a,false)."
    )
    impossible = ask(model, "why not x", plan=Plan(()))
    assert impossible.status == "none" and not impossible.principle_dropped
    assert impossible.proof.startswith("no plan meets the question: ")
    assert impossible.explanation.endswith(
        "There is no alternative plan: no plan can include action x."
    )


def test_utilitarian_judgement_messages():
    model = Model.load([TROLLEY])
    worse = judge(model, Plan.parse("refrain"), ["utilitarianism"]).judgements[0]
    assert worse.proof == (
        "a state of utility 4 is reachable in 1 step, more than the final state's -4"
    )
    best = judge(model, Plan.parse("pull"), ["utilitarianism"]).judgements[0]
    assert best.proof.startswith("no reachable state is better: ")
    stopped = judge(
        Model.load([TROLLEY]), Plan.parse("refrain"), ["utilitarianism"], budget=cancelled()
    ).judgements[0]
    assert stopped.status == "bounded" and stopped.permissible
    assert stopped.proof.endswith("; a better reachable state may exist")


@pytest.mark.parametrize(
    "search", ["plan", "satisficing", "deontology", "utilitarianism", "do-no-harm", "best"]
)
def test_a_cancelled_budget_starts_no_solve(search):
    """A budget cancelled before the call stops every search before it solves
    (whatever the load of the machine: no solve runs, so none can finish)."""
    from ethasp.planning.engines.best_state import best_reachable

    model = Model.load([MODELS / "rescue.lp"])
    planner = model.planner
    planner.ground_to(1)
    solves = []
    original = planner.ctl.solve
    planner.ctl.solve = lambda *args, **kwargs: solves.append(args) or original(*args, **kwargs)
    if search in ("plan", "satisficing"):
        result = find_plan(model, budget=cancelled(), satisficing=search == "satisficing")
    elif search == "best":
        result = best_reachable(planner, cancelled())
    else:
        result = plan_with_principles(model, [search], budget=cancelled())
    assert result.status == "bounded", result
    assert "cancelled" in result.proof
    assert solves == []
