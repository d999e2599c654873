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
* **Uniform-cost search** (:mod:`ethasp.planning.engines.cheapest`:
  symbolic layers by cost and an explicit search over configurations, in
  turns, in a child process): its plan is a cheapest one, checked by its
  trace; meanwhile it proves that every plan costs at least what it has
  expanded, which proves the solver's plan least once that reaches its
  cost; with nothing left to expand, no plan exists.

The answer is the same on every run, whichever search proves what first:
the plan reported is the least of the cheapest plans of the fewest steps
(:func:`_least_cheapest`, where the solver finds it within a fixed number of
conflicts; else the plan of uniform-cost search, whose turns make it the same
on every run), the proof one text ("no plan costs less than
C"), and at the maximal horizon without a proof the search waits for
uniform-cost search to decide.  A search cut short by the maximal horizon or
a limit says ``bounded``, with the cheapest plan found so far, if any, and
what was proven about cheaper ones.  The statuses and the result are those
of :class:`ethasp.planning.search_base.SearchResult`, with the plan's
``cost``.
"""

from __future__ import annotations

import functools
from dataclasses import replace

from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import GroundingStopped, Planner, Setting
from ethasp.planning.engines.layers import Status, can_fork
from ethasp.planning.plan import Plan, steps
from ethasp.planning.search_base import (
    BOUNDED,
    FOUND,
    NONE,
    SEARCHED,
    SearchResult,
    checked,
    checkpoints,
    one_plan_wanted,
    plans_of,
    settled_before,
    too_long,
)

# Least plans are found by the solver's heuristic only where its levels fit in
# clingo's numbers (steps times usable actions), as in ethasp.planning.search.
LEAST_LEVELS = 2**30
# Conflicts within which the solver finds the least of the cheapest plans
# (beyond them, uniform-cost search's plan is reported).
LEAST_CONFLICTS = 20_000

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

    def settled(self, cost: int | None, longest: int) -> bool:
        """Has the engine ended the search: a plan of at most ``longest``
        steps, no plan at all, or every plan costing at least ``cost`` (the
        incumbent's)?  Exactly where :meth:`_Search.decided` answers: a
        cheaper plan beyond the maximal horizon ends nothing, the solver
        goes on within it."""
        status = self.status
        if status is None:
            return False
        plan = self.plan()
        return (
            (plan is not None and len(plan) <= longest)
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
    settled = settled_before(planner, setting, budget, max_horizon, start, longest)
    if settled is not None:
        return settled
    _clingo_searches(planner)
    plain = not setting.constraints
    engine = _Engine(planner, setting, budget, read_plan=plain)
    setting = replace(
        setting, cheapest=True, canonical=plain and not all_plans and one_plan_wanted(setting)
    )
    try:
        search = _Search(planner, setting, budget, max_horizon, start, task, engine, longest)
        search.all_plans = all_plans  # the least is the first of them all
        result = search.run(below)
    finally:
        engine.stop()
    if all_plans and result.status == FOUND and result.plan is not None:
        result.plans = _all_cheapest(planner, setting, budget, result)
        result.plan = result.plans[0]
    return result


def _clingo_searches(planner: Planner) -> None:
    """Cheapest plans are clingo's and uniform-cost search's (Fast Downward's
    tasks give every action cost 1): where Fast Downward was asked for, one
    line of warning says so."""
    from ethasp.planning import systems

    if getattr(planner.model, "planning_system", systems.DEFAULT) == systems.FAST_DOWNWARD:
        systems.warn(
            "Fast Downward does not search for cheapest plans (a model with action "
            "costs): clingo searches instead"
        )


def _all_cheapest(
    planner: Planner, setting: Setting, budget: Budget, found: SearchResult
) -> list[Plan]:
    """Every cheapest plan of as few steps as ``found.plan``: every plan of at
    most that many steps that costs no more (``found`` is proven cheapest, of
    the fewest steps among the cheapest), least first."""
    assert found.plan is not None and found.cost is not None
    outcome = planner.solve(
        len(found.plan),
        replace(setting, canonical=False, least=False, max_cost=found.cost),
        budget,
        models=0,
    )
    plans = plans_of(outcome.models) if outcome.satisfiable else []
    return sorted(set(plans) | {found.plan}, key=lambda plan: plan.actions)


def _arithmetic(cost: int, length: int, least: int) -> bool:
    """Does arithmetic alone prove that no plan costs less than ``cost``, given
    that none of at most ``length`` steps does?  Nothing costs less than 0,
    and with every action costing at least ``least`` > 0 a plan of cost below
    ``cost`` has at most (cost - 1) // least steps."""
    return cost == 0 or (least > 0 and (cost - 1) // least <= length)


def _least_cheapest(
    planner: Planner, setting: Setting, budget: Budget, cost: int, witness: Plan
) -> Plan | None:
    """The least plan (step by step, by the actions' terms, as
    :func:`ethasp.planning.search.shortest` reports shortest plans) of the
    cheapest plans of the fewest steps, ``witness`` one of them: the optimum
    of ``planning/cost.lp`` and ``planning/lexicographic.lp`` at that horizon,
    under the bound ``cost``, so that the plan does not depend on which
    search proved what first.  The empty plan is its own least.  None where
    the solver needs more than :data:`LEAST_CONFLICTS` conflicts for it or
    the budget stops it first.

    The solve runs on a control of its own, made for it (:func:`_fresh`):
    on the search's control, what the solver learnt in the solves before
    (some of them stopped where another engine answered first, at a moment
    that depends on the machine's load) and what it grounded for them (the
    mutexes and the canonical order, grounded after solves that met many
    conflicts) change how many conflicts the least plan takes, so the
    conflict limit would decide differently from run to run between this
    plan and uniform-cost search's.  A control made from the model alone
    takes the same conflicts on every run."""
    length = len(witness)
    if length == 0:
        return witness
    usable = len(planner.search_atoms("usable", 1))
    if (length + 1) * max(1, usable) >= LEAST_LEVELS:
        return None
    try:
        own, constraints = _fresh(planner, setting)
        own.use_least(budget)
    except GroundingStopped:
        return None
    least = replace(
        setting,
        constraints=constraints,
        least=True,
        satisficing=False,
        canonical=False,
        max_cost=cost,
    )
    outcome = own.solve(length, least, budget, conflicts=LEAST_CONFLICTS, mutex_after=float("inf"))
    if not outcome.satisfiable:
        return None
    return plans_of([outcome.symbols])[0]


def _fresh(planner: Planner, setting: Setting) -> tuple[Planner, frozenset]:
    """A planner of the same model with nothing solved or learnt yet, and the
    setting's question constraints made on it (questions are named in the
    order they are made: made in the order of the originals' names).  A
    search for plans avoids no state (:meth:`Planner.avoid` is for searches
    of best states, which the solver optimises on its own control)."""
    assert setting.other_state is None
    own = Planner(planner.model)
    by_question: dict = {}
    for constraint in setting.constraints:
        by_question.setdefault(constraint.question, []).append(constraint.term)
    made = []
    for name in sorted(by_question, key=lambda symbol: symbol.arguments[0].number):
        made += own.question(by_question[name])
    return own, frozenset(made)


class _Search:
    """One search for a cheapest plan (see the module docstring).

    ``plan`` and ``cost``: the cheapest plan found so far; ``limit``: every
    plan sought costs less (the cost of ``plan``, or a bound asked for).
    The answer does not depend on which search proved what first: a cheapest
    plan is reported as :func:`_least_cheapest` makes it, with one proof text
    ("no plan costs less than C"); at the maximal horizon without a proof the
    search waits for uniform-cost search to decide (within the budget)."""

    def __init__(
        self,
        planner: Planner,
        setting: Setting,
        budget: Budget,
        max_horizon: int,
        start: int,
        task: str,
        engine: _Engine,
        longest: int | None,
    ):
        self.planner, self.setting, self.budget = planner, setting, budget
        self.max_horizon = min(max_horizon, longest) if longest is not None else max_horizon
        self.horizon, self.task, self.engine, self.longest = start, task, engine, longest
        self.all_plans = False
        self.plan: Plan | None = None
        self.cost = 0
        self.limit: int | None = None

    # -- answers ------------------------------------------------------------------------

    def proven(self) -> SearchResult:
        """No plan costs less than :attr:`limit` (proven)."""
        if self.plan is None:
            return SearchResult(
                NONE, horizon=self.horizon, proof=f"no plan costs less than {self.limit}"
            )
        return self.least(self.plan, self.cost)

    def least(self, witness: Plan, cost: int) -> SearchResult:
        """The answer for a proven least cost and a cheapest plan of the fewest
        steps (``witness``): the least such plan, or where finding it takes
        more than the solver's share, uniform-cost search's plan (which its
        turns make the same on every run); a limit reached before either is
        known ends the search ``bounded`` with the witness."""
        if self.all_plans:  # every cheapest plan is listed, the least first
            return SearchResult(
                FOUND,
                plan=witness,
                horizon=len(witness),
                proof=f"no plan costs less than {cost}",
                cost=cost,
            )
        plan = _least_cheapest(self.planner, self.setting, self.budget, cost, witness)
        if plan is None:
            plan = self.engine_plan()
        if plan is None:
            return SearchResult(
                BOUNDED,
                plan=witness,
                horizon=len(witness),
                cost=cost,
                optimal=False,
                proof=f"no plan costs less than {cost}, but which cheapest plan to report "
                f"was not settled ({self.budget.why_stopped() or 'uniform-cost search stopped'})",
            )
        return SearchResult(
            FOUND, plan=plan, horizon=len(plan), proof=f"no plan costs less than {cost}", cost=cost
        )

    def engine_plan(self) -> Plan | None:
        """Uniform-cost search's cheapest plan, waited for within the budget
        (None where the engine does not read plans here, stops, or the budget
        ends first)."""
        engine = self.engine
        while engine.engine is not None and engine.read_plan and not self.budget.expired():
            status = engine.status
            proposed = engine.plan()
            if proposed is not None:
                return checked(self.planner, proposed, "uniform-cost search")
            if status is not None and (status.complete or status.stopped):
                return None
            engine.engine.news.wait(0.05)
            engine.engine.news.clear()
        return None

    def cut(self, why: str) -> SearchResult:
        """Bounded: the cheapest plan so far (if any) is not proven cheapest."""
        if self.plan is None:
            return SearchResult(BOUNDED, horizon=self.horizon, proof=why)
        return SearchResult(
            BOUNDED,
            plan=self.plan,
            horizon=self.horizon,
            cost=self.cost,
            optimal=False,
            proof=f"a plan of cost {self.cost} found; no plan of at most "
            f"{steps(self.horizon)} costs less, but a longer one may ({why})",
        )

    def decided(self) -> SearchResult | None:
        """What uniform-cost search has decided, if anything: a cheapest plan (of
        at most the maximal horizon's steps), no plan at all, or no plan
        costing less than :attr:`limit`."""
        status = self.engine.status
        if status is None:
            return None
        proposed = self.engine.plan()
        if proposed is not None:
            best = checked(self.planner, proposed, "uniform-cost search")
            lowest = _cost(self.planner, best)
            if self.limit is not None and lowest >= self.limit:
                return self.proven()
            if len(best) <= self.max_horizon:
                return self.least(best, lowest)
        if status.complete:
            return SearchResult(NONE, horizon=0, proof=SEARCHED)
        if self.limit is not None and status.cost_bound >= self.limit:
            return self.proven()
        return None

    # -- the search ---------------------------------------------------------------------

    def run(self, below: int | None) -> SearchResult:
        self.limit = below
        planner, setting, budget = self.planner, self.setting, self.budget
        checks = checkpoints(self.max_horizon)
        least = _least_cost(planner)
        while True:
            decided = self.decided()
            if decided is not None:
                return decided
            horizon = self.horizon
            budget.report(self.task, horizon=horizon)
            settled = functools.partial(self.engine.settled, self.limit, self.max_horizon)
            searching = replace(
                setting, max_cost=self.limit - 1 if self.limit is not None else None
            )
            outcome = planner.solve(horizon, searching, budget.until(settled), moot=settled)
            if outcome.satisfiable is None:
                if budget.expired():
                    return self.cut(f"{budget.why_stopped()} at horizon {horizon}")
                continue  # the engine decided: look again
            if outcome.satisfiable:
                self.plan = plans_of([outcome.symbols])[0]
                self.cost = self.limit = _cost(planner, self.plan)
            at_most = replace(setting, max_cost=self.limit - 1 if self.limit is not None else None)
            if self.limit is not None:
                if self.longest is not None and horizon >= self.longest:
                    return self.proven()
                if _arithmetic(self.limit, horizon, least):
                    return self.proven()
            elif self.longest is not None and horizon >= self.longest:
                return SearchResult(NONE, horizon=self.longest, proof=too_long(self.longest))
            if horizon in checks or horizon >= self.max_horizon:
                # No path one step longer without a repeated state (costing less
                # than the limit): every (cheaper) plan has at most `horizon` steps.
                exists = planner.simple_path_exists(horizon + 1, at_most, budget.until(settled))
                if exists is False:
                    if self.limit is None:
                        return SearchResult(NONE, horizon=0, proof=SEARCHED)
                    return self.proven()
                if exists is None and budget.expired():
                    return self.cut(f"{budget.why_stopped()} at horizon {horizon}")
            if horizon >= self.max_horizon:
                return self.at_maximum()
            self.horizon += 1

    def at_maximum(self) -> SearchResult:
        """At the maximal horizon without a proof: what uniform-cost search
        decides, waited for within the budget; else bounded."""
        engine = self.engine.engine
        while engine is not None and not self.budget.expired():
            decided = self.decided()
            if decided is not None:
                return decided
            if not engine.status.working:
                break
            engine.news.wait(0.05)
            engine.news.clear()
        decided = self.decided()
        if decided is not None:
            return decided
        why = (
            f"{self.budget.why_stopped()} at horizon {self.max_horizon}"
            if self.budget.expired()
            else f"the maximal horizon is {self.max_horizon}"
        )
        if self.plan is None:
            return SearchResult(
                BOUNDED,
                horizon=self.max_horizon,
                proof=f"no plan up to horizon {self.max_horizon} ({why})",
            )
        return self.cut(why)


def cost_of(planner: Planner, plan: Plan) -> int:
    """The cost of a plan of the planner's model."""
    return _cost(planner, plan)
