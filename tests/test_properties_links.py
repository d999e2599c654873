"""Property tests: the E-links and D-links of ``ethasp explain`` (encodings/
questions/producers.lp and demands.lp) against their definitions computed by
brute force (tests/links_oracle.py, every subsequence tried), on random models
and random plans: STRIPS models with negative preconditions (plan-explainer's
setting), then models with conditional effects, derived variables and
exogenous events."""

from __future__ import annotations

import random

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from links_oracle import e_and_d_links, links_of_json
from oracle import features, plan_through, random_model

from ethasp import Model, Plan
from ethasp.questions.steps import explain_steps

SEEDS = st.integers(min_value=0, max_value=10**9)


def _check(spec, plan: list[str]) -> None:
    explanation = explain_steps(Model.from_string(spec.to_asp()), Plan.parse(" ".join(plan)))
    data = explanation.to_json()
    expected_e, expected_d = e_and_d_links(spec, plan)
    assert links_of_json(data["d_links"]) == expected_d, (spec, plan)
    assert links_of_json(data["e_links"]) == expected_e, (spec, plan)


@settings(max_examples=60, deadline=None)
@given(SEEDS, st.integers(0, 4))
def test_strips_links_agree_with_the_definitions(seed, walk):
    spec = random_model(seed, max_variables=5, max_actions=5)
    plan = plan_through(spec, random.Random(seed), walk)
    assume(plan is not None and len(plan) <= 7)
    _check(spec, plan)


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(SEEDS, st.integers(0, 5))
def test_strips_links_agree_with_the_definitions_at_scale(seed, walk):
    spec = random_model(seed, max_variables=6, max_actions=6, far_goal=seed % 2 == 0)
    plan = plan_through(spec, random.Random(seed), walk)
    assume(plan is not None and len(plan) <= 8)
    _check(spec, plan)


@pytest.mark.slow
@settings(max_examples=120, deadline=None)
@given(SEEDS, st.integers(0, 4))
def test_links_with_every_feature_agree_with_the_definitions(seed, walk):
    spec = random_model(seed, max_variables=5, max_actions=5, **features(seed))
    plan = plan_through(spec, random.Random(seed), walk)
    assume(plan is not None and len(plan) <= 7)
    _check(spec, plan)
