"""Property tests: cheapest plans of models with action costs (cost/2) against
the brute-force oracle (tests/oracle.py: uniform-cost search over explicit
configurations), on random models with costs from 0 to 4 and every feature
(conditional effects, derived variables, exogenous events): plain plan search
(the solver's proofs alone, and with uniform-cost search beside it), HPlans
under each principle that restricts plan search, and all cheapest plans."""

from __future__ import annotations

import itertools

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import features, random_model

import ethasp.planning.cost_search as cost_search
from ethasp import Model, find_plan, validate
from ethasp.principles.restriction import plan_with_principles

SEEDS = st.integers(min_value=0, max_value=10**9)
PRINCIPLES = ["deontology", "do-no-harm", "utilitarianism", "avoid-any-harm"]


def spec_of(seed: int):
    return random_model(seed, max_variables=4, max_actions=5, costs=True, **features(seed))


def _check(spec, result, expected) -> None:
    if expected is None:
        assert result.status == "none", (result, spec)
        return
    assert result.status in ("found", "bounded"), (result, expected, spec)
    if result.status == "found":
        assert result.cost == expected, (result, expected, spec)
    if result.plan is not None:
        plan = [str(a) for a in result.plan]
        assert spec.is_plan(plan), (result, spec)
        assert result.cost == spec.plan_cost(plan) >= expected, (result, expected, spec)


@settings(max_examples=40, deadline=None)
@given(SEEDS)
def test_cheapest_plans_agree_with_the_oracle(seed):
    spec = spec_of(seed)
    result = find_plan(Model.from_string(spec.to_asp()), max_horizon=40)
    expected = spec.cheapest_plan_cost()
    _check(spec, result, expected)
    # Tiny models: uniform-cost search beside the solver settles every one,
    # and the plan is the least of the cheapest plans of the fewest steps
    # (the same on every run, whichever search proved what first).
    assert result.status != "bounded", (result, spec)
    if result.plan is not None:
        assert [str(a) for a in result.plan] == spec.least_cheapest_plan(), (result, spec)


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(SEEDS)
def test_the_solvers_proofs_alone_agree_with_the_oracle(seed):
    spec = spec_of(seed)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(cost_search, "UNIFORM_COST", False)
        result = find_plan(Model.from_string(spec.to_asp()), max_horizon=40)
    _check(spec, result, spec.cheapest_plan_cost())
    if result.status == "found":
        assert [str(a) for a in result.plan] == spec.least_cheapest_plan(), (result, spec)


@pytest.mark.slow
@settings(max_examples=120, deadline=None)
@given(SEEDS, st.sampled_from(PRINCIPLES))
def test_cheapest_hplans_agree_with_the_oracle(seed, principle):
    spec = spec_of(seed)
    result = plan_with_principles(Model.from_string(spec.to_asp()), [principle], max_horizon=40)
    expected = spec.cheapest_permissible_cost([principle])
    if expected is None:
        assert result.status == "none", (result, spec)
    else:
        assert result.status in ("found", "bounded"), (result, expected, spec)
    if result.status == "found":
        plan = [str(a) for a in result.plan]
        assert spec.plan_cost(plan) == expected, (result, expected, spec)
        assert spec.permissible(plan, principle), (result, spec)


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(SEEDS)
def test_all_cheapest_plans(seed):
    spec = spec_of(seed)
    model = Model.from_string(spec.to_asp())
    result = find_plan(model, max_horizon=20, all_plans=True)
    expected = spec.cheapest_plan_cost()
    if expected is None:
        assert result.status in ("none", "bounded"), (result, spec)
    else:
        assert result.status in ("found", "bounded"), (result, expected, spec)
    assume(result.status == "found")
    assert result.cost == expected
    for plan in result.plans:
        assert validate(model, plan).valid
        assert spec.plan_cost([str(a) for a in plan]) == expected
        assert len(plan) == len(result.plan)
    if len(result.plan) <= 4:  # every cheapest plan of that length, by brute force
        every = {
            plan
            for plan in itertools.product(spec.actions, repeat=len(result.plan))
            if spec.is_plan(list(plan)) and spec.plan_cost(list(plan)) == expected
        }
        assert {tuple(str(a) for a in plan) for plan in result.plans} == every
