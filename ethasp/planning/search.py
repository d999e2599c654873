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
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field, replace

from ethasp.errors import InputError
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import MUTEX_AFTER, Planner, Setting
from ethasp.planning.engines import layers as layers_module
from ethasp.planning.engines.layers import Atoms, Layers, Status
from ethasp.planning.plan import Plan, steps

FOUND, NONE, BOUNDED = "found", "none", "bounded"

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

# Seconds a solve takes before the h^2 mutexes are grounded while the layers
# still work: often they end the search first, and the grounding (which
# cannot be interrupted) would only delay the end (freecell p01: 0.7 s).
# (Waiting longer, as long as their grounding is expected to take, slowed IPC
# scanalyzer on an idle machine: p4 found no shortest plan in 30 s instead of
# 24 s.)
MUTEX_AFTER_LAYERS = 0.25

# Solver threads for plain plan search once the layers have given up (their
# core is free): clasp's competing portfolio, about 1.3x to 1.8x faster on
# the hard horizons of depots.
SOLVER_THREADS = 2

# Any-plan search: seconds of solving a horizon gets before the search moves
# on to a larger one, and the factor by which horizons (and slices) grow then.
SLICE = 0.25
GROWTH = 1.5


@dataclass
class SearchResult:
    """The outcome of a plan search.

    ``plan`` is a plan (or None): a shortest one when ``optimal``, else (an
    any-plan search, ``satisficing``) just a plan; ``plans`` all shortest
    plans when they were asked for, ``horizon`` the last horizon searched,
    and ``proof`` says why there is no plan (status ``none``), why the plan
    is a shortest one or how it was found (status ``found``) or what cut the
    search short (status ``bounded``).
    """

    status: str
    plan: Plan | None = None
    horizon: int = 0
    proof: str = ""
    plans: list[Plan] = field(default_factory=list)
    optimal: bool = True

    def to_json(self) -> dict:
        return {
            "status": self.status,
            "plan": self.plan.to_list() if self.plan is not None else None,
            "optimal": self.optimal if self.plan is not None else None,
            "horizon": self.horizon,
            "proof": self.proof,
            **({"plans": [plan.to_list() for plan in self.plans]} if self.plans else {}),
        }


def _checkpoints(limit: int) -> set[int]:
    """The horizons after which the loop-free check runs: powers of four and the
    limit (each check costs a solve; they only prove that no plan exists)."""
    result, power = {limit}, 1
    while power <= limit:
        result.add(power)
        power *= 4
    return result


def plans_of(models: list) -> list[Plan]:
    """The plans of answer sets (their ``occurs/2`` atoms), without repeats."""
    plans = [Plan.from_symbols(symbols) for symbols in models]
    return list(dict.fromkeys(plans))


class _Exact:
    """Exact layers (:mod:`ethasp.planning.engines.layers`) beside a search, started once
    the solver has worked :data:`LAYERS_AFTER` seconds (with the search, for
    models of at least :data:`LAYERS_AT_ONCE_ACTIONS` ground actions or
    :data:`LAYERS_AT_ONCE_VARIABLES` state variables), for
    searches with the goal and without utility thresholds or states to avoid
    (the layers know the model's plans, and every plan a setting allows is one
    of them).  With ``greedy`` (any-plan search) and ``read_plan`` (plain
    search), the greedy forward search (:mod:`ethasp.planning.engines.greedy`) runs
    instead of the layers, started with the search."""

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
            # proves that there is none) instead of the layers.
            from ethasp.planning.engines.greedy import Greedy

            self.greedy = Greedy(Atoms(planner), budget, read_plan=True).start()
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

    def greedy_complete(self) -> bool:
        """Did the greedy search expand every reachable state without a goal state?"""
        return self.greedy is not None and self.greedy.status.complete

    def settle(self, horizon: int) -> bool:
        """At the maximal horizon, with no plan of at most ``horizon`` steps: is
        every reachable state (configuration) within ``horizon`` steps, so that
        no plan exists at all?  The engine beside the search (started now if it
        has not been) is waited for until it tells: the layers once they have
        layer ``horizon + 1`` or know every state; the greedy search once it
        has expanded every state or stopped.  False where it cannot tell
        within the budget, or where no engine serves the setting."""
        if not self.usable:
            return False
        self.start()
        engine = self.greedy if self.greedy is not None else self.layers
        if engine is None:
            return False
        while not self.budget.expired():
            status = engine.status
            if status.complete:
                return True
            if not status.working or status.bound > horizon + 1:
                return False
            engine.news.wait(0.05)
            engine.news.clear()
        return False

    def moot(self, horizon: int) -> bool:
        """Is a solve at this horizon made pointless by what the layers proved
        (or by a plan that the greedy search proposed, of at most
        :attr:`max_horizon` steps)?"""
        proposed = self.greedy_plan()
        if (proposed is not None and len(proposed) <= self.max_horizon) or self.greedy_complete():
            return True
        status = self.status()
        if status is None:
            return False
        return (
            (status.plan is not None and len(status.plan) <= self.max_horizon)
            or status.complete
            or status.bound > horizon
        )

    def done(self) -> bool:
        """Did an engine end the search: a plan proposed, or every reachable
        state searched?  (A bound that makes one horizon moot does not: the
        search goes on, and the groundings a slow solve asks for pay there.)"""
        if self.greedy_plan() is not None or self.greedy_complete():
            return True
        status = self.status()
        return status is not None and (status.plan is not None or status.complete)

    def mutex_after(self) -> float:
        """Seconds a solve takes before the h^2 mutexes are grounded."""
        if self.greedy is not None and self.greedy.status.working:
            # Never while the greedy search works: at the large horizons of
            # any-plan search their grounding takes seconds, uninterrupted.
            return float("inf")
        status = self.status()
        if status is not None and status.working:
            return MUTEX_AFTER_LAYERS
        return MUTEX_AFTER

    def watch(self, horizon: int) -> Budget:
        """The budget of a solve at this horizon: it also stops when the layers
        make it moot (and starts them once the solver has worked long enough)."""
        started = time.monotonic()

        def moot() -> bool:
            if self.layers is None and self.solving + time.monotonic() - started > LAYERS_AFTER:
                self.start()
            return self.moot(horizon)

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


def _one_plan_wanted(setting: Setting) -> bool:
    """Does a search under this setting want just some plan of each length (so
    that independent actions may be taken in one order, ``planning/
    canonical.lp``)?  Not with utility thresholds, states to avoid or
    optimisation (they read the states a plan passes)."""
    return (
        setting.goal
        and setting.at_least is None
        and setting.other_state is None
        and not setting.optimize
    )


def _before(budget: Budget, planner: Planner) -> str:
    """Why a search stopped before its first solve."""
    grounding = " (while grounding its first parts)" if planner.grounding else ""
    return f"{budget.why_stopped()} before the search began{grounding}"


def _searched(horizon: int) -> str:
    """Why there is no plan: plans up to the horizon refuted, and no path one
    step longer without a repeated state."""
    return (
        f"no plan up to horizon {horizon}, and no path of {steps(horizon + 1)} without a "
        "repeated state: every reachable state was searched"
    )


def _settled(horizon: int) -> str:
    """Why there is no plan, where the engine beside the search knew every
    reachable state by the maximal horizon."""
    return (
        f"no plan up to horizon {horizon} (the maximal horizon), and exact reachability "
        "knows every reachable state: none is a goal state"
    )


def _bound_proof(bound: int, why: str, horizon: int) -> str:
    """Why no plan has fewer than ``horizon`` steps, horizons below ``bound``
    refuted by ``why`` and the others by solves."""
    if horizon == 0:
        return "the goal holds in the initial state"
    if bound <= 0:
        return f"no plan has fewer than {steps(horizon)} (every smaller horizon refuted)"
    if bound >= horizon:
        return f"no plan has fewer than {steps(horizon)}: {why}"
    return (
        f"no plan has fewer than {steps(horizon)}: none has fewer than {steps(bound)} ({why}), "
        f"and the horizons {bound} to {horizon - 1} refuted"
    )


def _layers_plan(planner: Planner, status: Status) -> Plan:
    """A plan read off the exact layers, checked by its trace (the encodings)."""
    return _checked(planner, status.plan, "exact reachability")


def _checked(planner: Planner, actions, engine: str) -> Plan:
    """A plan that an engine proposed, checked by its trace (the encodings)."""
    plan = Plan(tuple(actions))
    answer = planner.trace(plan)
    if not answer.get("plan", 0):
        raise RuntimeError(f"{engine} proposed {plan}, which the encodings refute")
    return plan


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
    """
    if max_horizon < 0:
        raise InputError("the maximal horizon must be at least 0")
    if budget.expired() or not planner.prepare(budget):
        return SearchResult(BOUNDED, horizon=start, proof=_before(budget, planner))
    if setting.goal and planner.is_fact("unreachable_goal"):
        return SearchResult(
            NONE, horizon=0, proof="the goal is unreachable even ignoring delete effects"
        )
    impossible = _impossible(planner, setting)
    if impossible:
        return SearchResult(NONE, horizon=0, proof=impossible)
    if longest is not None and start > longest:
        return SearchResult(NONE, horizon=start, proof=_too_long(longest, start_proof))
    if start > max_horizon:
        return SearchResult(
            BOUNDED,
            horizon=max_horizon,
            proof=f"every plan has more than {steps(max_horizon)} ({start_proof}), "
            "the maximal horizon",
        )
    plain = not setting.constraints and not all_plans
    exact = _Exact(planner, setting, budget, read_plan=plain, threads=threads)
    exact.max_horizon = max_horizon
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


def _impossible(planner: Planner, setting: Setting) -> str:
    """Why no plan meets the setting's question constraints, if the grounding
    knows it before any search (a constraint against the goal, or one that
    needs what relaxed reachability excludes); else the empty text."""
    if not setting.goal or not setting.constraints:
        return ""
    found = planner.impossible(sorted(setting.constraints, key=str))
    if not found:
        return ""
    constraint, why = found[0]
    if why == "goal":
        return f"the question's constraint {constraint} contradicts the goal"
    return (
        f"the question's constraint {constraint} needs an action or a fact that is "
        "unreachable even ignoring delete effects"
    )


def _too_long(longest: int, why: str) -> str:
    """Why no plan exists when every plan has more steps than the question allows."""
    return (
        f"every plan has more than {steps(longest)} ({why}), and the question allows at "
        f"most {steps(longest)}"
    )


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
    bound, why = start, start_proof  # every plan has at least `bound` steps
    horizon = start
    exact.head_start()
    while True:
        status = exact.status()
        if status is not None:
            if status.plan is not None and len(status.plan) <= max_horizon:
                plan = _layers_plan(planner, status)
                return SearchResult(
                    FOUND,
                    plan=plan,
                    horizon=len(plan),
                    proof=(
                        f"no plan has fewer than {steps(len(plan))}: exact reachability found no "
                        f"goal state within {steps(len(plan) - 1)}"
                        if len(plan)
                        else "the goal holds in the initial state"
                    ),
                )
            if status.complete:
                return SearchResult(
                    NONE,
                    horizon=horizon,
                    proof=(
                        "exact reachability layers ran out of new states without meeting a goal "
                        "state: no goal state is reachable"
                    ),
                )
            if status.bound > bound:
                bound = status.bound
                why = f"exact reachability found no goal state within {steps(bound - 1)}"
        if bound > horizon:
            horizon = bound
        if horizon > max_horizon:
            if longest is not None and max_horizon >= longest:
                return SearchResult(NONE, horizon=max_horizon, proof=_too_long(longest, why))
            return SearchResult(
                BOUNDED,
                horizon=max_horizon,
                proof=f"every plan has more than {steps(max_horizon)} ({why}), the maximal horizon",
            )
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
            plans = plans_of(outcome.models if all_plans else [outcome.symbols])
            return SearchResult(
                FOUND,
                plan=plans[0],
                horizon=horizon,
                proof=_bound_proof(bound, why, horizon),
                plans=plans if all_plans else [],
            )
        if longest is not None and horizon >= longest:
            return SearchResult(
                NONE,
                horizon=horizon,
                proof=(
                    f"no plan up to horizon {horizon}, and the question allows at most "
                    f"{steps(longest)}"
                ),
            )
        if horizon in checkpoints:
            # No plan of at most h steps, and no simple path of h + 1 steps: every
            # reachable state is within h steps of the initial one (a shortest
            # path to a state is simple), so none is a goal state.
            began = time.monotonic()
            exists = planner.simple_path_exists(horizon + 1, setting, exact.watch(horizon))
            exact.solved(time.monotonic() - began)
            if exists is None:
                if budget.expired():
                    return SearchResult(
                        BOUNDED,
                        horizon=horizon,
                        proof=f"{budget.why_stopped()} at horizon {horizon}",
                    )
            elif not exists:
                return SearchResult(NONE, horizon=horizon, proof=_searched(horizon))
        if horizon >= max_horizon:
            if exact.settle(max_horizon):
                return SearchResult(NONE, horizon=horizon, proof=_settled(max_horizon))
            return SearchResult(
                BOUNDED,
                horizon=max_horizon,
                proof=f"no plan up to horizon {max_horizon} (the maximal horizon)",
            )
        horizon += 1


def any_plan(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    max_horizon: int = DEFAULT_SATISFICING_HORIZON,
    start: int = 0,
    start_proof: str = "",
    task: str = "plan search",
    longest: int | None = None,
) -> SearchResult:
    """Some plan under a setting, found fast and not proven shortest
    (``optimal`` False); ``longest`` as in :func:`shortest`.

    The solver gets each horizon for a slice of time only: a horizon it
    refutes in time is a lower bound (as in :func:`shortest`); one it cannot
    decide in time is left for a larger one (a search to horizon h finds the
    plans of at most h steps, so larger horizons leave it more room), the
    horizon and the slice growing by :data:`GROWTH`.  For plain plan search
    (no restriction, no question constraint) a greedy forward search
    (:mod:`ethasp.planning.engines.greedy`) runs beside it in a child process and
    may deliver a plan (or the proof that none exists) first; otherwise exact
    layers run beside it as in :func:`shortest`.  A plan from either engine is
    checked by its trace.  ``none`` is proven as by :func:`shortest`: relaxed or exact
    reachability, or a refuted horizon without a simple path of its length.
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
        return SearchResult(
            NONE, horizon=start, optimal=False, proof=_too_long(longest, start_proof)
        )
    plain = not setting.constraints
    exact = _Exact(planner, setting, budget, read_plan=plain, greedy=True)
    exact.max_horizon = max_horizon
    setting = replace(setting, satisficing=True, canonical=plain and _one_plan_wanted(setting))
    try:
        return _any_plan(
            planner, setting, budget, max_horizon, start, start_proof, task, exact, longest
        )
    finally:
        exact.stop()


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
    bound, why = start, start_proof  # every plan has at least `bound` steps
    horizon, slice_, checked = start, SLICE, 0
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
                proof="a plan found by greedy forward search (not proven shortest)",
            )
        if exact.greedy_complete():
            return SearchResult(
                NONE,
                horizon=horizon,
                optimal=False,
                proof=(
                    "greedy forward search expanded every reachable state (but those from "
                    "which even the relaxed goal is unreachable), and none is a goal state"
                ),
            )
        status = exact.status()
        if status is not None:
            if status.plan is not None and len(status.plan) <= max_horizon:
                plan = _layers_plan(planner, status)
                return SearchResult(
                    FOUND,
                    plan=plan,
                    horizon=len(plan),
                    optimal=False,
                    proof="a plan read off exact reachability layers",
                )
            if status.complete:
                return SearchResult(
                    NONE,
                    horizon=horizon,
                    optimal=False,
                    proof=(
                        "exact reachability layers ran out of new states without meeting a goal "
                        "state: no goal state is reachable"
                    ),
                )
            if status.bound > bound:
                bound = status.bound
                why = f"exact reachability found no goal state within {steps(bound - 1)}"
        horizon = max(horizon, bound)
        if horizon > max_horizon:
            if longest is not None and max_horizon >= longest:
                return SearchResult(
                    NONE, horizon=max_horizon, optimal=False, proof=_too_long(longest, why)
                )
            return SearchResult(
                BOUNDED,
                horizon=max_horizon,
                optimal=False,
                proof=f"no plan found up to horizon {max_horizon} (the maximal "
                f"horizon; every plan has at least {steps(bound)})",
            )
        budget.report(task, horizon=horizon)
        began = time.monotonic()
        end = began + slice_
        watch = exact.watch(horizon)

        def past(end: float = end) -> bool:
            return time.monotonic() > end

        outcome = planner.solve(
            horizon,
            setting,
            watch.until(past),
            models=1,
            mutex_after=exact.mutex_after(),
            moot=exact.done,
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
            if exact.moot(horizon):
                continue  # the layers proved more: look again
            # The slice ran out: more room, and more time for it.
            horizon = min(max_horizon, max(horizon + 1, int(horizon * GROWTH) + 1))
            slice_ *= GROWTH
            continue
        if outcome.satisfiable:
            plan = plans_of([outcome.symbols])[0]
            return SearchResult(
                FOUND,
                plan=plan,
                horizon=horizon,
                optimal=False,
                proof=f"a plan found at horizon {horizon} (not proven shortest)",
            )
        bound, why = horizon + 1, f"horizon {horizon} refuted"
        if longest is not None and horizon >= longest:
            return SearchResult(
                NONE,
                horizon=horizon,
                optimal=False,
                proof=(
                    f"no plan up to horizon {horizon}, and the question allows at most "
                    f"{steps(longest)}"
                ),
            )
        if horizon >= 4 * checked or horizon == max_horizon:
            checked = max(horizon, 1)
            exists = planner.simple_path_exists(horizon + 1, setting, exact.watch(horizon))
            if exists is False:
                return SearchResult(NONE, horizon=horizon, optimal=False, proof=_searched(horizon))
            if exists is None and budget.expired():
                return SearchResult(
                    BOUNDED,
                    horizon=horizon,
                    optimal=False,
                    proof=f"{budget.why_stopped()} at horizon {horizon}",
                )
        if horizon >= max_horizon:
            if exact.settle(max_horizon):
                return SearchResult(
                    NONE, horizon=horizon, optimal=False, proof=_settled(max_horizon)
                )
            return SearchResult(
                BOUNDED,
                horizon=max_horizon,
                optimal=False,
                proof=f"no plan up to horizon {max_horizon} (the maximal horizon)",
            )
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
