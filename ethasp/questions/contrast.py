"""Contrastive questions answered (steps 1 to 5 of the paper's iterative process).

A question "Why A rather than B?" (or any form of :mod:`ethasp.questions.question`)
about the original plan becomes constraint facts (``contrast(Q,C)``) that the
fixed encoding ``encodings/questions/questions.lp`` reads.  The question's
constraints and the chosen principle restrict the model (the HModel,
:mod:`ethasp.principles.restriction`), which is solved for the contrast plan
(the HPlan).  If the search proves that the HModel has no plan (status
``none``), the principle is dropped and the model solved again (step 3), so
that the explanation shows why the contrast is impermissible; if the search
under the principle was cut short (``bounded``), the principle is kept and
the answer is ``bounded``.  If no plan meets the question at all (proven), a
minimal subset of the constraints that conflict is found with solver
assumptions (each constraint is switched on by an assumption on
``active(Q,C)``).  Both plans are judged and explained (step 4,
:mod:`ethasp.principles.judgement`), and the contrastive explanation sets the
reasons of the two side by side (step 5).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import clingo

from ethasp.errors import InputError
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import Constraint
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan, parse_action, steps
from ethasp.planning.search import BOUNDED, DEFAULT_MAX_HORIZON, FOUND, NONE
from ethasp.planning.validation import static_failures, validate
from ethasp.principles import causal
from ethasp.principles.causal import model_kind
from ethasp.principles.judgement import Judgement, check_plan
from ethasp.principles.principle import GROUPS, PLAN, available_principles, select_principles
from ethasp.principles.restriction import (
    HPlanResult,
    one_restricting_principle,
    plan_with_principles,
)
from ethasp.questions.impasse import Impasse, impasse
from ethasp.questions.question import EITHER, Question
from ethasp.reasons import words
from ethasp.reasons.reasons import DEFAULT_LIMIT, judge

DEFAULT_PRINCIPLE = "deontology"
DEFAULT_CAM_PRINCIPLE = "hera-deontology"  # the same concept, for causal agency models


@dataclass(frozen=True)
class Resolved:
    """A question with its names resolved against a model: whether it is about
    a fact, its constraint terms, and what the plan asked about must meet."""

    question: Question
    fact: bool
    terms: list[clingo.Symbol]
    presupposed: list[clingo.Symbol]


def _is_variable(model: Model, term: clingo.Symbol) -> bool:
    return model.planner.defines("variable", term) or model.planner.defines("derived", term)


def _unknown_action(model: Model, question: Question, term: clingo.Symbol, also: str = "") -> str:
    """The one line for a name that is no action of the model."""
    failing = static_failures(model, [term])
    if failing:
        facts = ", ".join(map(model.naming.fact, failing[term]))
        return (
            f"question '{question}': action {model.naming.action(term)} never applies: "
            f"precondition {facts} does not hold and no action changes it"
        )
    return f"question '{question}': unknown action {model.naming.action(term)}{also}"


def _resolve_choice(model: Model, question: Question) -> Resolved:
    """Resolve the names of a question about a choice in a causal agency model:
    a choice is one action, so a question asks why A, why not B, why A rather
    than B, or why (not) F of its world; an action's name is read as the
    action unless the question says ``fact``."""
    if question.kind not in ("why", "why-not", "rather-than") or (
        question.at is not None or question.within is not None
    ):
        raise InputError(
            f"question '{question}': a choice in a causal agency model is one action; "
            "ask why A, why not B, why A rather than B, or why (not) F"
        )
    actions = causal.actions(model)
    subject = parse_action(question.action) if question.action is not None else None
    other = parse_action(question.other) if question.other is not None else None
    fact = question.what == "fact" or (question.what is None and subject not in actions)
    names = ", ".join(map(model.naming.action, actions))
    if fact and not _is_variable(model, subject):
        raise InputError(f"question '{question}': unknown action or variable {subject}")
    for term in (subject, other) if not fact else (other,):
        if term is not None and term not in actions:
            raise InputError(
                f"question '{question}': unknown action {model.naming.action(term)} "
                f"(the actions: {names})"
            )
    return Resolved(
        question, fact, question.contrasts(subject, other, fact), question.presupposes(subject)
    )


def resolve(model: Model, question: Question) -> Resolved:
    """Resolve the names of a question: an action or a state variable (one line
    for a name that is both, unless the question says which, or neither)."""
    if model.is_cam:
        return _resolve_choice(model, question)
    if question.kind == "cheaper":
        raise InputError(
            f"question '{question}': its contrast is the cost of the plan asked about "
            "(see check_question)"
        )
    subject = parse_action(question.action) if question.action is not None else None
    other = parse_action(question.other) if question.other is not None else None
    fact = False
    if question.kind in EITHER:
        is_action = model.planner.defines("action", subject)
        is_variable = _is_variable(model, subject)
        if question.what is None and is_action and is_variable:
            raise InputError(
                f"question '{question}': {question.action} is both an action and a "
                f"state variable; say which: '{question.about_fact(False)}' or "
                f"'{question.about_fact(True)}'"
            )
        if question.what == "fact" or (question.what is None and is_variable and not is_action):
            if not is_variable:
                raise InputError(f"question '{question}': unknown state variable {subject}")
            fact = True
        elif not is_action:
            raise InputError(
                _unknown_action(
                    model, question, subject, "" if question.what else " (nor a state variable)"
                )
            )
        if fact and question.within is not None:
            raise InputError(
                f"question '{question}': {question.action} is a state variable; a "
                "window of steps applies to actions (ask: why [not] F at T)"
            )
    else:
        for term in (subject, other):
            if term is not None and not model.planner.defines("action", term):
                raise InputError(_unknown_action(model, question, term))
    return Resolved(
        question,
        fact,
        question.contrasts(subject, other, fact),
        question.presupposes(subject, other),
    )


def _met(model: Model, plan: Plan, terms: Sequence[clingo.Symbol]) -> set[clingo.Symbol]:
    """The constraint terms that the plan meets (a causal agency model's
    choice, or a plan: :meth:`ethasp.planning.driver.planner.Planner.met`)."""
    if model.is_cam:
        return causal.met_constraints(model, plan, terms)
    return model.planner.met(plan, terms)


def _subject_words(model: Model, resolved: Resolved) -> str:
    question = resolved.question
    if resolved.fact:
        return model.naming.fact(str(parse_action(question.action)))
    return model.naming.action(parse_action(question.action))


def _already(model: Model, resolved: Resolved, plan: Plan) -> str:
    """Why the plan already meets a question's contrast, in words."""
    question, naming = resolved.question, model.naming
    name = _subject_words(model, resolved) if question.action is not None else ""
    other = naming.action(parse_action(question.other)) if question.other else ""
    kind, length = question.kind, len(plan)
    if kind == "length":
        return f"the plan has {steps(length)}, at most {question.steps}"
    if kind == "rather-than":
        return f"the plan does not use {name} and uses {other}"
    if kind in ("before", "after"):
        # The contrast is met: the first B (before) or the first A (after)
        # comes before any of the other.
        first, then = (other, name) if kind == "before" else (name, other)
        term = parse_action(question.other if kind == "before" else question.action)
        at = plan.actions.index(term) + 1
        return f"the plan does not use {then} before its first {first} (step {at})"
    negative = kind == "why"
    if resolved.fact:
        value = "false" if negative else "true"
        if question.at is not None and question.at > length:
            return f"{name} is {value} at the end of the plan, which has only {steps(length)}"
        where = f"after step {question.at}" if question.at is not None else "at the end of the plan"
        return f"{name} is {'already ' if not negative else ''}{value} {where}"
    if question.at is not None:
        if negative:
            if question.at > length:
                return f"the plan has only {steps(length)}"
            there = naming.action(plan.actions[question.at - 1])
            return f"step {question.at} of the plan is {there}"
        return f"step {question.at} of the plan already is {name}"
    if question.within is not None:
        first, last = question.within
        if negative:
            return f"the plan does not use {name} at any step from {first} to {last}"
        term = parse_action(question.action)
        at = next(
            step for step in range(first, min(last, length) + 1) if plan.actions[step - 1] == term
        )
        return f"the plan already uses {name} at step {at}"
    return f"the plan does not use {name}" if negative else f"the plan already uses {name}"


def check_question(model: Model, question: Question, plan: Plan) -> list[Constraint]:
    """The question's constraints, after checking it against the plan it is about.

    Raises InputError (one line) if it names an action or state variable the
    model lacks, or a name that is both, or if its presupposition fails: the
    plan already meets all its constraints (then there is nothing to
    contrast: e.g. "why not A" about a plan that uses A, "why F" about a plan
    that ends with F false, "why A before B" about a plan whose first B comes
    before any A), or a question about two actions names an A (for ``before``
    and ``after`` also a B) that the plan does not use.
    """
    if question.kind == "cheaper":
        return [
            Constraint(clingo.Function("q", [clingo.Number(1)]), _cheaper(model, question, plan))
        ]
    resolved = resolve(model, question)
    met = _met(model, plan, resolved.terms + resolved.presupposed)
    for term in resolved.presupposed:
        if term not in met:
            raise InputError(
                f"question '{question}': the plan does not use "
                f"{model.naming.action(term.arguments[0])}; ask about what the plan does"
            )
    if all(term in met for term in resolved.terms):
        raise InputError(
            f"question '{question}': {_already(model, resolved, plan)} (the plan "
            f"already meets its contrast "
            f"{', '.join(model.naming.constraint(t) for t in resolved.terms)}); "
            "ask about what the plan does"
        )
    return [Constraint(clingo.Function("q", [clingo.Number(1)]), term) for term in resolved.terms]


def _cheaper(model: Model, question: Question, plan: Plan) -> clingo.Symbol:
    """The constraint of ``why not a cheaper plan``: ``cheaper_than(C)``, C the
    plan's cost (one line where the model has no costs or the plan costs 0)."""
    if not model.planner.has_costs:
        raise InputError(
            f"question '{question}': the model has no action costs (cost/2), so plans "
            "cost their number of steps: ask 'why not in N steps'"
        )
    cost = validate(model, plan).cost or 0
    if cost == 0:
        raise InputError(f"question '{question}': the plan costs 0, and no plan costs less")
    return clingo.Function("cheaper_than", [clingo.Number(cost)])


def cost_bound(constraints: Sequence[Constraint]) -> int | None:
    """The cost every plan meeting the constraints must stay below (their
    ``cheaper_than(C)``), or None."""
    bounds = [
        c.term.arguments[0].number
        for c in constraints
        if c.term.name == "cheaper_than" and len(c.term.arguments) == 1
    ]
    return min(bounds) if bounds else None


def beyond_horizon(question: Question, terms: Sequence[clingo.Symbol], max_horizon: int) -> str:
    """Why a question cannot be searched within ``max_horizon`` steps: the
    empty text if it can.  A question that needs a step beyond the horizon
    (``why not A at T``, ``why not A within T1..T2`` with T1 beyond it) is
    answered ``bounded`` without a search; one that only names such a step
    (``why A at T``, ``why F at T``, a window that ends beyond it) is
    refused in one line (InputError).  Either way nothing is grounded for it:
    a step of a question is a horizon of its own (``questions/
    restriction.lp`` counts the steps up to it)."""
    for term in terms:
        steps_named = [
            argument.number
            for argument in term.arguments
            if argument.type == clingo.SymbolType.Number
        ]
        bounds = term.name in ("at_most", "cheaper_than")
        if bounds or not steps_named or max(steps_named) <= max_horizon:
            continue
        first = steps_named[0]
        if term.name in ("at", "within") and first > max_horizon:
            return (
                f"the question needs an action at step {first}, beyond the maximal horizon "
                f"{max_horizon}: no plan up to horizon {max_horizon} has one "
                "(--max-horizon N searches further)"
            )
        raise InputError(
            f"question '{question}': step {max(steps_named)} is beyond the maximal horizon "
            f"{max_horizon}, where no plan is searched; ask about steps up to "
            f"{max_horizon}, or raise it with --max-horizon N"
        )
    return ""


def longest(constraints: Sequence[Constraint]) -> int | None:
    """The most steps a plan meeting the constraints may have (their
    ``at_most(N)``), or None."""
    bounds = [
        c.term.arguments[0].number
        for c in constraints
        if c.term.name == "at_most" and len(c.term.arguments) == 1
    ]
    return min(bounds) if bounds else None


# -- the contrast plan -------------------------------------------------------------


@dataclass
class ContrastSearch:
    """The search for the contrast plan: the HPlan, with the principle or without.

    ``principle_dropped``: the search under the principle proved that no plan
    meeting the constraints is permissible (``dropped_because``), and the
    plan was searched without it; ``note``: what else was learnt (a plan
    meeting the constraints without the principle, when the search under it
    was cut short and the principle therefore kept); ``impermissible``: no
    plan meeting the constraints is permissible under the principle (proven),
    and none meeting them was found without it (bounded).
    """

    result: HPlanResult
    principle_dropped: bool
    conflict: list[Constraint] = field(default_factory=list)
    dropped_because: str = ""
    note: str = ""
    impermissible: bool = False


def minimal_conflict(
    model: Model, constraints: Sequence[Constraint], max_horizon: int, budget: Budget
) -> list[Constraint]:
    """A subset-minimal set of constraints under which the model has no plan (proven).

    Deletion-based: a constraint is left out whenever the others still have no
    plan, proven; a search cut by the horizon or the budget keeps the constraint.
    Every search runs on the model's one grounding, the constraints switched
    by assumptions.
    """
    core = list(constraints)
    for constraint in list(core):
        trial = [c for c in core if c != constraint]
        if (
            plan_with_principles(
                model,
                [],
                max_horizon,
                constraints=trial,
                budget=budget,
                max_length=longest(trial),
                below=cost_bound(trial),
            ).status
            == NONE
        ):
            core = trial
    return core


def contrast_plan(
    model: Model,
    constraints: Sequence[Constraint],
    under: str,
    max_horizon: int = DEFAULT_MAX_HORIZON,
    time_limit: float | None = None,
    budget: Budget | None = None,
    satisficing: bool = False,
) -> ContrastSearch:
    """The HPlan of the constraints and the principle ``under`` (steps 2 and 3);
    with ``satisficing`` any such plan, not proven shortest.

    The principle is dropped only on a proof (status ``none``) that no plan
    meeting the constraints is permissible under it; a search under it that
    ended ``bounded`` (the maximal horizon, the time limit) keeps it, and the
    answer is ``bounded``.
    """
    budget = budget or Budget(time_limit)
    length = longest(constraints)
    below = cost_bound(constraints)
    result = plan_with_principles(
        model,
        [under],
        max_horizon,
        constraints=constraints,
        budget=budget,
        satisficing=satisficing,
        max_length=length,
        below=below,
    )
    if result.status == FOUND:
        return ContrastSearch(result, False)
    if result.status == BOUNDED and budget.expired():
        return ContrastSearch(result, False)
    # Without the principle: a plan to judge when the principle is proven to stand in
    # the way, or the proof that no plan meets the question at all.
    dropped = plan_with_principles(
        model,
        [],
        max_horizon,
        constraints=constraints,
        budget=budget,
        satisficing=satisficing,
        max_length=length,
        below=below,
    )
    if dropped.status == NONE:
        # No plan meets the question at all: the principle is not what stands in
        # the way, and is not said to be dropped.
        return ContrastSearch(
            dropped, False, minimal_conflict(model, constraints, max_horizon, budget)
        )
    if result.status == NONE:
        if dropped.status == FOUND:
            return ContrastSearch(dropped, True, [], result.proof)
        return ContrastSearch(
            HPlanResult(
                BOUNDED,
                [],
                None,
                dropped.horizon,
                f"{result.proof}; without {under}, {dropped.proof}",
            ),
            False,
            impermissible=True,
        )
    note = ""
    if dropped.status == FOUND and result.plan is None:
        note = (
            f"a plan meeting the question exists without {under} "
            f"({model.naming.actions(dropped.plan) or 'the empty plan'}), but the search "
            f"under {under} was cut short, so {under} is kept: it is dropped only when "
            "no plan meeting the question is proven permissible under it"
        )
    return ContrastSearch(result, False, note=note)


# -- answers -----------------------------------------------------------------------


@dataclass
class Side:
    """One plan of a contrastive explanation, judged under one principle."""

    plan: Plan
    principle: str
    judgement: Judgement
    cost: int | None = None  # the plan's cost, in a model with action costs

    def to_json(self, model: Model | None = None) -> dict:
        explanation = self.judgement.explanation
        return {
            "plan": self.plan.to_list(),
            **({"cost": self.cost} if self.cost is not None else {}),
            "principle": self.principle,
            "permissible": self.judgement.permissible,
            "status": self.judgement.status,
            "sufficient_reasons": explanation.sufficient_reasons if explanation else [],
            "necessary_reasons": explanation.necessary_reasons if explanation else [],
            "inus_reasons": explanation.inus_reasons if explanation else [],
            "reasons_truncated": explanation.truncated if explanation else False,
            "chosen_reason": explanation.chosen_reason if explanation else [],
            "explanation": explanation.text if explanation else "",
        }


@dataclass
class Answer:
    """The answer to contrastive questions about a plan.

    ``original`` is the plan asked about, judged under ``principle``;
    ``contrast`` the contrast plan (HPlan) judged under ``under``, or None if
    there is none.  ``status`` is that of the contrast plan's search (found,
    none: proven, bounded); ``principle_dropped`` says that no plan meeting the
    constraints is permissible under ``under`` (proven: ``dropped_because``),
    so the contrast plan was made without it (and is judged under it);
    ``conflict`` lists a minimal set of constraints that no plan meets.
    ``impasse``: with the principle dropped, the minimal conflicts of the goal
    and the constraints under it, and the cheapest repair, with their words
    (the contrastive explanation stays the paper's).
    ``difference`` holds, for each side, the literals of the reason its words
    give that do not hold of the other plan; ``optimal`` is False when the
    contrast plan comes from an any-plan search (not proven shortest);
    ``note`` says what else was learnt (a plan that meets the question
    without the principle, when the search under it was cut short).
    """

    questions: list[Question]
    principle: str
    under: str
    original: Side
    contrast: Side | None
    status: str
    proof: str
    principle_dropped: bool
    constraints: list[Constraint]
    conflict: list[Constraint]
    difference: dict[str, list[str]]
    explanation: str
    dropped_because: str = ""
    optimal: bool = True
    note: str = ""
    impasse: Impasse | None = None

    @property
    def unmeetable(self) -> bool:
        """No plan meets the constraints imposed (proven, with a conflict)."""
        return self.contrast is None and self.status == NONE and bool(self.conflict)

    def to_json(self) -> dict:
        return {
            "questions": [str(q) for q in self.questions],
            "original": self.original.to_json(),
            "contrast": self.contrast.to_json() if self.contrast else None,
            "constraints": [str(c) for c in self.constraints],
            "status": self.status,
            "optimal": self.optimal if self.contrast else None,
            "proof": self.proof,
            "principle_dropped": self.principle_dropped,
            "principle_dropped_because": self.dropped_because,
            "conflict": [str(c) for c in self.conflict],
            "reason_difference": self.difference,
            "explanation": self.explanation,
            "note": self.note,
            **(self.impasse.to_json() if self.impasse is not None else {}),
        }


def _difference(original: Side, contrast: Side | None) -> dict[str, list[str]]:
    """The literals of the reason each side's words give that do not hold of
    the other plan (its principle's formula has no such atom with that value):
    what tells the two apart.  Nothing without a contrast plan."""
    if contrast is None:
        return {"original_only": [], "contrast_only": []}
    return {
        "original_only": _only(original, contrast),
        "contrast_only": _only(contrast, original),
    }


def _only(side: Side, other: Side) -> list[str]:
    mine, theirs = side.judgement.explanation, other.judgement.explanation
    if mine is None:
        return []
    shared = theirs.actual if theirs is not None else frozenset()
    return [
        text
        for literal, text in zip(mine.literals, mine.spoken_reason, strict=True)
        if literal not in shared
    ]


def _side_sentences(side: Side, modal: str, opening: str, alternatively: bool) -> str:
    explanation = side.judgement.explanation
    labels = explanation.labels
    option = f"{words.agent(labels)} {modal} {words.plan_phrase(labels, side.plan)}."
    option = f"Alternatively, {option}" if alternatively else words.capitalize(option)
    verdict = words.verdict_sentence(explanation, opening, principle=True, pronoun=True)
    if side.judgement.status == BOUNDED:
        verdict = verdict[:-1] + " (as far as searched)."
    return f"{option} {verdict}"


def contrastive_text(
    original: Side,
    contrast: Side | None,
    conflict: Sequence[Constraint],
    status: str,
    under: str = "",
    impermissible: bool = False,
) -> str:
    """The words of a contrastive explanation (step 5).  Without a contrast
    plan: why not (``conflict``: the constraints no plan meets together;
    ``impermissible``: no plan meeting them is permissible under ``under``,
    and none was found without it)."""
    text = _side_sentences(original, "could", "This would be", alternatively=False)
    if contrast is not None:
        return f"{text} {_side_sentences(contrast, 'could', 'Doing so is', alternatively=True)}"
    labels = original.judgement.explanation.labels
    if status == NONE:
        if conflict:
            phrases = [words.constraint_phrase(labels, c.term) for c in conflict]
            return f"{text} There is no alternative plan: no plan can {words.join(phrases)}."
        return f"{text} There is no alternative plan: no plan reaches the goal."
    principle = f" under {words.principle_phrase(under)}" if under else ""
    if impermissible:
        return (
            f"{text} There is no alternative plan that is permissible{principle}, and "
            "none without it was found within the search bounds (one may exist)."
        )
    return (
        f"{text} No alternative plan permissible{principle} was found within the search "
        "bounds (one may exist)."
    )


def _judge_side(
    model: Model, plan: Plan, principle: str, max_horizon: int, budget: Budget, reasons_limit: int
) -> Side:
    report = judge(
        model, plan, [principle], max_horizon, reasons_limit=reasons_limit, budget=budget
    )
    cost = validate(model, plan).cost if model.planner.has_costs else None
    return Side(plan, principle, report.judgements[0], cost)


def original_plan(
    model: Model,
    principle: str,
    max_horizon: int = DEFAULT_MAX_HORIZON,
    time_limit: float | None = None,
    budget: Budget | None = None,
    satisficing: bool = False,
) -> Plan:
    """The plan that plan search under the principle makes (the plan asked about)."""
    result = plan_with_principles(
        model, [principle], max_horizon, time_limit, budget=budget, satisficing=satisficing
    )
    if result.plan is None:
        raise InputError(f"no plan to ask about: {result.proof}")
    return result.plan


def one_principle(name: str, kind: str = PLAN) -> str:
    """The one principle a name names (a plan is judged under one): a group
    (``paper``, ``hera``, ``all``) is refused with one line.  ``kind`` is the
    kind of model (``cam``: a causal agency model)."""
    key = name.strip().lower()
    if key == "all" or key in GROUPS:
        known = ", ".join(p.name for p in available_principles(kind))
        raise InputError(
            f"principle {name!r} names a group; a plan asked about is judged "
            f"under one principle: {known}"
        )
    return select_principles([name], kind)[0].name


def _constraints(model: Model, terms: Sequence[clingo.Symbol], before: int) -> list[Constraint]:
    """The constraints of a question's terms: grounded for plan search in a
    planning model (:meth:`ethasp.planning.driver.planner.Planner.question`),
    numbered after the ``before`` ones in a causal agency model, whose
    choices are each checked."""
    if not model.is_cam:
        return model.planner.question(terms)
    name = clingo.Function("q", [clingo.Number(before + 1)])
    return [Constraint(name, term) for term in terms]


def answer_questions(
    model: Model,
    questions: Sequence[Question],
    plan: Plan,
    principle: str,
    under: str,
    previous: Sequence[Constraint] = (),
    max_horizon: int = DEFAULT_MAX_HORIZON,
    time_limit: float | None = None,
    reasons_limit: int = DEFAULT_LIMIT,
    budget: Budget | None = None,
    satisficing: bool = False,
    conflicting: Sequence[Constraint] = (),
) -> Answer:
    """Answer the questions about ``plan`` (judged under ``principle``) with a
    contrast plan under ``under``; ``previous`` constraints stay imposed.
    With ``satisficing`` the contrast plan is any such plan, not proven
    shortest.  ``conflicting``: a subset of ``previous`` that no plan meets
    (proven before): then no search is needed, and none is made."""
    budget = budget or Budget(time_limit)
    kind = model_kind(model)
    principle = one_principle(principle, kind)
    under = one_restricting_principle(under, kind=kind)
    check_plan(model, plan)
    new: list[Constraint] = []
    beyond = ""
    for question in questions:
        asked = check_question(model, question, plan)
        terms = [constraint.term for constraint in asked]
        why = beyond_horizon(question, terms, max_horizon) if not model.is_cam else ""
        if why:
            beyond = beyond or why
            new += asked  # not registered: nothing is grounded for it
        else:
            new += _constraints(model, terms, len(previous) + len(new))
    constraints = list(dict.fromkeys(list(previous) + new))
    original = _judge_side(model, plan, principle, max_horizon, budget, reasons_limit)
    if beyond:
        search = ContrastSearch(HPlanResult(BOUNDED, [under], None, max_horizon, beyond), False)
    elif conflicting and set(conflicting) <= set(previous):
        search = ContrastSearch(
            HPlanResult(
                NONE,
                [],
                None,
                0,
                (
                    "no plan meets the constraints imposed by the questions before "
                    f"({', '.join(map(str, conflicting))}: proven when they were asked)"
                ),
            ),
            False,
            list(conflicting),
        )
    else:
        search = contrast_plan(
            model, constraints, under, max_horizon, budget=budget, satisficing=satisficing
        )
    contrast = None
    if search.result.plan is not None:
        contrast = _judge_side(model, search.result.plan, under, max_horizon, budget, reasons_limit)
    explanation = contrastive_text(
        original, contrast, search.conflict, search.result.status, under, search.impermissible
    )
    stuck = None
    # A causal agency model has no goal and no steps: every action was judged,
    # and the contrast's judgement says why the principle forbids it.
    if search.principle_dropped and not model.is_cam and not budget.expired():
        # (principle_dropped: the search under it proved no plan permissible)
        stuck = impasse(
            model, under, constraints, max_horizon, budget, reasons_limit, unreachable=True
        )
    return Answer(
        list(questions),
        principle,
        under,
        original,
        contrast,
        search.result.status,
        search.result.proof,
        search.principle_dropped,
        constraints,
        search.conflict,
        _difference(original, contrast),
        explanation,
        search.dropped_because,
        search.result.optimal,
        search.note,
        stuck,
    )


def ask(
    model: Model,
    question: str | Question | Sequence[str | Question],
    plan: Plan | None = None,
    principle: str = DEFAULT_PRINCIPLE,
    under: str | None = None,
    max_horizon: int = DEFAULT_MAX_HORIZON,
    time_limit: float | None = None,
    reasons_limit: int = DEFAULT_LIMIT,
    budget: Budget | None = None,
    satisficing: bool = False,
) -> Answer:
    """Ask "why A rather than B?" (or any form of :mod:`ethasp.questions.question`)
    about a plan.

    The plan asked about is ``plan``, or else the plan the model comes with
    (a HERA situation's), or else the plan that plan search under
    ``principle`` makes; it is judged under ``principle``.  The contrast plan
    must satisfy ``under`` (default: ``principle``; a principle that can
    restrict plan search).  Questions are text (see
    :mod:`ethasp.questions.question`) or :class:`Question` objects.  With
    ``satisficing``, both plans that are searched (the plan asked about when
    none is given, and the contrast plan) come from any-plan searches: found
    fast, permissible, not proven shortest.
    """
    items = [question] if isinstance(question, (str, Question)) else list(question)
    questions = [q if isinstance(q, Question) else Question.parse(q) for q in items]
    if not questions:
        raise InputError("no question given")
    budget = budget or Budget(time_limit)
    kind = model_kind(model)
    if model.is_cam and principle == DEFAULT_PRINCIPLE:
        principle = DEFAULT_CAM_PRINCIPLE
    one_principle(principle, kind)
    one_restricting_principle(under or principle, kind=kind)
    if plan is None:
        plan = model.own_plan()
    if plan is None:
        plan = original_plan(model, principle, max_horizon, budget=budget, satisficing=satisficing)
    return answer_questions(
        model,
        questions,
        plan,
        principle,
        under or principle,
        max_horizon=max_horizon,
        reasons_limit=reasons_limit,
        budget=budget,
        satisficing=satisficing,
    )
