"""The exact reachability engine (ethasp/planning/engines/reachability.py) against
explicit breadth-first search (tests/oracle.py): layers, best states, goal
distances and paths, on random models with conditional effects and derived
variables; and the ground model it reads from the planner."""

from __future__ import annotations

import clingo
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from oracle import random_model
from test_groups import weighted_token_model

from ethasp import Model
from ethasp.planning.engines.reachability import Reachability, from_atoms

S = clingo.Function


def ground(spec):
    """The engine's model of an oracle model, by hand (derived variables too)."""
    derived = spec.derived
    conditional = spec.ceff
    ceff, cpre = [], []
    for action, effects in conditional.items():
        for key, conditions, sets in effects:
            ceff += [(S(action), S(key), S(v), b) for v, b in sets.items()]
            cpre += [(S(action), S(key), S(v), b) for v, b in conditions.items()]
    axioms = [(S(d), clingo.Number(k)) for d, bodies in derived.items() for k in range(len(bodies))]
    axiom_pre = [
        (S(d), clingo.Number(k), S(v), b)
        for d, bodies in derived.items()
        for k, body in enumerate(bodies)
        for v, b in body.items()
    ]
    return from_atoms(
        [S(v) for v in spec.variables],
        [S(a) for a in spec.actions],
        [(S(a), S(v), b) for a in spec.actions for v, b in spec.pre[a].items()],
        [(S(a), S(v), b) for a in spec.actions for v, b in spec.eff[a].items()],
        ceff,
        cpre,
        [S(v) for v in spec.init],
        [(S(v), b) for v, b in spec.goal.items()],
        {(S(v), b): u for (v, b), u in spec.fact_utility.items()},
        axiom_pre,
        axioms,
        [S(d) for d in derived],
    )


def spec_of(seed: int):
    return random_model(
        seed, max_variables=6, max_actions=6, conditional=seed % 2 == 0, derived=seed % 3 == 0
    )


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(st.integers(min_value=0, max_value=10**9))
def test_layers_best_states_and_paths_agree_with_breadth_first_search(seed):
    spec = spec_of(seed)
    r = Reachability(ground(spec))
    assert r.run()
    distances = spec.distances()
    for k, layer in enumerate(r.layers):
        expected = {state for state, d in distances.items() if d == k}
        found = {frozenset(str(v) for v in s) for s in _states(r, layer)}
        assert found == expected, (k, spec)
    best = r.best_of(r.reached)
    assert best.utility == spec.best_reachable_utility()
    state = frozenset(str(v) for v in best.state)
    assert spec.state_utility(state) == best.utility and distances[state] == best.layer
    first = r.first_layer(r.goal())
    assert first == spec.shortest_plan_length()
    if first is not None:
        target = r.best_in_layer(first, r.goal())
        plan = [str(a) for a in r.path_to(target.state, first)]
        assert spec.is_plan(plan) and len(plan) == first


def test_the_planner_reads_the_ground_model_from_the_encodings():
    model = Model.from_string("""
        variable(a;b). action(go). pre(go,a,false). eff(go,a,true).
        ceff(go,k,b,true). cpre(go,k,a,false).
        derived(d). axiom(d,1). axiom_pre(d,1,a,true).
        init(b). goal(d,true). utility(b,true,2). utility(a,true,-1).""")
    ground_model = model.planner.ground_model()
    assert [str(v) for v in ground_model.variables] == ["a", "b"]
    (action,) = ground_model.actions
    assert {(str(e.variable), e.value, e.condition) for e in action.effects} == {
        ("a", True, ()),
        ("b", True, ((S("a"), False),)),
    }
    assert ground_model.axioms == {S("d"): [((S("a"), True),)]}
    assert {key: u for key, u in ground_model.weights.items() if u} == {
        (S("b"), True): 2,
        (S("a"), True): -1,
    }
    r = model.planner.reachability()
    assert r.run() and len(r.layers) == 2 and r.first_layer(r.goal()) == 1


def test_an_action_without_effects_prints_nothing(caplog):
    """An action that writes no variable has an empty renaming; the diagrams'
    package logs a warning (on standard error, where logging is not set up)
    when asked for one, so it never is (the warning showed in some answers
    and not in others, as engines raced)."""
    model = Model.from_string("""
        variable(a). action(abide;go). eff(go,a,true). goal(a,true).""")
    r = model.planner.reachability()
    assert r.run() and r.first_layer(r.goal()) == 1
    assert [str(a) for a in r.least_path(r.goal(), 1)] == ["go"]
    (goal_state,) = r.states(r.goal() & r.layers[1])
    assert [str(a) for a in r.path_to(goal_state, 1)] == ["go"]  # (abide tried first)
    r.start_backward(r.goal())
    while not r.back_complete:
        assert r.expand_backward()
    assert [record.getMessage() for record in caplog.records] == []


def test_a_budget_stops_the_engine_without_a_claim():
    from ethasp.planning.budget import Budget

    spec = random_model(7, max_variables=6, max_actions=6)
    r = Reachability(ground(spec))
    cancelled = Budget()
    cancelled.cancel()
    assert not r.expand(cancelled) and not r.complete and r.stopped


def test_a_transition_relation_beyond_the_node_limit_is_not_built():
    """A relation that grows beyond the node limit while it is built stops the
    engine before its first layer (some orders of the variables make it grow
    beyond any use), and the searches go on without it."""
    spec = random_model(11, max_variables=6, max_actions=6)
    small = Reachability(ground(spec), node_limit=2)
    assert not small.expand() and small.unbuilt and "diagram nodes" in small.unbuilt
    assert small.stopped == small.unbuilt and len(small.layers) == 1
    assert small.closed() is None and not small.complete
    full = Reachability(ground(spec))
    assert full.run() and not full.unbuilt


class _After:
    """A budget that runs out after ``checks`` looks at it (then for good)."""

    def __init__(self, checks: int):
        self.checks = checks

    def expired(self) -> bool:
        self.checks -= 1
        return self.checks < 0

    def why_stopped(self) -> str:
        return "the time limit was reached"


@pytest.mark.parametrize("checks", [0, 1, 3])
def test_a_budget_stops_the_transition_relation_while_it_is_built(checks):
    """The relations are built by the first search, under its budget (which
    is looked at between two actions): a budget that runs out then stops the
    search without a claim, and a later search goes on from there to the
    same layers as an engine built at once."""
    spec = random_model(3, max_variables=6, max_actions=6)
    assert len(spec.actions) > 3
    r = Reachability(ground(spec))
    assert not r.expand(_After(checks)) and not r.complete and len(r.layers) == 1
    assert "while the transition relation was built" in r.stopped
    assert r.run()
    fresh = Reachability(ground(spec))
    assert fresh.run()
    assert [_states(r, layer) for layer in r.layers] == [
        _states(fresh, layer) for layer in fresh.layers
    ]


def _states(r: Reachability, layer) -> set[frozenset]:
    """The states of a layer, each as its true variables (each once)."""
    states = list(r.states(layer))
    assert len(set(states)) == len(states)
    return set(states)


@settings(max_examples=60, deadline=None)
@given(
    st.integers(min_value=0, max_value=10**9),
    st.sampled_from([1, 2, 16]),
    st.sampled_from([0, 5_000]),
)
def test_every_state_has_a_shortest_path_and_each_layer_its_best(seed, cluster, merge):
    """Paths to every reachable state (actions in clusters of 1, 2 or 16
    written variables, merged again into joint relations or not, so that a
    predecessor is looked for cluster by cluster) and the best state of each
    layer and each prefix, asked one after another (the engine remembers
    utilities between queries), against the oracle."""
    import ethasp.planning.engines.reachability as reachability

    spec = spec_of(seed)
    saved = reachability.CLUSTER_VARIABLES, reachability.MERGE_NODES
    reachability.CLUSTER_VARIABLES, reachability.MERGE_NODES = cluster, merge
    try:
        r = Reachability(ground(spec))
    finally:
        reachability.CLUSTER_VARIABLES, reachability.MERGE_NODES = saved
    assert r.run()
    distances = spec.distances()
    for k, layer in enumerate(r.layers):
        states = [state for state, d in distances.items() if d == k]
        best = r.best_in_layer(k)
        assert best.utility == max(spec.state_utility(s) for s in states)
        within = r.best_of(r.prefix(k))
        assert within.utility == max(spec.state_utility(s) for s, d in distances.items() if d <= k)
        for state in _states(r, layer):
            plan = [str(a) for a in r.path_to(state, k)]
            assert len(plan) == k
            assert spec.run(plan) == frozenset(str(v) for v in state), (plan, state)


def _reached(r: Reachability, sets) -> list[set[frozenset]]:
    """The reachable states of each set, each as the text of its true variables
    (up to the last set that has one)."""
    found = [
        {frozenset(str(v) for v in s) for s in _states(r, layer & r.reached)} for layer in sets
    ]
    while found and not found[-1]:
        found.pop()
    return found


@settings(max_examples=120, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.booleans(), st.booleans())
def test_groups_in_binary_agree_with_a_bit_per_variable_and_breadth_first_search(
    seed, conditional, derived
):
    """Mutex groups as finite-domain variables in binary: the same layers
    (against explicit breadth-first search), best states, goal distances,
    backward layers (their reachable states) and least paths as with a
    diagram variable per variable."""
    spec = weighted_token_model(seed, conditional, derived)
    ground_model = Model.from_string(spec.to_asp()).planner.ground_model()
    grouped, plain = Reachability(ground_model), Reachability(ground_model, grouped=False)
    assert all(len(m) == 1 for m in plain.layout.units)
    assert grouped.run() and plain.run()
    distances = spec.distances()
    assert len(grouped.layers) == len(plain.layers) == max(distances.values()) + 1
    for k, layer in enumerate(grouped.layers):
        expected = {state for state, d in distances.items() if d == k}
        assert {frozenset(str(v) for v in s) for s in _states(grouped, layer)} == expected
    best = grouped.best_of(grouped.reached)
    assert best.utility == plain.best_of(plain.reached).utility == spec.best_reachable_utility()
    assert spec.state_utility(frozenset(str(v) for v in best.state)) == best.utility
    first = grouped.first_layer(grouped.goal())
    assert first == plain.first_layer(plain.goal()) == spec.shortest_plan_length()
    grouped.start_backward(grouped.goal())
    plain.start_backward(plain.goal())
    while not (grouped.back_complete and plain.back_complete):
        assert grouped.expand_backward() and plain.expand_backward()
    assert _reached(grouped, grouped.back_layers) == _reached(plain, plain.back_layers)
    if first is not None:
        least = grouped.least_path(grouped.goal(), first)
        assert least == plain.least_path(plain.goal(), first)
        assert spec.is_plan([str(a) for a in least]) and len(least) == first
        # Read off through both directions, wherever they meet: the same path.
        for r in (grouped, plain):
            for forward in range(first + 1):
                assert r.least_path_meeting(forward, first - forward) == least
        target = grouped.best_in_layer(first, grouped.goal())
        path = [str(a) for a in grouped.path_to(target.state, first)]
        assert spec.is_plan(path) and len(path) == first


def test_the_token_models_give_groups_of_several_bits():
    """(The property test above meets groups: most token models have one.)"""
    widths = []
    for seed in range(20):
        spec = weighted_token_model(seed, False, False)
        r = Reachability(Model.from_string(spec.to_asp()).planner.ground_model())
        widths += [
            len(bits) for unit, bits in enumerate(r.layout.bits) if len(r.layout.units[unit]) > 1
        ]
    assert len(widths) >= 10 and max(widths) >= 2


TOKEN = """
    variable(at(t,p0);at(t,p1);at(t,p2);v). action(go(p0,p1);go(p1,p2)).
    pre(go(A,B),at(t,A),true) :- action(go(A,B)).
    eff(go(A,B),at(t,A),false) :- action(go(A,B)).
    eff(go(A,B),at(t,B),true) :- action(go(A,B)).
    init(at(t,p0)). goal(at(t,p2),true).
"""


def _units(r: Reachability) -> list[list[str]]:
    return sorted([str(v) for v in members] for members in r.layout.units)


def test_a_group_is_one_variable_in_binary_and_a_weighted_member_a_bit_of_its_own():
    r = Reachability(Model.from_string(TOKEN).planner.ground_model())
    assert _units(r) == [["at(t,p0)", "at(t,p1)", "at(t,p2)"], ["v"]]
    assert r.layout.width == 3  # two bits for the codes 0-3, one for v
    assert r.run() and r.first_layer(r.goal()) == 2
    assert [str(a) for a in r.least_path(r.goal(), 2)] == ["go(p0,p1)", "go(p1,p2)"]
    weighted = Reachability(
        Model.from_string(TOKEN + "utility(at(t,p1),true,5).").planner.ground_model()
    )
    assert _units(weighted) == [["at(t,p0)", "at(t,p2)"], ["at(t,p1)"], ["v"]]
    assert weighted.run() and weighted.first_layer(weighted.goal()) == 2
    best = weighted.best_of(weighted.reached)
    assert best.utility == 5 and {str(v) for v in best.state} == {"at(t,p1)"}


@settings(max_examples=60, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.booleans())
def test_clusters_split_down_to_single_actions_give_the_same_layers_and_paths(seed, tokens):
    """A cluster whose relation outgrows CLUSTER_NODES is split in two, again
    and again (here every cluster, down to one action each): the same layers
    and least paths as with whole clusters."""
    import ethasp.planning.engines.reachability as reachability_module

    spec = weighted_token_model(seed, seed % 2 == 0, seed % 3 == 0) if tokens else spec_of(seed)
    ground_model = Model.from_string(spec.to_asp()).planner.ground_model()
    whole = Reachability(ground_model)
    saved = reachability_module.CLUSTER_NODES, reachability_module.MERGE_NODES
    reachability_module.CLUSTER_NODES = reachability_module.MERGE_NODES = -1
    try:
        split = Reachability(ground_model)
        assert split.run() and whole.run()
    finally:
        reachability_module.CLUSTER_NODES, reachability_module.MERGE_NODES = saved
    assert len(split._groups) == len(ground_model.actions)  # one action a cluster
    assert [_states(split, layer) for layer in split.layers] == [
        _states(whole, layer) for layer in whole.layers
    ]
    first = whole.first_layer(whole.goal())
    assert split.first_layer(split.goal()) == first
    if first is not None:
        assert split.least_path(split.goal(), first) == whole.least_path(whole.goal(), first)
