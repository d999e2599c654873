"""Exact layers beside plan search (ethasp.planning.engines.layers) against the oracle.

The layers must only prove what is true: a lower bound on the length of every
plan, the length of a shortest plan, a shortest plan (valid), or that no goal
state is reachable.  Plan search with the layers started at once must find
plans of the oracle's lengths, in a child process and in a thread.
"""

import time

import clingo
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from oracle import features, random_model
from test_groups import token_model

import ethasp.planning.engines.layers as layers_module
import ethasp.planning.search as search_module
from ethasp import Model, find_plan, validate
from ethasp.planning.budget import Budget
from ethasp.planning.engines.layers import Atoms, Layers, search_model

WAIT = 60.0  # seconds a test waits for the layers at most (they take milliseconds)


def finished(layers: Layers):
    """The layers' final status (waiting for them)."""
    end = time.monotonic() + WAIT
    while layers.status.working and time.monotonic() < end:
        layers.news.wait(0.05)
        layers.news.clear()
    return layers.status


def run_layers(model: Model, read_plan: bool = True):
    layers = Layers(Atoms(model.planner), Budget(None), read_plan=read_plan).start()
    try:
        return finished(layers)
    finally:
        layers.stop()


@pytest.fixture(params=["process", "thread"])
def mode(request, monkeypatch):
    if request.param == "thread":
        monkeypatch.setattr(layers_module, "can_fork", lambda: False)
    elif not layers_module.can_fork():
        pytest.skip("no child processes here")
    return request.param


def check_against_oracle(spec, status, model):
    expected = spec.shortest_plan_length()
    assert not status.stopped, status
    if expected is None:
        assert status.complete and status.plan is None
        assert status.bound >= 0
    else:
        assert status.goal_layer == expected and status.bound == expected
        plan = [str(action) for action in status.plan]
        assert len(plan) == expected and spec.is_plan(plan)


@pytest.mark.slow
@settings(max_examples=80, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.booleans(), st.booleans(), st.booleans())
def test_layers_prove_the_shortest_length_and_read_a_shortest_plan(
    seed, conditional, derived, events
):
    """Diagrams, or explicit layers of configurations with events."""
    spec = random_model(
        seed, conditional=conditional, derived=derived, far_goal=seed % 2 == 0, events=events
    )
    model = Model.from_string(spec.to_asp())
    if model.planner.is_fact("unreachable_goal"):
        # Plan search answers this before any layer is computed.
        assert spec.shortest_plan_length() is None
    else:
        check_against_oracle(spec, run_layers(model), model)


@pytest.mark.parametrize("seed", [3, 17, 2024])
def test_layers_in_a_process_and_in_a_thread_agree(seed, mode):
    spec = random_model(seed, max_variables=5, max_actions=5, far_goal=True)
    model = Model.from_string(spec.to_asp())
    if model.planner.is_fact("unreachable_goal"):
        pytest.skip("relaxed reachability answers this one")
    check_against_oracle(spec, run_layers(model), model)


def test_search_model_drops_what_never_changes():
    model = Model.from_string("""
        variable(lit;door;far;stuck). init(lit). action(open;go;fly).
        pre(open,lit,true). eff(open,door,true).
        pre(go,door,true). eff(go,far,true). eff(go,lit,true).
        pre(fly,stuck,true). eff(fly,far,true).
        goal(far,true). goal(lit,true).""")
    ground = search_model(Atoms(model.planner))
    assert sorted(map(str, ground.variables)) == ["door", "far"]  # lit and stuck never change
    assert sorted(str(a.name) for a in ground.actions) == ["go", "open"]  # fly is never usable
    go = next(a for a in ground.actions if str(a.name) == "go")
    assert [(str(v), b) for v, b in go.pre] == [("door", True)]
    assert [str(e.variable) for e in go.effects] == ["far"]  # lit stays true
    assert [(str(v), b) for v, b in ground.goal] == [("far", True)]


@pytest.mark.slow
@pytest.mark.parametrize(
    "knob, value",
    [
        ("LAYERS_AFTER", 0.0),  # after the first solve
        ("LAYERS_AT_ONCE_ACTIONS", 1),
    ],
)  # before any solve
@settings(max_examples=50, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.booleans())
def test_plan_search_with_layers_started_early_finds_shortest_plans(knob, value, seed, conditional):
    """The layers start early (after the first solve, or with the search in a
    child process): their bounds and plans must agree with the solver's,
    whichever proves first."""
    spec = random_model(
        seed, far_goal=seed % 3 == 0, **dict(features(seed), conditional=conditional)
    )
    model = Model.from_string(spec.to_asp())
    saved = getattr(search_module, knob)
    setattr(search_module, knob, value)
    try:
        result = find_plan(model, max_horizon=20)
    finally:
        setattr(search_module, knob, saved)
    expected = spec.shortest_plan_length()
    if expected is None:
        assert result.status == "none", result
    else:
        assert result.status == "found", result
        assert len(result.plan) == expected and result.optimal
        assert spec.is_plan([str(a) for a in result.plan])


def test_models_with_events_get_explicit_layers():
    """The diagrams know no exogenous events: they refuse a model with events,
    and the layers beside plan search are then explicit ones of configurations
    (state, time), which prove the same kinds of claims (checked against the
    oracle above, as plan search with the layers started early)."""
    from ethasp.planning.engines.reachability import Reachability

    model = Model.from_string(
        "variable(a;b). action(go). eff(go,a,true). event(e). "
        "event_at(e,2). event_effect(e,1,b,true). "
        "event_condition(e,1,a,true). goal(b,true)."
    )
    ground = search_model(Atoms(model.planner))
    assert [str(event.name) for event in ground.events] == ["e"]
    with pytest.raises(ValueError, match="exogenous events"):
        Reachability(ground)
    status = run_layers(model)
    assert status.goal_layer == 1 and [str(a) for a in status.plan] == ["go"]


def test_layers_bound_restricted_searches_without_reading_plans():
    """With a restriction, the layers only give lower bounds (read_plan off)."""
    spec = random_model(11, max_variables=5, max_actions=5, far_goal=True)
    model = Model.from_string(spec.to_asp())
    if model.planner.is_fact("unreachable_goal"):
        pytest.skip("relaxed reachability answers this one")
    status = run_layers(model, read_plan=False)
    assert status.plan is None
    expected = spec.shortest_plan_length()
    if expected is not None:
        assert status.goal_layer == expected


def test_a_plan_from_the_layers_is_checked_by_its_trace():
    model = Model.from_string("variable(a). action(x). eff(x,a,true). goal(a,true).")
    status = layers_module.Status(
        bound=1, goal_layer=1, plan=(clingo.parse_term("x"), clingo.parse_term("x"))
    )
    plan = search_module._layers_plan(model.planner, status)  # valid: x x reaches a
    assert validate(model, plan).valid
    bad = layers_module.Status(bound=1, goal_layer=1, plan=(clingo.parse_term("y"),))
    with pytest.raises(RuntimeError):
        search_module._layers_plan(model.planner, bad)


def test_budget_until_stops_on_its_condition():
    flag = []
    budget = Budget(None).until(lambda: bool(flag))
    assert not budget.expired()
    flag.append(1)
    assert budget.expired()
    parent = Budget(None)
    child = parent.until(lambda: False).until(lambda: False)
    parent.cancel()
    assert child.expired()


@pytest.mark.slow
@settings(max_examples=80, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.booleans(), st.booleans(), st.booleans())
def test_bidirectional_layers_prove_the_shortest_length_and_read_a_shortest_plan(
    seed, conditional, derived, tokens
):
    """Forward layers and backward layers from the goal states (pre-images):
    where they first meet is the oracle's shortest length, the plan read off
    through both is valid and the least one, as forward layers read it, and
    `complete` only when no goal state is reachable (``tokens``: models with
    mutex groups, tests/test_groups.py)."""
    if tokens:
        spec = token_model(seed, conditional, derived)
    else:
        spec = random_model(seed, conditional=conditional, derived=derived, far_goal=seed % 2 == 1)
    model = Model.from_string(spec.to_asp())
    if model.planner.is_fact("unreachable_goal"):
        assert spec.shortest_plan_length() is None
    else:
        both = Layers(Atoms(model.planner), Budget(None), bidirectional=True).start()
        forward = Layers(Atoms(model.planner), Budget(None), bidirectional=False).start()
        try:
            status = finished(both)
            check_against_oracle(spec, status, model)
            assert status.plan == finished(forward).plan
        finally:
            both.stop()
            forward.stop()


@pytest.mark.parametrize("seed", [5, 8, 13, 21, 34, 55, 89, 144])
def test_plain_search_solves_with_two_threads_once_the_layers_give_up(seed, monkeypatch):
    """Layers that give up leave their core to a second solver thread: the
    search still proves shortest plans, and the grounding goes back to one
    thread (later searches on it answer the same every time)."""
    if not layers_module.can_fork():
        pytest.skip("no child processes here")
    spec = random_model(seed, max_variables=6, max_actions=6, far_goal=True)
    model = Model.from_string(spec.to_asp())
    planner = model.planner
    if planner.is_fact("unreachable_goal"):
        pytest.skip("relaxed reachability answers this one")
    original = Layers.__init__

    def giving_up(self, *args, **kwargs):  # a node limit of 0: they give up at once
        original(self, *args, **{**kwargs, "node_limit": 0})

    counts = []
    threads = type(planner).threads
    monkeypatch.setattr(Layers, "__init__", giving_up)
    monkeypatch.setattr(search_module, "LAYERS_AT_ONCE_ACTIONS", 0)  # waited for at the start
    # ... until they report (however busy the machine: they give up at once)
    monkeypatch.setattr(search_module, "HEAD_START", 60.0)
    monkeypatch.setattr(search_module, "_cores", lambda: 2)
    monkeypatch.setattr(
        type(planner), "threads", lambda self, count: (counts.append(count), threads(self, count))
    )
    result = find_plan(model, max_horizon=20)
    expected = spec.shortest_plan_length()
    if expected is None:
        assert result.status == "none", result
    else:
        assert result.status == "found" and result.optimal, result
        # the least shortest plan, found with one thread after the portfolio's refutations
        assert [str(a) for a in result.plan] == spec.least_shortest_plan()
        assert len(result.plan) == expected
    assert counts[0] == 2 or result.horizon == 0  # the layers gave up first
    assert counts[-1] == 1 and planner._threads == 1
    assert str(planner.ctl.configuration.solve.parallel_mode).startswith("1")
