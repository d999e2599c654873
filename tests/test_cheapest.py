"""The engines for cheapest plans (ethasp.planning.engines.cheapest: explicit
uniform-cost search, and ethasp.planning.engines.cost_layers: symbolic), each
alone against the brute-force oracle (tests/oracle.py) on random models with
action costs: the cost of the plan each proposes is the least (and the plan
is a plan), "complete" means no plan, and every cost bound it tells holds."""

from __future__ import annotations

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import features, random_model

from ethasp import Model, Plan
from ethasp.planning.engines.cheapest import CostAtoms, cheapest_plan, race
from ethasp.planning.engines.cost_layers import CostLayers
from ethasp.planning.engines.explicit import Events
from ethasp.planning.engines.layers import search_model
from ethasp.planning.engines.task import Task

SEEDS = st.integers(min_value=0, max_value=10**9)


def _findings(search) -> tuple[list[int], dict]:
    bounds, last = [], {}
    for changes in search:
        if "cost_bound" in changes:
            bounds.append(changes["cost_bound"])
        if changes and "cost_bound" not in changes:
            last = changes
    return bounds, last


def _check(spec, model: Model, bounds: list[int], last: dict) -> None:
    expected = spec.cheapest_plan_cost()
    assert all(bound <= (expected if expected is not None else bound) for bound in bounds)
    if expected is None:
        assert last == {"complete": True}, (last, spec)
        return
    assert last["cost"] == expected, (last, expected, spec)
    plan = [str(action) for action in last["plan"]]
    assert spec.is_plan(plan) and spec.plan_cost(plan) == expected, (plan, spec)
    assert model.planner.trace(Plan(tuple(last["plan"]))).get("plan", 0)


def _setup(seed: int, events: bool = True):
    chosen = features(seed)
    if not events:
        chosen["events"] = False
    spec = random_model(seed, max_variables=5, max_actions=6, costs=True, **chosen)
    model = Model.from_string(spec.to_asp())
    model.planner.prepare()
    # (As the layers, the engines serve searches where relaxed reachability
    # found the goal reachable: the search model leaves out the goal literals
    # on variables that never change.)
    assume(not model.planner.is_fact("unreachable_goal"))
    atoms = CostAtoms(model.planner)
    return spec, model, atoms, search_model(atoms)


@settings(max_examples=80, deadline=None)
@given(SEEDS)
def test_explicit_uniform_cost_search_agrees_with_the_oracle(seed):
    spec, model, atoms, ground = _setup(seed)
    task = Task(ground)
    bounds, last = _findings(
        cheapest_plan(task, Events(ground.events, task.index), atoms.costs, None)
    )
    _check(spec, model, bounds, last)


@settings(max_examples=80, deadline=None)
@given(SEEDS)
def test_symbolic_uniform_cost_search_agrees_with_the_oracle(seed):
    spec, model, atoms, ground = _setup(seed, events=False)
    bounds, last = _findings(CostLayers(ground, atoms.costs).search(None))
    _check(spec, model, bounds, last)


def test_a_race_publishes_the_first_answer_and_the_greatest_bound():
    published = []

    def slow():
        yield {"cost_bound": 1}
        yield {}
        yield {"cost_bound": 4}
        yield {"plan": ("a",), "cost": 4}

    def stops():
        yield {"cost_bound": 2}
        yield {"stopped": "a limit"}

    race([slow(), stops()], lambda **changes: published.append(changes))
    assert published == [
        {"cost_bound": 1},
        {"cost_bound": 2},
        {"cost_bound": 4},
        {"plan": ("a",), "cost": 4},
    ]
    published.clear()
    race([stops()], lambda **changes: published.append(changes))
    assert published[-1] == {"stopped": "a limit"}


@pytest.mark.parametrize("limit", [1, 3])
def test_the_explicit_search_stops_at_its_limit(limit):
    model = Model.from_string(
        "variable(v(1..6)). action(set(I)) :- variable(v(I)). eff(set(I),v(I),true) :- "
        "variable(v(I)). goal(v(I),true) :- variable(v(I)). cost(set(1),1)."
    )
    model.planner.prepare()
    atoms = CostAtoms(model.planner)
    ground = search_model(atoms)
    task = Task(ground)
    _, last = _findings(
        cheapest_plan(task, Events(ground.events, task.index), atoms.costs, None, limit=limit)
    )
    assert "configurations" in last["stopped"]
