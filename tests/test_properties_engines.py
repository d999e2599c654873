"""Property tests: the engines' negative claims against the encodings themselves.

An engine (ethasp.planning.engines) that says "no plan", "every plan has at
least k steps" or "no reachable state is better" claims something about
every plan, which no trace can witness.  So on random models that draw every
feature (exogenous events, conditional effects, derived variables,
``oracle.features``), each such claim is checked twice: by clingo running the
encodings alone on the same model at fixed horizons (``planning/plan.lp``
for plans, ``judgement/best.lp`` with ``at_least/1`` for better states, as
their headers run them from the command line), and by the brute-force oracle
(tests/oracle.py).  The horizon that covers every plan is the depth of the
oracle's configuration graph (a shortest path to any configuration is no
longer), and at least the last event's step (the encodings check the goal
and the state there).
"""

from __future__ import annotations

import pytest
from conftest import answer_sets
from hypothesis import given, settings
from hypothesis import strategies as st
from oracle import features, random_model
from test_groups import weighted_token_model
from test_layers import finished

import ethasp.planning.engines.explicit as explicit_module
import ethasp.planning.engines.reachability as reachability_module
from ethasp import Model, find_plan
from ethasp.planning.budget import Budget
from ethasp.planning.engines import best_state, model_features
from ethasp.planning.engines.explicit import Events, search
from ethasp.planning.engines.greedy import EXHAUSTED, greedy_plan
from ethasp.planning.engines.layers import Atoms, Layers, Status, search_model
from ethasp.planning.engines.reachability import Reachability
from ethasp.planning.engines.task import Task

pytestmark = pytest.mark.slow

SEEDS = st.integers(min_value=0, max_value=10**9)


def spec_of(seed: int, far: bool, tokens: bool = False):
    """A random model drawing every feature; with ``tokens``, one of tokens that
    move (mutex groups, which the diagrams encode in binary: tests/
    test_groups.py) with conditional effects, derived variables and
    utilities of facts drawn."""
    if tokens:
        return weighted_token_model(seed, conditional=seed % 2 == 0, derived=seed % 3 == 0)
    return random_model(seed, max_variables=4, max_actions=4, far_goal=far, **features(seed))


def depth(spec) -> int:
    """A horizon that covers every plan and every reachable state."""
    return max(max(spec.configurations().values()), spec.last_event)


# -- the encodings, at fixed horizons ------------------------------------------------


def plan_within(spec, actions: int) -> bool:
    """Do the encodings find a plan of at most ``actions`` actions?  (Run to
    the last event at least, the steps after ``actions`` idle: ``past/1``.)"""
    horizon = max(actions, spec.last_event)
    idle = "".join(f"past({t}).\n" for t in range(actions + 1, horizon + 1))
    found = answer_sets(
        ["planning/plan.lp"], spec.to_asp() + idle, ("1", "-c", f"horizon={horizon}")
    )
    return bool(found)


def state_at_least(spec, utility: int) -> bool:
    """Do the encodings reach a state worth at least ``utility`` (at a horizon
    that covers every reachable state)?"""
    horizon = depth(spec)
    program = (
        spec.to_asp()
        + f"time(0..{horizon}). step(1..{horizon}). horizon({horizon}).\n"
        + f"at_least({utility}).\n"
    )
    files = [
        "planning/model.lp",
        "planning/relaxed.lp",
        "planning/transition.lp",
        "planning/events.lp",
        "judgement/best.lp",
        "judgement/state.lp",
    ]
    return bool(answer_sets(files, program, ("1", "--opt-mode=ignore")))


def check_no_plan(spec) -> None:
    """A claim that no plan exists, against the encodings and the oracle."""
    assert spec.shortest_plan_length() is None, spec
    assert not plan_within(spec, depth(spec)), spec


def check_lower_bound(spec, bound: int) -> None:
    """A claim that every plan has at least ``bound`` steps."""
    shortest = spec.shortest_plan_length()
    assert shortest is None or shortest >= bound, (bound, spec)
    if bound > 0:
        assert not plan_within(spec, bound - 1), (bound, spec)


def check_no_better_state(spec, utility: int) -> None:
    """A claim that no reachable state is worth more than ``utility``."""
    assert spec.best_reachable_utility() <= utility, (utility, spec)
    assert not state_at_least(spec, utility + 1), (utility, spec)


# -- the engines' claims ----------------------------------------------------------------


def layers_status(model: Model, read_plan: bool) -> Status:
    layers = Layers(Atoms(model.planner), Budget(None), read_plan=read_plan).start()
    try:
        return finished(layers)
    finally:
        layers.stop()


def check_status(spec, status: Status) -> None:
    """What exact layers (diagrams or explicit) proved."""
    assert not status.working, status
    check_lower_bound(spec, status.bound)
    if status.complete:
        check_no_plan(spec)
    if status.goal_layer is not None:
        check_lower_bound(spec, status.goal_layer)  # a shortest length: none shorter
        assert spec.shortest_plan_length() == status.goal_layer


@settings(max_examples=60, deadline=None)
@given(SEEDS, st.booleans(), st.booleans(), st.booleans())
def test_the_layers_bounds_and_nones_hold_in_the_encodings(seed, far, read_plan, tokens):
    """The exact layers beside plan search (the diagrams, or the explicit layers
    of configurations on a model with events)."""
    spec = spec_of(seed, far, tokens)
    model = Model.from_string(spec.to_asp())
    if model.planner.is_fact("unreachable_goal"):
        check_no_plan(spec)  # relaxed reachability's claim: no engine starts
    else:
        check_status(spec, layers_status(model, read_plan))


@settings(max_examples=60, deadline=None)
@given(SEEDS, st.booleans())
def test_the_explicit_layers_bounds_and_nones_hold_in_the_encodings(seed, far):
    """The explicit layers of configurations on every model (they handle every
    feature), their lower bounds one by one as they grow."""
    spec = spec_of(seed, far)
    planner = Model.from_string(spec.to_asp()).planner
    if planner.is_fact("unreachable_goal"):
        # Decided before any engine starts (the search model leaves out the goal
        # literals on variables that never change).
        check_no_plan(spec)
    else:
        ground = search_model(Atoms(planner))
        task = Task(ground)
        statuses: list[Status] = []

        def publish(**changes) -> None:
            last = statuses[-1] if statuses else Status()
            statuses.append(Status(**{**last.__dict__, **changes}))

        search(task, Events(ground.events, task.index), Budget(None), publish, lambda: False)
        for status in statuses:
            check_lower_bound(spec, status.bound)
        check_status(spec, statuses[-1])


@settings(max_examples=60, deadline=None)
@given(SEEDS, st.booleans())
def test_greedy_nones_hold_in_the_encodings(seed, far):
    """Greedy search's "none" (every reachable state expanded), on the models it
    handles (no events: the model without them)."""
    spec = spec_of(seed, far)
    spec.events = []
    model = Model.from_string(spec.to_asp())
    if model.planner.is_fact("unreachable_goal"):
        check_no_plan(spec)
    else:
        plan, why = greedy_plan(Task(search_model(Atoms(model.planner))))
        if plan is None:
            assert why == EXHAUSTED, why
            check_no_plan(spec)
        else:
            assert spec.is_plan([str(action) for action in plan])


@settings(max_examples=80, deadline=None)
@given(SEEDS, st.booleans(), st.booleans())
def test_the_diagrams_bounds_nones_and_best_states_hold_in_the_encodings(seed, far, tokens):
    """Exact reachability (binary decision diagrams) on the models it handles
    (no events): the first layer with a goal state, "none", the best utility."""
    spec = spec_of(seed, far, tokens)
    spec.events = []
    ground = Model.from_string(spec.to_asp()).planner.ground_model()
    r = Reachability(ground)
    assert r.run()
    first = r.first_layer(r.goal())
    if first is None:
        check_no_plan(spec)
    else:
        check_lower_bound(spec, first)
    best = r.best_of(r.reached)
    check_no_better_state(spec, best.utility)
    assert spec.best_reachable_utility() == best.utility


@settings(max_examples=40, deadline=None)
@given(SEEDS, st.booleans(), st.booleans())
def test_no_better_state_holds_in_the_encodings(seed, far, fallback):
    """best_state's proven "no reachable state is better" (the best reachable
    state, and a comparison with it), from the layers or, with ``fallback``,
    from clingo optimisation and the loop-free threshold (the layers give up at
    once); and its "a better state exists" with its witness plan."""
    spec = spec_of(seed, far)
    saved = reachability_module.DEFAULT_NODE_LIMIT, explicit_module.CONFIGURATION_LIMIT
    if fallback:
        reachability_module.DEFAULT_NODE_LIMIT = explicit_module.CONFIGURATION_LIMIT = 1
    try:
        model = Model.from_string(spec.to_asp())
        best = best_state.best_reachable(model.planner, Budget(60), max_horizon=16)
        if best.status == best_state.PROVEN:
            check_no_better_state(spec, best.utility)
            assert best.utility == spec.best_reachable_utility()
        compared = best_state.better_state(
            Model.from_string(spec.to_asp()).planner, spec.best_reachable_utility() - 1, Budget(60)
        )
        assert compared.better is not None, compared  # the best state is better
        assert spec.run([str(a) for a in compared.better.plan]) == frozenset(
            str(v) for v, b in compared.better.facts if b
        )
        none = best_state.better_state(
            Model.from_string(spec.to_asp()).planner, spec.best_reachable_utility(), Budget(60)
        )
        assert none.better is None, none
        if none.status == best_state.PROVEN:
            check_no_better_state(spec, spec.best_reachable_utility())
    finally:
        reachability_module.DEFAULT_NODE_LIMIT, explicit_module.CONFIGURATION_LIMIT = saved


@settings(max_examples=60, deadline=None)
@given(SEEDS, st.booleans(), st.integers(min_value=0, max_value=6))
def test_plan_search_nones_and_bounds_hold_in_the_encodings(seed, far, horizon):
    """Plan search (the encodings, with the engines beside them): "none" and the
    lower bound of a bounded search."""
    spec = spec_of(seed, far)
    result = find_plan(Model.from_string(spec.to_asp()), max_horizon=horizon)
    if result.status == "none":
        check_no_plan(spec)
    elif result.status == "bounded":
        check_lower_bound(spec, horizon + 1)
    else:
        check_lower_bound(spec, len(result.plan))
        assert spec.is_plan([str(a) for a in result.plan])


def test_the_models_drawn_have_every_feature():
    """The seeds draw events, conditional effects and derived variables, each in
    half of the models, every combination alike."""
    seen = set()
    for seed in range(64):
        spec = spec_of(seed, False)
        planner = Model.from_string(spec.to_asp()).planner
        seen.add(frozenset(planner.features))
        assert model_features(planner.ground_model()) <= planner.features
    assert len(seen) == 8  # every combination of the three features
