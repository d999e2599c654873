"""Property tests: utilitarianism on random models of up to 7 variables and 8
actions, against the explicit-state oracle (tests/oracle.py).

Verdicts, best reachable states and shortest utilitarian HPlans must be right
and proven (``proven`` / ``none``), never ``bounded``, within the default
limits: exact reachability decides them, whatever the length of the paths.
"""

from __future__ import annotations

import random

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import RandomModel, features, plan_through, random_model

from ethasp import Model, Plan
from ethasp.planning.budget import Budget
from ethasp.planning.engines.best_state import best_reachable
from ethasp.principles.judgement import judge
from ethasp.principles.restriction import plan_with_principles

SEEDS = st.integers(min_value=0, max_value=10**9)


def dense_model(seed: int) -> RandomModel:
    """Denser than the oracle's default models: 5 to 7 variables, 5 to 8 actions
    with up to two preconditions and one to three effects, so that many states
    are reachable and paths are long; a quarter with conditional effects, and
    a quarter with every feature (conditional effects, derived variables,
    exogenous events: searched by the explicit layers of configurations, as
    the decision diagrams of exact reachability know no events)."""
    if seed % 4 == 0:
        return random_model(seed, max_variables=7, max_actions=8, conditional=True, far_goal=True)
    if seed % 4 == 1:
        return random_model(
            seed, max_variables=5, max_actions=5, conditional=True, derived=True, events=True
        )
    rng = random.Random(seed)
    variables = [f"v{i}" for i in range(rng.randint(5, 7))]
    actions = [f"a{i}" for i in range(rng.randint(5, 8))]
    pre = {
        a: {v: rng.random() < 0.5 for v in rng.sample(variables, rng.randint(0, 2))}
        for a in actions
    }
    eff = {
        a: {v: rng.random() < 0.5 for v in rng.sample(variables, rng.randint(1, 3))}
        for a in actions
    }
    init = frozenset(v for v in variables if rng.random() < 0.4)
    goal = {v: rng.random() < 0.5 for v in rng.sample(variables, rng.randint(1, 2))}
    fact_utility = {
        (v, b): rng.randint(-3, 3) for v in variables for b in (True, False) if rng.random() < 0.5
    }
    action_utility = {a: rng.randint(-2, 2) for a in actions if rng.random() < 0.5}
    return RandomModel(variables, actions, pre, eff, init, goal, action_utility, fact_utility)


# (About 4 in 10 drawn models have no plan through the walk; 40 of the others.)
@pytest.mark.slow
@settings(max_examples=40, deadline=None)
@given(SEEDS, st.integers(min_value=0, max_value=8))
def test_utilitarian_verdicts_are_right_and_proven(seed, walk):
    """Verdicts and best states against the oracle, each reported state with a
    plan that reaches it (the better plan of an impermissible verdict)."""
    spec = dense_model(seed)
    plan = plan_through(spec, random.Random(seed), walk)
    assume(plan is not None)
    model = Model.from_string(spec.to_asp())
    judgement = judge(
        model, Plan.parse(" ".join(plan)), ["utilitarianism"], budget=Budget(120)
    ).judgements[0]
    assert judgement.status == "proven", judgement
    assert judgement.permissible == spec.permissible(plan, "utilitarianism"), judgement
    if not judgement.permissible:
        better = judgement.compared
        state = frozenset(v for v in spec.variables if v in better.literals)
        assert better.utility == spec.state_utility(state) > spec.state_utility(spec.run(plan))
        # Found at its shortest distance (by the diagrams, or the explicit
        # layers with events), with a plan that reaches it.
        assert spec.distances()[state] == better.distance
        assert judgement.better_plan == better.plan and len(better.plan) == better.distance
        assert spec.run([str(a) for a in better.plan]) == state
    best = best_reachable(model.planner, Budget(120))
    assert best.status == "proven" and best.utility == spec.best_reachable_utility()
    state = frozenset(v for v in spec.variables if v in best.state)
    assert state in spec.distances()
    assert spec.run([str(a) for a in best.plan]) == state


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(SEEDS)
def test_shortest_utilitarian_hplans_are_right_and_proven(seed):
    spec = dense_model(seed)
    result = plan_with_principles(
        Model.from_string(spec.to_asp()), ["utilitarianism"], budget=Budget(120)
    )
    expected = spec.shortest_permissible_length(["utilitarianism"])
    if expected is None:
        assert result.status == "none", (result, spec)
    else:
        assert result.status == "found", (result, spec)
        plan = [str(action) for action in result.plan]
        assert spec.is_plan(plan) and spec.permissible(plan, "utilitarianism"), (plan, spec)
        assert len(plan) == expected, (plan, expected, spec)


@pytest.mark.slow
@settings(max_examples=30, deadline=None)
@given(SEEDS, st.sampled_from([["utilitarianism", "deontology"], ["utilitarianism", "do-no-harm"]]))
def test_utilitarian_hplans_with_other_principles_are_right(seed, principles):
    spec = dense_model(seed)
    result = plan_with_principles(
        Model.from_string(spec.to_asp()), principles, max_horizon=24, budget=Budget(60)
    )
    expected = spec.shortest_permissible_length(principles)
    if result.status == "bounded":  # the loop-free threshold may need long paths
        assert expected is None or expected > result.horizon
    elif expected is None:
        assert result.status == "none", (result, spec)
    else:
        assert result.status == "found" and len(result.plan) == expected, (result, spec)
        plan = [str(action) for action in result.plan]
        assert all(spec.permissible(plan, p) for p in principles), (plan, spec)


@pytest.mark.slow
@settings(max_examples=24, deadline=None)
@given(SEEDS, st.integers(min_value=0, max_value=6))
def test_the_fallback_without_diagrams_is_right_when_it_claims(seed, walk):
    """With a node limit of 1, exact reachability gives up at once and clingo
    optimisation (upper bound, loop-free threshold) answers: right whenever it
    claims a proof, else bounded."""
    import ethasp.planning.engines.explicit as explicit
    import ethasp.planning.engines.reachability as reachability

    spec = random_model(seed, max_variables=5, max_actions=5, **features(seed))
    plan = plan_through(spec, random.Random(seed), walk)
    saved = reachability.DEFAULT_NODE_LIMIT, explicit.CONFIGURATION_LIMIT
    reachability.DEFAULT_NODE_LIMIT = 1  # the diagrams give up at once,
    explicit.CONFIGURATION_LIMIT = 1  # and so do the explicit layers (events)
    try:
        model = Model.from_string(spec.to_asp())
        best = best_reachable(model.planner, Budget(30))
        if best.status == "proven":
            assert best.utility == spec.best_reachable_utility()
        elif best.utility is not None:
            assert best.utility <= spec.best_reachable_utility()
        if plan is not None:
            judgement = judge(
                model, Plan.parse(" ".join(plan)), ["utilitarianism"], budget=Budget(30)
            ).judgements[0]
            if judgement.status == "proven":
                assert judgement.permissible == spec.permissible(plan, "utilitarianism")
            else:
                assert judgement.permissible  # bounded: no better state found
        result = plan_with_principles(
            Model.from_string(spec.to_asp()), ["utilitarianism"], max_horizon=16, budget=Budget(30)
        )
        expected = spec.shortest_permissible_length(["utilitarianism"])
        if result.status == "found":
            assert len(result.plan) == expected
        elif result.status == "none":
            assert expected is None
    finally:
        reachability.DEFAULT_NODE_LIMIT, explicit.CONFIGURATION_LIMIT = saved
