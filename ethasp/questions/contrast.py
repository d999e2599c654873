"""Contrastive questions answered (steps 1 to 5 of the paper's iterative process).

A question "Why A rather than B?" about the original plan becomes constraint
facts (``contrast(Q,C)``, :mod:`ethasp.questions.question`) that the fixed encoding
``encodings/questions/questions.lp`` reads.  The question's constraints and the chosen
principle restrict the model (the HModel, :mod:`ethasp.principles.restriction`), which is
solved for the contrast plan (the HPlan).  If the HModel has no plan, the
principle is dropped and the model solved again (step 3), so that the
explanation shows why the contrast is impermissible.  If there is no plan even
then, a minimal subset of the question's constraints that conflict is found
with solver assumptions (each constraint is switched on by an assumption on
``active(Q,C)``).  Both plans are judged and explained (step 4,
:mod:`ethasp.principles.judgement`), and the contrastive explanation sets the reasons of
the two side by side (step 5).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

import clingo
from clorm import unify

from ethasp.errors import InputError
from ethasp.planning.budget import Budget
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan, parse_action
from ethasp.planning.naming import Naming
from ethasp.planning.planner import Constraint, occurrences
from ethasp.planning.search import BOUNDED, DEFAULT_MAX_HORIZON, FOUND, NONE
from ethasp.planning.validation import static_failures, validate
from ethasp.principles.judgement import Judgement
from ethasp.principles.principle import select_principles
from ethasp.principles.restriction import HPlanResult, plan_with_principles
from ethasp.questions.question import Question
from ethasp.reasons import words
from ethasp.reasons.reasons import DEFAULT_LIMIT, judge
from ethasp.vocabulary import Answered, UnknownAction

QUESTIONS = "questions/questions.lp"
DEFAULT_PRINCIPLE = "deontology"


def constraints_of(model: Model, questions: Sequence[Question], first: int = 1) -> list[Constraint]:
    """The constraints of the questions, their actions resolved to model terms."""
    result = []
    for number, question in enumerate(questions, start=first):
        name = clingo.Function("q", [clingo.Number(number)])
        action = parse_action(question.action)
        other = parse_action(question.other) if question.other is not None else None
        result += [Constraint(name, term) for term in question.contrasts(action, other)]
    return result


def check_question(model: Model, question: Question, plan: Plan) -> list[Constraint]:
    """The question's constraints, after checking it against the plan it is about.

    Raises InputError if it names an action the model lacks, or if the plan
    already meets all its constraints (then there is nothing to contrast: e.g.
    "why not A" about a plan that uses A).
    """
    constraints = constraints_of(model, [question])
    horizon = len(plan)
    facts = [f"time(0..{horizon}).", f"horizon({horizon})."]
    if horizon:
        facts.append(f"step(1..{horizon}).")
    symbols = [clingo.Function("contrast", [c.question, c.term]) for c in constraints]
    ctl = model.planner.program([QUESTIONS], "\n".join(facts) + "\n",
                                symbols=symbols + occurrences(plan))
    symbols: list[clingo.Symbol] = []
    with ctl.solve(yield_=True) as handle:
        for answer in handle:
            symbols = list(answer.symbols(shown=True))
            break
    answer = unify([Answered, UnknownAction], symbols)
    unknown = sorted((atom.action.symbol for atom in answer.query(UnknownAction).all()), key=str)
    if unknown:
        failing = static_failures(model, unknown[:1])
        if failing:
            facts = ", ".join(map(model.naming.fact, failing[unknown[0]]))
            raise InputError(f"question '{question}': action {model.naming.action(unknown[0])} "
                             f"never applies: precondition {facts} does not hold and no "
                             "action changes it")
        raise InputError(f"question '{question}': unknown action "
                         f"{model.naming.action(unknown[0])}")
    if list(answer.query(Answered).all()):
        raise InputError(f"question '{question}': the plan already meets its contrast "
                         f"({', '.join(model.naming.constraint(c.term) for c in constraints)}); "
                         "ask about what the plan does")
    return constraints


# -- the contrast plan -------------------------------------------------------------

@dataclass
class ContrastSearch:
    """The search for the contrast plan: the HPlan, with the principle or without."""

    result: HPlanResult
    principle_dropped: bool
    conflict: list[Constraint] = field(default_factory=list)
    dropped_because: str = ""


def minimal_conflict(model: Model, constraints: Sequence[Constraint], max_horizon: int,
                     budget: Budget) -> list[Constraint]:
    """A subset-minimal set of constraints under which the model has no plan (proven).

    Deletion-based: a constraint is left out whenever the others still have no
    plan, proven; a search cut by the horizon or the budget keeps the constraint.
    Every search runs on the model's one grounding, the constraints switched
    by assumptions.
    """
    core = list(constraints)
    for constraint in list(core):
        trial = [c for c in core if c != constraint]
        if plan_with_principles(model, [], max_horizon, constraints=trial,
                                budget=budget).status == NONE:
            core = trial
    return core


def contrast_plan(model: Model, constraints: Sequence[Constraint], under: str,
                  max_horizon: int = DEFAULT_MAX_HORIZON, time_limit: float | None = None,
                  budget: Budget | None = None, satisficing: bool = False) -> ContrastSearch:
    """The HPlan of the constraints and the principle ``under`` (steps 2 and 3);
    with ``satisficing`` any such plan, not proven shortest."""
    budget = budget or Budget(time_limit)
    result = plan_with_principles(model, [under], max_horizon, constraints=constraints,
                                  budget=budget, satisficing=satisficing)
    if result.status == FOUND:
        return ContrastSearch(result, False)
    dropped = plan_with_principles(model, [], max_horizon, constraints=constraints,
                                   budget=budget, satisficing=satisficing)
    if dropped.status == FOUND:
        return ContrastSearch(dropped, True, [], result.proof)
    # No plan meets the question at all (or none was found): the principle is not
    # what stands in the way, and is not said to be dropped.
    conflict = (minimal_conflict(model, constraints, max_horizon, budget)
                if dropped.status == NONE else [])
    return ContrastSearch(dropped, False, conflict, "")


# -- answers -----------------------------------------------------------------------

@dataclass
class Side:
    """One plan of a contrastive explanation, judged under one principle."""

    plan: Plan
    principle: str
    judgement: Judgement

    def to_json(self, model: Model | None = None) -> dict:
        explanation = self.judgement.explanation
        return {
            "plan": self.plan.to_list(),
            "principle": self.principle,
            "permissible": self.judgement.permissible,
            "status": self.judgement.status,
            "sufficient_reasons": explanation.sufficient_reasons if explanation else [],
            "necessary_reasons": explanation.necessary_reasons if explanation else [],
            "chosen_reason": explanation.chosen_reason if explanation else [],
            "explanation": explanation.text if explanation else "",
        }


@dataclass
class Answer:
    """The answer to contrastive questions about a plan.

    ``original`` is the plan asked about, judged under ``principle``;
    ``contrast`` the contrast plan (HPlan) judged under ``under``, or None if
    there is none.  ``status`` is that of the contrast plan's search (found,
    none: proven, bounded); ``principle_dropped`` says that no plan met the
    constraints and ``under`` together, so the principle was left out;
    ``conflict`` lists a minimal set of constraints that no plan meets.
    ``difference`` holds the literals of the chosen reasons that only one side
    has; ``optimal`` is False when the contrast plan comes from an any-plan
    search (not proven shortest).
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
        }


def _difference(original: Side, contrast: Side | None) -> dict[str, list[str]]:
    mine = original.judgement.explanation.chosen_reason if original.judgement.explanation else []
    theirs = (contrast.judgement.explanation.chosen_reason
              if contrast and contrast.judgement.explanation else [])
    return {"original_only": [lit for lit in mine if lit not in theirs],
            "contrast_only": [lit for lit in theirs if lit not in mine]}


def _side_sentences(side: Side, modal: str, opening: str, alternatively: bool) -> str:
    explanation = side.judgement.explanation
    labels = explanation.labels
    option = f"{words.agent(labels)} {modal} {words.plan_phrase(labels, side.plan)}."
    option = f"Alternatively, {option}" if alternatively else words.capitalize(option)
    verdict = words.verdict_sentence(explanation, opening, principle=True, pronoun=True)
    if side.judgement.status == BOUNDED:
        verdict = verdict[:-1] + " (as far as searched)."
    return f"{option} {verdict}"


def contrastive_text(original: Side, contrast: Side | None, conflict: Sequence[Constraint],
                     status: str, naming: Naming = Naming()) -> str:
    """The words of a contrastive explanation (step 5); ``naming`` names the
    constraints (a PDDL model's in PDDL form)."""
    text = _side_sentences(original, "could", "This would be", alternatively=False)
    if contrast is not None:
        return f"{text} {_side_sentences(contrast, 'could', 'Doing so is', alternatively=True)}"
    if status == NONE:
        if conflict:
            return (f"{text} There is no alternative plan: no plan meets the question's "
                    f"constraints {', '.join(naming.constraint(c.term) for c in conflict)}.")
        return f"{text} There is no alternative plan: no plan reaches the goal."
    return (f"{text} No alternative plan was found within the search bounds (one may "
            "exist).")


def _judge_side(model: Model, plan: Plan, principle: str, max_horizon: int,
                budget: Budget, reasons_limit: int) -> Side:
    report = judge(model, plan, [principle], max_horizon, reasons_limit=reasons_limit,
                   budget=budget)
    return Side(plan, principle, report.judgements[0])


def original_plan(model: Model, principle: str, max_horizon: int = DEFAULT_MAX_HORIZON,
                  time_limit: float | None = None, budget: Budget | None = None,
                  satisficing: bool = False) -> Plan:
    """The plan that plan search under the principle makes (the plan asked about)."""
    result = plan_with_principles(model, [principle], max_horizon, time_limit, budget=budget,
                                  satisficing=satisficing)
    if result.plan is None:
        raise InputError(f"no plan to ask about: {result.proof}")
    return result.plan


def answer_questions(model: Model, questions: Sequence[Question], plan: Plan,
                     principle: str, under: str, previous: Sequence[Constraint] = (),
                     max_horizon: int = DEFAULT_MAX_HORIZON, time_limit: float | None = None,
                     reasons_limit: int = DEFAULT_LIMIT, budget: Budget | None = None,
                     satisficing: bool = False) -> Answer:
    """Answer the questions about ``plan`` (judged under ``principle``) with a
    contrast plan under ``under``; ``previous`` constraints stay imposed.
    With ``satisficing`` the contrast plan is any such plan, not proven
    shortest."""
    budget = budget or Budget(time_limit)
    principle = select_principles([principle])[0].name
    under = select_principles([under])[0].name
    validation = validate(model, plan)
    if not validation.valid:
        raise InputError(f"not a plan: {validation.message(model.naming)}")
    new: list[Constraint] = []
    for question in questions:
        terms = [constraint.term for constraint in check_question(model, question, plan)]
        new += model.planner.question(terms)
    constraints = list(dict.fromkeys(list(previous) + new))
    original = _judge_side(model, plan, principle, max_horizon, budget, reasons_limit)
    search = contrast_plan(model, constraints, under, max_horizon, budget=budget,
                           satisficing=satisficing)
    contrast = None
    if search.result.plan is not None:
        contrast = _judge_side(model, search.result.plan, under, max_horizon, budget,
                               reasons_limit)
    return Answer(list(questions), principle, under, original, contrast, search.result.status,
                  search.result.proof, search.principle_dropped, constraints, search.conflict,
                  _difference(original, contrast),
                  contrastive_text(original, contrast, search.conflict, search.result.status,
                                   model.naming),
                  search.dropped_because, search.result.optimal)


def ask(model: Model, question: str | Question | Sequence[str | Question],
        plan: Plan | None = None, principle: str = DEFAULT_PRINCIPLE, under: str | None = None,
        max_horizon: int = DEFAULT_MAX_HORIZON, time_limit: float | None = None,
        reasons_limit: int = DEFAULT_LIMIT, budget: Budget | None = None,
        satisficing: bool = False) -> Answer:
    """Ask "why A rather than B?" about a plan.

    The plan asked about is ``plan``, or else the plan that plan search under
    ``principle`` makes; it is judged under ``principle``.  The contrast plan
    must satisfy ``under`` (default: ``principle``).  Questions are text (see
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
    if plan is None:
        plan = original_plan(model, principle, max_horizon, budget=budget,
                             satisficing=satisficing)
    return answer_questions(model, questions, plan, principle, under or principle,
                            max_horizon=max_horizon, reasons_limit=reasons_limit, budget=budget,
                            satisficing=satisficing)
