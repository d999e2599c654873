"""Plan search: shortest plans by increasing horizon, over the planner's grounding.

Every search runs on the model's one grounding (:class:`ethasp.planning.
planner.Planner`) under a :class:`~ethasp.planning.driver.planner.Setting` (the
goal, restrictions, question constraints, utility thresholds) and a
:class:`~ethasp.planning.budget.Budget`.  Every result carries a status:

* ``found``: a plan was found, a shortest one: every smaller horizon was
  refuted, by a solve or by a proven lower bound on the length;
* ``none``: there is no plan, with a proof: the goal is not even relaxed
  reachable (``encodings/planning/relaxed.lp``); or the exact reachable
  states (:mod:`ethasp.planning.engines.reachability`) hold no goal state; or at
  some horizon no simple path of that length exists
  (``encodings/planning/loopfree.lp``), so every reachable state has been
  searched;
* ``bounded``: the search stopped at the maximal horizon or the budget
  (time limit, cancellation) without a plan; a plan may still exist.

Engines race for speed, never for the answer: while no limit is hit, a
search answers the same on every run, whichever engine proves what first.
The plan of a shortest search is the *least* shortest plan (plans of a
length compared step by step, step 1 first, by their actions' terms), read
off the exact layers where forward and backward ones meet
(:meth:`~ethasp.planning.engines.reachability.Reachability.least_path_meeting`)
or found by the solver's least-plan heuristic (``planning/lexicographic.lp``);
each kind of claim has one proof text; and ``none`` at the maximal horizon
is claimed exactly when the layers know every reachable state within one
step beyond it, or no path one step beyond it lacks a repeated state,
however far the race got.  Any-plan searches take the greedy search's plan
where it runs and finds one, else the solver's, whose horizons and slices
are measured in conflicts, not seconds.
"""

from __future__ import annotations

import os
import time
from dataclasses import replace

from ethasp.errors import InputError
from ethasp.memo import results
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import (
    MUTEX_AFTER,
    GroundingStopped,
    Planner,
    Setting,
    final_facts,
)
from ethasp.planning.engines import layers as layers_module
from ethasp.planning.engines.layers import Atoms, Layers, Status
from ethasp.planning.plan import Plan, steps
from ethasp.planning.search_base import (
    BOUNDED,
    FOUND,
    GREEDY_PROOF,
    NONE,
    SEARCHED,
    SearchResult,
    plans_of,
    settled_before,
)
from ethasp.planning.search_base import before_search as _before
from ethasp.planning.search_base import checked as _checked
from ethasp.planning.search_base import checkpoints as _checkpoints
from ethasp.planning.search_base import impossible_constraint as _impossible
from ethasp.planning.search_base import one_plan_wanted as _one_plan_wanted
from ethasp.planning.search_base import too_long as _too_long

DEFAULT_MAX_HORIZON = 64
# Any-plan search looks further by default: it does not pay for every horizon.
DEFAULT_SATISFICING_HORIZON = 256

# Seconds of solving after which exact layers start beside the encodings (the
# smallest tasks are solved before, without the cost of starting them).
LAYERS_AFTER = 0.03
# Models with at least this many ground actions start the layers with the
# search: there the layers often find a shortest plan before the solver has
# refuted the first few horizons.
LAYERS_AT_ONCE_ACTIONS = 32
# ... and so do models of at least this many state variables: reading their
# atoms in this process (to start the layers later) would cost more than
# starting a child process that reads them (PDDL tasks declare an atom for
# every typed combination of the arguments of a predicate that actions change).
LAYERS_AT_ONCE_VARIABLES = 1000
# Seconds the solver waits, at the start of a search, for an engine started
# with it (layers, greedy search) to finish: where it finishes that soon, the
# solver's work would only have taken a core from it (the machine may have
# fewer free cores than processes).
HEAD_START = 0.3

# Conflicts a solve meets before the h^2 mutexes are grounded while the layers
# still work: often they end the search first, and the grounding (which
# cannot be interrupted) would only delay the end (freecell p01: 0.7 s).
MUTEX_AFTER_LAYERS = 5 * MUTEX_AFTER

# Solver threads for plain plan search once the layers have given up (their
# core is free): clasp's competing portfolio, about 1.3x to 1.8x faster on
# the hard horizons of depots.
SOLVER_THREADS = 2

# Any-plan search: conflicts a horizon's solve may meet before the search
# moves on to a larger one (work, not seconds: the same horizons on every
# run), and the factor by which horizons (and slices) grow then.
SLICE = 2000
GROWTH = 1.5


class _Exact:
    """Exact layers (:mod:`ethasp.planning.engines.layers`) beside a search, started once
    the solver has worked :data:`LAYERS_AFTER` seconds (with the search, for
    models of at least :data:`LAYERS_AT_ONCE_ACTIONS` ground actions or
    :data:`LAYERS_AT_ONCE_VARIABLES` state variables), for
    searches with the goal and without utility thresholds or states to avoid
    (the layers know the model's plans, and every plan a setting allows is one
    of them).  With ``greedy`` (any-plan search) and ``read_plan`` (plain
    search), the greedy forward search (:mod:`ethasp.planning.engines.greedy`) runs
    instead of the layers, started with the search.  Each engine only on a
    model it handles (:meth:`~ethasp.planning.driver.planner.Planner.handles`):
    the layers (for their proof that no plan exists) where the greedy search
    does not handle the model (events), the solver alone where neither does."""

    def __init__(
        self,
        planner: Planner,
        setting: Setting,
        budget: Budget,
        read_plan: bool,
        greedy: bool = False,
        threads: bool = True,
    ):
        self.planner = planner
        self.budget = budget
        self.read_plan = read_plan
        self.threads = threads
        self.max_horizon = DEFAULT_SATISFICING_HORIZON  # set by the search
        # (With exogenous events, the layers are explicit ones of configurations.)
        self.usable = setting.goal and setting.at_least is None and setting.other_state is None
        self.layers: Layers | None = None
        self.greedy: Layers | None = None
        self.solving = 0.0  # seconds spent in solves so far
        self.atoms: Atoms | None = None
        if not self.usable:
            return
        if greedy and read_plan:
            # Any-plan search: a greedy forward search proposes a plan (or
            # proves that there is none) instead of the layers, on a model
            # it handles (not one with events: the layers serve those).
            from ethasp.planning.engines import greedy as greedy_engine

            if planner.handles(greedy_engine.FEATURES):
                self.greedy = greedy_engine.Greedy(Atoms(planner), budget, read_plan=True).start()
                return
            # The layers, for the proof that no plan exists: the plan is the
            # solver's (any-plan search reads no plan off the layers).
            self.read_plan = read_plan = False
        if not planner.handles(layers_module.FEATURES):
            self.usable = False  # the solver alone
            return
        large = (
            len(planner.get("action", 1)) >= LAYERS_AT_ONCE_ACTIONS
            or len(planner.get("variable", 1)) >= LAYERS_AT_ONCE_VARIABLES
        )
        if large and layers_module.can_fork():
            # Started now, before any solve: the child process works while
            # this process goes on grounding.
            self.layers = Layers(Atoms(planner), budget, read_plan=read_plan).start()
        else:
            # The ground atoms the layers need, read now: the planner's control
            # cannot be read while it solves, which is when the layers start.
            self.atoms = Atoms(planner)

    def status(self) -> Status | None:
        return self.layers.status if self.layers is not None else None

    def start(self) -> None:
        if self.layers is None and self.atoms is not None:
            self.layers = Layers(self.atoms, self.budget, read_plan=self.read_plan).start()

    def head_start(self) -> None:
        """Wait up to :data:`HEAD_START` seconds for an engine started with the
        search (not for layers that start later) to finish, where it may end
        the search with a plan (plain plan search)."""
        engine = (
            self.greedy
            if self.greedy is not None
            else (self.layers if self.atoms is None else None)
        )
        if engine is None or not self.read_plan:
            return
        end = time.monotonic() + HEAD_START
        # Meanwhile: what checking the engine's plan by its trace will read.
        self.planner.prepare_traces()
        while engine.status.working and not self.budget.expired():
            left = end - time.monotonic()
            if left <= 0:
                return
            engine.news.wait(min(left, 0.05))
            engine.news.clear()

    def greedy_plan(self) -> tuple | None:
        """The actions of a plan the greedy search proposed, if any (unchecked)."""
        return self.greedy.status.plan if self.greedy is not None else None

    def greedy_working(self) -> bool:
        return self.greedy is not None and self.greedy.status.working

    def greedy_news(self) -> None:
        """Wait a moment for news of the greedy search."""
        if self.greedy is not None:
            self.greedy.news.wait(0.05)
            self.greedy.news.clear()

    def greedy_complete(self) -> bool:
        """Did the greedy search expand every reachable state without a goal state?"""
        return self.greedy is not None and self.greedy.status.complete

    def settle(self, horizon: int) -> bool:
        """At the maximal horizon, with no plan of at most ``horizon`` steps: do
        the layers know every reachable state (configuration) within
        ``horizon + 1`` steps, so that no plan exists at all?  The layers
        (started now if they have not been) are waited for until they tell:
        once they know every state, or have a layer beyond ``horizon + 1``,
        or stopped.  The answer does not depend on how far they got before
        (:meth:`complete`): the same on every run.  False where they cannot
        tell within the budget, or where they do not serve the setting."""
        if not self.usable or self.greedy is not None:
            return False
        self.start()
        engine = self.layers
        if engine is None:
            return False
        while not self.budget.expired():
            if self.complete(horizon):
                return True
            status = engine.status
            if not status.working or status.bound > horizon + 1:
                return False
            engine.news.wait(0.05)
            engine.news.clear()
        return False

    def complete(self, horizon: int) -> bool:
        """Did the layers find every reachable state within ``horizon + 1``
        layers, none a goal state?  (Completeness found later is not claimed:
        another run might have stopped waiting before.)"""
        status = self.status()
        return status is not None and status.complete and status.bound <= horizon + 1

    def least_plan(self, length: int) -> tuple | None:
        """The least plan of ``length`` steps read off the layers, for a search
        whose plans they know (plain plan search): waited for while they work
        (the solver may have found the length first); None where they do not
        serve it, or stopped."""
        if self.layers is None or not self.read_plan:
            return None
        while not self.budget.expired():
            status = self.layers.status
            if status.plan is not None:
                return status.plan if len(status.plan) == length else None
            if not status.working or status.bound > length:
                return None
            self.layers.news.wait(0.05)
            self.layers.news.clear()
        return None

    def least_ready(self, length: int) -> bool:
        """Have the layers found the least plan of ``length`` steps (see
        :meth:`least_plan`, which then returns at once)?"""
        if self.layers is None or not self.read_plan:
            return False
        status = self.layers.status
        return status.plan is not None

    def moot(self, horizon: int) -> bool:
        """Is a solve at this horizon made pointless by what another engine
        proved (:meth:`done`), or by a lower bound of the layers beyond it?"""
        if self.done():
            return True
        status = self.status()
        return status is not None and status.bound > horizon

    def done(self) -> bool:
        """Did an engine end the search: a plan of at most :attr:`max_horizon`
        steps proposed, or every reachable state searched (the layers: within
        one layer beyond the maximal horizon, see :meth:`complete`)?  (A bound
        that makes one horizon moot does not: the search goes on, and the
        groundings a slow solve asks for pay there.)"""
        proposed = self.greedy_plan()
        if (proposed is not None and len(proposed) <= self.max_horizon) or self.greedy_complete():
            return True
        status = self.status()
        if status is None:
            return False
        read = status.plan is not None and len(status.plan) <= self.max_horizon
        return read or self.complete(self.max_horizon)

    def mutex_after(self) -> float:
        """Conflicts a solve meets before the h^2 mutexes are grounded."""
        if self.greedy is not None:
            # Never beside the greedy search: at the large horizons of any-plan
            # search their grounding takes seconds, uninterrupted.  (Not "while
            # it works": the program the solver's plan comes from must not
            # depend on how far another engine got.)
            return float("inf")
        status = self.status()
        if status is not None and status.working:
            return MUTEX_AFTER_LAYERS
        return MUTEX_AFTER

    def watch(self, horizon: int, bounds: bool = True) -> Budget:
        """The budget of a solve at this horizon: it also stops when another
        engine ends the search, or (``bounds``) when the layers make it moot
        (and starts them once the solver has worked long enough).  Any-plan
        searches do without ``bounds``: where a solve stops must not depend
        on how far the layers got, since the solver's plan is their answer."""
        started = time.monotonic()

        def moot() -> bool:
            if self.layers is None and self.solving + time.monotonic() - started > LAYERS_AFTER:
                self.start()
            return self.moot(horizon) if bounds else self.done()

        return self.budget.until(moot)

    def solved(self, seconds: float) -> None:
        self.solving += seconds
        if self.solving > LAYERS_AFTER:
            self.start()

    def spare_core(self) -> bool:
        """Did the layers give up (too many diagram nodes), leaving the core they
        took to a second solver thread?"""
        status = self.status()
        return (
            self.read_plan
            and self.threads
            and status is not None
            and bool(status.stopped)
            and _cores() >= 2
        )

    def stop(self) -> None:
        for engine in (self.layers, self.greedy):
            if engine is not None:
                engine.stop()


def _cores() -> int:
    """The processor cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def _shortest_proof(length: int) -> str:
    """Why a plan of ``length`` steps is a shortest one."""
    if length == 0:
        return "the goal holds in the initial state"
    return f"no plan has fewer than {steps(length)}"


def _at_maximum(horizon: int) -> str:
    """Why a search ended bounded at the maximal horizon."""
    return f"no plan up to horizon {horizon} (the maximal horizon)"


def _layers_plan(planner: Planner, status: Status) -> Plan:
    """A plan read off the exact layers, checked by its trace (the encodings)."""
    return _checked(planner, status.plan, "exact reachability")


# Least plans are found by the solver's heuristic only where its levels fit in
# clingo's numbers (steps times usable actions).
LEAST_LEVELS = 2**30


def _least(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    exact: _Exact,
    length: int,
    witness: Plan,
) -> Plan:
    """The least plan of ``length`` steps under the setting, ``length`` being
    the length of a shortest one and ``witness`` one of them: the solver's
    optimum of ``planning/lexicographic.lp`` at that horizon, or read off the
    layers where they know the setting's plans, whichever comes first (the
    same plan: both are the least one, so they race for speed only; the
    layers may take long to reach a horizon the solver settles at once, or the
    other way round).  Where the budget stops both first, the witness (a
    shortest plan all the same)."""
    if length == 0:
        return witness
    if exact.least_ready(length):
        read = exact.least_plan(length)
        if read is not None:
            return _checked(planner, read, "exact reachability")
    solved = _least_by_solver(
        planner, setting, budget.until(lambda: exact.least_ready(length)), length
    )
    if solved is not None:
        return solved
    read = exact.least_plan(length)
    if read is not None:
        return _checked(planner, read, "exact reachability")
    return witness


def _search_model(planner: Planner):
    """The planner's search model (:func:`ethasp.planning.engines.layers.
    search_model`), read once per planner: the searches of the sets of a
    goal's items on one soft HModel each hand it to the external planner."""
    memo = results(planner)
    if "search_model" not in memo:
        memo["search_model"] = layers_module.search_model(Atoms(planner))
    return memo["search_model"]


def _with_final_facts(model, facts):
    """A search model whose goal also asks ``facts`` of the final state
    (question constraints ``ends(F,B)``, see :func:`ethasp.planning.driver.
    planner.final_facts`).  A fact about a variable that no action changes is
    its value in every state, or else no plan meets it, which the encodings
    proved before any search (``questions/questions.lp``: relaxed
    reachability, and the goal): such facts are no goal facts of the task."""
    changing = set(model.variables)
    goal = list(model.goal)
    goal += [fact for fact in facts if fact[0] in changing and fact not in goal]
    return replace(model, goal=goal)


def _least_by_solver(planner: Planner, setting: Setting, budget: Budget, length: int):
    """The solver's least plan of ``length`` steps (the optimum, proven), or
    None where it does not fit in clingo's numbers or the budget stops it."""
    usable = len(planner.search_atoms("usable", 1))
    if (length + 1) * max(1, usable) >= LEAST_LEVELS:
        return None
    planner.threads(1)
    try:
        planner.use_least(budget)
    except GroundingStopped:
        return None
    least = replace(setting, least=True, satisficing=False, optimize=True)
    outcome = planner.solve(length, least, budget)
    if not outcome.satisfiable:
        return None
    return plans_of([outcome.symbols])[0]


def _external(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    max_horizon: int,
    longest: int | None,
    optimal: bool,
    all_plans: bool = False,
    deciding: bool = False,
) -> SearchResult | None:
    """The search by an external planner (:mod:`ethasp.planning.systems`):
    its result, or None where clingo searches (not chosen, not compiled, or
    the planner failed).  Its plan is checked by its trace; it is reported as
    the planner found it (the planner is chosen by the options and the task
    alone, and searches deterministically), so it may be another shortest
    plan than the least one that clingo reports."""
    from ethasp.planning import systems

    if not systems.usable(planner, setting, all_plans):
        return None
    from ethasp.planning.engines import downward, sas

    # Question constraints ends(F,B), the only ones handed over: goal facts
    # (those no plan meets were refused before: impossible_constraint).
    facts = final_facts(setting.constraints) or []
    ground = _with_final_facts(_search_model(planner), facts)
    try:
        task = downward.compiled(ground)
    except sas.NotCompiled as why:
        systems.warn(f"{why}: clingo searches instead")
        return None
    outcome = downward.solve(task, budget, optimal, deciding)
    if outcome.status == downward.STOPPED:
        return SearchResult(
            BOUNDED, optimal=optimal, proof=f"{budget.why_stopped()} during Fast Downward's search"
        )
    if outcome.status == downward.FAILED:
        systems.warn(f"Fast Downward failed ({outcome.why}): clingo searches instead")
        return None
    if outcome.status == downward.NO_PLAN:
        return SearchResult(NONE, horizon=0, optimal=optimal, proof=SEARCHED)
    plan = _checked(planner, task.plan(outcome.operators), "Fast Downward", setting.constraints)
    length = len(plan)
    if longest is not None and length > longest:
        if not optimal:
            return None  # more steps than the question allows: clingo looks within them
        return SearchResult(NONE, horizon=longest, proof=_too_long(longest))
    if length > max_horizon:
        if not optimal:
            return None  # too long for the search: clingo looks within the horizon
        return SearchResult(BOUNDED, horizon=max_horizon, proof=_at_maximum(max_horizon))
    proof = _shortest_proof(length) if optimal else GREEDY_PROOF
    return SearchResult(FOUND, plan=plan, horizon=length, optimal=optimal, proof=proof)


def shortest(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    max_horizon: int = DEFAULT_MAX_HORIZON,
    start: int = 0,
    start_proof: str = "",
    all_plans: bool = False,
    task: str = "plan search",
    longest: int | None = None,
    threads: bool = True,
    below: int | None = None,
) -> SearchResult:
    """A shortest plan under a setting, searching horizons ``start`` to ``max_horizon``.

    ``start`` must be a proven lower bound on the length of every plan under
    the setting (``start_proof`` says why); horizons below it are not solved.
    ``longest``, if given, is a proven upper bound (a question constraint
    allows no longer plan): once the horizons up to it are refuted, there is
    no plan.
    Exact layers run beside the solver (see :class:`_Exact`): their lower
    bounds skip horizons, and for plain plan search (no restriction, no
    question constraint, one plan) a shortest plan read off them, checked by
    its trace, ends the search; where they give up, plain plan search solves
    with :data:`SOLVER_THREADS` threads (one again when it ends), unless
    ``threads`` is False: searches that promise the same plan on every run
    (in an HModel: restrictions, questions) keep one.

    A model with action costs gets a cheapest plan instead
    (:func:`ethasp.planning.cost_search.cheapest`), of cost less than
    ``below`` if given.
    """
    if planner.has_costs:
        from ethasp.planning.cost_search import cheapest

        return cheapest(
            planner, setting, budget, max_horizon, start, all_plans, task, longest, below
        )
    if below is not None:
        raise InputError("a bound on the cost of plans needs a model with action costs")
    settled = settled_before(planner, setting, budget, max_horizon, start, longest)
    if settled is not None:
        return settled
    external = _external(planner, setting, budget, max_horizon, longest, True, all_plans)
    if external is not None:
        return external
    if start > max_horizon:
        return SearchResult(
            BOUNDED,
            horizon=max_horizon,
            proof=f"every plan has more than {steps(max_horizon)} ({start_proof}), "
            "the maximal horizon",
        )
    plain = not setting.constraints and not all_plans
    exact = _Exact(planner, setting, budget, read_plan=plain, threads=threads)
    # (A plan beyond the question's steps ends no search: it meets no question.)
    exact.max_horizon = max_horizon if longest is None else min(max_horizon, longest)
    if plain and _one_plan_wanted(setting):
        setting = replace(setting, canonical=True)
    try:
        return _shortest(
            planner,
            setting,
            budget,
            max_horizon,
            start,
            start_proof,
            all_plans,
            task,
            exact,
            longest,
        )
    finally:
        exact.stop()
        planner.threads(1)  # later searches on this grounding: one answer each time


def _shortest(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    max_horizon: int,
    start: int,
    start_proof: str,
    all_plans: bool,
    task: str,
    exact: _Exact,
    longest: int | None = None,
) -> SearchResult:
    if longest is not None:
        max_horizon = min(max_horizon, longest)
    checkpoints = _checkpoints(max_horizon)
    bound = start  # every plan has at least `bound` steps
    horizon = start
    exact.head_start()
    while True:
        status = exact.status()
        if status is not None:
            if status.plan is not None and len(status.plan) <= max_horizon and not all_plans:
                plan = _layers_plan(planner, status)  # the least shortest plan
                return SearchResult(
                    FOUND, plan=plan, horizon=len(plan), proof=_shortest_proof(len(plan))
                )
            if exact.complete(max_horizon):
                return SearchResult(NONE, horizon=0, proof=SEARCHED)
            bound = max(bound, status.bound)
        if bound > horizon:
            horizon = bound
        if horizon > max_horizon:
            return _at_max(planner, setting, budget, exact, max_horizon, longest)
        budget.report(task, horizon=horizon)
        if exact.spare_core():
            planner.threads(SOLVER_THREADS)  # the layers' core, for the solver
        began = time.monotonic()
        outcome = planner.solve(
            horizon,
            setting,
            exact.watch(horizon),
            models=0 if all_plans else 1,
            mutex_after=exact.mutex_after(),
            moot=exact.done,
        )
        exact.solved(time.monotonic() - began)
        if outcome.satisfiable is None:
            if budget.expired():
                return SearchResult(
                    BOUNDED, horizon=horizon, proof=f"{budget.why_stopped()} at horizon {horizon}"
                )
            continue  # the layers proved more: look again
        if outcome.satisfiable:
            proof = _shortest_proof(horizon)
            if all_plans:
                plans = sorted(plans_of(outcome.models), key=lambda plan: plan.actions)
                return SearchResult(FOUND, plan=plans[0], horizon=horizon, proof=proof, plans=plans)
            witness = plans_of([outcome.symbols])[0]
            plan = _least(planner, setting, budget, exact, horizon, witness)
            return SearchResult(FOUND, plan=plan, horizon=horizon, proof=proof)
        if longest is not None and horizon >= longest:
            return SearchResult(NONE, horizon=longest, proof=_too_long(longest))
        if horizon in checkpoints:
            # No plan of at most h steps, and no simple path of h + 1 steps: every
            # reachable state is within h steps of the initial one (a shortest
            # path to a state is simple), so none is a goal state.
            exists = planner.simple_path_exists(horizon + 1, setting, exact.watch(horizon))
            if exists is None:
                if budget.expired():
                    return SearchResult(
                        BOUNDED,
                        horizon=horizon,
                        proof=f"{budget.why_stopped()} at horizon {horizon}",
                    )
            elif not exists:
                return SearchResult(NONE, horizon=0, proof=SEARCHED)
        if horizon >= max_horizon:
            return _at_max(planner, setting, budget, exact, max_horizon, longest)
        horizon += 1


def _at_max(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    exact: _Exact,
    max_horizon: int,
    longest: int | None,
    optimal: bool = True,
) -> SearchResult:
    """No plan of at most ``max_horizon`` steps (proven): ``none`` if the
    question allows no more, or if the layers know every reachable state
    within one step beyond, or if no path one step beyond has no repeated
    state; else ``bounded``.  Both checks are made here, whatever the race
    proved before, so that the claim is the same on every run."""
    if longest is not None and max_horizon >= longest:
        return SearchResult(NONE, horizon=longest, optimal=optimal, proof=_too_long(longest))
    if exact.settle(max_horizon):
        return SearchResult(NONE, horizon=0, optimal=optimal, proof=SEARCHED)
    exists = planner.simple_path_exists(max_horizon + 1, setting, budget)
    if exists is False:
        return SearchResult(NONE, horizon=0, optimal=optimal, proof=SEARCHED)
    if exists is None and budget.expired():
        return SearchResult(
            BOUNDED,
            horizon=max_horizon,
            optimal=optimal,
            proof=f"{budget.why_stopped()} at horizon {max_horizon}",
        )
    return SearchResult(
        BOUNDED, horizon=max_horizon, optimal=optimal, proof=_at_maximum(max_horizon)
    )


def any_plan(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    max_horizon: int = DEFAULT_SATISFICING_HORIZON,
    start: int = 0,
    start_proof: str = "",
    task: str = "plan search",
    longest: int | None = None,
    deciding: bool = False,
) -> SearchResult:
    """Some plan under a setting, found fast and not proven shortest
    (``optimal`` False); ``longest`` as in :func:`shortest`; ``deciding``:
    a search that decides whether a plan exists, where a proof that none does
    is as likely (an external planner then searches in a way that exhausts
    the states faster, see :mod:`ethasp.planning.engines.downward`).

    The solver gets each horizon for a slice of work only (:data:`SLICE`
    conflicts): a horizon it refutes within it is a lower bound (as in
    :func:`shortest`); one it cannot decide is left for a larger one (a
    search to horizon h finds the plans of at most h steps, so larger
    horizons leave it more room), the horizon and the slice growing by
    :data:`GROWTH`.  For plain plan search (no restriction, no question
    constraint) on a model without exogenous events, a greedy forward search
    (:mod:`ethasp.planning.engines.greedy`) runs beside it in a child process;
    its plan is the answer wherever it finds one (the solver's plan only where
    it gives up), so that the answer does not depend on which finished first.
    Otherwise (and on a model with events, which the greedy search does not
    model) exact layers run beside it, for the proof that no plan exists.  A plan from either engine
    is checked by its trace.  ``none`` is proven as by :func:`shortest`:
    relaxed or exact reachability, or no path one step beyond a refuted
    horizon without a repeated state.
    """
    if max_horizon < 0:
        raise InputError("the maximal horizon must be at least 0")
    if budget.expired() or not planner.prepare(budget):
        return SearchResult(BOUNDED, horizon=start, optimal=False, proof=_before(budget, planner))
    if setting.goal and planner.is_fact("unreachable_goal"):
        return SearchResult(
            NONE,
            horizon=0,
            optimal=False,
            proof="the goal is unreachable even ignoring delete effects",
        )
    impossible = _impossible(planner, setting)
    if impossible:
        return SearchResult(NONE, horizon=0, optimal=False, proof=impossible)
    if longest is not None and start > longest:
        return SearchResult(NONE, horizon=longest, optimal=False, proof=_too_long(longest))
    result = _external(planner, setting, budget, max_horizon, longest, False, deciding=deciding)
    if result is None:
        plain = not setting.constraints
        exact = _Exact(planner, setting, budget, read_plan=plain, greedy=True)
        exact.max_horizon = max_horizon if longest is None else min(max_horizon, longest)
        setting = replace(setting, satisficing=True, canonical=plain and _one_plan_wanted(setting))
        try:
            result = _any_plan(
                planner, setting, budget, max_horizon, start, start_proof, task, exact, longest
            )
        finally:
            exact.stop()
    if result.plan is not None and planner.has_costs:  # (whichever planner found it)
        from ethasp.planning.cost_search import cost_of

        result.cost = cost_of(planner, result.plan)
    return result


def _any_plan(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    max_horizon: int,
    start: int,
    start_proof: str,
    task: str,
    exact: _Exact,
    longest: int | None = None,
) -> SearchResult:
    if longest is not None:
        max_horizon = min(max_horizon, longest)
    horizon, slice_, checked = start, float(SLICE), 0
    witness: Plan | None = None  # the solver's plan, if the greedy search gives up
    exact.head_start()
    while True:
        proposed = exact.greedy_plan()
        if proposed is not None and len(proposed) <= max_horizon:
            plan = _checked(planner, proposed, "greedy search")
            return SearchResult(
                FOUND,
                plan=plan,
                horizon=len(plan),
                optimal=False,
                proof=GREEDY_PROOF,
            )
        if exact.greedy_complete() or exact.complete(max_horizon):
            return SearchResult(NONE, horizon=0, optimal=False, proof=SEARCHED)
        if witness is not None:
            if exact.greedy_working() and not budget.expired():
                exact.greedy_news()  # the greedy search has the first word
                continue
            return SearchResult(
                FOUND,
                plan=witness,
                horizon=len(witness),
                optimal=False,
                proof=f"a plan found at horizon {horizon} (not proven shortest)",
            )
        if horizon > max_horizon:
            return _at_max(planner, setting, budget, exact, max_horizon, longest, optimal=False)
        budget.report(task, horizon=horizon)
        began = time.monotonic()
        outcome = planner.solve(
            horizon,
            setting,
            exact.watch(horizon, bounds=False),
            models=1,
            mutex_after=exact.mutex_after(),
            moot=exact.done,
            conflicts=int(slice_),
        )
        exact.solved(time.monotonic() - began)
        if outcome.satisfiable is None:
            if budget.expired():
                return SearchResult(
                    BOUNDED,
                    horizon=horizon,
                    optimal=False,
                    proof=f"{budget.why_stopped()} at horizon {horizon}",
                )
            if exact.done():
                continue  # another engine ended the search
            # The slice ran out: more room, and more work for it.
            if horizon >= max_horizon:
                slice_ *= GROWTH
                continue
            horizon = min(max_horizon, max(horizon + 1, int(horizon * GROWTH) + 1))
            slice_ *= GROWTH
            continue
        if outcome.satisfiable:
            witness = plans_of([outcome.symbols])[0]
            continue
        if longest is not None and horizon >= longest:
            return SearchResult(NONE, horizon=longest, optimal=False, proof=_too_long(longest))
        if horizon >= 4 * checked or horizon == max_horizon:
            checked = max(horizon, 1)
            exists = planner.simple_path_exists(horizon + 1, setting, exact.watch(horizon, False))
            if exists is False:
                return SearchResult(NONE, horizon=0, optimal=False, proof=SEARCHED)
            if exists is None and budget.expired():
                return SearchResult(
                    BOUNDED,
                    horizon=horizon,
                    optimal=False,
                    proof=f"{budget.why_stopped()} at horizon {horizon}",
                )
        if horizon >= max_horizon:
            return _at_max(planner, setting, budget, exact, max_horizon, longest, optimal=False)
        horizon += 1


def find_plan(
    model,
    max_horizon: int | None = None,
    time_limit: float | None = None,
    all_plans: bool = False,
    budget: Budget | None = None,
    satisficing: bool = False,
) -> SearchResult:
    """A shortest plan for the model (all shortest plans with ``all_plans``);
    with ``satisficing``, some plan, found fast and not proven shortest.
    ``max_horizon`` defaults to :data:`DEFAULT_MAX_HORIZON` (shortest plans)
    or :data:`DEFAULT_SATISFICING_HORIZON` (any plan).

    A model without a goal has nothing to plan for: InputError (under a
    principle, :func:`ethasp.principles.restriction.plan_with_principles`
    finds a shortest permissible action sequence instead).
    """
    model.require_planning("plan search without a principle")
    if not model.planner.get("goal", 2):
        raise InputError(
            "the model has no goal, so plan search has nothing to reach (with "
            "--principle NAME it finds a shortest action sequence permissible "
            "under NAME)"
        )
    budget = budget or Budget(time_limit)
    if satisficing:
        if all_plans:
            raise InputError(
                "all shortest plans cannot be listed by an any-plan search (satisficing)"
            )
        return any_plan(
            model.planner,
            Setting(),
            budget,
            DEFAULT_SATISFICING_HORIZON if max_horizon is None else max_horizon,
        )
    return shortest(
        model.planner,
        Setting(),
        budget,
        DEFAULT_MAX_HORIZON if max_horizon is None else max_horizon,
        all_plans=all_plans,
    )
