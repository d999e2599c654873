"""Property tests: a `bounded` answer is one that a horizon cut short.

On random models with every feature (conditional effects, derived
variables, exogenous events) and small maximal horizons, every answer that
says `bounded` (no time limit is set) must be one that a brute-force search
of the same horizon would not have settled either (tests/oracle.py:
`RandomModel.within`): where the states reachable within the horizon are
all the reachable states, or a plan within it exists, the answer is a
proof.  And every proof agrees with the oracle.
"""

import random

from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import features, plan_through, random_model

from ethasp import Model, Plan, find_plan, judge
from ethasp.principles.restriction import plan_with_principles

SEEDS = st.integers(min_value=0, max_value=10**9)
HORIZONS = st.integers(min_value=0, max_value=4)
PRINCIPLES = [
    [],
    ["deontology"],
    ["do-no-harm"],
    ["utilitarianism"],
    ["avoid-any-harm"],
    ["deontology", "do-no-harm"],
]


def check(result, spec, principles, horizon) -> None:
    settled = spec.within(principles, horizon)
    expected = spec.shortest_permissible_length(principles)
    if result.status == "bounded":
        assert settled == "open", (result, settled, spec)
    elif result.status == "found":
        plan = [str(action) for action in result.plan]
        assert len(plan) <= horizon and spec.is_plan(plan), (result, spec)
        assert all(spec.permissible(plan, p) for p in principles), (result, spec)
        if result.optimal:
            assert len(plan) == expected, (result, expected, spec)
    else:
        assert result.status == "none" and expected is None, (result, spec)


@settings(max_examples=90, deadline=None)
@given(SEEDS, HORIZONS, st.sampled_from(PRINCIPLES), st.booleans())
def test_plans_are_bounded_only_where_the_horizon_cut_the_search(
    seed, horizon, principles, satisficing
):
    spec = random_model(seed, **features(seed))
    model = Model.from_string(spec.to_asp())
    if principles:
        result = plan_with_principles(
            model, principles, max_horizon=horizon, satisficing=satisficing
        )
    else:
        result = find_plan(model, max_horizon=horizon, satisficing=satisficing)
    check(result, spec, principles, horizon)


# (About half the drawn models have no plan through the walk; 50 of the others.)
@settings(max_examples=50, deadline=None)
@given(SEEDS, HORIZONS, st.integers(min_value=0, max_value=3))
def test_utilitarian_judgements_are_bounded_only_where_the_horizon_cut_the_search(
    seed, horizon, walk
):
    spec = random_model(seed, **features(seed))
    plan = plan_through(spec, random.Random(seed), walk)
    assume(plan is not None)
    judgement = judge(
        Model.from_string(spec.to_asp()),
        Plan.parse(" ".join(plan)),
        ["utilitarianism"],
        max_horizon=horizon,
        reasons_limit=0,
    ).judgements[0]
    if judgement.status == "bounded":
        assert max(spec.configurations().values()) > horizon, (judgement, spec)
        assert judgement.permissible  # no better state was found
    else:
        assert judgement.permissible == spec.permissible(plan, "utilitarianism"), (judgement, spec)
