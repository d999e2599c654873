"""Property tests: minimal conflicts and maximal goal subsets against a
brute-force oracle (tests/oracle.py tries every subset of the goal), on random
models with every feature (conditional effects, derived variables, exogenous
events), for the paper's three principles and HERA's principles that have an
HModel.

The conflicts are exactly the subset-minimal sets of goal facts that no
permissible plan reaches; the goal subsets exactly the subset-maximal ones
that a permissible plan reaches, each with a shortest such plan, which the
principle's judgement confirms.
"""

import itertools

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import features, goal_structure, random_model, with_goal

from ethasp import Model
from ethasp.principles.conflict import goal_conflicts

SEEDS = st.integers(min_value=0, max_value=10**9)
PAPER = ["deontology", "utilitarianism", "do-no-harm"]
HERA = [
    "hera-deontology",
    "goal-deontology",
    "avoid-any-harm",
    "avoid-avoidable-harm",
    "hera-utilitarianism",
]
HORIZON = 40


def _facts(items) -> frozenset:
    return frozenset((str(item.fact[0]), item.fact[1]) for item in items)


def check_against_oracle(seed: int, principle: str, larger: bool = False) -> None:
    sizes = {"max_variables": 6, "max_actions": 5} if larger else {}
    spec = random_model(seed, **sizes, **features(seed))
    result = goal_conflicts(Model.from_string(spec.to_asp()), [principle], max_horizon=HORIZON)
    conflicts, subsets = goal_structure(spec, principle)
    assert result.status == "proven", (result.proof, spec)
    assert not result.conflicts_truncated and not result.goal_subsets_truncated
    assert {_facts(c) for c in result.conflicts} == conflicts, (result, spec)
    assert {_facts(s.items) for s in result.goal_subsets} == subsets, (result, spec)
    assert result.empty_goal_fails == (frozenset() in conflicts)
    for subset in result.goal_subsets:
        plan = [str(action) for action in subset.plan]
        reduced = with_goal(spec, dict(_facts(subset.items)))
        assert reduced.is_plan(plan) and reduced.permissible(plan, principle), (plan, spec)
        assert subset.optimal
        assert len(plan) == reduced.shortest_permissible_length([principle]), (plan, spec)


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(SEEDS, st.sampled_from(PAPER))
def test_conflicts_of_the_papers_principles_agree_with_the_oracle(seed, principle):
    check_against_oracle(seed, principle)


@pytest.mark.slow
@settings(max_examples=100, deadline=None)
@given(SEEDS, st.sampled_from(HERA))
def test_conflicts_of_heras_principles_agree_with_the_oracle(seed, principle):
    check_against_oracle(seed, principle)


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(SEEDS, st.sampled_from(PAPER + HERA))
def test_conflicts_of_larger_goals_agree_with_the_oracle(seed, principle):
    check_against_oracle(seed, principle, larger=True)


@settings(max_examples=25, deadline=None)
@given(SEEDS, st.sampled_from(PAPER))
def test_conflicts_agree_with_the_oracle(seed, principle):
    check_against_oracle(seed, principle)


@settings(max_examples=20, deadline=None)
@given(SEEDS, st.sampled_from(PAPER), st.integers(min_value=1, max_value=2))
def test_the_limit_cuts_both_lists(seed, principle, limit):
    spec = random_model(seed, max_variables=6, max_actions=5, **features(seed))
    assume(len(spec.goal) >= 3)
    result = goal_conflicts(
        Model.from_string(spec.to_asp()), [principle], max_horizon=HORIZON, limit=limit
    )
    conflicts, subsets = goal_structure(spec, principle)
    assert len(result.conflicts) <= limit and len(result.goal_subsets) <= limit
    assert {_facts(c) for c in result.conflicts} <= conflicts
    assert {_facts(s.items) for s in result.goal_subsets} <= subsets
    assert result.conflicts_truncated == (len(conflicts) > limit)
    assert result.goal_subsets_truncated == (len(subsets) > limit)


def test_the_oracle_is_monotone_on_an_example():
    """The oracle's own premise: a set reached permissibly has its subsets reached."""
    spec = random_model(7, max_variables=6, max_actions=5)
    facts = sorted(spec.goal.items())
    conflicts, subsets = goal_structure(spec, "do-no-harm")
    for size in range(len(facts) + 1):
        for subset in itertools.combinations(facts, size):
            covered = any(frozenset(subset) <= s for s in subsets)
            blocked = any(c <= frozenset(subset) for c in conflicts)
            assert covered != blocked
