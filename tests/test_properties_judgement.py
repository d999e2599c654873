"""Property tests: judgements and queries against the brute-force oracle, on
random models with every feature (conditional effects, derived variables,
exogenous events)."""

import random

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import features, holds, plan_through, random_formula, random_model

from ethasp import Model, Plan, judge, query

PRINCIPLES = ["deontology", "do-no-harm", "utilitarianism"]


def model_with_plan(seed: int, walk: int):
    """A random model that has a plan, and a random plan of it."""
    rng = random.Random(seed)
    for offset in range(50):
        spec = random_model(seed + offset, **features(seed + offset))
        plan = plan_through(spec, rng, walk)
        if plan is not None:
            return spec, plan
    raise AssertionError("no model with a plan")


def text(formula: tuple) -> str:
    """The textual syntax, written out fully parenthesised (independent of the printer)."""
    kind = formula[0]

    def fact(variable, value):
        return variable if value else f"-{variable}"

    if kind in ("good", "bad", "neutral"):
        element = formula[1]
        name = element[1] if element[0] == "action" else fact(element[1], element[2])
        return f"{kind.capitalize()}({name})"
    if kind == "caused":
        return f"Caused({fact(formula[1], formula[2])})"
    if kind == "geq":
        return (
            "GEq("
            + " & ".join(fact(*f) for f in formula[1])
            + ", "
            + " & ".join(fact(*f) for f in formula[2])
            + ")"
        )
    if kind == "not":
        return f"not ({text(formula[1])})"
    operator = {"and": "and", "or": "or", "imp": "->"}[kind]
    return f"({text(formula[1])}) {operator} ({text(formula[2])})"


@pytest.mark.slow
@settings(max_examples=90, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.integers(min_value=0, max_value=6))
def test_verdicts_agree_with_the_definitions(seed, walk):
    spec, plan = model_with_plan(seed, walk)
    report = judge(Model.from_string(spec.to_asp()), Plan.parse(" ".join(plan)))
    final = spec.run(plan)
    assert report.utility == spec.state_utility(final)
    assert report.final_state == sorted(v if v in final else f"-{v}" for v in spec.variables)
    for judgement in report.judgements:
        assert judgement.status == "proven", judgement
        assert judgement.permissible == spec.permissible(plan, judgement.principle), judgement
    utilitarian = report.judgements[2]
    if utilitarian.permissible:
        assert utilitarian.best_reachable.utility == spec.best_reachable_utility()
    else:  # decided by the first better state found, at its shortest distance
        better = frozenset(v for v in spec.variables if v in utilitarian.compared.literals)
        assert spec.state_utility(better) == utilitarian.compared.utility > report.utility
        if spec.events:  # searched by horizons 0, 1, 2, 4, ...: within that many steps
            assert spec.distances()[better] <= utilitarian.compared.distance
        else:
            assert spec.distances()[better] == utilitarian.compared.distance
    best = (
        judge(
            Model.from_string(spec.to_asp()),
            Plan.parse(" ".join(plan)),
            ["utilitarianism"],
            best=True,
            reasons_limit=0,
        )
        .judgements[0]
        .best_reachable
    )
    assert best.status == "proven" and best.utility == spec.best_reachable_utility()


@pytest.mark.slow
@settings(max_examples=200, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.integers(min_value=0, max_value=4))
def test_formulas_agree_with_the_definitions(seed, walk):
    spec, plan = model_with_plan(seed, walk)
    rng = random.Random(seed)
    formulas = [random_formula(spec, rng) for _ in range(3)]
    model = Model.from_string(spec.to_asp())
    for formula in formulas:
        result = query(model, Plan.parse(" ".join(plan)), text(formula))
        assert result.value == holds(spec, plan, formula), (text(formula), plan)


@pytest.mark.slow
@settings(max_examples=120, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.integers(min_value=1, max_value=150))
def test_long_sequences_have_the_oracle_final_state_and_failure(seed, length):
    """trace.lp walks back over blocks of steps; long sequences exercise the jumps."""
    from ethasp import validate

    spec = random_model(seed, **features(seed))
    rng = random.Random(seed)
    state, plan = spec.init, []
    for t in range(1, length + 1):
        options = [a for a in spec.actions if spec.applicable(state, a)]
        # now and then an action that may be inapplicable
        action = rng.choice(spec.actions if rng.random() < 0.02 or not options else options)
        plan.append(action)
        if not spec.applicable(state, action):
            break
        state = spec.step(state, t, action)
    check = validate(Model.from_string(spec.to_asp()), Plan.parse(" ".join(plan)))
    final = spec.run(plan)
    if final is None:
        assert check.failure_step == len(plan)
    else:
        assert check.failure_step is None
        assert check.final_state == sorted(v if v in final else f"-{v}" for v in spec.variables)
        assert check.valid == spec.is_goal(final)


@settings(max_examples=40, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.integers(min_value=0, max_value=4))
def test_the_facts_a_utilitarian_explanation_names_compare_as_its_states_do(seed, walk):
    """The words of a GEq atom name some facts of each side and say how the
    sides compare ("better", "as good as", "worse"): the relation is that of
    the final state to the state compared with (by the oracle's utilities),
    and the utilities of the facts named on each side sum to values that
    compare the same way."""
    spec, plan = model_with_plan(seed, walk)
    report = judge(Model.from_string(spec.to_asp()), Plan.parse(" ".join(plan)), ["utilitarianism"])
    explanation = report.judgements[0].explanation
    assert explanation is not None
    # (No comparison where no other state is reachable: the reason is empty.)
    assume(explanation.comparisons)
    relation = {1: "better", 0: "equal", -1: "worse"}

    def compare(left: int, right: int) -> str:
        return relation[(left > right) - (left < right)]

    def worth(facts) -> int:
        return sum(spec.fact_utility.get((str(v), b), 0) for v, b in facts)

    assert explanation.alternative is not None
    other = sum(
        spec.fact_utility.get((lit.lstrip("-"), not lit.startswith("-")), 0)
        for lit in explanation.alternative
    )
    for atom, comparison in explanation.comparisons.items():
        assert str(atom).startswith("geq(final,"), atom
        assert comparison.relation == compare(spec.state_utility(spec.run(plan)), other)
        assert compare(worth(comparison.left), worth(comparison.right)) == comparison.relation
