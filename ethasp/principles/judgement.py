"""Judgements of plans under ethical principles, and queries in the language L.

Data flow, each step computed once: the plan's trace (the model's planner:
validity, final state, Caused, the final state's utility,
``encodings/planning/trace.lp`` and ``encodings/judgement/judge.lp``); for
principles that compare with reachable states, the state to compare with
(:mod:`ethasp.principles.utilitarianism`); then one small program over the
trace's facts evaluates the language L (``encodings/judgement/language.lp``)
for the formula of every principle chosen (``encodings/principles/``).  This
module reads the ``verdict/2`` atoms back, and keeps the atoms of the
formulas that the reasons read (:mod:`ethasp.reasons.reasons`).

Every judgement has a status.  Deontology and do-no-harm depend on the plan
alone: ``proven``.  Utilitarianism compares the final state with the
reachable states:

* a reachable state better than the final state is found: ``impermissible``,
  ``proven``, at once (the search for a *best* state stops there);
* no reachable state is better, proven (exact reachability, or the upper
  bound): ``permissible``, ``proven``;
* otherwise ``permissible`` as far as searched, ``bounded``: a better
  reachable state may exist.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable, Sequence

import clingo
from clorm import unify

from ethasp.errors import InputError
from ethasp.planning.budget import Budget
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.planning.search import DEFAULT_MAX_HORIZON
from ethasp.planning.planner import Answer, occurrences
from ethasp.planning.validation import TRACE_ATOMS, Validation, read_validation, validate
from ethasp.principles.formula import Elements, parse_formula
from ethasp.principles.principle import Principle, available_principles, select_principles
from ethasp.principles.utilitarianism import (BOUNDED, PROVEN, BestReachable, ReachableState,
                                              best_reachable, better_state)
from ethasp.vocabulary import UtilityOfFinal, Verdict

# The program that evaluates formulas over a plan's trace.
LANGUAGE = "judgement/language.lp"
FORMULAS = ("planning/model.lp", LANGUAGE)
QUERY_NAME = clingo.Function("query")

# What reasons read of an evaluation of formulas (its #show statements).
EVIDENCE = "judgement/evidence.lp"


@dataclass
class Judgement:
    """The verdict of one principle on a plan.

    ``permissible`` is the verdict of the principle's formula; ``status`` is
    ``proven`` or ``bounded`` (a verdict against the states searched so far,
    which a better reachable state could overturn), and ``proof`` says why.
    Principles that compare with reachable states report the state compared
    with (``compared``: a better state when impermissible, a best one when
    permissible) and ``best_reachable`` when a best state was established.
    ``formula`` is the ASP name of the principle's formula (``formula(N,F)``).
    ``explanation`` holds its reasons and words (:mod:`ethasp.reasons.reasons`).
    """

    principle: str
    permissible: bool
    status: str
    proof: str
    formula: str
    best_reachable: BestReachable | None = None
    compared: ReachableState | None = None
    explanation: "Explanation | None" = None  # ethasp.reasons.explanation.Explanation

    def to_json(self) -> dict:
        """The judgement as one JSON object (the single place that builds it)."""
        data: dict = {"principle": self.principle, "permissible": self.permissible,
                      "status": self.status, "proof": self.proof}
        if self.compared is not None:
            data["compared_with"] = self.compared.to_json()
        if self.best_reachable is not None:
            data["best_reachable"] = self.best_reachable.to_json()
        if self.explanation is not None:
            data.update(self.explanation.to_json())
        return data


@dataclass
class JudgementReport:
    """A plan, its final state (literals ``v`` / ``-v``) and utility, and its judgements."""

    plan: Plan
    final_state: list[str]
    utility: int
    judgements: list[Judgement] = field(default_factory=list)

    def to_json(self) -> dict:
        return {"plan": self.plan.to_list(), "final_state": self.final_state,
                "utility": self.utility,
                "judgements": [judgement.to_json() for judgement in self.judgements]}


@dataclass
class QueryResult:
    """The truth value of a formula of L for a model and a plan."""

    plan: Plan
    formula: str
    value: bool

    def to_json(self) -> dict:
        return {"plan": self.plan.to_list(), "formula": self.formula, "value": self.value}


def _require_plan(model: Model, validation: Validation) -> None:
    if not validation.valid:
        raise InputError(f"not a plan: {validation.message(model.naming)}")


def evaluation(model: Model, plan: Plan) -> Answer:
    """The plan's evaluation, computed once per plan by the model's planner: its
    trace (validity, final state, Caused, utility) and the formula of every
    principle that depends on the plan alone, with the atoms reasons read
    (``judgement/evidence.lp``)."""
    plain = [p.encoding for p in available_principles() if not p.reads_alternatives]
    return model.planner.trace(plan, [LANGUAGE, EVIDENCE, *plain])


def trace_facts(model: Model, plan: Plan) -> list[clingo.Symbol]:
    """A valid plan's trace as atoms: ``occurs/2``, ``final/2``, ``caused/2``."""
    trace = model.planner.trace(plan)
    return occurrences(plan) + trace.select([("final", 2), ("caused", 2)])


def final_utility(model: Model, plan: Plan) -> int:
    """u(s_n) of a plan's final state (``utility_of_final/1`` of judge.lp)."""
    answer = unify([UtilityOfFinal], model.planner.trace(plan).get("utility_of_final", 1))
    return next(iter(answer.query(UtilityOfFinal).all())).utility


def evaluate(model: Model, plan: Plan, encodings: Sequence[str], facts: Iterable = ()
             ) -> Answer:
    """Evaluate formulas of L (given by principle encodings and facts, clingo
    symbols or clorm facts: for instance a state to compare with) over a plan's
    trace: the verdicts and the atoms that reasons read (``judgement/evidence.lp``)."""
    symbols = trace_facts(model, plan) + [getattr(fact, "raw", fact) for fact in facts]
    return model.planner.solve_program(list(FORMULAS) + [EVIDENCE] + list(encodings),
                                       symbols=symbols)


@dataclass
class _Compared:
    """What the comparing principles are judged against."""

    permissible: bool
    status: str
    proof: str
    state: ReachableState | None
    best: BestReachable | None


def _compare(model: Model, plan: Plan, utility: int, budget: Budget, max_horizon: int,
             want_best: bool) -> _Compared:
    """Decide whether a reachable state is better than the final state."""
    planner = model.planner
    comparison = better_state(planner, utility, budget, max_horizon)
    best = comparison.best
    if want_best and (best is None or best.status != PROVEN):
        best = best_reachable(planner, budget, max_horizon)
    if comparison.better is not None:
        return _Compared(False, PROVEN, comparison.proof + ", more than the final state's "
                         f"{utility}", comparison.better, best)
    if comparison.status == PROVEN:
        if best is None or best.found is None:
            # No reachable state is better, and the final state is reachable: it is a best one.
            final = [(s.arguments[0], s.arguments[1].name == "true")
                     for s in planner.trace(plan).get("final", 2)]
            best = BestReachable(PROVEN, f"the final state is reachable and {comparison.proof}",
                                 ReachableState(final, utility, len(plan)))
        return _Compared(True, PROVEN, comparison.proof, None, best)
    return _Compared(True, BOUNDED, f"{comparison.proof}; a better reachable state may exist",
                     None, best)


def judge(model: Model, plan: Plan, principles: Iterable[str] | None = None,
          max_horizon: int = DEFAULT_MAX_HORIZON, time_limit: float | None = None,
          budget: Budget | None = None, best: bool = False) -> JudgementReport:
    """Judge a plan under the principles (all when None), without explanations.

    ``max_horizon`` and ``budget`` (or ``time_limit``) bound the search for a
    reachable state better than the final state (utilitarianism); with
    ``best`` the search goes on to a best reachable state.  Raises InputError
    if the plan is not a plan.  (:func:`ethasp.reasons.reasons.judge` adds the
    explanations.)
    """
    budget = budget or Budget(time_limit)
    chosen = select_principles(principles)
    answer = evaluation(model, plan)
    validation = read_validation(plan, answer.select(TRACE_ATOMS))
    _require_plan(model, validation)
    utility = final_utility(model, plan)
    compared = None
    facts: list = []
    comparing = [principle for principle in chosen if principle.reads_alternatives]
    if comparing:
        compared = _compare(model, plan, utility, budget, max_horizon, best)
        if compared.state is not None:
            facts = compared.state.asp_facts()
        elif compared.best is not None and compared.best.found is not None:
            facts = compared.best.found.asp_facts()
        comparison = evaluate(model, plan, [p.encoding for p in comparing], facts)
        answer = Answer(answer.get("verdict", 2) + comparison.get("verdict", 2))
    verdicts = {str(atom.name.symbol): atom.value == "true"
                for atom in unify([Verdict], answer.get("verdict", 2)).query(Verdict).all()}
    judgements = []
    for principle in chosen:
        permissible = verdicts[principle.asp_name]
        if not principle.reads_alternatives:
            judgements.append(Judgement(principle.name, permissible, PROVEN,
                                        "the principle depends on the plan alone",
                                        principle.asp_name))
            continue
        assert compared is not None
        if permissible != compared.permissible:
            raise RuntimeError(f"{principle.name}: the formula's verdict disagrees with the "
                               "comparison of reachable states")
        judgements.append(Judgement(principle.name, permissible, compared.status,
                                    compared.proof, principle.asp_name, compared.best,
                                    compared.state))
    return JudgementReport(plan, validation.final_state, utility, judgements)


def query(model: Model, plan: Plan, formula: str) -> QueryResult:
    """Evaluate a formula of L (text, see :mod:`ethasp.principles.formula`) for a plan."""
    parsed = parse_formula(formula, Elements.of_model(model))
    _require_plan(model, validate(model, plan))
    answer = evaluate(model, plan, [], parsed.facts(QUERY_NAME))
    verdicts = unify([Verdict], answer.get("verdict", 2)).query(Verdict).all()
    value = any(str(atom.name.symbol) == "query" and atom.value == "true" for atom in verdicts)
    return QueryResult(plan, str(parsed), value)
