"""Faster plan search: the greedy forward search of any-plan search
(ethasp.planning.engines.greedy), the trace of a plan over the facts of its own
actions, and plans read from answer sets without the typed vocabulary;
against the oracle and on IPC instances (exact layers started early:
test_layers.py)."""

from pathlib import Path

import clingo
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from oracle import features, random_model
from test_layers import finished

from ethasp import Model, find_plan, validate
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import TRACE_ENCODINGS, occurrences
from ethasp.planning.engines.greedy import EXHAUSTED, Greedy, Task, greedy_plan
from ethasp.planning.engines.layers import Atoms, search_model
from ethasp.planning.plan import Plan

IPC = Path(__file__).resolve().parent / "data" / "ipc"


def task_of(model: Model) -> Task:
    return Task(search_model(Atoms(model.planner)))


# -- the greedy search against the oracle ----------------------------------------


@pytest.mark.slow
@settings(max_examples=120, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.booleans(), st.booleans())
def test_greedy_search_finds_a_plan_exactly_when_one_exists(seed, conditional, derived):
    """Greedy search prunes only relaxed dead ends and repeated states, so it
    finds a plan whenever one exists; every plan it proposes is a plan.  (It
    runs where the goal is relaxed reachable: the search model keeps the goal
    literals on variables that may change, relaxed reachability decides the
    others before any engine starts.)  Derived variables are computed in each
    state, and their relaxed axioms (true by an axiom, false once each axiom
    has a failed literal) must never make a state with a plan a dead end."""
    spec = random_model(
        seed,
        max_variables=5,
        max_actions=6,
        conditional=conditional,
        derived=derived,
        far_goal=seed % 2 == 0,
    )
    model = Model.from_string(spec.to_asp())
    if model.planner.is_fact("unreachable_goal"):
        assert spec.shortest_plan_length() is None  # no engine starts
    else:
        plan, why = greedy_plan(task_of(model))
        if spec.shortest_plan_length() is None:
            assert plan is None and why == EXHAUSTED
        else:
            assert plan is not None, why
            assert spec.is_plan([str(action) for action in plan])


def test_greedy_heuristic_is_zero_at_the_goal_and_none_at_relaxed_dead_ends():
    model = Model.from_string(
        "variable(a;b). action(go;stop). eff(go,a,true). "
        "pre(stop,a,true). eff(stop,b,true). goal(b,true)."
    )
    task = task_of(model)
    h, helpful = task.heuristic(task.init)
    assert h == 2 and [task.steps[i].name for i in helpful] == [clingo.Function("go")]
    goal = task.init | sum(1 << task.index[v] for v in task.variables)
    assert task.heuristic(goal)[0] == 0
    dead = Model.from_string(
        "variable(a;b). action(go). pre(go,a,true). eff(go,b,true). goal(b,true)."
    )
    # b is never relaxed reachable: relaxed reachability proves it, the search
    # of the encodings answers none before any engine starts.
    assert find_plan(dead).status == "none"


def test_greedy_heuristic_counts_what_makes_a_derived_variable_false():
    """go needs the derived blocked to be false; blocked holds while a does, so
    the relaxed plan must also clear a (a derived variable is not simply
    assumed false: that would make the estimate blind to such preconditions)."""
    model = Model.from_string(
        "variable(a;b). derived(blocked). axiom(blocked,1). "
        "axiom_pre(blocked,1,a,true). init(a). action(clear;go). "
        "eff(clear,a,false). pre(go,blocked,false). eff(go,b,true). "
        "goal(b,true)."
    )
    task = task_of(model)
    full = task.full(task.init)
    assert full & (1 << task.index[clingo.Function("blocked")])
    h, helpful = task.heuristic(full)
    assert h == 2 and [task.steps[i].name for i in helpful] == [clingo.Function("clear")]
    plan, _ = greedy_plan(task)
    assert [str(a) for a in plan] == ["clear", "go"]


def test_greedy_engine_in_a_child_process_proposes_a_plan():
    model = Model.load(
        [
            IPC / "depots-strips-automatic" / "domain.pddl",
            IPC / "depots-strips-automatic" / "p1.pddl",
        ]
    )
    planner = model.planner
    planner.is_fact("unreachable_goal")  # the searches grounded
    engine = Greedy(lambda: Atoms(planner), Budget(None)).start()
    try:
        status = finished(engine)
    finally:
        engine.stop()
    assert status.plan is not None and validate(model, Plan(status.plan)).valid


@pytest.mark.slow
@pytest.mark.parametrize("domain", sorted(path.name for path in IPC.iterdir() if path.is_dir()))
def test_any_plan_on_ipc_instances_is_a_valid_plan(domain):
    model = Model.load([IPC / domain / "domain.pddl", IPC / domain / "p1.pddl"])
    result = find_plan(model, satisficing=True, time_limit=60)
    assert result.status == "found" and not result.optimal
    assert validate(model, result.plan).valid


# -- the trace over the facts of the plan's actions -------------------------------


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(
    st.integers(min_value=0, max_value=10**9),
    st.booleans(),
    st.booleans(),
    st.lists(st.integers(min_value=0, max_value=7), max_size=5),
)
def test_trace_over_the_plans_actions_equals_trace_over_the_model(
    seed, conditional, derived, picks
):
    spec = random_model(
        seed, conditional=conditional, derived=derived, events=features(seed)["events"]
    )
    model = Model.from_string(spec.to_asp())
    names = [*spec.actions, "nothing"]  # an unknown action too
    plan = Plan(tuple(clingo.Function(names[i % len(names)]) for i in picks))
    planner = model.planner
    short = planner.trace(plan)
    whole = planner.solve_program(TRACE_ENCODINGS, symbols=occurrences(plan))
    assert sorted(map(str, short.symbols)) == sorted(map(str, whole.symbols))


def test_plan_from_symbols_orders_by_step_and_ignores_other_atoms():
    symbols = [
        clingo.parse_term(text)
        for text in (
            "occurs(b,2)",
            "holds(x,1)",
            "occurs(push(m),1)",
            "occurs(c,10)",
            "occurs(d,3)",
        )
    ]
    assert str(Plan.from_symbols(symbols)) == "push(m) b d c"
