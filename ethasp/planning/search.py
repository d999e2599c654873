"""Plan search: shortest plans by increasing horizon, over the planner's grounding.

Every search runs on the model's one grounding (:class:`ethasp.planning.
planner.Planner`) under a :class:`~ethasp.planning.planner.Setting` (the
goal, restrictions, question constraints, utility thresholds) and a
:class:`~ethasp.planning.budget.Budget`.  Every result carries a status:

* ``found``: a plan was found, a shortest one: every smaller horizon was
  refuted, by a solve or by a proven lower bound on the length;
* ``none``: there is no plan, with a proof: the goal is not even relaxed
  reachable (``encodings/planning/relaxed.lp``); or the exact reachable
  states (:mod:`ethasp.planning.reachability`) hold no goal state; or at
  some horizon no simple path of that length exists
  (``encodings/planning/loopfree.lp``), so every reachable state has been
  searched;
* ``bounded``: the search stopped at the maximal horizon or the budget
  (time limit, cancellation) without a plan; a plan may still exist.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from clorm import unify

from ethasp.errors import InputError
from ethasp.planning.budget import Budget
from ethasp.planning.plan import Plan
from ethasp.planning.planner import Planner, Setting
from ethasp.vocabulary import Occurs

FOUND, NONE, BOUNDED = "found", "none", "bounded"

DEFAULT_MAX_HORIZON = 64


@dataclass
class SearchResult:
    """The outcome of a plan search.

    ``plan`` is a shortest plan (or None), ``plans`` all shortest plans when
    they were asked for, ``horizon`` the last horizon searched, and ``proof``
    says why there is no plan (status ``none``), why the plan is a shortest
    one (status ``found``) or what cut the search short (status ``bounded``).
    """

    status: str
    plan: Plan | None = None
    horizon: int = 0
    proof: str = ""
    plans: list[Plan] = field(default_factory=list)

    def to_json(self) -> dict:
        return {
            "status": self.status,
            "plan": self.plan.to_list() if self.plan is not None else None,
            "horizon": self.horizon,
            "proof": self.proof,
            **({"plans": [plan.to_list() for plan in self.plans]} if self.plans else {}),
        }


def _checkpoints(limit: int) -> set[int]:
    """The horizons after which the loop-free check runs: powers of two and the limit."""
    result, power = {limit}, 1
    while power <= limit:
        result.add(power)
        power *= 2
    return result


def plans_of(models: list) -> list[Plan]:
    """The plans of answer sets (their ``occurs/2`` atoms), without repeats."""
    plans = [Plan.from_occurs(unify([Occurs], symbols).query(Occurs).all()) for symbols in models]
    return list(dict.fromkeys(plans))


def shortest(planner: Planner, setting: Setting, budget: Budget,
             max_horizon: int = DEFAULT_MAX_HORIZON, start: int = 0, start_proof: str = "",
             all_plans: bool = False, task: str = "plan search") -> SearchResult:
    """A shortest plan under a setting, searching horizons ``start`` to ``max_horizon``.

    ``start`` must be a proven lower bound on the length of every plan under
    the setting (``start_proof`` says why); horizons below it are not solved.
    """
    if max_horizon < 0:
        raise InputError("the maximal horizon must be at least 0")
    if setting.goal and planner.is_fact("unreachable_goal"):
        return SearchResult(NONE, horizon=0,
                            proof="the goal is unreachable even ignoring delete effects")
    checkpoints = _checkpoints(max_horizon)
    if start > max_horizon:
        return SearchResult(BOUNDED, horizon=max_horizon,
                            proof=f"every plan has more than {max_horizon} steps ({start_proof}), "
                                  "the maximal horizon")
    for horizon in range(start, max_horizon + 1):
        budget.report(task, horizon=horizon)
        outcome = planner.solve(horizon, setting, budget, models=0 if all_plans else 1)
        if outcome.satisfiable is None:
            return SearchResult(BOUNDED, horizon=horizon,
                                proof=f"{budget.why_stopped()} at horizon {horizon}")
        if outcome.satisfiable:
            plans = plans_of(outcome.models if all_plans else [outcome.symbols])
            if horizon == 0:
                why = "the goal holds in the initial state"
            elif horizon == start:
                why = f"no plan has fewer than {horizon} steps: {start_proof}"
            else:
                why = f"no plan of fewer than {horizon} steps (every smaller horizon refuted)"
            return SearchResult(FOUND, plan=plans[0], horizon=horizon, proof=why,
                                plans=plans if all_plans else [])
        if horizon in checkpoints and horizon > 0:
            exists = planner.simple_path_exists(horizon, setting, budget)
            if exists is None:
                return SearchResult(BOUNDED, horizon=horizon,
                                    proof=f"{budget.why_stopped()} at horizon {horizon}")
            if not exists:
                return SearchResult(
                    NONE, horizon=horizon,
                    proof=f"no plan up to horizon {horizon}, and no path of {horizon} steps "
                          "without a repeated state: every reachable state was searched")
    return SearchResult(BOUNDED, horizon=max_horizon,
                        proof=f"no plan up to horizon {max_horizon} (the maximal horizon)")


def find_plan(model, max_horizon: int = DEFAULT_MAX_HORIZON, time_limit: float | None = None,
              all_plans: bool = False, budget: Budget | None = None) -> SearchResult:
    """A shortest plan for the model (all shortest plans with ``all_plans``).

    A model without a goal has nothing to plan for: InputError (under a
    principle, :func:`ethasp.principles.restriction.plan_with_principles`
    finds a shortest permissible action sequence instead).
    """
    if not model.planner.get("goal", 2):
        raise InputError("the model has no goal, so plan search has nothing to reach (with "
                         "--principle NAME it finds a shortest action sequence permissible "
                         "under NAME)")
    budget = budget or Budget(time_limit)
    return shortest(model.planner, Setting(), budget, max_horizon, all_plans=all_plans)
