"""Property tests: plan search against a brute-force explicit-state search,
on random models with every feature (conditional effects, derived variables,
exogenous events)."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from oracle import features, random_model

from ethasp import Model, find_plan, validate


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(st.integers(min_value=0, max_value=10**9))
def test_plan_existence_and_shortest_length(seed):
    spec = random_model(seed, **features(seed))
    model = Model.from_string(spec.to_asp())
    result = find_plan(model, max_horizon=20)
    expected = spec.shortest_plan_length()
    if expected is None:
        assert result.status == "none", result
    else:
        assert result.status == "found", result
        assert len(result.plan) == expected
        assert spec.is_plan([str(a) for a in result.plan])


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.lists(st.integers(0, 3), max_size=5))
def test_validation_agrees_with_the_oracle(seed, choices):
    spec = random_model(seed, **features(seed))
    plan = [spec.actions[i % len(spec.actions)] for i in choices]
    from ethasp import Plan

    check = validate(Model.from_string(spec.to_asp()), Plan.parse(" ".join(plan)))
    assert check.valid == spec.is_plan(plan)
    if spec.run(plan) is None:
        assert check.failure_step == spec.first_failure(plan)
    else:
        final = spec.run(plan)
        expected = sorted(v if v in final else f"-{v}" for v in spec.variables)
        assert check.failure_step is None and check.final_state == expected
