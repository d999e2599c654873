"""Judgements of plans under ethical principles, and queries in the language L.

One clingo call evaluates the plan's trace (``encodings/planning/trace.lp``), the
language L (``encodings/judgement/language.lp``), the utility of the final state
(``encodings/judgement/judge.lp``) and the chosen principles (``encodings/principles/``);
this module reads the ``verdict/2`` atoms back.

Every judgement has a status.  Deontology and do-no-harm depend on the plan
alone: ``proven``.  Utilitarianism compares the final state with a best
reachable state found by optimisation (:mod:`ethasp.principles.utilitarianism`):

* the final state is worse than a state found: ``impermissible``, ``proven``
  (that state is reachable, whether or not it is a best one);
* otherwise, if the best state is proven best: ``permissible``, ``proven``;
* otherwise ``permissible`` as far as searched, ``bounded``: a better
  reachable state may exist.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable

import clingo
from clorm import unify

from ethasp.errors import InputError
from ethasp.principles.formula import Elements, parse_formula
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.principles.principle import Principle, select_principles
from ethasp.planning.search import DEFAULT_MAX_HORIZON
from ethasp.principles.utilitarianism import BOUNDED, PROVEN, BestReachable, best_reachable
from ethasp.planning.validation import Validation, read_validation, validate
from ethasp.vocabulary import UtilityOfFinal, Verdict

JUDGE = ("planning/model.lp", "planning/trace.lp", "judgement/language.lp", "judgement/judge.lp")
QUERY = ("planning/model.lp", "planning/trace.lp", "judgement/language.lp")
QUERY_NAME = clingo.Function("query")


@dataclass
class Judgement:
    """The verdict of one principle on a plan.

    ``permissible`` is the verdict of the principle's formula; ``status`` is
    ``proven`` or ``bounded`` (a verdict against the states searched so far,
    which a better reachable state could overturn), and ``proof`` says why.
    Principles that compare with reachable states report ``best_reachable``.
    ``formula`` is the ASP name of the principle's formula (``formula(N,F)``).
    ``explanation`` holds its reasons and words (:mod:`ethasp.reasons.reasons`).
    """

    principle: str
    permissible: bool
    status: str
    proof: str
    formula: str
    best_reachable: BestReachable | None = None
    explanation: "Explanation | None" = None  # ethasp.reasons.explanation.Explanation

    def to_json(self) -> dict:
        """The judgement as one JSON object (the single place that builds it)."""
        data: dict = {"principle": self.principle, "permissible": self.permissible,
                      "status": self.status, "proof": self.proof}
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


def _judgement(principle: Principle, permissible: bool, best: BestReachable | None,
               utility: int) -> Judgement:
    if not principle.reads_alternatives:
        return Judgement(principle.name, permissible, PROVEN,
                         "the principle depends on the plan alone", principle.asp_name)
    assert best is not None
    if not permissible:
        proof = (f"a reachable state has utility {best.utility}, more than the final "
                 f"state's {utility}")
        return Judgement(principle.name, False, PROVEN, proof, principle.asp_name, best)
    if best.status == PROVEN:
        proof = f"the final state is as good as a best reachable state: {best.proof}"
        return Judgement(principle.name, True, PROVEN, proof, principle.asp_name, best)
    proof = (f"no better state found ({best.proof}); a better reachable state may exist")
    return Judgement(principle.name, True, BOUNDED, proof, principle.asp_name, best)


def judge(model: Model, plan: Plan, principles: Iterable[str] | None = None,
          max_horizon: int = DEFAULT_MAX_HORIZON,
          time_limit: float | None = None) -> JudgementReport:
    """Judge a plan under the principles (all when None), without explanations.

    ``max_horizon`` and ``time_limit`` bound the search for a best reachable
    state (utilitarianism).  Raises InputError if the plan is not a plan.
    (:func:`ethasp.reasons.reasons.judge` adds the explanations.)
    """
    chosen = select_principles(principles)
    facts: list = list(plan.facts())
    best: BestReachable | None = None
    if any(principle.reads_alternatives for principle in chosen):
        _require_plan(model, validate(model, plan))  # before a search that may be long
        best = best_reachable(model, max_horizon, time_limit)
        facts += best.alternative_facts()
    encodings = list(JUDGE) + [principle.encoding for principle in chosen]
    symbols = model.solve_once(encodings, facts)
    validation = read_validation(plan, symbols)
    _require_plan(model, validation)
    answer = unify([Verdict, UtilityOfFinal], symbols)
    verdicts = {str(atom.name.symbol): atom.value == "true" for atom in answer.query(Verdict).all()}
    utility = next(iter(answer.query(UtilityOfFinal).all())).utility
    judgements = [_judgement(principle, verdicts[principle.asp_name], best, utility)
                  for principle in chosen]
    return JudgementReport(plan, validation.final_state, utility, judgements)


def query(model: Model, plan: Plan, formula: str) -> QueryResult:
    """Evaluate a formula of L (text, see :mod:`ethasp.principles.formula`) for a plan."""
    parsed = parse_formula(formula, Elements.of_model(model))
    symbols = model.solve_once(QUERY, list(plan.facts()) + parsed.facts(QUERY_NAME))
    _require_plan(model, read_validation(plan, symbols))
    verdicts = unify([Verdict], symbols).query(Verdict).all()
    value = any(str(atom.name.symbol) == "query" and atom.value == "true" for atom in verdicts)
    return QueryResult(plan, str(parsed), value)
