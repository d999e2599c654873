"""Property tests: the ADL translation of PDDL against a brute-force PDDL semantics.

Random small tasks (tests/pddl_oracle.py) with typed and either-typed objects,
predicates of arity 0 to 2, derived predicates (stratified, some recursive),
and actions whose preconditions and effect conditions use every connective
and quantifier, with conditional and universally quantified effects, and
static predicates (no effect changes them) in plain conjuncts of
preconditions, positive and negative.  The oracle grounds and searches them
explicitly; ethasp translates them into lifted rules that clingo grounds,
keeping only the action instances whose static preconditions and equalities
hold.
"""

from __future__ import annotations

import contextlib
import io
import random

import clingo
import pytest
from conftest import ENCODINGS
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from pddl_oracle import PddlTask, asp_atom, random_task

from ethasp import InputError, Model, Plan, find_plan, validate
from ethasp.planning.readers.pddl import PddlFile, translate
from ethasp.vocabulary import Action

SEEDS = st.integers(min_value=0, max_value=10**9)
HORIZON = 12


def program(task: PddlTask) -> str:
    with contextlib.redirect_stderr(io.StringIO()):
        return translate(
            PddlFile("d.pddl", task.domain_text()), PddlFile("p.pddl", task.problem_text())
        )


def model_of(task: PddlTask) -> Model:
    return Model.from_string((ENCODINGS / "planning/pddl.lp").read_text() + program(task))


def context(task: PddlTask) -> str:
    return task.domain_text() + task.problem_text()


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(SEEDS)
def test_shortest_plan_lengths_agree_with_the_oracle(seed):
    task = random_task(seed)
    model = model_of(task)
    distances = task.distances()
    expected = task.shortest_plan_length(distances)
    result = find_plan(model, max_horizon=HORIZON)
    if expected is not None and expected <= HORIZON:
        assert result.status == "found", (result, context(task))
        assert len(result.plan) == expected, (result, expected, context(task))
        state = task.init
        for action in result.plan:
            state = task.step(state, str(action))
            assert state is not None, (result, context(task))
        assert task.is_goal(state)
    else:
        assert result.status != "found", (result, context(task))
        if expected is None and len(distances) <= 8:
            # no path without a repeated state is longer than 7 steps: a proof at 8
            assert result.status == "none", (result, context(task))


def conjuncts(f, positive: bool = True) -> list:
    """The literals (``(atom or equality, positive)``) that are plain conjuncts
    of a formula in negation normal form."""
    kind = f[0]
    if kind in ("atom", "="):
        return [(f, positive)]
    if kind == "not":
        return conjuncts(f[1], not positive)
    if (kind == "and" and positive) or (kind == "or" and not positive):
        return [literal for g in f[1] for literal in conjuncts(g, positive)]
    if kind == "imply" and not positive:
        return conjuncts(f[1], True) + conjuncts(f[2], False)
    return []


def failing(task: PddlTask, pre, binding) -> tuple[bool, set[str]]:
    """Whether a plain equality conjunct fails, and the plain static conjuncts
    that fail initially (as literals ``v`` / ``-v``)."""
    changed = {
        literal[1] for _, _, _, effect in task.actions for literal in effect_literals(effect)
    }
    static = set(task.predicates) - changed - {name for name, _, _ in task.derived}
    equality, failed = False, set()
    for atom, positive in conjuncts(pre):
        if atom[0] == "=" and task.holds(atom, task.init, binding) != positive:
            equality = True
        elif (
            atom[0] == "atom"
            and atom[1] in static
            and task.holds(atom, task.init, binding) != positive
        ):
            name = asp_atom((atom[1], task.ground_terms(atom[2], binding)))
            failed.add(name if positive else f"-{name}")
    return equality, failed


def effect_literals(e) -> list:
    if e[0] == "lit":
        return [e]
    if e[0] == "and":
        return [literal for g in e[1] for literal in effect_literals(g)]
    return effect_literals(e[2])  # forall, when


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(SEEDS)
def test_the_actions_are_those_whose_static_preconditions_hold(seed):
    """The translation keeps exactly the instances whose plain equality and
    static conjuncts hold (static predicates of any arity, both signs)."""
    task = random_task(seed)
    model = model_of(task)
    actions = {str(a.name.symbol) for a in model.facts([Action]).query(Action).all()}
    expected = {
        term
        for term, (pre, _), binding in task.ground_actions()
        if failing(task, pre, binding) == (False, set())
    }
    assert actions == expected, context(task)


@pytest.mark.slow
@settings(max_examples=150, deadline=None)
@given(SEEDS, st.integers(min_value=0, max_value=10**6))
def test_validation_agrees_with_the_oracle(seed, choice_seed):
    task = random_task(seed)
    model = model_of(task)
    actions = sorted(str(a.name.symbol) for a in model.facts([Action]).query(Action).all())
    ground = {term for term, _, _ in task.ground_actions()}
    assert set(actions) <= ground, context(task)
    # an action the translation leaves out fails its precondition everywhere
    # (an equality, or a static precondition)
    reachable = list(task.distances())
    for term, (pre, _), binding in task.ground_actions():
        if term not in actions:
            assert not any(task.holds(pre, task.closure(s), binding) for s in reachable), term
    rng = random.Random(choice_seed)
    pruned = sorted(ground - set(actions))
    assume(actions or pruned)  # (a task without ground actions: about 1 in 150)
    sequence = [
        rng.choice(pruned)
        if pruned and (rng.random() < 0.2 or not actions)
        else rng.choice(actions)
        for _ in range(rng.randint(0, 5))
    ]
    reasons = {
        term: failing(task, pre, binding)
        for term, (pre, _), binding in task.ground_actions()
        if term in sequence
    }
    if any(reasons[term][0] for term in sequence if term in pruned):
        # an instance whose equality fails is no instance of its schema
        with pytest.raises(InputError, match="unknown action"):
            validate(model, Plan.parse(" ".join(sequence)))
    else:
        _check_validation(task, model, sequence, pruned, reasons)


def _check_validation(task, model, sequence, pruned, reasons) -> None:
    check = validate(model, Plan.parse(" ".join(sequence)))
    state, failure = task.init, None
    for index, action in enumerate(sequence, start=1):
        succ = task.step(state, action)
        if succ is None:
            failure = index
            break
        state = succ
    assert check.failure_step == failure, (sequence, check, context(task))
    if failure is None:
        assert check.valid == task.is_goal(state), (sequence, check, context(task))
        true = sorted(literal for literal in check.final_state if not literal.startswith("-"))
        assert true == sorted(asp_atom(atom) for atom in state), (sequence, context(task))
    else:
        assert not check.valid
        term = sequence[failure - 1]
        assert check.static == (term in pruned), (sequence, check, context(task))
        if term in pruned:
            assert set(check.unmet_preconditions) == reasons[term][1], (sequence, context(task))


@pytest.mark.slow
@settings(max_examples=100, deadline=None)
@given(SEEDS)
def test_relaxed_reachability_and_mutexes_are_sound(seed):
    """Every fact of a reachable state, derived facts included, is relaxed
    reachable; no mutex pair holds in a reachable state; a relaxed proof that
    the goal is unreachable means the oracle has no plan."""
    task = random_task(seed)
    ctl = clingo.Control(logger=lambda code, message: None)
    for name in (
        "planning/pddl.lp",
        "planning/model.lp",
        "planning/relaxed.lp",
        "planning/mutex.lp",
    ):
        ctl.load(str(ENCODINGS / name))
    ctl.add("base", [], program(task))
    ctl.ground([("base", [])])
    atoms = [atom.symbol for atom in ctl.symbolic_atoms if atom.is_fact]
    reachable = {
        (str(a.arguments[0]), a.arguments[1].name) for a in atoms if a.match("reachable", 2)
    }
    variables = {str(a.arguments[0]) for a in atoms if a.match("variable", 1)}
    derived = {
        str(a.arguments[0])
        for a in atoms
        if a.match("derived", 1) and a.arguments[0].name in task.predicates
    }
    mutexes = [
        tuple(str(x) if i % 2 == 0 else x.name for i, x in enumerate(a.arguments))
        for a in atoms
        if a.match("mutex", 4)
    ]
    distances = task.distances()
    for state in distances:
        full = {asp_atom(atom) for atom in task.closure(state)}
        for name in variables | derived:
            value = "true" if name in full else "false"
            assert (name, value) in reachable, (name, value, context(task))
        for v, b, w, c in mutexes:
            assert not ((v in full) == (b == "true") and (w in full) == (c == "true")), (
                v,
                b,
                w,
                c,
                context(task),
            )
    if any(a.match("unreachable_goal", 0) for a in atoms):
        assert task.shortest_plan_length(distances) is None, context(task)
