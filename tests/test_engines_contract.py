"""The engines' contract (ethasp.planning.engines): each engine declares the
model features it handles, and is used only on models whose features it
handles."""

from __future__ import annotations

import importlib
import pkgutil

import pytest

from ethasp import Model
from ethasp.planning import engines
from ethasp.planning.engines import reachability

ENGINES = [
    name
    for module in pkgutil.iter_modules(engines.__path__)
    if (name := module.name) != "task"  # what explicit and greedy search over
]

BASE = "variable(a;b). action(go). eff(go,a,true). goal(a,true).\n"
EVENT = "event(e). event_at(e,1). event_effect(e,1,b,true).\n"
CONDITIONAL = "ceff(go,1,b,true). cpre(go,1,a,false).\n"
DERIVED = "derived(d). axiom(d,1). axiom_pre(d,1,a,true).\n"


def test_every_engine_declares_its_features_and_the_contract_lists_it():
    assert set(ENGINES) == {
        "reachability",
        "explicit",
        "layers",
        "greedy",
        "best_state",
        "cheapest",
        "cost_layers",
    }
    for name in ENGINES:
        module = importlib.import_module(f"ethasp.planning.engines.{name}")
        assert module.FEATURES <= engines.ALL_FEATURES, name
        assert f"* ``{name}``" in engines.__doc__, name


def test_the_contract_says_what_reachability_handles():
    assert {engines.CONDITIONAL_EFFECTS, engines.DERIVED_VARIABLES} == reachability.FEATURES
    assert "Conditional effects and derived variables; no exogenous events." in engines.__doc__


@pytest.mark.parametrize(
    ("extra", "features"),
    [
        ("", set()),
        (EVENT, {engines.EVENTS}),
        (CONDITIONAL, {engines.CONDITIONAL_EFFECTS}),
        (DERIVED, {engines.DERIVED_VARIABLES}),
        (EVENT + CONDITIONAL + DERIVED, set(engines.ALL_FEATURES)),
    ],
)
def test_the_planner_reads_the_features_of_the_ground_model(extra, features):
    planner = Model.from_string(BASE + extra).planner
    assert planner.features == features
    assert planner.exact_reachability == (engines.EVENTS not in features)


def test_an_engine_refuses_a_model_it_does_not_handle():
    planner = Model.from_string(BASE + EVENT).planner
    assert not engines.handles(reachability.FEATURES, planner.features)
    with pytest.raises(RuntimeError, match="exogenous events"):
        planner.reachability()
    with pytest.raises(ValueError, match="exogenous events"):
        reachability.Reachability(planner.ground_model(), reachability.DEFAULT_NODE_LIMIT)


def test_features_of_a_model_whose_rules_give_them():
    # Features are read from the ground model, not the text: here an event is
    # due only through a rule.
    text = BASE + "event(e). step_of(1). event_at(e,T) :- step_of(T).\n"
    assert Model.from_string(text).planner.features == {engines.EVENTS}
