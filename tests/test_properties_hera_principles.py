"""Property tests: HERA's principles that have a restriction (hera-deontology,
goal-deontology, avoid-any-harm, avoid-avoidable-harm, hera-utilitarianism)
on random models with every feature (conditional effects, derived variables,
exogenous events), against the brute-force oracle (tests/oracle.py): the
verdicts on plans, and shortest HPlans or a proven "none"."""

import random

from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import features, plan_through, random_model

from ethasp import Model, Plan, judge
from ethasp.principles.restriction import plan_with_principles

SEEDS = st.integers(min_value=0, max_value=10**9)
RESTRICTED = [
    "hera-deontology",
    "goal-deontology",
    "avoid-any-harm",
    "avoid-avoidable-harm",
    "hera-utilitarianism",
]
HORIZON = 40


# (About half the drawn models have no plan through the walk; 40 of the others.)
@settings(max_examples=40, deadline=None)
@given(SEEDS, st.integers(min_value=0, max_value=5))
def test_verdicts_agree_with_the_oracle(seed, walk):
    spec = random_model(seed, **features(seed))
    plan = plan_through(spec, random.Random(seed), walk)
    assume(plan is not None)
    report = judge(
        Model.from_string(spec.to_asp()), Plan.parse(" ".join(plan)), RESTRICTED, reasons_limit=0
    )
    for judgement in report.judgements:
        assert judgement.status == "proven", judgement
        assert judgement.permissible == spec.permissible(plan, judgement.principle), (
            judgement.principle,
            plan,
            spec,
        )


@settings(max_examples=100, deadline=None)
@given(SEEDS, st.sampled_from(RESTRICTED))
def test_hplans_agree_with_the_oracle(seed, principle):
    spec = random_model(seed, **features(seed))
    result = plan_with_principles(
        Model.from_string(spec.to_asp()), [principle], max_horizon=HORIZON
    )
    expected = spec.shortest_permissible_length([principle])
    if expected is None:
        assert result.status == "none", (result, spec)
    else:
        assert result.status == "found", (result, spec, expected)
        plan = [str(action) for action in result.plan]
        assert spec.is_plan(plan) and spec.permissible(plan, principle), (plan, spec)
        assert len(plan) == expected, (plan, expected, spec)
