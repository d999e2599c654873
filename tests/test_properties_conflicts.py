"""Property tests: minimal conflicts and maximal goal subsets against a
brute-force oracle (tests/oracle.py tries every subset of the goal), on random
models with every feature (conditional effects, derived variables, exogenous
events), for the paper's three principles and HERA's principles that have an
HModel.

The conflicts are exactly the subset-minimal sets of goal facts that no
permissible plan reaches; the goal subsets exactly the subset-maximal ones
that a permissible plan reaches, each with a shortest such plan, which the
principle's judgement confirms.
"""

import itertools
import random

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import features, goal_structure, random_model, with_goal

from ethasp import Model
from ethasp.planning import systems
from ethasp.principles.conflict import goal_conflicts

SEEDS = st.integers(min_value=0, max_value=10**9)
PAPER = ["deontology", "utilitarianism", "do-no-harm"]
HERA = [
    "hera-deontology",
    "goal-deontology",
    "avoid-any-harm",
    "avoid-avoidable-harm",
    "hera-utilitarianism",
]
HORIZON = 40


def _facts(items) -> frozenset:
    return frozenset((str(item.fact[0]), item.fact[1]) for item in items)


def check_against_oracle(
    seed: int, principle: str, larger: bool = False, system: str | None = None
) -> None:
    sizes = {"max_variables": 6, "max_actions": 5} if larger else {}
    drawn = features(seed)
    if system == systems.FAST_DOWNWARD:  # the features its task compiles
        drawn = {**drawn, "derived": False, "events": False}
    spec = random_model(seed, **sizes, **drawn)
    model = Model.from_string(spec.to_asp())
    if system is not None:
        model.planning_system = system
    result = goal_conflicts(model, [principle], max_horizon=HORIZON)
    conflicts, subsets = goal_structure(spec, principle)
    assert result.status == "proven", (result.proof, spec)
    assert not result.conflicts_truncated and not result.goal_subsets_truncated
    assert {_facts(c) for c in result.conflicts} == conflicts, (result, spec)
    assert {_facts(s.items) for s in result.goal_subsets} == subsets, (result, spec)
    assert result.empty_goal_fails == (frozenset() in conflicts)
    for subset in result.goal_subsets:
        plan = [str(action) for action in subset.plan]
        reduced = with_goal(spec, dict(_facts(subset.items)))
        assert reduced.is_plan(plan) and reduced.permissible(plan, principle), (plan, spec)
        assert subset.optimal
        assert len(plan) == reduced.shortest_permissible_length([principle]), (plan, spec)


@pytest.mark.slow
@settings(max_examples=90, deadline=None)
@given(SEEDS, st.sampled_from(PAPER))
def test_conflicts_of_the_papers_principles_agree_with_the_oracle(seed, principle):
    check_against_oracle(seed, principle)


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(SEEDS, st.sampled_from(HERA))
def test_conflicts_of_heras_principles_agree_with_the_oracle(seed, principle):
    check_against_oracle(seed, principle)


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(SEEDS, st.sampled_from(PAPER + HERA))
def test_conflicts_of_larger_goals_agree_with_the_oracle(seed, principle):
    check_against_oracle(seed, principle, larger=True)


@settings(max_examples=25, deadline=None)
@given(SEEDS, st.sampled_from(PAPER))
def test_conflicts_agree_with_the_oracle(seed, principle):
    check_against_oracle(seed, principle)


@pytest.mark.skipif(not systems.installed(), reason="Fast Downward is not installed")
@pytest.mark.slow
@settings(max_examples=80, deadline=None)
@given(SEEDS, st.sampled_from(PAPER + HERA))
def test_conflicts_decided_by_fast_downward_agree_with_the_oracle(seed, principle):
    # Each set of items a task's goal facts, decided by the planner's proofs
    # without the depth (on models whose features its task compiles).
    check_against_oracle(seed, principle, system=systems.FAST_DOWNWARD)


@settings(max_examples=20, deadline=None)
@given(SEEDS, st.sampled_from(PAPER), st.integers(min_value=1, max_value=2))
def test_the_limit_cuts_both_lists(seed, principle, limit):
    spec = random_model(seed, max_variables=6, max_actions=5, **features(seed))
    assume(len(spec.goal) >= 3)
    result = goal_conflicts(
        Model.from_string(spec.to_asp()), [principle], max_horizon=HORIZON, limit=limit
    )
    conflicts, subsets = goal_structure(spec, principle)
    assert len(result.conflicts) <= limit and len(result.goal_subsets) <= limit
    assert {_facts(c) for c in result.conflicts} <= conflicts
    assert {_facts(s.items) for s in result.goal_subsets} <= subsets
    assert result.conflicts_truncated == (len(conflicts) > limit)
    assert result.goal_subsets_truncated == (len(subsets) > limit)


def test_the_oracle_is_monotone_on_an_example():
    """The oracle's own premise: a set reached permissibly has its subsets reached."""
    spec = random_model(7, max_variables=6, max_actions=5)
    facts = sorted(spec.goal.items())
    conflicts, subsets = goal_structure(spec, "do-no-harm")
    for size in range(len(facts) + 1):
        for subset in itertools.combinations(facts, size):
            covered = any(frozenset(subset) <= s for s in subsets)
            blocked = any(c <= frozenset(subset) for c in conflicts)
            assert covered != blocked


# A model of three goal facts: one action reaches a and b at once, another c;
# deontology forbids nothing.
WITNESSED = """
variable(a; b; c). action(both; third).
eff(both,a,true). eff(both,b,true). eff(third,c,true).
goal(a,true). goal(b,true). goal(c,true).
"""


def test_a_set_that_a_plan_found_reaches_is_decided_without_a_search(monkeypatch):
    """A plan found for some items is checked against every item; a set of
    items it reaches is reachable without a search of its own (the insertion
    and growth of the exploration decide many such sets), and a set it does
    not reach is still searched."""
    from ethasp.principles.goal_items import GoalItems
    from ethasp.principles.principle import select_principles

    items = GoalItems(Model.from_string(WITNESSED), select_principles(["deontology"]))
    assert [str(item.term) for item in items.items] == [
        "goal(a,true)",
        "goal(b,true)",
        "goal(c,true)",
    ]
    searched: list[frozenset[int]] = []
    search = GoalItems._reach
    monkeypatch.setattr(
        GoalItems, "_reach", lambda self, chosen: searched.append(chosen) or search(self, chosen)
    )

    def reached_by(plan) -> set[int]:  # both makes a and b, third c
        names = {str(action) for action in plan}
        return ({0, 1} if "both" in names else set()) | ({2} if "third" in names else set())

    first = items.reach(frozenset({0}))
    assert first.status == "found" and "both" in [str(a) for a in first.plan]
    known = [reached_by(first.plan)]  # {a, b} at least: the set {a, b} needs no search
    for size in range(1, 4):
        for chosen in map(frozenset, itertools.combinations(range(3), size)):
            searched.clear()
            found = items.reach(chosen)
            assert found.status == "found" and chosen <= reached_by(found.plan), chosen
            if any(chosen <= reached for reached in known):
                assert searched == [], chosen
            else:
                assert searched == [chosen], chosen
                known.append(reached_by(found.plan))


# -- the questions' constraints count like goal facts --------------------------------

QUESTION_PRINCIPLES = ["deontology", "utilitarianism", "do-no-harm"]


def _random_terms(spec, rng) -> list[tuple]:
    """One or two constraint terms in the oracle's form (question_oracle.py)."""
    a, b = rng.choice(spec.actions), rng.choice(spec.actions)
    f = rng.choice(spec.variables + list(spec.derived))
    t = rng.randint(1, 3)
    t1 = rng.randint(1, 2)
    choices = [
        ("used", a),
        ("unused", a),
        ("before", b, a),
        ("at", a, t),
        ("not_at", a, t),
        ("within", a, t1, t1 + 1),
        ("not_within", a, t1, t1 + 1),
        ("ends", f, rng.random() < 0.5),
        ("fact_at", f, rng.random() < 0.5, t),
        ("at_most", rng.randint(0, 3)),
    ]
    return rng.sample(choices, rng.randint(1, 2))


def _symbol(term: tuple):
    import clingo

    def argument(value):
        if isinstance(value, bool):
            return clingo.Function("true" if value else "false")
        if isinstance(value, int):
            return clingo.Number(value)
        return clingo.Function(value)

    return clingo.Function(term[0], [argument(value) for value in term[1:]])


def _item_key(item) -> tuple:
    if item.fact is not None:
        return ("goal", str(item.fact[0]), item.fact[1])
    term = item.term
    return (term.name, *(_plain(argument) for argument in term.arguments))


def _plain(symbol):
    import clingo

    if symbol.type == clingo.SymbolType.Number:
        return symbol.number
    if symbol.name in ("true", "false") and not symbol.arguments:
        return symbol.name == "true"
    return str(symbol)


@pytest.mark.slow
@settings(max_examples=72, deadline=None)
@given(SEEDS, st.sampled_from(QUESTION_PRINCIPLES))
def test_conflicts_of_goals_and_question_constraints_agree_with_the_oracle(seed, principle):

    spec = random_model(seed, **features(seed))
    terms = _random_terms(spec, random.Random(seed))
    model = Model.from_string(spec.to_asp())
    constraints = model.planner.question([_symbol(term) for term in terms])
    result = goal_conflicts(model, [principle], constraints, max_horizon=HORIZON)
    _agrees_with_the_oracle(result, spec, terms, principle)


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(SEEDS, st.sampled_from(QUESTION_PRINCIPLES))
def test_conflicts_after_a_contrast_proved_no_permissible_plan_agree_with_the_oracle(
    seed, principle
):
    """Where the contrast's search under the principle proved that no
    permissible plan meets the goal and the question (a dropped principle),
    the conflicts take that proof instead of deciding the whole set again
    (ethasp/questions/impasse.py): they are still exactly the oracle's."""
    from ethasp.principles.restriction import plan_with_principles
    from ethasp.questions.contrast import longest

    spec = random_model(seed, **features(seed))
    terms = [t for t in _random_terms(spec, random.Random(seed)) if t[0] != "at_most"]
    assume(terms)
    model = Model.from_string(spec.to_asp())
    constraints = model.planner.question([_symbol(term) for term in terms])
    under = plan_with_principles(
        model, [principle], HORIZON, constraints=constraints, max_length=longest(constraints)
    )
    assume(under.status == "none")
    result = goal_conflicts(model, [principle], constraints, max_horizon=HORIZON, unreachable=True)
    _agrees_with_the_oracle(result, spec, terms, principle)


def _agrees_with_the_oracle(result, spec, terms, principle) -> None:
    from question_oracle import shortest_meeting

    items = [("goal", v, b) for v, b in sorted(spec.goal.items())] + [tuple(t) for t in terms]

    def reachable(subset) -> bool:
        goal = {i[1]: i[2] for i in subset if i[0] == "goal"}
        asked = [i for i in subset if i[0] != "goal"]
        return shortest_meeting(with_goal(spec, goal), asked, [principle]) is not None

    known = {}
    for size in range(len(items) + 1):
        for subset in itertools.combinations(items, size):
            known[frozenset(subset)] = reachable(subset)
    conflicts = {s for s, ok in known.items() if not ok and all(known[s - {i}] for i in s)}
    subsets = {
        s for s, ok in known.items() if ok and all(not known[s | {i}] for i in items if i not in s)
    }
    assert result.status == "proven", (result.proof, terms, spec)
    assert {frozenset(map(_item_key, c)) for c in result.conflicts} == conflicts, (terms, spec)
    assert {frozenset(map(_item_key, s.items)) for s in result.goal_subsets} == subsets
    for subset in result.goal_subsets:
        keys = [_item_key(item) for item in subset.items]
        goal = {k[1]: k[2] for k in keys if k[0] == "goal"}
        asked = [k for k in keys if k[0] != "goal"]
        expected = shortest_meeting(with_goal(spec, goal), asked, [principle])
        assert len(subset.plan) == expected, (subset.plan, keys, spec)
