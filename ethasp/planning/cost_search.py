"""Cheapest plans: plan search for models with action costs (``cost/2``).

A model with action costs (``encodings/planning/model.lp``: ``cost/2``, an
action without one costing 0) asks for a plan of least cost; among the
cheapest, one of fewest steps.  :func:`ethasp.planning.search.shortest`
hands such models to :func:`cheapest`, so that plain plan search, the
HModels of principles and the contrast plans of questions all find cheapest
plans.

Two searches race, and the first proof ends the search:

* **The solver, horizon by horizon.**  At horizon h it finds a cheapest plan
  of at most h steps (``planning/cost.lp``: the cost, then the steps,
  minimised), and once a plan of cost C is known, only plans of cost at most
  C - 1 (a bound on the objective).  A cheaper plan may be longer, so C is
  proven least only when no cheaper plan can have more than h steps:
  - every action costs at least m > 0 (every usable one), so a plan of cost
    below C has at most (C - 1) // m steps; or
  - no path of h + 1 steps without a repeated state costs at most C - 1:
    costs are never negative, so if a cheaper plan exists, one without a
    repeated state exists (cutting out a loop costs nothing), and the first
    h + 1 steps of a longer one would be such a path; so every cheaper plan
    has at most h steps (``planning/loopfree.lp`` with the cost bound).
  Without any plan yet, ``none`` is proven as for shortest plans.
* **Uniform-cost search** (:mod:`ethasp.planning.engines.cheapest`) over
  explicit configurations, in a child process: its plan is a cheapest one,
  checked by its trace; meanwhile it proves that every plan costs at least
  what it has expanded, which proves the solver's plan least once that
  reaches its cost; with nothing left to expand, no plan exists.

A search cut short by the maximal horizon or a limit says ``bounded``, with
the cheapest plan found so far, if any, and what was proven about cheaper
ones.  The statuses and the result are those of
:class:`ethasp.planning.search.SearchResult`, with the plan's ``cost``.
"""

from __future__ import annotations

import functools
from dataclasses import replace

from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import Planner, Setting
from ethasp.planning.engines.layers import Status, can_fork
from ethasp.planning.plan import Plan, steps
from ethasp.planning.search_base import (
    BOUNDED,
    FOUND,
    NONE,
    SearchResult,
    checked,
    checkpoints,
    one_plan_wanted,
    plans_of,
    searched,
    settled_before,
    too_long,
)

# Whether uniform-cost search runs beside the solver (tests turn it off to
# test the solver's proofs alone).
UNIFORM_COST = True


class _Engine:
    """Uniform-cost search beside the solver, for settings whose plans are plans
    of the model (the goal, no utility threshold, no state to avoid); its plan
    is taken only where the setting imposes nothing the engine does not know
    (``read_plan``: no question constraint in ASP)."""

    def __init__(self, planner: Planner, setting: Setting, budget: Budget, read_plan: bool):
        from ethasp.planning.engines.cheapest import Cheapest, CostAtoms

        self.read_plan = read_plan
        self.engine = None
        usable = setting.goal and setting.at_least is None and setting.other_state is None
        if UNIFORM_COST and usable:
            atoms = (lambda: CostAtoms(planner)) if can_fork() else CostAtoms(planner)
            self.engine = Cheapest(atoms, budget, read_plan=read_plan).start()

    @property
    def status(self) -> Status | None:
        return self.engine.status if self.engine is not None else None

    def plan(self) -> tuple | None:
        status = self.status
        return status.plan if status is not None and self.read_plan else None

    def settled(self, cost: int | None) -> bool:
        """Has the engine ended the search: a plan, no plan at all, or every
        plan costing at least ``cost`` (the incumbent's)?"""
        status = self.status
        if status is None:
            return False
        return (
            self.plan() is not None
            or status.complete
            or (cost is not None and status.cost_bound >= cost)
        )

    def stop(self) -> None:
        if self.engine is not None:
            self.engine.stop()


def _cost(planner: Planner, plan: Plan) -> int:
    """The cost of a plan (``plan_cost/1`` of its trace)."""
    return planner.trace(plan).get("plan_cost", 1)[0].arguments[0].number


def _least_cost(planner: Planner) -> int:
    """The least cost of an action that plan search may use (0 if there is none)."""
    costs = planner.action_costs()
    usable = [costs.get(atom.arguments[0], 0) for atom in planner.search_atoms("usable", 1)]
    return min(usable, default=0)


def cheapest(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    max_horizon: int,
    start: int = 0,
    start_proof: str = "",
    all_plans: bool = False,
    task: str = "plan search",
    longest: int | None = None,
    below: int | None = None,
) -> SearchResult:
    """A cheapest plan under a setting (all cheapest plans of fewest steps with
    ``all_plans``), searching horizons ``start`` to ``max_horizon``; the
    arguments are those of :func:`ethasp.planning.search.shortest` (see the
    module docstring).  ``below``: only plans that cost less than this
    (``none`` is then the proof that no plan costs less)."""
    settled = settled_before(planner, setting, budget, max_horizon, start, start_proof, longest)
    if settled is not None:
        return settled
    plain = not setting.constraints
    engine = _Engine(planner, setting, budget, read_plan=plain)
    setting = replace(
        setting, cheapest=True, canonical=plain and not all_plans and one_plan_wanted(setting)
    )
    try:
        result = _cheapest(
            planner, setting, budget, max_horizon, start, start_proof, task, engine, longest, below
        )
    finally:
        engine.stop()
    if all_plans and result.status == FOUND and result.plan is not None:
        result.plans = _all_cheapest(planner, setting, budget, result)
    return result


def _all_cheapest(
    planner: Planner, setting: Setting, budget: Budget, found: SearchResult
) -> list[Plan]:
    """Every cheapest plan of as few steps as ``found.plan``: every plan of at
    most that many steps that costs no more (``found`` is proven cheapest, of
    the fewest steps among the cheapest)."""
    assert found.plan is not None and found.cost is not None
    outcome = planner.solve(
        len(found.plan),
        replace(setting, canonical=False, max_cost=found.cost),
        budget,
        models=0,
    )
    plans = plans_of(outcome.models) if outcome.satisfiable else []
    return plans if found.plan in plans else [found.plan, *plans]


def _proven(cost: int, length: int, planner: Planner, least: int) -> str:
    """Why no plan costs less than ``cost``, from arithmetic alone, given that
    none of at most ``length`` steps does ('' if that does not prove it):
    nothing costs less than 0, and with every action costing at least
    ``least`` > 0 a cheaper plan has few steps."""
    if cost == 0:
        return "no plan costs less than 0"
    if least > 0 and (cost - 1) // least <= length:
        return (
            f"every action costs at least {least}, so a plan of cost below {cost} would have "
            f"at most {steps((cost - 1) // least)}, and none up to horizon {length} costs less"
        )
    return ""


def _cheapest(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    max_horizon: int,
    start: int,
    start_proof: str,
    task: str,
    engine: _Engine,
    longest: int | None,
    below: int | None = None,
) -> SearchResult:
    if longest is not None:
        max_horizon = min(max_horizon, longest)
    checks = checkpoints(max_horizon)
    least = _least_cost(planner)
    horizon = start
    plan: Plan | None = None  # the cheapest plan found so far
    cost = 0
    # Every plan sought costs less than `limit` (the cheapest plan's cost so far,
    # or the bound asked for).
    limit = below

    def cheaper(proof: str) -> SearchResult:
        """The search proved that no plan costs less than ``limit``."""
        if plan is not None:
            return found(proof, plan, cost)
        if not proof.startswith("no plan costs less"):
            proof = f"no plan costs less than {limit}: {proof}"
        return SearchResult(NONE, horizon=horizon, proof=proof)

    def found(proof: str, found_plan: Plan, found_cost: int) -> SearchResult:
        return SearchResult(FOUND, plan=found_plan, horizon=horizon, proof=proof, cost=found_cost)

    def cut(why: str) -> SearchResult:
        """Bounded: the cheapest plan so far (if any) is not proven cheapest."""
        if plan is None:
            return SearchResult(BOUNDED, horizon=horizon, proof=why)
        return SearchResult(
            BOUNDED,
            plan=plan,
            horizon=horizon,
            cost=cost,
            optimal=False,
            proof=f"a plan of cost {cost} found; no plan of at most {steps(horizon)} costs "
            f"less, but a longer one may ({why})",
        )

    while True:
        status = engine.status
        if status is not None:
            proposed = engine.plan()
            if proposed is not None:
                best = checked(planner, proposed, "uniform-cost search")
                horizon, lowest = len(best), _cost(planner, best)
                if limit is not None and lowest >= limit:
                    return cheaper(
                        f"no plan costs less than {limit}: uniform-cost search found a cheapest "
                        f"plan, of cost {lowest}"
                    )
                return found(
                    f"no plan costs less than {lowest}: uniform-cost search expanded every "
                    "cheaper configuration",
                    best,
                    lowest,
                )
            if status.complete:
                return SearchResult(
                    NONE,
                    horizon=horizon,
                    proof="uniform-cost search expanded every reachable configuration without "
                    "meeting a goal state: no goal state is reachable",
                )
            if limit is not None and status.cost_bound >= limit:
                return cheaper(
                    f"no plan costs less than {limit}: uniform-cost search expanded every "
                    f"configuration reachable for less"
                )
        if horizon > max_horizon:
            if longest is not None and plan is None:
                return SearchResult(NONE, horizon=max_horizon, proof=too_long(longest, start_proof))
            return cut(f"the maximal horizon is {max_horizon}")
        budget.report(task, horizon=horizon)
        settled = functools.partial(engine.settled, limit)
        searching = replace(setting, max_cost=limit - 1 if limit is not None else None)
        outcome = planner.solve(horizon, searching, budget.until(settled), moot=settled)
        if outcome.satisfiable is None:
            if budget.expired():
                return cut(f"{budget.why_stopped()} at horizon {horizon}")
            continue  # the engine proved more: look again
        if outcome.satisfiable:
            plan = plans_of([outcome.symbols])[0]
            cost = limit = _cost(planner, plan)
        if limit is not None:
            if longest is not None and horizon >= longest:
                return cheaper(
                    f"no plan of at most {steps(horizon)} costs less than {limit}, and the "
                    f"question allows at most {steps(longest)}"
                )
            proof = _proven(limit, horizon, planner, least)
            if proof:
                return cheaper(proof)
            if horizon in checks or horizon >= max_horizon:
                bounded = replace(setting, max_cost=limit - 1)
                exists = planner.simple_path_exists(horizon + 1, bounded, budget.until(settled))
                if exists is False:
                    return cheaper(
                        f"no plan of at most {steps(horizon)} costs less than {limit}, and no "
                        f"path of {steps(horizon + 1)} without a repeated state does (a "
                        "cheaper plan would have such a path as its first steps)"
                    )
                if exists is None and budget.expired():
                    return cut(f"{budget.why_stopped()} at horizon {horizon}")
        else:
            if longest is not None and horizon >= longest:
                return SearchResult(
                    NONE,
                    horizon=horizon,
                    proof=f"no plan up to horizon {horizon}, and the question allows at most "
                    f"{steps(longest)}",
                )
            if horizon in checks:
                exists = planner.simple_path_exists(
                    horizon + 1, replace(setting, cheapest=False), budget.until(settled)
                )
                if exists is False:
                    return SearchResult(NONE, horizon=horizon, proof=searched(horizon))
                if exists is None and budget.expired():
                    return cut(f"{budget.why_stopped()} at horizon {horizon}")
        if horizon >= max_horizon:
            if plan is None:
                return SearchResult(
                    BOUNDED,
                    horizon=max_horizon,
                    proof=f"no plan up to horizon {max_horizon} (the maximal horizon)",
                )
            return cut(f"the maximal horizon is {max_horizon}")
        horizon += 1


def cost_of(planner: Planner, plan: Plan) -> int:
    """The cost of a plan of the planner's model."""
    return _cost(planner, plan)
