"""The engines' contract (ethasp.planning.engines): each engine declares the
model features it handles, refuses a model with any other, and the planner
asks before it uses one; a reachable state that an engine reports comes with
a plan that reaches it, checked by its trace."""

from __future__ import annotations

import importlib
import pkgutil
import random
from dataclasses import replace

import clingo
import pytest
from oracle import plan_through, random_model

import ethasp.planning.engines.layers as layers_module
import ethasp.planning.search as search_module
from ethasp import Model, Plan, find_plan, judge
from ethasp.planning import engines
from ethasp.planning.budget import Budget
from ethasp.planning.engines import (
    best_state,
    cheapest,
    cost_layers,
    downward,
    explicit,
    greedy,
    reachability,
    sas,
)
from ethasp.planning.engines.layers import Atoms, Layers, search_model
from ethasp.planning.engines.task import Task

ENGINES = [
    name
    for module in pkgutil.iter_modules(engines.__path__)
    # (task: what explicit and greedy search over; sas: what downward searches;
    # groups: the mutex groups that sas writes)
    if (name := module.name) not in ("task", "sas", "groups")
]

BASE = "variable(a;b). action(go). eff(go,a,true). goal(a,true).\n"
FEATURE_TEXT = {
    engines.EVENTS: "event(e). event_at(e,1). event_effect(e,1,b,true).\n",
    engines.CONDITIONAL_EFFECTS: "ceff(go,1,b,true). cpre(go,1,a,false).\n",
    engines.DERIVED_VARIABLES: "derived(d). axiom(d,1). axiom_pre(d,1,a,true).\n",
}
EVENT = FEATURE_TEXT[engines.EVENTS]
CONDITIONAL = FEATURE_TEXT[engines.CONDITIONAL_EFFECTS]
DERIVED = FEATURE_TEXT[engines.DERIVED_VARIABLES]


def module(name: str):
    return importlib.import_module(f"ethasp.planning.engines.{name}")


# -- each engine, started on a planner's model the way the package starts it ----------


def _reachability(planner) -> None:
    reachability.Reachability(planner.ground_model(), reachability.DEFAULT_NODE_LIMIT)


def _explicit(planner) -> None:
    ground = planner.ground_model()
    task = Task(ground)
    explicit.Configurations(task, explicit.Events(ground.events, task.index))


def _layers(planner) -> None:
    Layers(Atoms(planner), Budget(None)).start().stop()


def _greedy(planner) -> None:
    greedy.Greedy(Atoms(planner), Budget(None)).start().stop()


def _greedy_search(planner) -> None:
    greedy.greedy_plan(Task(search_model(Atoms(planner))))


def _best_state(planner) -> None:
    best_state.best_reachable(planner, Budget(None))


def _better_state(planner) -> None:
    best_state.better_state(planner, 0, Budget(None))


ENTRIES = {
    "reachability": [_reachability, lambda planner: planner.reachability()],
    "explicit": [_explicit],
    "layers": [_layers],
    "greedy": [_greedy, _greedy_search],
    "best_state": [_best_state, _better_state],
    "downward": [lambda planner: downward.compiled(search_model(Atoms(planner)))],
    "cheapest": [
        lambda planner: cheapest.Cheapest(cheapest.CostAtoms(planner), Budget(None)).start().stop()
    ],
    "cost_layers": [lambda planner: cost_layers.CostLayers(search_model(Atoms(planner)), {})],
}

UNHANDLED = [
    (name, feature)
    for name in ENGINES
    for feature in sorted(engines.ALL_FEATURES - module(name).FEATURES)
]


def test_every_engine_declares_its_features_and_the_contract_lists_it():
    assert set(ENGINES) == {
        *("reachability", "explicit", "layers", "greedy", "best_state", "downward"),
        *("cheapest", "cost_layers"),
    }
    assert set(ENTRIES) == set(ENGINES)
    for name in ENGINES:
        assert module(name).FEATURES <= engines.ALL_FEATURES, name
        assert f"* ``{name}``" in engines.__doc__, name


def test_the_contract_says_what_each_engine_handles():
    assert {engines.CONDITIONAL_EFFECTS, engines.DERIVED_VARIABLES} == reachability.FEATURES
    assert "Conditional effects and derived variables; no exogenous events." in engines.__doc__
    # Greedy search knows no events: the planner gives such models the layers.
    assert {engines.CONDITIONAL_EFFECTS, engines.DERIVED_VARIABLES} == greedy.FEATURES
    assert "Conditional effects and derived\n  variables; no exogenous events" in engines.__doc__
    for name in ("explicit", "layers", "best_state", "cheapest"):
        assert module(name).FEATURES == engines.ALL_FEATURES, name
    assert set(UNHANDLED) == {
        ("reachability", engines.EVENTS),
        ("greedy", engines.EVENTS),
        ("cost_layers", engines.EVENTS),
        ("downward", engines.EVENTS),
        ("downward", engines.DERIVED_VARIABLES),
    }


@pytest.mark.parametrize(("name", "feature"), UNHANDLED)
def test_every_engine_refuses_every_feature_it_does_not_handle(name, feature):
    planner = Model.from_string(BASE + FEATURE_TEXT[feature]).planner
    assert feature in planner.features and not planner.handles(module(name).FEATURES)
    for entry in ENTRIES[name]:
        with pytest.raises(engines.Unhandled, match=f"does not model {feature}"):
            entry(planner)


@pytest.mark.parametrize("name", sorted(ENTRIES))
@pytest.mark.parametrize("feature", sorted(engines.ALL_FEATURES))
def test_every_engine_would_refuse_any_feature(name, feature, monkeypatch):
    """Each engine reads its own ``FEATURES`` when it starts: declared without a
    feature, it refuses a model with it (so a declaration is never a comment)."""
    monkeypatch.setattr(module(name), "FEATURES", engines.ALL_FEATURES - {feature})
    planner = Model.from_string(BASE + FEATURE_TEXT[feature]).planner
    for entry in ENTRIES[name]:
        with pytest.raises(engines.Unhandled, match=f"does not model {feature}"):
            entry(planner)


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
    assert Atoms(planner).features == features
    assert engines.model_features(planner.ground_model()) == features
    assert planner.exact_reachability == (engines.EVENTS not in features)
    for name in ENGINES:
        assert planner.handles(module(name).FEATURES) == (features <= module(name).FEATURES)


def test_features_of_a_model_whose_rules_give_them():
    # Features are read from the ground model, not the text: here an event is
    # due only through a rule.
    text = BASE + "event(e). step_of(1). event_at(e,T) :- step_of(T).\n"
    assert Model.from_string(text).planner.features == {engines.EVENTS}


@pytest.mark.parametrize(("extra", "why"), [(EVENT, "exogenous events"), (DERIVED, "derived")])
def test_the_planners_task_refuses_what_it_does_not_write(extra, why):
    from ethasp.planning.budget import Budget
    from ethasp.planning.engines import downward
    from ethasp.planning.engines.layers import Atoms, search_model

    planner = Model.from_string(BASE + extra).planner
    planner.prepare(Budget(None))
    assert not engines.handles(downward.FEATURES, planner.features)
    with pytest.raises(sas.NotCompiled, match=why):
        sas.task(search_model(Atoms(planner)))


# -- the planner asks before it uses an engine ---------------------------------------


def _models_with_plans(count: int):
    """Random models with events, conditional effects and derived variables
    (and the same without the events), each with a plan to judge."""
    found = []
    for seed in range(1000):
        spec = random_model(
            seed, max_variables=4, max_actions=4, conditional=True, derived=True, events=True
        )
        plan = plan_through(spec, random.Random(seed), 2)
        if plan is None:
            continue
        for variant in (spec, replace(spec, events=[])):
            if variant.shortest_plan_length() and variant.is_plan(plan):
                found.append((variant, plan))
        if len(found) >= count:
            return found
    raise AssertionError("too few random models with plans")


@pytest.mark.parametrize("name", ["reachability", "explicit", "layers", "greedy"])
def test_the_planner_asks_before_it_uses_an_engine(name, monkeypatch):
    """With one engine declared to handle nothing, every search still answers
    right: the planner asked, and went without it (were it used, it would
    refuse and the search would fail).  The layers run in a thread here, so
    that they see the declaration too, and start with the search."""
    monkeypatch.setattr(module(name), "FEATURES", frozenset())
    monkeypatch.setattr(layers_module, "can_fork", lambda: False)
    monkeypatch.setattr(search_module, "LAYERS_AT_ONCE_ACTIONS", 0)
    monkeypatch.setattr(search_module, "LAYERS_AFTER", 0.0)
    for spec, plan in _models_with_plans(4):
        model = Model.from_string(spec.to_asp())
        shortest = find_plan(model, max_horizon=20)
        assert shortest.status == "found", shortest
        assert len(shortest.plan) == spec.shortest_plan_length()
        assert spec.is_plan([str(a) for a in shortest.plan])
        some = find_plan(model, satisficing=True, max_horizon=20)
        assert some.status == "found" and spec.is_plan([str(a) for a in some.plan])
        judgement = judge(
            model, Plan.parse(" ".join(plan)), ["utilitarianism"], budget=Budget(60)
        ).judgements[0]
        assert judgement.status == "proven", judgement
        assert judgement.permissible == spec.permissible(plan, "utilitarianism")


def test_without_an_engine_for_reachable_states_utilitarianism_is_bounded(monkeypatch):
    """The principles ask too: were best_state declared to handle none of a
    model's features, utilitarian verdicts and HPlans would answer bounded
    (a better reachable state may exist), and explanations go without a
    compared state, rather than fail."""
    from ethasp.principles.restriction import plan_with_principles
    from ethasp.reasons.reasons import judge as explain

    monkeypatch.setattr(best_state, "FEATURES", frozenset())
    model = Model.from_string(BASE + CONDITIONAL + "utility(b,true,1).")
    assert "conditional effects" in best_state.unhandled(model.planner)
    judgement = judge(model, Plan.parse("go"), ["utilitarianism"]).judgements[0]
    assert judgement.status == "bounded" and judgement.permissible
    assert "no engine here searches the reachable states" in judgement.proof
    hplan = plan_with_principles(model, ["utilitarianism"])
    assert hplan.status == "bounded" and hplan.plan is None
    assert explain(model, Plan.parse("go"), ["utilitarianism"]).judgements[0].status == "bounded"


# -- witnesses -------------------------------------------------------------------


def test_a_better_reachable_state_comes_with_the_better_plan():
    model = Model.load(["asp/trolley.lp"])
    judgement = judge(model, Plan.parse("refrain"), ["utilitarianism"]).judgements[0]
    assert not judgement.permissible and judgement.status == "proven"
    assert str(judgement.better_plan) == "pull"
    assert judgement.compared.plan == judgement.better_plan
    data = judgement.to_json()
    assert data["better_plan"] == ["pull"] and data["compared_with"]["plan"] == ["pull"]
    best = best_state.best_reachable(model.planner)
    assert best.plan is not None and best.to_json()["plan"] == ["pull"]


def test_a_state_whose_plan_the_encodings_refute_is_not_reported():
    model = Model.load(["asp/trolley.lp"])
    planner = model.planner
    pull = [clingo.Function("pull")]
    final = [(clingo.Function(v), v != "five_will_die") for v in ("five_will_die", "done")]
    final.append((clingo.Function("one_will_die"), True))
    state = best_state.witnessed(planner, final, 4, pull, "test")
    assert state.distance == 1 and str(state.plan) == "pull"
    with pytest.raises(RuntimeError, match="the encodings refute"):
        best_state.witnessed(planner, final, 5, pull, "test")  # not its utility
    with pytest.raises(RuntimeError, match="the encodings refute"):
        best_state.witnessed(planner, final, 4, [], "test")  # not its final state
    with pytest.raises(RuntimeError, match="the encodings refute"):
        best_state.witnessed(planner, final, 4, [clingo.Function("fly")], "test")  # no action
    gate = Model.from_string(BASE + "action(stop). pre(stop,a,true). eff(stop,b,true).").planner
    reached = [(clingo.Function("a"), False), (clingo.Function("b"), True)]
    with pytest.raises(RuntimeError, match="the encodings refute"):
        best_state.witnessed(gate, reached, 0, [clingo.Function("stop")], "test")  # inapplicable
