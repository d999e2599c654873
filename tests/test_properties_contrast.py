"""Property tests: contrast plans on random models (with every feature:
conditional effects, derived variables, exogenous events) meet the
question's constraints, and the principle whenever it was not dropped
(brute-force checks written from the definitions)."""

import random

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import features, random_model

from ethasp import InputError, Model, Plan
from ethasp.questions.contrast import ask

PRINCIPLES = ["deontology", "utilitarianism", "do-no-harm"]


def meets(plan: list[str], kind: str, a: str, b: str | None) -> bool:
    if kind == "why":
        return a not in plan
    if kind == "why-not":
        return a in plan
    if kind == "rather-than":
        return a not in plan and b in plan
    # "why a before b": contrast b, and no a before the first b
    return b in plan and a not in plan[: plan.index(b)]


@pytest.mark.slow
# (About 4 in 9 drawn models have no plan; 65 of the others.)
@settings(max_examples=65, deadline=None)
@given(
    st.integers(min_value=0, max_value=10**9),
    st.sampled_from(PRINCIPLES),
    st.sampled_from(["why", "why-not", "rather-than", "before"]),
)
def test_contrast_plans_meet_the_constraints(seed, under, kind):
    spec = random_model(seed, **features(seed))
    rng = random.Random(seed)
    assume(spec.shortest_plan_length() is not None)
    model = Model.from_string(spec.to_asp())
    from ethasp.planning.search import find_plan

    plan = [str(a) for a in find_plan(model).plan]
    a, b = rng.choice(spec.actions), rng.choice(spec.actions)
    text = {
        "why": f"why {a}",
        "why-not": f"why not {a}",
        "rather-than": f"why {a} rather than {b}",
        "before": f"why {a} before {b}",
    }[kind]
    try:
        answer = ask(
            model,
            text,
            plan=Plan.parse(" ".join(plan)),
            principle="deontology",
            under=under,
            max_horizon=16,
        )
    except InputError as error:
        refused(str(error), plan, kind, a, b)
    else:
        assert not meets(plan, kind, a, b)
        if answer.contrast is None:
            assert answer.status in ("none", "bounded")
        else:
            _check_contrast(spec, answer, under, kind, a, b)


def refused(message: str, plan: list[str], kind: str, a: str, b: str) -> None:
    """A question is refused only when the plan already meets the contrast, or
    (questions about two actions) does not use the action asked about (for
    "before", also the other one)."""
    if kind in ("rather-than", "before") and a not in plan:
        assert f"the plan does not use {a}" in message
    elif kind == "before" and b not in plan:
        assert f"the plan does not use {b}" in message
    else:
        assert "already meets" in message
        assert meets(plan, kind, a, b)


def _check_contrast(spec, answer, under, kind, a, b) -> None:
    contrast = [str(x) for x in answer.contrast.plan]
    assert spec.is_plan(contrast)
    assert meets(contrast, kind, a, b)
    if not answer.principle_dropped:
        assert spec.permissible(contrast, under)
    assert answer.contrast.judgement.permissible == spec.permissible(contrast, under)
