"""Property tests: HModels (ethical plan generation) against a brute-force
oracle, on random models with every feature (conditional effects, derived
variables, exogenous events).

Soundness: every HPlan is a plan of the model and permissible under each
principle asked for (Propositions 1 and 2).  Completeness: when a permissible
plan exists, one of the same shortest length is found (Proposition 3, in its
strong form); when none exists, the status is "none", which needs a proof.
"""

import itertools

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from oracle import features, random_model

from ethasp import Model
from ethasp.principles.restriction import plan_with_principles

# The three principles of the paper (the oracle knows these).
PRINCIPLES = ("deontology", "utilitarianism", "do-no-harm")

SINGLE = [[name] for name in PRINCIPLES]
PAIRS = [list(pair) for pair in itertools.combinations(PRINCIPLES, 2)]
SEEDS = st.integers(min_value=0, max_value=10**9)

# Random models have at most 4 variables: every shortest permissible plan and
# every loop-free threshold (over states with produced flags) stays far below.
HORIZON = 40


def check_against_oracle(seed: int, principles: list[str]) -> None:
    spec = random_model(seed, **features(seed))
    result = plan_with_principles(Model.from_string(spec.to_asp()), principles, max_horizon=HORIZON)
    expected = spec.shortest_permissible_length(principles)
    if expected is None:
        assert result.status == "none", (result, spec)
        assert result.plan is None
        return
    assert result.status == "found", (result, spec, expected)
    plan = [str(action) for action in result.plan]
    assert spec.is_plan(plan), (plan, spec)
    for principle in principles:
        assert spec.permissible(plan, principle), (principle, plan, spec)
    assert len(plan) == expected, (plan, expected, spec)


@pytest.mark.slow
@settings(max_examples=180, deadline=None)
@given(SEEDS, st.sampled_from(SINGLE))
def test_hplans_of_one_principle_agree_with_the_oracle(seed, principles):
    check_against_oracle(seed, principles)


@pytest.mark.slow
@settings(max_examples=120, deadline=None)
@given(SEEDS, st.sampled_from([*PAIRS, list(PRINCIPLES)]))
def test_hplans_of_several_principles_agree_with_the_oracle(seed, principles):
    check_against_oracle(seed, principles)


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(SEEDS)
def test_the_utilitarian_bound_is_the_proven_best_reachable_utility(seed):
    spec = random_model(seed, **features(seed))
    result = plan_with_principles(
        Model.from_string(spec.to_asp()), ["utilitarianism"], max_horizon=HORIZON
    )
    assert result.best.status == "proven", result
    assert result.best.utility == spec.best_reachable_utility()
    assert result.to_json()["best_utility"] == result.best.utility
