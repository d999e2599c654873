"""Every proof and status message says exactly what was proven (one test per
kind of message: plans, HPlans, contrasts, utilitarian judgements)."""

from __future__ import annotations

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


@pytest.mark.parametrize("layers_after", [0.0, float("inf")])
def test_plan_messages(monkeypatch, layers_after):
    """One proof text for each kind of claim, whether the exact layers or the
    solver proves it first."""
    monkeypatch.setattr(search_module, "LAYERS_AFTER", layers_after)
    found = find_plan(Model.load([TROLLEY]))
    assert found.proof == "no plan has fewer than 1 step"
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
    # (the loop-free threshold, or the exact layers: the same words)
    assert horizon.proof == "no goal state is reachable (an exhaustive search proved it)"
    cut = find_plan(Model.load([MODELS / "rescue.lp"]), max_horizon=2)
    assert cut.status == "bounded"
    assert cut.proof == "no plan up to horizon 2 (the maximal horizon)"
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
