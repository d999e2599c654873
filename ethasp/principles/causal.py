"""Choices in causal agency models (HERA's CAMs): their evaluation.

In a CAM (:mod:`ethasp.planning.readers.cam`) an agent chooses one of its
actions; its plans are those actions, one at a time.  A choice is evaluated
by one small program over the model's facts: the worlds of the actions and
of the interventions the formulas need (``encodings/cam/world.lp``), HERA's
causal notions (``cam/causes.lp``, ``cam/alternatives.lp``), the meaning of
the operators of L for a choice (``cam/language.lp``), the formulas of the
principles (``encodings/principles/cam/``, evaluated by
``judgement/language.lp``), and what a judgement reports (``cam/report.lp``).
Each evaluation is computed once per choice and set of formulas.

Python decides nothing here: it checks that a plan is one action of the
model, and reads the world, the utility of the consequences and what the
action causes back from the answer set.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import clingo

from ethasp.errors import InputError
from ethasp.memo import results
from ethasp.planning.driver.planner import Answer
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.principles.principle import CAM, PLAN

WORLDS = (
    "planning/model.lp",
    "cam/model.lp",
    "cam/world.lp",
    "cam/causes.lp",
    "cam/alternatives.lp",
)
# The worlds of interventions depend on the values of the actions' worlds, so
# the grounder leaves these programs to the solver (which finds their one
# answer set).  clasp's equivalence preprocessing (clingo 5.8) wrongly finds
# some of them unsatisfiable (a random model of 30 variables under
# hera-utilitarianism); without it they are solved right.
SOLVING = ("--eq=0",)
LANGUAGE = (
    *WORLDS,
    "cam/language.lp",
    "judgement/language.lp",
    "judgement/evidence.lp",
    "cam/report.lp",
)


# The vocabulary of CAMs beyond the planning model's (cam/model.lp).
VOCABULARY = (
    ("cam_action", 2),
    ("cam_background", 1),
    ("cam_event", 1),
    ("cam_consequence", 2),
    ("cam_mechanism", 2),
    ("cam_intention", 3),
    ("cam_goal", 3),
)


def model_kind(model: Model) -> str:
    """The kind of model, as principles are defined for: ``cam`` or ``plan``."""
    return CAM if model.is_cam else PLAN


def actions(model: Model) -> list[clingo.Symbol]:
    """A CAM's actions, in the order of its file."""
    found = sorted(
        (atom.arguments[1].number, atom.arguments[0]) for atom in model.planner.get("cam_action", 2)
    )
    return [action for _, action in found]


def description(model: Model) -> str | None:
    """What a CAM describes (its ``description``), if it says."""
    for atom in model.planner.get("cam_description", 1):
        return atom.arguments[0].string
    return None


def chosen_action(model: Model, plan: Plan) -> clingo.Symbol:
    """The action a plan of a CAM chooses; one line unless the plan is one of
    the model's actions."""
    known = actions(model)
    names = ", ".join(map(model.naming.action, known))
    if len(plan) != 1:
        raise InputError(
            f"a choice in a causal agency model is one action, not {len(plan)} (its "
            f"actions: {names})"
        )
    action = plan.actions[0]
    if action not in known:
        raise InputError(
            f"unknown action {model.naming.action(action)} of the causal agency model "
            f"(its actions: {names})"
        )
    return action


def evaluation(
    model: Model,
    plan: Plan,
    encodings: Sequence[str] = (),
    facts: Iterable[clingo.Symbol] = (),
) -> Answer:
    """The evaluation of a choice: the world, the utility of its consequences
    and its direct consequences (``cam/report.lp``), the verdicts of the
    formulas of the ``encodings`` and of ``facts`` (``formula/2``, ``conj/3``),
    and the atoms reasons read (``judgement/evidence.lp``); once per choice."""
    action = chosen_action(model, plan)
    extra = tuple(facts)
    key = ("cam evaluation", action, tuple(sorted(encodings)), extra)
    memo = results(model.planner)
    if key not in memo:
        planner = model.planner
        memo[key] = planner.solve_program(
            [*LANGUAGE, *sorted(encodings)],
            planner.vocabulary_text(VOCABULARY),
            symbols=[clingo.Function("cam_chosen", [action]), *extra],
            arguments=SOLVING,
        )
    return memo[key]


QUESTIONS = (*WORLDS, "cam/questions.lp", "questions/questions.lp")


def met_constraints(model: Model, plan: Plan, terms: Sequence[clingo.Symbol]) -> set[clingo.Symbol]:
    """The constraint terms of contrastive questions (``contrast(Q,C)``,
    ``encodings/questions/questions.lp``) that a choice meets."""
    action = chosen_action(model, plan)
    key = ("cam met", action, tuple(terms))
    memo = results(model.planner)
    if key not in memo:
        name = clingo.Function("q")
        planner = model.planner
        answer = planner.solve_program(
            QUESTIONS,
            planner.vocabulary_text(VOCABULARY),
            symbols=[
                clingo.Function("cam_chosen", [action]),
                *(clingo.Function("contrast", [name, term]) for term in terms),
            ],
            arguments=SOLVING,
        )
        memo[key] = {atom.arguments[1] for atom in answer.get("met", 3)}
    return memo[key]


def world(model: Model, answer: Answer) -> tuple[list[str], int, list[str]]:
    """The world of an evaluated choice as literals (``v``, ``-v``, in the
    order of the model's variables), the utility of its consequences, and the
    facts of consequences the action causes."""
    values = {
        atom.arguments[0]: atom.arguments[1].name == "true" for atom in answer.get("final", 2)
    }
    order = [atom.arguments[0] for atom in model.planner.get("variable", 1)]
    literals = [str(v) if values[v] else f"-{v}" for v in order if v in values]
    utility = next(atom.arguments[0].number for atom in answer.get("cam_utility", 1))
    position = {variable: index for index, variable in enumerate(order)}
    caused = sorted(
        answer.get("cam_caused_fact", 2), key=lambda atom: position.get(atom.arguments[0], 0)
    )
    direct = [
        str(atom.arguments[0]) if atom.arguments[1].name == "true" else f"-{atom.arguments[0]}"
        for atom in caused
    ]
    return literals, utility, direct
