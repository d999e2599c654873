"""Property tests of the whole question language and of step-by-step
explanations on random models (conditional effects, derived variables and
exogenous events included), against the brute-force oracle of
tests/question_oracle.py, which simulates events (tests/oracle.py):

* every form: a contrast plan meets the question and is a shortest one
  (permissible under the principle, or, with the principle dropped, a
  shortest one without it); the principle is dropped exactly when no plan
  meeting the question is permissible under it (and some plan meets it);
  "none" only when no plan meets the question, with a conflict that no plan
  meets; a question whose presupposition fails is refused;
* causal links (from steps and events, to steps, events and the goal),
  removable steps, the steps that serve the goal and the valued facts each
  step causes exactly as defined.
"""

from __future__ import annotations

import dataclasses
import itertools
import random

from hypothesis import given, settings
from hypothesis import strategies as st
from links_oracle import e_and_d_links, links_of_json
from oracle import features, plan_through, random_model
from question_oracle import (
    after_step,
    causes,
    links,
    meets,
    removable,
    serving,
    shortest_meeting,
    trajectory,
    value,
)

from ethasp import InputError, Model, Plan
from ethasp.questions.contrast import ask
from ethasp.questions.steps import explain_steps

PRINCIPLES = ["deontology", "utilitarianism", "do-no-harm"]
FORMS = [
    "why",
    "why-not",
    "rather-than",
    "before",
    "after",
    "at",
    "not-at",
    "within",
    "not-within",
    "ends",
    "not-ends",
    "fact-at",
    "not-fact-at",
    "length",
]
MAX_HORIZON = 12
# The features random models draw: none, each alone, and all of them together.
KINDS = {
    "plain": {},
    "conditional": {"conditional": True},
    "derived": {"derived": True},
    "events": {"events": True},
    "every feature": {"conditional": True, "derived": True, "events": True},
}


def _b(value: bool) -> str:
    return "true" if value else "false"


def question(form: str, spec, plan: list[str], rng: random.Random):
    """A question of the form about the plan: its text, its constraint terms
    as the oracle writes them, and as questions.lp writes them.  Most
    questions ask about what the plan does (their presupposition holds);
    some pick their names at random."""
    fitting = rng.random() < 0.8
    a, b = rng.choice(spec.actions), rng.choice(spec.actions)
    facts = spec.variables + list(spec.derived)
    f = rng.choice(facts)
    t = rng.randint(1, len(plan) + 2)
    t1 = rng.randint(1, len(plan) + 1)
    t2 = rng.randint(t1, t1 + 2)
    states = trajectory(spec, plan)
    if fitting and plan:
        if form in ("before", "after") and len(plan) > 1:
            # Two steps in order: an A before a B ("before"), a B before an A ("after").
            i, j = sorted(rng.sample(range(len(plan)), 2))
            a, b = (plan[i], plan[j]) if form == "before" else (plan[j], plan[i])
        elif form in ("why", "rather-than", "before", "after"):
            a = rng.choice(plan)
        elif form == "at":
            t = rng.randint(1, len(plan))
            a = plan[t - 1]
        elif form == "within":
            at = rng.randint(1, len(plan))
            a, t1, t2 = plan[at - 1], rng.randint(1, at), rng.randint(at, len(plan) + 1)
        elif form in ("why-not", "not-at", "not-within"):
            a = rng.choice([x for x in spec.actions if x not in plan] or spec.actions)
    if fitting and form in ("ends", "not-ends", "fact-at", "not-fact-at"):
        state = after_step(states, plan, t) if form.endswith("fact-at") else states[-1]
        wanted = not form.startswith("not")
        fitting_facts = [x for x in facts if value(spec, state, x) == wanted]
        f = rng.choice(fitting_facts or facts)
    table = {
        "why": (f"why {a}", [("unused", a)]),
        "why-not": (f"why not {a}", [("used", a)]),
        "rather-than": (f"why {a} rather than {b}", [("unused", a), ("used", b)]),
        "before": (f"why {a} before {b}", [("before", b, a)]),
        "after": (f"why {a} after {b}", [("before", a, b)]),
        "at": (f"why {a} at {t}", [("not_at", a, t)]),
        "not-at": (f"why not {a} at {t}", [("at", a, t)]),
        "within": (f"why {a} within {t1}..{t2}", [("not_within", a, t1, t2)]),
        "not-within": (f"why not {a} within {t1}..{t2}", [("within", a, t1, t2)]),
        "ends": (f"why {f}", [("ends", f, False)]),
        "not-ends": (f"why not {f}", [("ends", f, True)]),
        "fact-at": (f"why {f} at {t}", [("fact_at", f, False, t)]),
        "not-fact-at": (f"why not {f} at {t}", [("fact_at", f, True, t)]),
        "length": (
            f"why not in {max(len(plan) - 1, 0)} steps",
            [("at_most", max(len(plan) - 1, 0))],
        ),
    }
    text, terms = table[form]
    return text, terms, [_asp(term) for term in terms]


def solvable(seed: int, **kinds):
    """The first random model from ``seed`` on that has a plan."""
    while True:
        spec = random_model(seed, **kinds)
        if spec.shortest_plan_length() is not None:
            return spec, seed
        seed += 1 << 20


def _asp(term: tuple) -> str:
    return f"{term[0]}({','.join(_b(x) if isinstance(x, bool) else str(x) for x in term[1:])})"


def presupposition_fails(spec, plan, form, terms, text) -> bool:
    """The question asks about what the plan does not do: "why A rather than B"
    about a plan without A; "why A before B" about one without a B, or whose
    first B comes before any A ("after": without an A, or whose first A comes
    before any B); or the plan already meets the contrast."""
    words = text.split()
    if form in ("rather-than", "before", "after") and words[1] not in plan:
        return True
    if form in ("before", "after") and words[3] not in plan:
        return True
    return all(meets(spec, plan, term) for term in terms)


@settings(max_examples=150, deadline=None)
@given(
    st.integers(min_value=0, max_value=10**9),
    st.sampled_from(PRINCIPLES),
    st.sampled_from(FORMS),
    st.sampled_from(sorted(KINDS)),
)
def test_every_form_against_brute_force(seed, under, form, kind):
    spec, seed = solvable(seed, **KINDS[kind])
    rng = random.Random(seed)
    plan = plan_through(spec, rng, rng.randint(0, 2)) or plan_through(spec, rng, 0)
    text, terms, written = question(form, spec, plan, rng)
    model = Model.from_string(spec.to_asp())
    try:
        answer = ask(
            model,
            text,
            plan=Plan.parse(" ".join(plan)),
            principle="deontology",
            under=under,
            max_horizon=MAX_HORIZON,
        )
    except InputError as error:
        assert presupposition_fails(spec, plan, form, terms, text), str(error)
    else:
        assert not presupposition_fails(spec, plan, form, terms, text)
        check_answer(spec, answer, terms, written, under)


def check_answer(spec, answer, terms, written, under) -> None:
    """The answer to a question whose presupposition holds, against brute force."""
    assert [str(c) for c in answer.constraints] == written
    permissible = shortest_meeting(spec, terms, [under])
    anyhow = shortest_meeting(spec, terms)
    if answer.contrast is not None:
        contrast = [str(x) for x in answer.contrast.plan]
        assert spec.is_plan(contrast)
        assert all(meets(spec, contrast, term) for term in terms), (contrast, terms)
        if answer.principle_dropped:
            assert permissible is None and len(contrast) == anyhow
        else:
            assert spec.permissible(contrast, under)
            assert len(contrast) == permissible, (contrast, permissible)
        assert answer.contrast.judgement.permissible == spec.permissible(contrast, under)
    elif answer.status == "none":
        assert anyhow is None
        conflict = [
            term
            for term, c in zip(terms, written, strict=True)
            if c in {str(x) for x in answer.conflict}
        ]
        assert conflict and shortest_meeting(spec, conflict) is None
    else:
        # Bounded: the searches were cut at the maximal horizon without a proof.
        assert answer.status == "bounded"
        assert permissible is None or permissible > MAX_HORIZON
    # The principle is dropped exactly when no plan meeting the question is
    # permissible under it (proven) and some plan meets the question.
    if answer.principle_dropped:
        assert permissible is None and anyhow is not None
    elif permissible is None and anyhow is not None and anyhow <= MAX_HORIZON:
        assert answer.status == "bounded"  # no proof found: not dropped


def _node(node):
    """A link's end as the oracle writes it."""
    if node.kind == "step":
        return node.step
    if node.kind == "event":
        return ("event", node.step, str(node.event))
    return "goal"


@settings(max_examples=150, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.sampled_from(sorted(KINDS)))
def test_links_and_removable_steps_against_brute_force(seed, kind):
    spec, seed = solvable(seed, **KINDS[kind])
    rng = random.Random(seed)
    plan = plan_through(spec, rng, rng.randint(0, 4)) or plan_through(spec, rng, 0)
    model = Model.from_string(spec.to_asp())
    explanation = explain_steps(model, Plan.parse(" ".join(plan)))
    found = set()
    for link in explanation.links:
        kind_of = ("condition", str(link.effect)) if link.kind == "condition" else link.kind
        found.add(
            (
                _node(link.provider),
                _node(link.consumer),
                str(link.variable),
                link.value,
                kind_of,
                None if link.via is None else str(link.via),
            )
        )
    expected = links(spec, plan)
    assert found == expected, (found - expected, expected - found)
    assert {step.step for step in explanation.steps if step.removable} == removable(spec, plan)
    serves = serving(expected)
    caused = causes(spec, plan)
    edges = {(link[0], link[1]) for link in expected}
    for step in explanation.steps:
        action = plan[step.step - 1]
        assert step.utility == spec.action_utility.get(action, 0)
        assert step.bad == spec.bad_action(action)
        assert {(str(v), b, u) for v, b, u in step.causes} == caused[step.step]
        # A step serves the goal when links lead from it to the goal; its chain
        # starts at it, follows links and ends at the goal.
        assert step.serves_goal == (step.step in serves)
        if step.chain:
            chain = [_node(node) for node in step.chain]
            assert chain[0] == step.step and chain[-1] == "goal"
            assert all(pair in edges for pair in itertools.pairwise(chain)), chain
    # Events are listed with the links from what they set.
    assert {(e.step, str(e.event)) for e in explanation.events if e.links} == {
        link[0][1:] for link in expected if isinstance(link[0], tuple)
    }


@settings(max_examples=60, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.integers(0, 5))
def test_a_sequence_that_misses_goal_facts_is_explained_against_those_it_reaches(seed, walk):
    """A HERA situation's plan may miss its goal: an executable sequence is
    explained as the plan it is of the goal facts it reaches (links,
    removable steps, E-links and D-links by the oracles on the model with that
    goal), and the goal facts it misses are named."""
    spec = random_model(seed, max_variables=5, max_actions=5, **features(seed))
    rng = random.Random(seed)
    sequence, config = [], (spec.init, 0)
    for _ in range(walk):
        options = [a for a in spec.actions if spec.applicable(config[0], a)]
        if not options:
            break
        sequence.append(rng.choice(options))
        config = spec.successor(config, sequence[-1])
    final = spec.run(sequence)
    assert final is not None  # every step was applicable
    reached = {v: b for v, b in spec.goal.items() if spec.satisfies(final, {v: b})}
    missed = {(v, b) for v, b in spec.goal.items() if v not in reached}
    explanation = explain_steps(
        Model.from_string(spec.to_asp()), Plan.parse(" ".join(sequence)), allow_missed_goal=True
    )
    assert {(str(v), b) for v, b in explanation.unmet_goal} == missed
    data = explanation.to_json()
    assert data.get("goal_reached", True) is not bool(missed)
    met = dataclasses.replace(spec, goal=reached)
    found_links = {
        (
            _node(link.provider),
            _node(link.consumer),
            str(link.variable),
            link.value,
            ("condition", str(link.effect)) if link.kind == "condition" else link.kind,
            None if link.via is None else str(link.via),
        )
        for link in explanation.links
    }
    assert found_links == links(met, sequence)
    assert {step.step for step in explanation.steps if step.removable} == removable(met, sequence)
    expected_e, expected_d = e_and_d_links(met, sequence)
    assert links_of_json(data["d_links"]) == expected_d, (spec, sequence)
    assert links_of_json(data["e_links"]) == expected_e, (spec, sequence)
    if missed:
        assert explanation.text.startswith("The plan does not reach its goal: ")
