"""HModels: restrictions compiled into planning models (the paper's Pi x e).

A restriction (a principle's, or a constraint of a contrastive question) is
a planning model: the paper defines the HModel of deontology as the model
without the bad actions, that of utilitarianism as the model whose goal also
asks for a best reachable state, that of do-no-harm as the model with
variables that record what the plan produced.  Each restriction's encoding
(``encodings/restrictions/P.lp`` for a principle P,
``encodings/questions/restriction.lp`` for question constraints) says what
it removes from the model and what it adds; ``encodings/restrictions/
hmodel.lp`` writes the HModel's facts.  They are computed by one clingo call
over the model's ground facts, and the HModel is a :class:`Model` of those
facts, with its own planner (grounded once): plan search in it is plain plan
search, with every engine (the encodings, relaxed reachability, exact layers,
greedy search, mutexes), and its proofs ("none", lower bounds) are proofs
about the restricted plans.

HModels are kept per model and restriction, so that a dialogue asks each
once.  The plans of an HModel are action sequences of the model: the HModel
keeps the model's action names and adds only state variables named
``ethasp(...)`` (a name models may not use), their effects and goals.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import clingo

from ethasp.memo import results
from ethasp.planning.model import Model

# A literal: a state (or derived) variable and its value.
Literal = tuple[clingo.Symbol, bool]

HMODEL = "restrictions/hmodel.lp"
QUESTIONS = "questions/restriction.lp"
QUESTION_RULES = "questions/questions.lp"
RELAXED = "planning/relaxed.lp"
RESTRICTIONS = "restrictions"
MODEL = "planning/model.lp"

# Constraint terms of questions that questions/restriction.lp compiles
# (at_most(N) is the search's maximal horizon and cheaper_than(C) its cost
# bound: the HModel leaves them out).
COMPILED_CONSTRAINTS = (
    "unused",
    "used",
    "before",
    "ends",
    "at",
    "not_at",
    "within",
    "not_within",
    "fact_at",
    "at_most",
    "cheaper_than",
)


@dataclass(frozen=True)
class Restriction:
    """What an HModel restricts: principles (ASP names), question constraint
    terms and the best reachable utility (utilitarianism's input)."""

    principles: tuple[str, ...] = ()
    terms: tuple[clingo.Symbol, ...] = ()
    best_utility: int | None = None
    soft: bool = False

    @classmethod
    def of(
        cls,
        principles: Iterable[str] = (),
        terms: Iterable[clingo.Symbol] = (),
        best_utility: int | None = None,
        soft: bool = False,
    ) -> Restriction:
        return cls(
            tuple(sorted(set(principles))),
            tuple(sorted(set(terms), key=str)),
            best_utility,
            soft,
        )

    @property
    def empty(self) -> bool:
        return not self.principles and not self.terms and not self.soft

    def describe(self) -> str:
        parts = list(self.principles) + [str(term) for term in self.terms]
        return ", ".join(parts) or "nothing"


def compiled(term: clingo.Symbol, derived: frozenset = frozenset()) -> bool:
    """Is a question constraint term one that questions/restriction.lp compiles?
    (``fact_at`` of a derived variable (in ``derived``) is not: the event that
    records a fact reads state variables only.)"""
    if term.type != clingo.SymbolType.Function or term.name not in COMPILED_CONSTRAINTS:
        return False
    return not (term.name == "fact_at" and term.arguments[0] in derived)


def hmodel(model: Model, restriction: Restriction) -> Model:
    """The HModel of the model under the restriction (made once per model and
    restriction): a model whose plans are the model's plans that satisfy it
    (the model itself where the restriction removes and adds nothing).  It
    is planned for as the model is (its ``planning_system``)."""
    made = _made(model, restriction)[0]
    made.planning_system = model.planning_system
    return made


def goal_items(model: Model, restriction: Restriction) -> dict[clingo.Symbol, list[Literal]]:
    """The items of the goal of a soft HModel (``restriction.soft``): for each
    goal fact ``goal(V,B)`` of the model and each question constraint term, the
    literals (V, B) it requires at the end of a plan of the HModel (its
    ``goal_of/3``; goal-deontology adds an unreachable literal to a bad goal
    fact's item).  The HModel itself requires none of them."""
    if not restriction.soft:
        raise ValueError("the goal items of an HModel whose goal is not soft")
    return _made(model, restriction)[2]


def impossible(model: Model, restriction: Restriction) -> list[tuple[clingo.Symbol, str]]:
    """The restriction's question constraints that no plan can meet, known
    before any search (``questions/questions.lp`` over the model and its
    relaxed reachability), each with why: ``goal`` (it contradicts the goal)
    or ``relaxed`` (it needs an action or a fact that relaxed reachability
    excludes)."""
    return _made(model, restriction)[1]


def _made(model: Model, restriction: Restriction):
    made = results(model).setdefault("hmodels", {})
    planner = model.planner
    with planner.lock:  # one compilation per restriction, whichever thread asks
        if restriction not in made:
            made[restriction] = _compile(model, restriction)
        return made[restriction]


# What questions.lp knows of a question before any search (its rules without a step).
IMPOSSIBLE = (("question_against_goal", "goal"), ("question_unreachable", "relaxed"))


def _compile(model: Model, restriction: Restriction):
    encodings = [MODEL, HMODEL]
    encodings += [f"{RESTRICTIONS}/{principle}.lp" for principle in restriction.principles]
    inputs: list[clingo.Symbol] = []
    question = clingo.Function("q")
    if restriction.terms:
        encodings += [QUESTIONS]
        if not restriction.soft:
            encodings += [RELAXED, QUESTION_RULES]
        inputs += [clingo.Function("contrast", [question, term]) for term in restriction.terms]
    if restriction.best_utility is not None:
        inputs.append(clingo.Function("best_utility", [clingo.Number(restriction.best_utility)]))
    if restriction.soft:
        inputs.append(clingo.Function("soft_goals"))
    shown = "#show restricts/0. #show goal_of/3.\n"
    if restriction.terms and not restriction.soft:
        shown += "".join(f"#show {name}/2.\n" for name, _ in IMPOSSIBLE)
    answer = model.planner.solve_program(encodings, shown, symbols=inputs)
    found = []
    for name, why in IMPOSSIBLE:
        found += [(atom.arguments[1], why) for atom in answer.get(name, 2)]
    items: dict[clingo.Symbol, list[Literal]] = {}
    for atom in sorted(answer.get("goal_of", 3)):
        item, variable, value = atom.arguments
        items.setdefault(item, []).append((variable, value.name == "true"))
    if not answer.get("restricts", 0):
        # The restriction changes nothing (deontology without bad actions, ...):
        # the HModel is the model itself, with its one grounding.
        return model, sorted(found, key=str), items
    facts = [atom.arguments[0] for atom in answer.get("hmodel", 1)]
    kind = "soft HModel" if restriction.soft else "HModel"
    return (
        Model.of_facts(f"<{kind} of {restriction.describe()}>", facts, model.naming),
        sorted(found, key=str),
        items,
    )
