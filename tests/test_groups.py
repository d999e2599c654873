"""Mutex groups (ethasp.planning.engines.groups) and the finite-domain
variables that Fast Downward's task makes of them (ethasp.planning.engines.sas):
every group found holds at most one true variable in every reachable state
(brute force), and Fast Downward on the task with groups finds shortest plans
and "none" exactly as the oracle says, on random models with tokens that move
(the shape of groups) and noise that may break them."""

from __future__ import annotations

import random

import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from oracle import RandomModel, _add_conditional_effects, _add_derived, answered, assert_shortest

from ethasp import Model, find_plan
from ethasp.planning import systems
from ethasp.planning.engines import Unhandled, groups, sas
from ethasp.planning.engines.layers import Atoms, search_model

SEEDS = st.integers(min_value=0, max_value=10**9)

installed = pytest.mark.skipif(
    not systems.installed(), reason="Fast Downward is not installed (the planners extra)"
)


def token_model(seed: int, conditional: bool = False, derived: bool = False) -> RandomModel:
    """Tokens ``t0``, ``t1`` at places (``at(tK,pI)``), a holder
    (``held(tK)``) and plain variables; actions that move a token (need it at
    one place, make it false there and true at another), pick it up and put it
    down, and noise: actions with random preconditions and effects on every
    variable, some of which add a token's place without moving it, delete one
    without needing it, or need one false (each breaks a group, or keeps its
    variable out of the task's group)."""
    rng = random.Random(seed)
    tokens = [f"t{k}" for k in range(rng.randint(1, 2))]
    places = [f"p{i}" for i in range(rng.randint(2, 3))]
    plain = [f"v{i}" for i in range(rng.randint(0, 2))]
    located = [f"at({t},{p})" for t in tokens for p in places]
    held = [f"held({t})" for t in tokens]
    variables = located + held + plain
    actions: list[str] = []
    pre: dict[str, dict[str, bool]] = {}
    eff: dict[str, dict[str, bool]] = {}

    def add(conditions: dict[str, bool], effects: dict[str, bool]) -> None:
        name = f"a{len(actions)}"
        actions.append(name)
        pre[name] = dict(conditions)
        eff[name] = dict(effects)
        for v in plain:  # a plain condition or effect now and then
            if rng.random() < 0.25:
                pre[name].setdefault(v, rng.random() < 0.5)
            if rng.random() < 0.2:
                eff[name].setdefault(v, rng.random() < 0.5)

    for t in tokens:
        for _ in range(rng.randint(1, 4)):
            a, b = rng.sample(places, 2)
            add({f"at({t},{a})": True}, {f"at({t},{a})": False, f"at({t},{b})": True})
        if rng.random() < 0.7:
            p = rng.choice(places)
            add({f"at({t},{p})": True}, {f"at({t},{p})": False, f"held({t})": True})
            q = rng.choice(places)
            add({f"held({t})": True}, {f"held({t})": False, f"at({t},{q})": True})
    for _ in range(rng.randint(0, 3)):  # noise
        conditions = {v: rng.random() < 0.5 for v in variables if rng.random() < 0.2}
        effects = {v: rng.random() < 0.5 for v in variables if rng.random() < 0.2}
        add(conditions, effects or {rng.choice(variables): rng.random() < 0.5})
    init = set()
    for t in tokens:
        init.add(f"at({t},{rng.choice(places)})")
        if rng.random() < 0.1:  # a second place: no group for this token
            init.add(f"at({t},{rng.choice(places)})")
    init |= {v for v in plain if rng.random() < 0.4}
    goal = {v: rng.random() < 0.8 for v in variables if rng.random() < 0.3}
    if not goal:
        goal = {rng.choice(located): True}
    spec = RandomModel(variables, actions, pre, eff, frozenset(init), goal)
    if derived:  # derived variables that preconditions and the goal read
        _add_derived(spec, rng)
    if conditional:  # conditional effects, which may make a member true
        _add_conditional_effects(spec, rng)
    return spec


def weighted_token_model(seed: int, conditional: bool = False, derived: bool = False):
    """A token model with utilities on some facts (members of groups among
    them, which the diagrams keep out of their groups)."""
    spec = token_model(seed, conditional, derived)
    rng = random.Random(seed)
    spec.fact_utility = {
        (v, rng.random() < 0.7): rng.randint(-3, 3) for v in spec.variables if rng.random() < 0.3
    }
    return spec


def search_model_of(spec: RandomModel):
    return search_model(Atoms(Model.from_string(spec.to_asp()).planner))


@settings(max_examples=150, deadline=None)
@given(SEEDS, st.booleans(), st.booleans())
def test_every_group_holds_one_true_variable_at_most_in_every_reachable_state(
    seed, conditional, derived
):
    spec = token_model(seed, conditional, derived)
    found = groups.groups(search_model_of(spec))
    members = [{str(v) for v in group} for group in found]
    assert all(len(group) > 1 for group in members)
    assert sum(len(group) for group in members) == len(set().union(*members)), "disjoint"
    for state in spec.distances():
        for group in members:
            assert len(group & state) <= 1, (group, sorted(state), spec)


def test_tokens_that_move_make_groups_and_the_task_one_variable_of_each():
    spec = RandomModel(
        ["at(t,p0)", "at(t,p1)", "at(t,p2)", "held(t)", "v"],
        ["a0", "a1", "a2", "a3"],
        {
            "a0": {"at(t,p0)": True},
            "a1": {"at(t,p1)": True},
            "a2": {"at(t,p2)": True},
            "a3": {"held(t)": True},
        },
        {
            "a0": {"at(t,p0)": False, "at(t,p1)": True},
            "a1": {"at(t,p1)": False, "at(t,p2)": True},
            "a2": {"at(t,p2)": False, "held(t)": True},
            "a3": {"held(t)": False, "at(t,p0)": True, "v": True},
        },
        frozenset({"at(t,p0)"}),
        {"held(t)": True, "v": True},
    )
    model = search_model_of(spec)
    found = groups.groups(model)
    assert [[str(v) for v in group] for group in found] == [
        ["at(t,p0)", "at(t,p1)", "at(t,p2)", "held(t)"]
    ]
    assert groups.at_most_one(model, found[0])
    text = sas.task(model).text
    # v (two values) and the group (four members and "none")
    assert text.count("begin_variable") == 2
    assert "\n5\nAtom v0(m0)" in text
    assert "begin_variable" in sas.task(model, grouped=False).text
    assert sas.task(model, grouped=False).text.count("begin_variable") == 5


def test_an_action_that_adds_without_moving_breaks_the_group():
    base = "variable(at(t,p0);at(t,p1)). init(at(t,p0)). action(go;put). goal(at(t,p1),true).\n"
    moving = "pre(go,at(t,p0),true). eff(go,at(t,p0),false). eff(go,at(t,p1),true).\n"
    model = search_model(
        Atoms(Model.from_string(base + moving + "eff(put,at(t,p1),true).").planner)
    )
    assert groups.groups(model) == []
    members = list(model.variables)
    assert not groups.at_most_one(model, members)
    # put needs the token at p0 and moves it: a group again
    model = search_model(
        Atoms(
            Model.from_string(
                base
                + moving
                + "pre(put,at(t,p0),true). eff(put,at(t,p0),false). eff(put,at(t,p1),true)."
            ).planner
        )
    )
    assert [len(group) for group in groups.groups(model)] == [2]


def test_a_member_read_false_or_deleted_without_being_needed_leaves_the_tasks_group():
    moves = (
        "variable(at(t,p0);at(t,p1);at(t,p2)). init(at(t,p0)). action(a;b;c). "
        "pre(a,at(t,p0),true). eff(a,at(t,p0),false). eff(a,at(t,p1),true). "
        "pre(b,at(t,p1),true). eff(b,at(t,p1),false). eff(b,at(t,p2),true). "
        "goal(at(t,p2),true).\n"
    )
    plain = search_model(Atoms(Model.from_string(moves + "eff(c,at(t,p0),false).").planner))
    assert [len(group) for group in groups.groups(plain)] == [3]  # deleting keeps it
    # c deletes at(t,p0) without needing it: at(t,p0) has its own variable
    assert sas.task(plain).text.count("begin_variable") == 2
    # c needs at(t,p1) false: at(t,p1) has its own variable, the others a group
    negated = search_model(
        Atoms(
            Model.from_string(
                moves + "pre(c,at(t,p1),false). pre(c,at(t,p2),true). eff(c,at(t,p2),false)."
            ).planner
        )
    )
    assert [len(group) for group in groups.groups(negated)] == [3]
    text = sas.task(negated).text
    assert text.count("begin_variable") == 2 and "\n3\nAtom v0(m0)" in text


def test_an_action_that_changes_nothing_in_the_task_is_no_operator_of_it():
    """c needs the token at p1 and makes it false at p2, where it is not then:
    without effects in the task, it is no operator (Fast Downward refuses
    operators without effects)."""
    model = search_model(
        Atoms(
            Model.from_string(
                "variable(at(t,p0);at(t,p1);at(t,p2)). init(at(t,p0)). action(a;b;c). "
                "pre(a,at(t,p0),true). eff(a,at(t,p0),false). eff(a,at(t,p1),true). "
                "pre(b,at(t,p1),true). eff(b,at(t,p1),false). eff(b,at(t,p2),true). "
                "pre(c,at(t,p1),true). eff(c,at(t,p2),false). goal(at(t,p2),true)."
            ).planner
        )
    )
    assert [len(group) for group in groups.groups(model)] == [3]
    text = sas.task(model).text
    assert text.count("begin_operator") == 2
    assert "\n0\n1\nend_operator" not in text  # (an operator of no effects)


def test_groups_refuse_events():
    model = Model.from_string(
        "variable(a;b). action(go). eff(go,a,true). goal(a,true). "
        "event(e). event_at(e,1). event_effect(e,1,b,true)."
    )
    with pytest.raises(Unhandled):
        groups.groups(model.planner.ground_model())


@installed
@pytest.mark.slow
@settings(max_examples=80, deadline=None)
@given(SEEDS, st.booleans())
@example(seed=999_999_999, conditional=False)  # an operator that changed nothing
def test_fast_downward_on_groups_agrees_with_the_oracle(seed, conditional):
    spec = token_model(seed, conditional)
    model = Model.from_string(spec.to_asp())
    model.planning_system = systems.FAST_DOWNWARD
    result = answered(lambda: find_plan(model, max_horizon=40))
    assert_shortest(result, spec)
