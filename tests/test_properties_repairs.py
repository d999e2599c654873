"""Property tests: repairs (the cheapest changes that admit a permissible
plan) against a brute-force oracle (tests/oracle.py tries every set of
changes in increasing cost), on random models with every feature
(conditional effects, derived variables, exogenous events) that declare
changeable initial values, creative alternatives, preventable events, goal
costs and fixed goal facts.

The repairs are exactly those of least cost; each admits a plan that the
principle permits in the repaired model (the oracle's judgement, and the
principle's own in the repair's judgements); with no repair, the answer is a
proven "none".
"""

import random

import clingo
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import add_repairs, features, least_repairs, random_model, repaired

from ethasp import Model
from ethasp.planning.plan import Plan
from ethasp.principles.repair import distance, repair

SEEDS = st.integers(min_value=0, max_value=10**9)
PRINCIPLES = [
    "deontology",
    "utilitarianism",
    "do-no-harm",
    "hera-deontology",
    "goal-deontology",
    "avoid-any-harm",
    "avoid-avoidable-harm",
]
HORIZON = 40


def key(change) -> tuple:
    """A change in the oracle's form."""
    term = change.term
    if term.name == "drop":
        return ("drop", str(term.arguments[0]), term.arguments[1].name == "true")
    return (term.name, str(term.arguments[0]))


def check_against_oracle(seed: int, principle: str) -> None:
    spec = random_model(seed, **features(seed))
    add_repairs(spec, random.Random(seed))
    result = repair(Model.from_string(spec.to_asp()), [principle], max_horizon=HORIZON, limit=100)
    least, expected = least_repairs(spec, principle)
    if least is None:
        assert result.status == "none" and not result.repairs, (result.proof, spec)
        return
    assert result.status == "found", (result.proof, spec)
    assert result.cost == least, (result.cost, least, spec)
    assert not result.truncated
    assert {frozenset(key(c) for c in r.changes) for r in result.repairs} == expected, spec
    for found in result.repairs:
        assert found.cost == least
        model = repaired(spec, [key(change) for change in found.changes])
        plan = [str(action) for action in found.plan]
        assert model.is_plan(plan) and model.permissible(plan, principle), (plan, spec)
        assert len(plan) == model.shortest_permissible_length([principle]), (plan, spec)
        assert [j.permissible for j in found.judgements] == [True], found.judgements


@pytest.mark.slow
@settings(max_examples=72, deadline=None)
@given(SEEDS, st.sampled_from(PRINCIPLES))
def test_repairs_agree_with_the_oracle(seed, principle):
    check_against_oracle(seed, principle)


@settings(max_examples=12, deadline=None)
@given(SEEDS, st.sampled_from(PRINCIPLES[:3]))
def test_a_few_repairs_agree_with_the_oracle(seed, principle):
    check_against_oracle(seed, principle)


@pytest.mark.slow
@settings(max_examples=40, deadline=None)
@given(SEEDS, st.sampled_from(PRINCIPLES[:3]), st.integers(min_value=0, max_value=4))
def test_repairs_towards_a_plan_keep_the_least_distance(seed, principle, walk):
    """With a given plan, each repair's plan is of least plan stability distance
    to it among the plans the repaired model permits (brute force over the
    plans up to the bound that distance allows)."""
    spec = random_model(seed, **features(seed))
    add_repairs(spec, random.Random(seed))
    rng = random.Random(seed + 1)
    given_plan = [rng.choice(spec.actions) for _ in range(walk)]
    towards = Plan(tuple(clingo.Function(action) for action in given_plan))
    result = repair(
        Model.from_string(spec.to_asp()), [principle], plan=towards, max_horizon=HORIZON, limit=100
    )
    for found in result.repairs:
        assert found.optimal and found.distance == distance(found.plan, towards)
        assume(len(given_plan) + found.distance <= 6)
        model = repaired(spec, [key(change) for change in found.changes])
        best = _least_distance(model, principle, given_plan, found.distance)
        assert found.distance == best, (found.plan, given_plan, spec)


def _least_distance(model, principle, given_plan, bound) -> int:
    """The least distance of a permissible plan of at most len(given)+bound steps."""
    import itertools

    best = bound
    for length in range(len(given_plan) + bound + 1):
        for plan in itertools.product(model.actions, repeat=length):
            plan = list(plan)
            if model.is_plan(plan) and model.permissible(plan, principle):
                best = min(best, _stability(plan, given_plan))
    return best


def _stability(plan, given_plan) -> int:
    counts = {}
    for action in plan:
        counts[action] = counts.get(action, 0) + 1
    for action in given_plan:
        counts[action] = counts.get(action, 0) - 1
    return sum(abs(c) for c in counts.values())
