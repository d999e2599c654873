"""Ethical plan generation: plans of model restrictions (HModels).

The constraint operator Pi x e of the paper (section "Ethical Plan
Generation") restricts plan search so that every plan found, an *HPlan*, is a
plan of the model that satisfies the principle e.  Each principle is an
encoding in ``encodings/restrictions/`` added to the ordinary multi-shot plan
search (:class:`ethasp.search.Search`); several principles together restrict
the search by all of them.

Utilitarianism needs the best utility of a reachable state first: it comes
from clingo optimisation over the reachable states, goal or not
(:func:`ethasp.utilitarianism.best_reachable`, ``encodings/judgement/best.lp``),
proven best or only a lower bound.  The plan search then keeps the plans whose
final state is at least that good (``best_utility/1``).

Statuses are those of plan search: ``found`` (a shortest HPlan, permissible
by a proof), ``none`` (proven: no permissible plan exists) or ``bounded``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Sequence

import clingo

from ethasp.errors import InputError
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.planning.search import BOUNDED, DEFAULT_MAX_HORIZON, FOUND, NONE, Search
from ethasp.principles.principle import Principle, select_principles
from ethasp.resources import ENCODINGS
from ethasp.principles.utilitarianism import PROVEN, BestReachable, best_reachable

RESTRICTIONS = "restrictions"


def _principles(names: Sequence[str]) -> list[Principle]:
    """The principles named, each once, each with a restriction encoding.

    A principle ``NAME`` (``encodings/principles/NAME.lp``) restricts plan
    search with ``encodings/restrictions/NAME.lp``; one without it can judge
    plans but not generate them.
    """
    chosen = select_principles(names)
    for principle in chosen:
        if not (ENCODINGS / RESTRICTIONS / f"{principle.asp_name}.lp").is_file():
            raise InputError(f"principle {principle.name} has no restriction encoding "
                             f"({RESTRICTIONS}/{principle.asp_name}.lp): it can judge plans "
                             "but not generate them")
    return chosen


def principle_names(names: Sequence[str]) -> list[str]:
    """The principles named (``do_no_harm`` is read as ``do-no-harm``), each once.

    Raises InputError for an unknown name.
    """
    return [principle.name for principle in _principles(names)]


# -- HPlans ------------------------------------------------------------------

@dataclass
class HPlanResult:
    """The outcome of plan search in the HModel of one or more principles.

    ``plan`` is a shortest plan permissible under every principle in
    ``principles`` (status ``found``), or None; ``plans`` all shortest ones
    when asked for.  ``status`` is ``found``, ``none`` (proven: no plan of the
    model is permissible under all the principles) or ``bounded``; ``proof``
    says why.  With utilitarianism, ``best`` is the best reachable state
    found (the plans had to reach its utility), proven best or only bounded.
    """

    status: str
    principles: list[str]
    plan: Plan | None = None
    horizon: int = 0
    proof: str = ""
    plans: list[Plan] = field(default_factory=list)
    best: BestReachable | None = None

    def to_json(self) -> dict:
        data = {
            "status": self.status,
            "plan": self.plan.to_list() if self.plan is not None else None,
            "principles": list(self.principles),
            "horizon": self.horizon,
            "proof": self.proof,
        }
        if self.plans:
            data["plans"] = [plan.to_list() for plan in self.plans]
        if self.best is not None:
            data["best_utility"] = self.best.utility
            data["best_utility_status"] = self.best.status
            data["best_reachable"] = self.best.to_json()
        return data


def restriction_encodings(principles: Sequence[str]) -> list[str]:
    """The restriction encodings of the principles."""
    return [f"{RESTRICTIONS}/{principle.asp_name}.lp" for principle in _principles(principles)]


def plan_with_principles(model: Model, principles: Sequence[str],
                         max_horizon: int = DEFAULT_MAX_HORIZON,
                         time_limit: float | None = None,
                         all_plans: bool = False,
                         encodings: Sequence[str] = (),
                         facts: Sequence = (),
                         assumptions: Sequence[tuple[clingo.Symbol, bool]] = ()) -> HPlanResult:
    """A shortest HPlan: a plan of the model permissible under all the principles.

    ``encodings``, ``facts`` and ``assumptions`` add further constraints to the
    HModel (the constraints of contrastive questions, for instance).
    """
    chosen = _principles(principles)
    names = [principle.name for principle in chosen]
    deadline = None if time_limit is None else time.monotonic() + time_limit
    facts = list(facts)
    best: BestReachable | None = None
    if any(principle.reads_alternatives for principle in chosen):
        best = best_reachable(model, max_horizon, time_limit)
        if best.utility is None:
            return HPlanResult(BOUNDED, names, horizon=best.searched, best=best,
                               proof=f"no reachable state valued yet: {best.proof}")
        facts.append(clingo.Function("best_utility", [clingo.Number(best.utility)]))
    remaining = None if deadline is None else max(0.0, deadline - time.monotonic())
    search = Search(model, restriction_encodings(names) + list(encodings), facts,
                    assumptions=assumptions)
    result = search.run(max_horizon, remaining, all_plans)
    under = " and ".join(names) if names else "no principle"
    if result.status == FOUND and best is not None and best.status != PROVEN:
        # A plan reaching the best utility found is no proof: a better state may exist.
        return HPlanResult(
            BOUNDED, names, horizon=result.horizon, best=best,
            proof=f"a plan of {result.horizon} steps reaches utility {best.utility}, but a "
                  f"better reachable state is not excluded ({best.proof})")
    if result.status == FOUND:
        return HPlanResult(FOUND, names, result.plan, result.horizon,
                           f"a shortest plan permissible under {under}", result.plans, best)
    if result.status == NONE:
        # With utilitarianism the search asked for utility >= best.utility, a lower
        # bound of the best reachable utility: no such goal state, no permissible plan.
        return HPlanResult(NONE, names, None, result.horizon,
                           f"no plan is permissible under {under}: {result.proof}", best=best)
    return HPlanResult(BOUNDED, names, None, result.horizon,
                       f"no plan permissible under {under} found: {result.proof}", best=best)
