"""Reachable states of high utility, for utilitarianism: proofs, not bounds.

Utilitarianism compares the final state of a plan with every reachable state
(Definition 2 of the paper).  Three engines answer, the first that can:

* exact reachability (:mod:`ethasp.planning.engines.reachability`): breadth-first
  layers of states, computed symbolically; every layer is exact, so a state
  better than a given utility is found at its shortest distance, and once no
  new state appears every reachable state is known (``proven``);
* for models with exogenous events, which the diagrams do not model,
  explicit breadth-first layers of configurations (state, time)
  (:mod:`ethasp.planning.engines.explicit`), with the same claims, up to a limit on
  the configurations;
* when its diagrams outgrow their limit, Fast Downward where the model's
  planning system hands searches to it (see the comment above
  :func:`_planner_search`), else clingo optimisation over the
  planner's grounding (``encodings/judgement/best.lp``, a search without the
  goal, at horizons 0, 1, 2, 4, 8, ...), proven by the relaxed upper bound
  or the loop-free threshold (``encodings/planning/loopfree.lp``).

Where Fast Downward searches, the best reachable state is first sought as a
goal state that attains the upper bound, by one A* search on a classical
goal (the model's goal and the facts every state of that utility has),
before any diagram is built: where one exists, it is the answer (the
nearest such goal state), however many layers the diagrams would grow to
reach it.

Each engine is used only on a model it handles (``FEATURES``, asked through
:meth:`ethasp.planning.driver.planner.Planner.handles`).  Every state they
report carries a plan that reaches it (:attr:`ReachableState.plan`: a path
read off the layers, or the actions of the answer set), checked by its trace
(``encodings/planning/trace.lp``) before it is reported: the trace must end
in that state, of that utility.  So "a better reachable state exists" comes
with the better plan.

Both stop as soon as the question is decided: a state better than the final
state decides "impermissible" at once; the search for the *best* state goes
on only for answers that need it (HPlans, ``best_reachable``).  An upper
bound (per variable, the best utility of a value reachable ignoring delete
effects) ends a search for the best as soon as a state attains it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import clingo
from clorm import Raw, unify

from ethasp import vocabulary  # (its predicates are made when first read)
from ethasp.memo import results
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import Planner, Setting
from ethasp.planning.engines import ALL_FEATURES, require
from ethasp.planning.plan import Plan, steps
from ethasp.planning.search import DEFAULT_MAX_HORIZON

if TYPE_CHECKING:  # the diagrams are loaded by the planner, where a model needs them
    from ethasp.planning.engines.reachability import Best, Reachability

# The model features this engine handles (ethasp.planning.engines).
FEATURES = ALL_FEATURES


PROVEN, BOUNDED = "proven", "bounded"

# The name of a compared state, as a conjunction of facts in ASP (conj/3).
BEST = clingo.Function("best")


def literal(variable: clingo.Symbol, value: bool) -> str:
    """A fact as text: ``v`` for true, ``-v`` for false."""
    return str(variable) if value else f"-{variable}"


@dataclass
class ReachableState:
    """A reachable state: its facts (variable, value), its utility, and the
    length of a path to it (the shortest, when found by exact reachability or
    the explicit layers); ``plan``, the actions of that path, is its witness
    (:func:`witnessed`: its trace ends in the state)."""

    facts: list[tuple[clingo.Symbol, bool]]
    utility: int
    distance: int
    plan: Plan | None = None

    @property
    def literals(self) -> list[str]:
        return sorted(literal(v, b) for v, b in self.facts)

    def asp_facts(self, name: clingo.Symbol = BEST) -> list:
        """``alternative(name)`` and its ``conj(name,V,B)`` facts."""
        return [vocabulary.Alternative(name=Raw(name))] + [
            vocabulary.Conj(name=Raw(name), variable=Raw(v), value="true" if b else "false")
            for v, b in self.facts
        ]

    def to_json(self) -> dict:
        data: dict = {"state": self.literals, "utility": self.utility, "distance": self.distance}
        if self.plan is not None:
            data["plan"] = self.plan.to_list()
        return data


@dataclass
class BestReachable:
    """A best reachable state (as far as searched).

    ``state`` is None when the search stopped before any state was valued.
    ``status`` is ``proven`` (no reachable state is better) or ``bounded``
    (a better one may exist), and ``proof`` says why; ``searched`` is how far
    the search looked (layers or horizon).
    """

    status: str
    proof: str
    found: ReachableState | None = None
    searched: int = 0

    @property
    def state(self) -> list[str] | None:
        return self.found.literals if self.found else None

    @property
    def utility(self) -> int | None:
        return self.found.utility if self.found else None

    @property
    def horizon(self) -> int:
        return self.found.distance if self.found else 0

    @property
    def facts(self) -> list[tuple[clingo.Symbol, str]]:
        return [(v, "true" if b else "false") for v, b in self.found.facts] if self.found else []

    @property
    def plan(self) -> Plan | None:
        """A plan that reaches the state (its witness)."""
        return self.found.plan if self.found else None

    def to_json(self) -> dict:
        return {
            "state": self.state,
            "utility": self.utility,
            "horizon": self.horizon,
            "plan": self.plan.to_list() if self.plan is not None else None,
            "status": self.status,
            "proof": self.proof,
        }


@dataclass
class Comparison:
    """Whether some reachable state is better than a given utility.

    ``better`` is a reachable state of higher utility (then the answer is yes,
    proven), or None: no reachable state is better (``status`` proven) or
    none was found within the bounds (``bounded``).  ``best`` is a best
    reachable state when the search established one.
    """

    status: str
    proof: str
    better: ReachableState | None = None
    best: BestReachable | None = None


# -- the exact engine -------------------------------------------------------------


def witnessed(
    planner: Planner, facts: list[tuple[clingo.Symbol, bool]], utility: int, plan, engine: str
) -> ReachableState:
    """A reachable state that an engine found, with the plan that reaches it,
    checked by the plan's trace (``encodings/planning/trace.lp``): the actions
    apply one after the other, and the final state (after the events still
    due) is that state, of that utility.  RuntimeError where the encodings
    refute the engine.  The state keeps its state variables (derived ones
    follow from them)."""
    plan = Plan(tuple(plan))
    trace = planner.trace(plan)
    final = {
        (atom.arguments[0], atom.arguments[1].name == "true") for atom in trace.get("final", 2)
    }
    variables = {variable for variable, _ in final}
    facts = [fact for fact in facts if fact[0] in variables]
    worth = [atom.arguments[0].number for atom in trace.get("utility_of_final", 1)]
    if (
        trace.get("invalid", 1)
        or trace.get("failure", 1)
        or final != set(facts)
        or worth != [utility]
    ):
        raise RuntimeError(
            f"{engine} found a state of utility {utility} reached by "
            f"{plan or '(the empty plan)'}, which the encodings refute"
        )
    return ReachableState(facts, utility, len(plan), plan)


def _state(planner: Planner, r: Reachability, best: Best) -> ReachableState:
    """A state of the diagrams, with the least of the shortest paths to it (the
    same plan on every run)."""
    facts = [(v, v in best.state) for v in planner.ground_model().variables]
    path = r.least_path(r.state(best.state), best.layer)
    return witnessed(planner, facts, best.utility, path, "exact reachability")


def upper_bound(planner: Planner) -> int:
    """No reachable state has a higher utility (per variable, the best utility of
    a value reachable ignoring delete effects: ``upper_bound/1`` of relaxed.lp)."""
    atoms = (
        unify([vocabulary.UpperBound], planner.bound().get("upper_bound", 1))
        .query(vocabulary.UpperBound)
        .all()
    )
    return next(iter(atoms)).bound


# Models with more variables than this are first probed by short searches for a
# better state (horizons, conflicts each: work, not seconds, so that the same
# state is found on every run) before exact reachability.
PROBE_VARIABLES = 300
PROBE_HORIZONS = (1, 2, 4, 8)
PROBE_CONFLICTS = 20_000


UB_PROOF = (
    "utility {u} is the upper bound (per variable, the best utility of a value "
    "reachable ignoring delete effects)"
)


def _grow(
    engine, budget: Budget, max_horizon: int, decided: Callable[[int], bool], task: str, what: str
) -> str:
    """Grow the layers of an engine (exact reachability's states or explicit
    configurations) until ``decided(k)`` holds for a layer k, every state is
    known, or a limit; return why it stopped ('' when decided or complete).
    ``what`` names the layers' contents in that reason."""
    k = 0
    while True:
        if k < len(engine.layers):
            budget.report(task, horizon=k)
            if decided(k):
                return ""
            k += 1
            continue
        if engine.complete:
            return ""
        if len(engine.layers) > max_horizon:
            # The last layer allowed: complete if no state lies beyond it.
            closed = engine.closed(budget)
            if closed:
                return ""
            if closed is None:
                return engine.stopped
            return f"the {what} reached within {steps(max_horizon)} (the maximal horizon)"
        if not engine.expand(budget):
            return engine.stopped


def _best_reachable(
    planner: Planner,
    budget: Budget,
    max_horizon: int,
    within: str,
    other_than: list[tuple[clingo.Symbol, bool]] | None,
) -> BestReachable:
    """:func:`best_reachable`, under the planner's lock; proven results are kept."""
    key = ("best_reachable", within, frozenset(other_than or ()), max_horizon)
    if key in results(planner):
        return results(planner)[key]
    # Where Fast Downward searches: first a goal state that attains the bound
    # (one A* search on a classical goal), which proves the best utility.
    result = _bound_by_planner(planner, budget, within, other_than)
    if result is None:
        result = _best_exact(planner, budget, max_horizon, within, other_than)
    if result is None:
        # The diagrams gave up: Fast Downward's searches, where it searches.
        result = _best_by_planner(planner, budget, within, other_than)
    if result is None:
        result = _best_by_optimisation(planner, budget, max_horizon, within, other_than)
    if result.status == PROVEN:
        results(planner)[key] = result
    return result


def _restriction(r: Reachability, within: str, other_than):
    states = r.goal() if within == "goal" else None
    if other_than is not None:
        avoid = ~r.condition(other_than)
        states = avoid if states is None else states & avoid
    return states


def _bound_states(planner: Planner, r: Reachability):
    """The reachable states that attain the upper bound are those with every
    ``best_fact/2`` of relaxed.lp: a cube, cheap to test a layer against."""
    atoms = (
        unify([vocabulary.BestFact], planner.bound().get("best_fact", 2))
        .query(vocabulary.BestFact)
        .all()
    )
    facts = [(atom.variable.symbol, atom.value == "true") for atom in atoms]
    return r.condition(facts)


# -- models with exogenous events: explicit layers of configurations ----------------


def configurations(planner: Planner):
    """The explicit layers of the planner's ground model (events included), made once."""
    if "configurations" not in results(planner):
        from ethasp.planning.engines.explicit import Configurations, Events
        from ethasp.planning.engines.task import Task

        ground = planner.ground_model()
        task = Task(ground)
        results(planner)["configurations"] = Configurations(task, Events(ground.events, task.index))
    return results(planner)["configurations"]


def _final_state(planner: Planner, layers, configuration) -> ReachableState:
    """A configuration's final state, as a reachable state, with a shortest
    path to the configuration."""
    final = layers.events.finish(configuration)
    variables = planner.ground_model().variables
    index = layers.task.index
    facts = [(v, bool(final >> index[v] & 1)) for v in variables]
    return witnessed(
        planner, facts, layers.task.utility(final), layers.path(configuration), "explicit layers"
    )


def _best_explicit(
    planner: Planner, budget: Budget, max_horizon: int, within: str, other_than
) -> BestReachable | None:
    """The best reachable state of a model with events, by explicit layers;
    None where they gave up (too many configurations) with time left."""
    layers = configurations(planner)
    task = layers.task
    # other_than: the states that agree with all these literals are left out.
    pos = sum(1 << task.index[v] for v, b in other_than or () if b)
    neg = sum(1 << task.index[v] for v, b in other_than or () if not b)
    found: list = []  # (utility, goal, -layer, configuration)

    def visit(k: int) -> bool:
        for configuration in layers.layers[k]:
            final = layers.events.finish(configuration)
            if other_than is not None and final & pos == pos and not final & neg:
                continue
            goal = task.is_goal(task.full(final))
            if within == "goal" and not goal:
                continue
            key = (task.utility(final), goal, -k)
            if not found or key > found[0][:3]:
                found[:] = [(*key, configuration)]
        return False

    layers = configurations(planner)
    stopped = _grow(layers, budget, max_horizon, visit, "best reachable state", "configurations")
    searched = len(layers.layers) - 1
    best = _final_state(planner, layers, found[0][3]) if found else None
    if not stopped:
        proof = (
            "every reachable state is known (explicit layers of configurations, exogenous "
            f"events included: no new one after {steps(searched)})"
        )
        if best is None:
            return BestReachable(PROVEN, proof + "; none is in the set asked for", None, searched)
        return BestReachable(PROVEN, proof, best, searched)
    if stopped.startswith("more than") and not budget.expired():
        return None  # the layers gave up: optimisation takes over
    return BestReachable(
        BOUNDED,
        f"searched the states reached within {steps(searched)}; stopped: {stopped}",
        best,
        searched,
    )


def _better_explicit(
    planner: Planner, utility: int, budget: Budget, max_horizon: int
) -> Comparison | None:
    """Is a reachable state better than ``utility`` (a model with events, by
    explicit layers)?  None where they gave up with time left."""
    layers = configurations(planner)
    found: list = []

    def visit(k: int) -> bool:
        for configuration in layers.layers[k]:
            if layers.task.utility(layers.events.finish(configuration)) > utility:
                found.append(configuration)
                return True
        return False

    layers = configurations(planner)
    stopped = _grow(
        layers, budget, max_horizon, visit, "a better reachable state", "configurations"
    )
    if found:
        state = _final_state(planner, layers, found[0])
        return Comparison(
            PROVEN,
            f"a state of utility {state.utility} is reachable in {steps(state.distance)}",
            better=state,
        )
    if not stopped:
        best = _best_explicit(planner, budget, max_horizon, "all", None)
        return Comparison(PROVEN, f"no reachable state is better: {best.proof}", best=best)
    if stopped.startswith("more than") and not budget.expired():
        return None  # the layers gave up: the threshold searches take over
    searched = len(layers.layers) - 1
    return Comparison(
        BOUNDED, f"no better state among those reached within {steps(searched)}; stopped: {stopped}"
    )


def _engine(planner: Planner) -> str | None:
    """The layers that serve the model: ``reachability`` (the diagrams) where
    they handle it, else ``explicit`` (models with events), else None (the
    searches in ASP alone)."""
    from ethasp.planning.engines import explicit, reachability

    if planner.handles(reachability.FEATURES):
        return "reachability"
    if planner.handles(explicit.FEATURES):
        return "explicit"
    return None


def _best_exact(
    planner: Planner, budget: Budget, max_horizon: int, within: str, other_than
) -> BestReachable | None:
    engine = _engine(planner)
    if engine == "explicit":
        return _best_explicit(planner, budget, max_horizon, within, other_than)
    if engine is None:
        return None  # optimisation in ASP
    bound = upper_bound(planner)
    r = planner.reachability()
    restriction = _restriction(r, within, other_than)
    attaining = _bound_states(planner, r)
    if restriction is not None:
        attaining &= restriction
    hit: list[int] = []

    def decided(k: int) -> bool:
        budget.report("best reachable state", horizon=k, bound=bound)
        if r.layers[k] & attaining != r.bdd.false:
            hit.append(k)
            return True
        return False

    stopped = _grow(r, budget, max_horizon, decided, "best reachable state", "layers of states")
    searched = len(r.layers) - 1
    if hit:
        states = r.prefix(hit[0]) & attaining
        best = r.best_of(_goal_first(r, states))
        return BestReachable(PROVEN, UB_PROOF.format(u=bound), _state(planner, r, best), searched)
    reached = r.prefix(searched)
    within_reached = reached if restriction is None else reached & restriction
    best = r.best_of(within_reached)
    if best is not None:
        best = r.best_of(_goal_first(r, within_reached, best.utility)) or best
    if not stopped:
        proof = (
            f"every reachable state is known (exact reachability: no new state after "
            f"{steps(searched)})"
        )
        if best is None:
            return BestReachable(PROVEN, proof + "; none is in the set asked for", None, searched)
        return BestReachable(PROVEN, proof, _state(planner, r, best), searched)
    if "diagram nodes" in stopped and not budget.expired():
        return None  # the exact engine gave up: optimisation takes over
    return BestReachable(
        BOUNDED,
        f"searched the states reached within {steps(searched)}; stopped: {stopped}",
        _state(planner, r, best) if best else None,
        searched,
    )


def _goal_first(r: Reachability, states, utility: int | None = None):
    """Goal states among ``states`` (of utility ``utility`` if given), if there
    are such goal states as good as the best of ``states``; else ``states``.
    The paper's max returns goal states first among equally good ones."""
    if not r.model.goal:
        return states
    goal_states = states & r.goal()
    if goal_states == r.bdd.false:
        return states
    if utility is None:
        return goal_states  # every state of ``states`` attains the bound
    best_goal = r.best_of(goal_states)
    return goal_states if best_goal is not None and best_goal.utility == utility else states


def _better_state(planner: Planner, utility: int, budget: Budget, max_horizon: int) -> Comparison:
    """:func:`better_state`, under the planner's lock."""
    bound = upper_bound(planner)
    if bound <= utility:
        return Comparison(PROVEN, f"no reachable state is better: {UB_PROOF.format(u=bound)}")
    known = results(planner).get(("best_reachable", "all", frozenset(), max_horizon))
    if known is not None and known.found is not None:
        # A best reachable state is known (proven): it decides.
        if known.utility > utility:
            return Comparison(
                PROVEN,
                f"a state of utility {known.utility} is reachable within "
                f"{steps(known.found.distance)} (a best one)",
                better=known.found,
                best=known,
            )
        return Comparison(PROVEN, f"no reachable state is better: {known.proof}", best=known)
    if len(planner.get("variable", 1)) > PROBE_VARIABLES and planner.reachability_pending():
        # Large models: a few short searches first, each with a share of the time;
        # a better state near the initial one decides before any diagram is built.
        for horizon in PROBE_HORIZONS:
            outcome = planner.solve(
                horizon,
                Setting(goal=False, at_least=utility + 1),
                budget,
                conflicts=PROBE_CONFLICTS,
            )
            if outcome.satisfiable:
                return _found_better(planner, outcome, horizon)
            if outcome.satisfiable is None and budget.expired():
                return Comparison(BOUNDED, f"{budget.why_stopped()} at horizon {horizon}")
    engine = _engine(planner)
    if engine is None:
        return _better_by_search(planner, utility, budget, max_horizon)
    if engine == "explicit":
        compared = _better_explicit(planner, utility, budget, max_horizon)
        return (
            compared
            if compared is not None
            else _better_by_search(planner, utility, budget, max_horizon)
        )
    r = planner.reachability()
    found: list[Best] = []

    def decided(k: int) -> bool:
        best = r.best_in_layer(k)
        budget.report(
            "a better reachable state", horizon=k, best=best.utility if best else None, bound=bound
        )
        if best is not None and best.utility > utility:
            found.append(best)
            return True
        return False

    stopped = _grow(r, budget, max_horizon, decided, "a better reachable state", "layers of states")
    if found:
        state = _state(planner, r, found[0])
        return Comparison(
            PROVEN,
            f"a state of utility {state.utility} is reachable in {steps(state.distance)}",
            better=state,
        )
    searched = len(r.layers) - 1
    if not stopped:
        reached = r.prefix(searched)
        best = r.best_of(reached)
        best = r.best_of(_goal_first(r, reached, best.utility)) or best
        result = BestReachable(
            PROVEN,
            f"every reachable state is known (exact reachability: "
            f"no new state after {steps(searched)})",
            _state(planner, r, best),
            searched,
        )
        return Comparison(PROVEN, f"no reachable state is better: {result.proof}", best=result)
    if "diagram nodes" in stopped and not budget.expired():
        # The diagrams gave up: Fast Downward's search, where it searches, else clingo's.
        compared = _better_by_planner(planner, utility, budget)
        if compared is not None:
            return compared
        return _better_by_search(planner, utility, budget, max_horizon)
    return Comparison(
        BOUNDED, f"no better state among those reached within {steps(searched)}; stopped: {stopped}"
    )


# -- an external planner: searches for a state of at least a utility ----------------
#
# Where the model's planning system hands searches to Fast Downward
# (ethasp.planning.systems), a goal state at the relaxed upper bound is
# sought first, before the exact layers (A*; where there is one, the answer:
# _bound_by_planner).  Where the exact layers then give up (diagram nodes: a
# limit of work, not of time), the best reachable utility is an
# oversubscription question answered by planner calls on the compiled goal
# "a state worth at least k" (ethasp.planning.engines.sas): any state at the
# bound first (one call where it is attained), then a bisection between the
# best utility found and the bound, each call by greedy search (a state worth
# at least k, or the proof that none is reachable: every state from which the
# relaxed count could still reach k was searched).  The best state reported
# is a goal state where a goal state is that good (the nearest, by A*), else
# the state that the search reached.  Each state is the final state of the
# planner's action sequence, checked by its trace.

PLANNER_PROOF = (
    "no reachable state is worth more than {u} (every state from which a better one "
    "might be reached was searched)"
)


def _planner_search(planner, ground, at_least: int, budget: Budget, goal: bool, optimal: bool):
    """One search for a state worth at least ``at_least`` (a goal state with
    ``goal``): ("state", a ReachableState), ("none", None), ("stopped", why)
    or ("failed", why)."""
    from ethasp.planning import systems
    from ethasp.planning.engines import downward, sas

    try:
        task = downward.compiled(ground, goal=goal, at_least=at_least)
    except sas.NotCompiled as why:
        systems.warn(f"{why}: clingo searches instead")
        return "failed", str(why)
    outcome = downward.solve(task, budget, optimal, deciding=not optimal)
    if outcome.status == downward.STOPPED:
        return "stopped", f"{budget.why_stopped()} during Fast Downward's search"
    if outcome.status == downward.FAILED:
        systems.warn(f"Fast Downward failed ({outcome.why}): clingo searches instead")
        return "failed", outcome.why
    if outcome.status == downward.NO_PLAN:
        return "none", None
    return "state", _reached(planner, task.plan(outcome.operators))


def _reached(planner: Planner, actions) -> ReachableState:
    """The final state of an action sequence an engine proposed and its
    utility, by its trace (``utility_of_final/1`` of ``judgement/judge.lp``)."""
    from ethasp.planning.plan import Plan

    plan = Plan(tuple(actions))
    answer = planner.trace(plan)
    if answer.get("failure", 1) or answer.get("invalid", 1):
        raise RuntimeError(f"Fast Downward proposed {plan}, which the encodings refute")
    final = {atom.arguments[0]: atom.arguments[1].name == "true" for atom in answer.get("final", 2)}
    facts = [(v, final.get(v, False)) for v in (a.arguments[0] for a in planner.get("variable", 1))]
    utility = answer.get("utility_of_final", 1)[0].arguments[0].number
    return ReachableState(facts, utility, len(plan), plan)


def _planner_model(planner: Planner):
    """The search model with the utilities of facts, or None where Fast
    Downward does not answer for this planner (its model's choice)."""
    from ethasp.planning import systems

    if getattr(planner.model, "planning_system", systems.DEFAULT) == systems.CLINGO:
        return None
    if not planner.prepare(None, relaxed=True) or not systems.usable(planner):
        return None
    from ethasp.planning.engines.layers import Atoms, search_model

    return search_model(Atoms(planner, weights=True))


def _planner_task(planner: Planner, within: str, other_than):
    """Fast Downward's search model with the utilities of facts, and the
    relaxed upper bound, where Fast Downward answers for the best reachable
    state (of every state, none avoided); else None."""
    if within != "all" or other_than is not None:
        return None
    ground = _planner_model(planner)
    if ground is None:
        return None
    return ground, upper_bound(planner)


def _bound_by_planner(
    planner: Planner, budget: Budget, within: str, other_than
) -> BestReachable | None:
    """A goal state that attains the upper bound, by Fast Downward: the
    nearest (A* with LM-cut on the task whose goal is the model's goal and
    every ``best_fact/2``, the facts every state of that utility has, see
    :mod:`ethasp.planning.engines.sas`).  Where one exists it is the answer,
    proven by the bound, whatever the diagrams would take to reach it; None
    where there is none, or Fast Downward does not search here."""
    task = _planner_task(planner, within, other_than)
    if task is None:
        return None
    ground, bound = task
    kind, found = _planner_search(planner, ground, bound, budget, True, True)
    if kind == "stopped":
        start = _reached(planner, [])
        return BestReachable(BOUNDED, f"{found}; best found {start.utility}, bound {bound}", start)
    if kind != "state":
        return None  # none attains it (or the planner failed): the other engines
    if found.utility != bound:  # (the trace's utility of the final state)
        raise RuntimeError(f"Fast Downward proposed {found.plan}, which the encodings refute")
    return BestReachable(PROVEN, UB_PROOF.format(u=bound), found, found.distance)


def _best_by_planner(
    planner: Planner, budget: Budget, within: str, other_than
) -> BestReachable | None:
    """The best reachable state by Fast Downward (see above), where no goal
    state attains the bound (:func:`_bound_by_planner` found none); None
    where it does not answer (the search goes on with the other engines)."""
    task = _planner_task(planner, within, other_than)
    if task is None:
        return None
    ground, bound = task
    best = _reached(planner, [])
    low, high = best.utility, bound
    target = high  # the bound first: often attained (by a state that is no goal state)
    while low < high:
        budget.report("best reachable state (Fast Downward)", best=low, bound=high)
        kind, found = _planner_search(planner, ground, target, budget, False, False)
        if kind == "failed":
            return None
        if kind == "stopped":
            return BestReachable(BOUNDED, f"{found}; best found {low}, bound {high}", best)
        if kind == "none":
            high = target - 1
        else:
            best, low = found, found.utility
        target = (low + high + 1) // 2
    # A goal state as good, the nearest (the paper's max: goal states first).
    kind, found = _planner_search(planner, ground, low, budget, True, True)
    if kind == "failed":
        return None
    if kind == "stopped":
        return BestReachable(BOUNDED, found, best)
    if kind == "state":
        best = found
    proof = UB_PROOF.format(u=bound) if low == bound else PLANNER_PROOF.format(u=low)
    return BestReachable(PROVEN, proof, best, best.distance)


def _better_by_planner(planner: Planner, utility: int, budget: Budget) -> Comparison | None:
    """Is a reachable state better than ``utility``, by Fast Downward (one
    greedy search for a state worth more)?  None where it does not answer."""
    ground = _planner_model(planner)
    if ground is None:
        return None
    kind, found = _planner_search(planner, ground, utility + 1, budget, False, False)
    if kind == "failed":
        return None
    if kind == "stopped":
        return Comparison(BOUNDED, found)
    if kind == "none":
        return Comparison(
            PROVEN, f"no reachable state is better: {PLANNER_PROOF.format(u=utility)}"
        )
    return Comparison(
        PROVEN,
        f"a state of utility {found.utility} is reachable within {steps(found.distance)}",
        better=found,
    )


# -- the fallback: optimisation and threshold searches in ASP ---------------------------


def _horizons(max_horizon: int) -> list[int]:
    """0, 1, 2, 4, 8, ... up to max_horizon, and max_horizon itself."""
    result, power = [0], 1
    while power < max_horizon:
        result.append(power)
        power *= 2
    if max_horizon > 0:
        result.append(max_horizon)
    return result


def _read_state(symbols, horizon: int) -> list[tuple[clingo.Symbol, bool]]:
    # The state at the time checked: the horizon, or the last event's step when
    # it is later (Planner.solve); at_horizon/3 holds at that one time only.
    atoms = unify([vocabulary.AtHorizon], symbols).query(vocabulary.AtHorizon).all()
    return sorted(
        ((a.variable.symbol, a.value == "true") for a in atoms), key=lambda pair: str(pair[0])
    )


def _lower(cost: list[int], other: list[int]) -> bool:
    """Is a clingo cost vector lower than another?  A priority level without
    ground elements yet counts as 0."""
    width = max(len(cost), len(other))
    return cost + [0] * (width - len(cost)) < other + [0] * (width - len(other))


def _best_by_optimisation(
    planner: Planner, budget: Budget, max_horizon: int, within: str, other_than
) -> BestReachable:
    bound = upper_bound(planner)
    other = planner.avoid(other_than) if other_than is not None else None
    setting = Setting(goal=within == "goal", other_state=other, optimize=True)
    best: ReachableState | None = None
    best_cost: list[int] | None = None
    horizon = 0
    for horizon in _horizons(max_horizon):
        budget.report(
            "best reachable state (optimisation)",
            horizon=horizon,
            best=best.utility if best else None,
            bound=bound,
        )
        outcome = planner.solve(horizon, setting, budget)
        if (
            outcome.symbols
            and outcome.cost
            and (best_cost is None or _lower(outcome.cost, best_cost))
        ):
            # (The utility of the state the optimum reached, computed, not read
            # off the cost vector, whose levels depend on what else is grounded:
            # a plan's cost, planning/cost.lp; least plans, planning/lexicographic.lp.)
            best = _answer_state(planner, outcome, horizon)
            best_cost = outcome.cost
        if outcome.satisfiable is None:
            return BestReachable(
                BOUNDED, f"{budget.why_stopped()} at horizon {horizon}", best, horizon
            )
        if best is not None and best.utility >= bound:
            return BestReachable(PROVEN, UB_PROOF.format(u=bound), best, horizon)
        exists = planner.simple_path_exists(horizon + 1, Setting(), budget)
        if exists is None:
            return BestReachable(
                BOUNDED, f"{budget.why_stopped()} at horizon {horizon}", best, horizon
            )
        if not exists:
            return BestReachable(
                PROVEN,
                f"every reachable state was searched (no path of "
                f"{steps(horizon + 1)} without a repeated state)",
                best,
                horizon,
            )
    return BestReachable(
        BOUNDED, f"searched up to horizon {horizon} (the maximal horizon)", best, horizon
    )


def _answer_state(planner: Planner, outcome, horizon: int, utility: int | None = None):
    """The state at the horizon of an answer set, with the plan of its actions
    (its utility computed where not given)."""
    facts = _read_state(outcome.symbols, horizon)
    if utility is None:
        utility = planner.ground_model().utility(v for v, b in facts if b)
    plan = Plan.from_symbols(outcome.symbols)
    return witnessed(planner, facts, utility, plan, "clingo")


def _found_better(planner: Planner, outcome, horizon: int) -> Comparison:
    """The better state of a satisfiable search for one, at ``horizon``."""
    state = _answer_state(planner, outcome, horizon)
    return Comparison(
        PROVEN,
        f"a state of utility {state.utility} is reachable within {steps(horizon)}",
        better=state,
    )


def _better_by_search(
    planner: Planner, utility: int, budget: Budget, max_horizon: int
) -> Comparison:
    setting = Setting(goal=False, at_least=utility + 1)
    horizon = 0
    for horizon in _horizons(max_horizon):
        budget.report("a better reachable state (search)", horizon=horizon)
        outcome = planner.solve(horizon, setting, budget)
        if outcome.satisfiable is None:
            return Comparison(BOUNDED, f"{budget.why_stopped()} at horizon {horizon}")
        if outcome.satisfiable:
            return _found_better(planner, outcome, horizon)
        exists = planner.simple_path_exists(horizon + 1, Setting(), budget)
        if exists is None:
            return Comparison(BOUNDED, f"{budget.why_stopped()} at horizon {horizon}")
        if not exists:
            return Comparison(
                PROVEN,
                f"no reachable state is better: every reachable state "
                f"was searched (no path of {steps(horizon + 1)} without "
                "a repeated state)",
            )
    return Comparison(BOUNDED, f"no better state within {steps(horizon)} (the maximal horizon)")


def unhandled(planner: Planner) -> str:
    """Why this engine does not serve the model ('' where it does): what the
    callers ask before they use it (they answer ``bounded`` instead)."""
    planner = getattr(planner, "planner", planner)
    if planner.handles(FEATURES):
        return ""
    missing = " or ".join(sorted(planner.features - FEATURES))
    return f"no engine here searches the reachable states of a model with {missing}"


def best_reachable(
    planner: Planner,
    budget: Budget | None = None,
    max_horizon: int = DEFAULT_MAX_HORIZON,
    within: str = "all",
    other_than: list[tuple[clingo.Symbol, bool]] | None = None,
) -> BestReachable:
    """A best state reachable from the initial state (``within="goal"``: a best
    goal state), other than the state ``other_than`` if given; among equally
    good states, goal states first, then the nearest.  (``planner`` may also
    be a :class:`~ethasp.planning.model.Model`.)

    Results are kept by the planner: a question is searched once per model.
    """
    planner = getattr(planner, "planner", planner)
    require("best reachable states", FEATURES, planner.features)
    with planner.lock:
        return _best_reachable(planner, budget or Budget(), max_horizon, within, other_than)


def better_state(
    planner: Planner,
    utility: int,
    budget: Budget | None = None,
    max_horizon: int = DEFAULT_MAX_HORIZON,
) -> Comparison:
    """Is a reachable state better than ``utility``?  Stops at the first layer
    that has one (that state is then at its shortest distance)."""
    planner = getattr(planner, "planner", planner)
    require("best reachable states", FEATURES, planner.features)
    with planner.lock:
        return _better_state(planner, utility, budget or Budget(), max_horizon)
