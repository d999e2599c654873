"""Fast Downward as an engine (ethasp.planning.engines.downward, the SAS+ task of
ethasp.planning.engines.sas, the choice of ethasp.planning.systems): plans and
"none" against the brute-force oracle, plain and under principles, with the
planner forced; the choice of auto; the fallback to clingo with one line of
warning; the budget ends the planner's process.

The tests that run the planner are skipped where it is not installed (the
``planners`` extra); those of the choice and the fallback run everywhere.
"""

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from oracle import answered, assert_shortest, random_model

from ethasp import Model, find_plan
from ethasp.execution.limits import descendants
from ethasp.planning import systems
from ethasp.planning.budget import Budget
from ethasp.planning.engines import downward, sas
from ethasp.planning.engines.layers import Atoms, search_model
from ethasp.principles.restriction import plan_with_principles

ROOT = Path(__file__).resolve().parent.parent
IPC = Path(__file__).resolve().parent / "data" / "ipc"
SEEDS = st.integers(min_value=0, max_value=10**9)
HORIZON = 40

installed = pytest.mark.skipif(
    not systems.installed(), reason="Fast Downward is not installed (the planners extra)"
)


def forced(text: str, system: str = systems.FAST_DOWNWARD) -> Model:
    model = Model.from_string(text)
    model.planning_system = system
    return model


# -- against the oracle --------------------------------------------------------------


@installed
@pytest.mark.slow
@settings(max_examples=80, deadline=None)
@given(SEEDS, st.booleans(), st.booleans())
def test_shortest_plans_and_none_agree_with_the_oracle(seed, conditional, far_goal):
    """A* with LM-cut (h^max with conditional effects) finds a shortest plan
    exactly when one exists, and proves "none" otherwise."""
    spec = random_model(
        seed, max_variables=5, max_actions=6, conditional=conditional, far_goal=far_goal
    )
    result = answered(lambda: find_plan(forced(spec.to_asp()), max_horizon=HORIZON))
    assert_shortest(result, spec)


@installed
@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(SEEDS, st.booleans())
def test_any_plan_search_finds_a_plan_exactly_when_one_exists(seed, conditional):
    spec = random_model(seed, max_variables=5, max_actions=6, conditional=conditional)
    model = forced(spec.to_asp())
    result = answered(lambda: find_plan(model, max_horizon=HORIZON, satisficing=True))
    if spec.shortest_plan_length() is None:
        assert result.status == "none", (result, spec)
    else:
        assert result.status == "found" and not result.optimal, (result, spec)
        assert spec.is_plan([str(action) for action in result.plan])


@installed
@pytest.mark.slow
@settings(max_examples=120, deadline=None)
@given(SEEDS, st.sampled_from(["deontology", "utilitarianism", "do-no-harm"]), st.booleans())
def test_hplans_agree_with_the_oracle(seed, principle, conditional):
    """HModels searched by Fast Downward: the do-no-harm HModel's flags, the
    utilitarian goal utility compiled into a counting phase."""
    spec = random_model(seed, conditional=conditional)
    result = answered(
        lambda: plan_with_principles(forced(spec.to_asp()), [principle], max_horizon=HORIZON)
    )
    expected = spec.shortest_permissible_length([principle])
    if expected is None:
        assert result.status == "none", (result, spec)
    else:
        assert result.status == "found", (result, spec, expected)
        plan = [str(action) for action in result.plan]
        assert spec.is_plan(plan) and spec.permissible(plan, principle), (plan, spec)
        assert len(plan) == expected, (plan, expected, spec)


# -- the task ----------------------------------------------------------------------


def test_the_task_keeps_the_variables_that_matter_and_their_actions():
    model = Model.from_string(
        "variable(a;b;noise). action(go;hum;stir). eff(go,a,true). "
        "pre(stir,a,true). eff(stir,b,true). eff(hum,noise,true). goal(b,true)."
    )
    model.planner.prepare(Budget(None))
    task = sas.task(search_model(Atoms(model.planner)))
    assert task.text.count("begin_variable") == 2  # a and b, not noise
    assert task.text.count("begin_operator") == 2  # go and stir, not hum
    assert [str(a) for a in task.plan(["a0", "a2"])] == [str(task.actions[0]), "stir"]


def test_a_goal_utility_compiles_into_a_count_and_too_large_counts_are_refused():
    model = Model.from_string(
        "variable(a;b). action(x;y). eff(x,a,true). eff(y,b,true). "
        "utility(a,true,2). utility(b,true,4). utility(b,false,1)."
    )
    model.planner.prepare(Budget(None))
    ground = search_model(Atoms(model.planner, weights=True))
    # Base utility 1 (b false); gains 2 (a) and 3 (b): 3 needs either.
    task = sas.threshold_task(ground, 3)
    assert "begin_variable\nstage" in task.text and "begin_variable\ncounter" in task.text
    assert "begin_goal\n2\n" in task.text  # the stage and the counter
    assert sas.threshold_task(ground, 1).text.count("counter") == 0  # every state is worth 1
    # 4 needs b (a alone gives 3), and b suffices: a goal fact, nothing counted.
    task = sas.threshold_task(ground, 4)
    assert "counter" not in task.text and "begin_goal\n1\n" in task.text
    # 6 needs both: two goal facts (as 5 does: a and b are worth 3 apart).
    for threshold in (5, 6):
        task = sas.threshold_task(ground, threshold)
        assert "counter" not in task.text and "begin_goal\n2\n" in task.text
    big = Model.from_string(
        "variable(a;b). action(x;y). eff(x,a,true). eff(y,b,true). "
        "utility(a,true,1000000). utility(b,true,999999)."
    )
    big.planner.prepare(Budget(None))
    with pytest.raises(sas.NotCompiled):
        sas.threshold_task(search_model(Atoms(big.planner, weights=True)), 999_999)
    # Both at their better values: nothing to count, a classical goal.
    task = sas.threshold_task(search_model(Atoms(big.planner, weights=True)), 1_999_999)
    assert "counter" not in task.text


@installed
def test_true_wins_when_effects_that_fire_together_set_a_variable_both_ways():
    model = forced(
        "variable(a;b). action(x). ceff(x,k1,a,false). ceff(x,k2,a,true). "
        "cpre(x,k1,b,false). cpre(x,k2,b,false). goal(a,true)."
    )
    result = find_plan(model)
    assert result.status == "found" and [str(a) for a in result.plan] == ["x"]


# -- the choice ----------------------------------------------------------------------


def test_clingo_searches_when_asked_and_auto_keeps_small_tasks(monkeypatch):
    def refuse(*args, **kwargs):
        raise AssertionError("Fast Downward was asked")

    monkeypatch.setattr(downward, "solve", refuse)
    text = "variable(a). action(go). eff(go,a,true). goal(a,true)."
    assert find_plan(forced(text, systems.CLINGO)).status == "found"
    assert find_plan(forced(text, systems.AUTO)).status == "found"  # 1 action: clingo


def test_a_missing_planner_falls_back_to_clingo_with_one_line_of_warning(monkeypatch, capsys):
    monkeypatch.setattr(systems, "installed", lambda: False)
    monkeypatch.setattr(systems, "_warned", set())
    text = "variable(a). action(go). eff(go,a,true). goal(a,true)."
    for _ in range(2):
        result = find_plan(forced(text))
        assert result.status == "found" and [str(a) for a in result.plan] == ["go"]
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and "Fast Downward is not installed" in lines[0]


def test_a_failing_planner_falls_back_to_clingo_with_one_line_of_warning(monkeypatch, capsys):
    monkeypatch.setattr(systems, "installed", lambda: True)
    monkeypatch.setattr(systems, "_warned", set())
    monkeypatch.setattr(
        downward,
        "solve",
        lambda task, budget, optimal=True, deciding=False: downward.Outcome(
            "failed", "x", why="boom"
        ),
    )
    result = find_plan(forced("variable(a). action(go). eff(go,a,true). goal(a,true)."))
    assert result.status == "found"
    assert capsys.readouterr().err.strip() == (
        "ethasp: warning: Fast Downward failed (boom): clingo searches instead"
    )


def test_models_the_planner_does_not_model_are_searched_by_clingo(monkeypatch, capsys):
    monkeypatch.setattr(systems, "installed", lambda: True)
    monkeypatch.setattr(systems, "_warned", set())
    model = forced(
        "variable(a). derived(d). axiom(d,k). axiom_pre(d,k,a,true). "
        "action(go). eff(go,a,true). goal(d,true)."
    )
    assert find_plan(model).status == "found"
    assert "does not search models with derived variables" in capsys.readouterr().err


@installed
def test_a_task_searched_again_is_answered_without_the_planner(monkeypatch):
    """The planner searches deterministically: the same task (text and
    configuration) searched again in the process gets the same answer
    without another run (utilitarianism's witness and its HModel's plan
    search write the same task)."""
    text = "variable(a;b). action(go;on). eff(go,a,true). pre(go,b,true). eff(on,b,true). "
    planner = forced(text + "goal(a,true).").planner
    task = downward.compiled(search_model(Atoms(planner)))
    runs = []
    spawn = downward.spawner.spawn
    monkeypatch.setattr(downward.spawner, "spawn", lambda *a, **k: runs.append(1) or spawn(*a, **k))
    monkeypatch.setattr(downward, "_ANSWERS", {})
    first = downward.solve(task, Budget(None))
    second = downward.solve(task, Budget(None))
    assert first.status == "plan" and task.plan(first.operators) == task.plan(second.operators)
    assert len(runs) == 1
    other = downward.compiled(search_model(Atoms(forced(text + "goal(b,true).").planner)))
    assert downward.solve(other, Budget(None)).status == "plan" and len(runs) == 2


# -- processes and limits --------------------------------------------------------------


@installed
def test_the_budget_ends_the_planner_and_its_process():
    """A task too hard for the time given (no plan, but 2^22 states before the
    planner knows it): bounded, and no planner left running."""
    toggles = [f"t{i}" for i in range(22)]
    text = (
        f"variable(a;b;{';'.join(toggles)}). action(set_a;set_b). "
        "pre(set_a,b,false). eff(set_a,a,true). pre(set_b,a,false). eff(set_b,b,true). "
        + "".join(
            f"pre(set_b,{t},true). action(on({t})). eff(on({t}),{t},true). "
            f"action(off({t})). eff(off({t}),{t},false). "
            for t in toggles
        )
        + "goal(a,true). goal(b,true)."
    )
    started = time.monotonic()
    result = find_plan(forced(text), time_limit=1.0)
    assert result.status == "bounded" and "Fast Downward" in result.proof, result
    assert time.monotonic() - started < 30
    time.sleep(0.2)  # SIGKILL is delivered at once; the process table may lag
    assert not [pid for pid in descendants(os.getpid()) if _name(pid) == "downward"]


def _name(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/comm").read_text().strip()
    except OSError:
        return ""


@installed
@pytest.mark.slow
def test_the_command_line_plans_with_each_planner_and_the_lengths_agree():
    ipc = IPC / "logistics-strips-typed"
    lengths = {}
    for system in systems.CHOICES:
        done = subprocess.run(
            [
                *(sys.executable, "-m", "ethasp.interfaces.cli", "plan"),
                *(str(ipc / "domain.pddl"), str(ipc / "p1.pddl")),
                *("--json", "--planner", system),
            ],
            capture_output=True,
            text=True,
            cwd=ROOT,
            check=True,
        )
        answer = json.loads(done.stdout)
        assert answer["status"] == "found" and answer["optimal"], answer
        lengths[system] = len(answer["plan"])
    assert len(set(lengths.values())) == 1, lengths


GRIPPER = [
    str(ROOT / "asp" / "pddl" / f"gripper-{part}") for part in ("domain.pddl", "problem.pddl")
]
GRIPPER_PLAN = " ".join(
    f"pick(ball_{n},a,left) throw(ball_{n},a,b,left)" for n in range(1, 5)
)  # a shortest plan: 8 steps


@installed
def test_a_satisficing_contrast_never_has_more_steps_than_the_question_allows():
    """Fast Downward's greedy plan for the contrast of "why not in 7 steps"
    has 13 steps; it meets no such question, and every plan has 8 steps or
    more: the answer is none (the same as without --satisficing), not that
    plan."""
    for satisficing in (["--satisficing"], []):
        done = subprocess.run(
            [
                *(sys.executable, "-m", "ethasp.interfaces.cli", "ask", *GRIPPER),
                str(ROOT / "asp" / "pddl" / "gripper-utility.lp"),
                *("--plan", GRIPPER_PLAN, "--question", "why not in 7 steps"),
                *("--planner", "fast-downward", "--json", *satisficing),
            ],
            capture_output=True,
            text=True,
            cwd=ROOT,
            check=True,
        )
        answer = json.loads(done.stdout)
        assert answer["status"] == "none" and answer["contrast"] is None, answer
        assert "no plan has at most 7 steps" in answer["proof"], answer["proof"]


def test_no_planner_is_assumed_where_none_is_chosen():
    model = Model.from_string("variable(a). action(go). eff(go,a,true). goal(a,true).")
    assert model.planning_system == systems.AUTO


@installed
@pytest.mark.slow
@settings(max_examples=100, deadline=None)
@given(SEEDS, st.booleans())
def test_a_goal_state_at_the_bound_is_fast_downwards_answer_first(seed, conditional):
    """Before the diagrams, one A* search for a goal state that attains the
    relaxed bound: where the oracle has one, the answer is such a goal state
    at the least distance; elsewhere the other engines answer, as proven."""
    from ethasp.planning.engines.best_state import best_reachable, upper_bound

    spec = random_model(seed, conditional=conditional)
    model = forced(spec.to_asp())
    best = answered(lambda: best_reachable(model))
    assert best.status == "proven" and best.utility == spec.best_reachable_utility(), (best, spec)
    bound = upper_bound(model.planner)
    attaining = [
        distance
        for state, distance in spec.distances().items()
        if spec.is_goal(state) and spec.state_utility(state) == bound
    ]
    if attaining:
        assert "upper bound" in best.proof
        final = spec.run([str(action) for action in best.plan])
        assert final is not None and spec.is_goal(final), (best, spec)
        assert spec.state_utility(final) == bound
        assert best.found.distance == len(best.plan) == min(attaining), (best, spec)


def test_fast_downward_answers_the_bound_without_the_diagrams(monkeypatch):
    """A goal state far away attains the bound: the diagrams, which would
    grow a layer for each step to it, are never built."""
    if not systems.installed():
        pytest.skip("Fast Downward is not installed (the planners extra)")
    from ethasp.planning.driver.planner import Planner
    from ethasp.planning.engines.best_state import best_reachable

    model = forced(
        "variable(p(0..12)). init(p(0)). action(s(0..11)). "
        "pre(s(I),p(I),true) :- action(s(I)). eff(s(I),p(I+1),true) :- action(s(I)). "
        "goal(p(12),true). utility(p(12),true,5)."
    )

    def refused(self):
        raise AssertionError("the diagrams were built")

    monkeypatch.setattr(Planner, "reachability", refused)
    best = best_reachable(model)
    assert best.status == "proven" and best.utility == 5 and len(best.plan) == 12
    assert "upper bound" in best.proof


@installed
@pytest.mark.slow
@settings(max_examples=80, deadline=None)
@given(SEEDS, st.booleans(), st.integers(min_value=-6, max_value=6))
def test_best_reachable_utility_and_better_states_agree_with_the_oracle(seed, conditional, shift):
    """Utilitarianism's proofs by Fast Downward, where the diagrams give up
    (here at once: a node limit of 1): the relaxed bound, the bisection by
    searches for a state worth at least k, a better state."""
    from ethasp.planning.engines import reachability
    from ethasp.planning.engines.best_state import best_reachable, better_state

    spec = random_model(seed, conditional=conditional)
    saved = reachability.DEFAULT_NODE_LIMIT
    reachability.DEFAULT_NODE_LIMIT = 1
    try:
        best = answered(lambda: best_reachable(forced(spec.to_asp())))
        utility = spec.best_reachable_utility() + shift
        compared = better_state(forced(spec.to_asp()), utility)
    finally:
        reachability.DEFAULT_NODE_LIMIT = saved
    assert best.status == "proven" and best.utility == spec.best_reachable_utility(), (best, spec)
    assert "was searched" in best.proof or "upper bound" in best.proof, best
    assert compared.status == "proven"
    assert (compared.better is not None) == (spec.best_reachable_utility() > utility)
    if compared.better is not None:
        assert compared.better.utility > utility


@installed
def test_facts_asked_of_the_final_state_are_goal_facts_of_the_task(monkeypatch):
    """Question constraints ends(F,B) (the goal's items in conflicts) are
    searched by Fast Downward as goal facts; its plan is checked to end
    with them, and a fact that never holds is no plan at all."""
    import clingo

    from ethasp.planning import search
    from ethasp.planning.driver.planner import Setting
    from ethasp.planning.search import shortest
    from ethasp.planning.search_base import checked

    model = forced(
        "variable(a;b;c;fixed). action(x;y). eff(x,a,true). pre(y,a,true). eff(y,b,true). "
        "eff(y,c,true). goal(c,true)."
    )
    planner = model.planner
    solved = []
    solve = downward.solve
    monkeypatch.setattr(downward, "solve", lambda *a: solved.append(a[0]) or solve(*a))

    def ends(variable: str, value: str) -> Setting:
        term = clingo.parse_term(f"ends({variable},{value})")
        return Setting(constraints=frozenset(planner.question([term])))

    found = shortest(planner, ends("b", "true"), Budget(None))
    assert found.status == "found" and [str(a) for a in found.plan] == ["x", "y"]
    assert "begin_goal\n2\n" in solved[-1].text  # c and b
    refuted = shortest(planner, ends("b", "false"), Budget(None))
    assert refuted.status == "none"  # y makes both b and c true
    never = shortest(planner, ends("fixed", "true"), Budget(None))
    assert never.status == "none"  # known before any search (relaxed reachability)
    against = shortest(planner, ends("c", "false"), Budget(None))
    assert against.status == "none" and "goal" in against.proof  # (questions.lp)
    # The task: facts of variables no action changes are no goal facts.
    ground = search_model(Atoms(planner))
    fixed, b = clingo.Function("fixed"), clingo.Function("b")
    assert search._with_final_facts(ground, [(fixed, False)]).goal == ground.goal
    assert search._with_final_facts(ground, [(b, True)]).goal == [*ground.goal, (b, True)]
    # A plan an engine proposes is checked to meet the constraints by the encodings.
    with pytest.raises(RuntimeError, match="question's encodings refute"):
        checked(
            planner,
            [clingo.Function("x"), clingo.Function("y")],
            "an engine",
            ends("b", "false").constraints,
        )


@installed
def test_goal_conflicts_are_decided_by_the_planner_without_the_depth(monkeypatch):
    """Each set of the goal's items is a goal of the planner's task, decided
    by the search that exhausts the states fastest; the depth of every
    reachable state is not computed."""
    from ethasp.principles import goal_items
    from ethasp.principles.conflict import goal_conflicts

    model = forced(
        "variable(a;b). action(x;y). eff(x,a,true). eff(y,b,true). "
        "goal(a,true). goal(b,true). utility(y,-1)."
    )
    configurations = []
    search = downward._search

    def recorded(task, budget, config, binary):
        configurations.append(config)
        return search(task, budget, config, binary)

    monkeypatch.setattr(downward, "_search", recorded)
    monkeypatch.setattr(goal_items, "reachable_depth", None)  # (called: a TypeError)
    result = goal_conflicts(model, ["deontology"])
    assert result.status == "proven"
    assert [[str(item.term) for item in c] for c in result.conflicts] == [["goal(b,true)"]]
    assert [[str(item.term) for item in s.items] for s in result.goal_subsets] == [["goal(a,true)"]]
    assert downward.DECIDING in configurations
    assert "by plan search and its proofs" in result.proof


@installed
def test_an_effect_without_condition_that_makes_a_variable_true_is_its_only_effect():
    """An action that makes v true unconditionally and false under a condition
    that always holds (true wins): one effect on v in the operator, so that
    A* with LM-cut searches it (it crashed on two effects on one variable)."""
    model = forced(
        "variable(v;w;s). action(a). pre(a,w,false). eff(a,v,true). ceff(a,k,v,false). "
        "ceff(a,k,w,true). cpre(a,k,s,false). goal(v,true). goal(w,true)."
    )
    model.planner.prepare(Budget(None))
    task = sas.task(search_model(Atoms(model.planner)))
    assert not task.conditional  # the condition on s, which never changes, always holds
    operator = task.text.split("begin_operator\n")[1].split("end_operator")[0].splitlines()
    effects = operator[3 : 3 + int(operator[2])]  # name, no prevail, count, effects
    assert sorted(effects) == ["0 0 -1 1", "0 1 0 1"]  # v true, w true (v, w: 0, 1)
    assert downward.configuration(task, True) == downward.OPTIMAL
    result = find_plan(model)
    assert result.status == "found" and [str(a) for a in result.plan] == ["a"]


@installed
def test_a_satisficing_plan_of_fast_downward_has_its_cost():
    """In a model with action costs, a plan that Fast Downward's any-plan
    search found carries its cost (read off its trace), as clingo's does."""
    text = """
        variable(at_b;at_c). action(hop;jump). pre(hop,at_b,false). eff(hop,at_b,true).
        pre(jump,at_b,true). eff(jump,at_c,true). goal(at_c,true).
        cost(hop,3). cost(jump,4)."""
    for system in (systems.FAST_DOWNWARD, systems.CLINGO):
        result = find_plan(forced(text, system), satisficing=True)
        assert result.status == "found" and result.optimal is False, system
        assert [str(action) for action in result.plan] == ["hop", "jump"]
        assert result.cost == 7 and result.to_json()["cost"] == 7, system


def test_a_cheapest_plan_asked_of_fast_downward_says_that_clingo_searches(monkeypatch, capsys):
    """Fast Downward's tasks give every action cost 1: where it is asked for
    and the model has action costs, the cheapest plan is clingo's (and
    uniform-cost search's), and one line says so."""
    monkeypatch.setattr(systems, "_warned", set())
    text = """
        variable(at_b;at_c). action(hop;jump;fly). pre(hop,at_b,false). eff(hop,at_b,true).
        pre(jump,at_b,true). eff(jump,at_c,true). eff(fly,at_c,true). goal(at_c,true).
        cost(hop,1). cost(jump,1). cost(fly,5)."""
    result = find_plan(forced(text))
    assert result.status == "found" and result.cost == 2
    assert [str(action) for action in result.plan] == ["hop", "jump"]
    assert "Fast Downward does not search for cheapest plans" in capsys.readouterr().err
