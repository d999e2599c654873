"""The canonical order of independent consecutive actions (encodings/planning/
canonical.lp): it removes plans in other orders, never every plan of a length;
against the oracle, and switched off where a search needs every order."""

import pytest
from conftest import answer_sets
from hypothesis import given, settings
from hypothesis import strategies as st
from oracle import features, random_model

from ethasp import Model
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import Setting
from ethasp.planning.plan import Plan
from ethasp.planning.search import plans_of

FILES = ["planning/plan.lp", "planning/canonical.lp"]
TWO = "variable(p;q). action(a;b). eff(a,p,true). eff(b,q,true). goal(p,true). goal(q,true)."


def plans(model: str, horizon: int, canonical: bool) -> set[tuple[str, ...]]:
    program = model + (" require(canonical)." if canonical else "")
    result = set()
    for answer in answer_sets(FILES, program, arguments=("0", "-c", f"horizon={horizon}")):
        steps = sorted(
            (int(a.split(",")[-1].rstrip(")")), a[len("occurs(") : a.rindex(",")])
            for a in answer
            if a.startswith("occurs(")
        )
        result.add(tuple(name for _, name in steps))
    return result


def test_independent_actions_come_in_the_order_of_their_terms():
    assert plans(TWO, 2, False) == {("a", "b"), ("b", "a")}
    assert plans(TWO, 2, True) == {("a", "b")}


@pytest.mark.parametrize(
    "extra",
    [
        "pre(b,p,true).",  # b reads what a writes
        "eff(b,p,false).",  # both write p
        "pre(a,q,false).",  # a reads what b writes
    ],
)
def test_dependent_actions_keep_both_orders_where_both_are_plans(extra):
    model = TWO + " " + extra
    assert plans(model, 2, True) == plans(model, 2, False)


def test_conditional_effects_and_derived_preconditions_are_never_independent():
    conditional = TWO + " ceff(a,k,r,true). cpre(a,k,q,true). variable(r)."
    assert plans(conditional, 2, True) == plans(conditional, 2, False)
    derived = TWO + " derived(d). axiom(d,k). axiom_pre(d,k,q,false). pre(a,d,true)."
    assert plans(derived, 2, True) == plans(derived, 2, False) == {("a", "b")}


def first_plan(model: Model, canonical: bool, max_horizon: int = 14):
    planner = model.planner
    if canonical:
        planner.use_canonical()
    for horizon in range(max_horizon + 1):
        outcome = planner.solve(horizon, Setting(canonical=canonical), Budget(None))
        if outcome.satisfiable:
            return plans_of([outcome.symbols])[0]
    return None


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.booleans(), st.booleans())
def test_canonical_search_finds_plans_of_the_shortest_length(seed, conditional, derived):
    spec = random_model(
        seed,
        max_variables=5,
        max_actions=6,
        conditional=conditional,
        derived=derived,
        far_goal=seed % 2 == 0,
        events=features(seed)["events"],
    )  # then no canonical order
    expected = spec.shortest_plan_length()
    plan = first_plan(Model.from_string(spec.to_asp()), canonical=True)
    if expected is None:
        assert plan is None
    elif expected <= 14:
        assert plan is not None and len(plan) == expected
        assert spec.is_plan([str(a) for a in plan])


def test_loop_free_check_and_other_settings_ignore_the_order():
    """Paths compare the states in between: the order is off for them, and a
    setting without ``canonical`` keeps every order."""
    model = Model.from_string(TWO)
    planner = model.planner
    assert planner.use_canonical()
    outcome = planner.solve(2, Setting(), Budget(None), models=0)
    found = {tuple(str(a) for a in plan) for plan in plans_of(outcome.models)}
    assert found == {("a", "b"), ("b", "a")}
    outcome = planner.solve(2, Setting(canonical=True), Budget(None), models=0)
    assert {tuple(str(a) for a in p) for p in plans_of(outcome.models)} == {("a", "b")}
    assert planner.simple_path_exists(2, Setting(canonical=True), Budget(None))
    assert Plan.parse("a b") in plans_of(outcome.models)
