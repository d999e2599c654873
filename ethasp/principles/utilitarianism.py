"""A best reachable state, by clingo optimisation (for utilitarianism).

The states are never listed: ``encodings/judgement/best.lp`` maximises the
utility of the state at the horizon of a search without the goal, so the
optimum at horizon h is a best state among those reachable in at most h steps
(the search may idle).  Horizons 0, 1, 2, 4, 8, ... (and the maximal horizon)
are solved, each once.  The result is ``proven`` a best reachable state when

* its utility equals ``upper_bound`` (per variable, the best utility of a
  relaxed reachable value): no reachable state can do better; or
* after solving horizon h, no path of h+1 actions without a repeated state
  exists (``encodings/planning/loopfree.lp``): every reachable state is then
  reachable in at most h steps, and all of them were searched;

and ``bounded`` otherwise (maximal horizon or time limit reached): a better
state may exist, but the state found is reachable.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Iterable, Sequence

import clingo
from clorm import Raw, unify

from ethasp.planning.model import Model
from ethasp.planning.search import DEFAULT_MAX_HORIZON, Search
from ethasp.planning.validation import literal
from ethasp.vocabulary import Alternative, AtHorizon, Conj, UpperBound

PROVEN, BOUNDED = "proven", "bounded"

# The name of the best state, as a conjunction of facts in ASP (conj/3).
BEST = clingo.Function("best")


@dataclass
class BestReachable:
    """A best reachable state (as far as searched).

    ``state`` lists its literals (``v`` / ``-v``), ``utility`` is its utility
    and ``horizon`` the horizon at which it was found; ``searched`` is the last
    horizon searched.  ``status`` is ``proven`` (no reachable state is better)
    or ``bounded``, and ``proof`` says why.  ``state`` is None when the time
    limit struck before any state was found.
    """

    status: str
    proof: str
    state: list[str] | None = None
    utility: int | None = None
    horizon: int = 0
    searched: int = 0
    facts: list[tuple[clingo.Symbol, str]] = field(default_factory=list)

    def alternative_facts(self) -> list:
        """``alternative(best)`` and its ``conj(best,V,B)`` facts (none if no state)."""
        if self.state is None:
            return []
        return [Alternative(name=Raw(BEST))] + [
            Conj(name=Raw(BEST), variable=Raw(variable), value=value)
            for variable, value in self.facts]

    def to_json(self) -> dict:
        return {"state": self.state, "utility": self.utility, "horizon": self.horizon,
                "status": self.status, "proof": self.proof}


def _horizons(max_horizon: int) -> list[int]:
    """0, 1, 2, 4, 8, ... up to max_horizon, and max_horizon itself."""
    result, power = [0], 1
    while power < max_horizon:
        result.append(power)
        power *= 2
    if max_horizon > 0:
        result.append(max_horizon)
    return result


def _lower(cost: list[int], other: list[int]) -> bool:
    """Is a clingo cost vector lower than another?  A priority level without
    ground elements yet (a lower one, added by later horizons) counts as 0."""
    width = max(len(cost), len(other))
    return cost + [0] * (width - len(cost)) < other + [0] * (width - len(other))


def best_reachable(model: Model, max_horizon: int = DEFAULT_MAX_HORIZON,
                   time_limit: float | None = None, encodings: Sequence[str] = (),
                   facts: Iterable = ()) -> BestReachable:
    """A best state reachable from the initial state, by optimisation.

    ``encodings`` and ``facts`` add constraints or lower-priority preferences
    on the state at the horizon (e.g. ``reasons/other_state.lp``: a best
    state other than a given one, goal states first on ties); the priority-0
    level of the cost is the utility of ``judgement/best.lp``.
    """
    deadline = None if time_limit is None else time.monotonic() + time_limit
    search = Search(model, ["judgement/best.lp", *encodings], facts, goal=False, optimize=True)
    best: BestReachable | None = None
    best_cost: list[int] | None = None
    bound: int | None = None
    horizon = 0

    def finish(status: str, proof: str) -> BestReachable:
        result = best or BestReachable(status, proof)
        result.status, result.proof, result.searched = status, proof, horizon
        return result

    for horizon in _horizons(max_horizon):
        satisfiable, symbols, cost = search.solve_at(horizon, deadline)
        if symbols and cost:
            facts_found = unify([AtHorizon, UpperBound], symbols)
            bound = next(iter(facts_found.query(UpperBound).all())).bound
            # The search may idle, so an optimum at a larger horizon is at least
            # as good, in every priority level, as one at a smaller horizon.
            if best_cost is None or _lower(cost, best_cost):
                pairs = sorted(((atom.variable.symbol, atom.value)
                                for atom in facts_found.query(AtHorizon).all()
                                if atom.time == horizon), key=str)
                best = BestReachable(BOUNDED, "", sorted(literal(v, b) for v, b in pairs),
                                     -cost[0], horizon, horizon, pairs)
                best_cost = cost
        if satisfiable is None:
            return finish(BOUNDED, f"time limit reached at horizon {horizon}")
        if best is not None and best.utility == bound:
            return finish(PROVEN, f"its utility {bound} is the upper bound (per variable, the "
                                  "best utility of a value reachable ignoring delete effects)")
        exists = search.simple_path_exists(horizon + 1, deadline)
        if exists is None:
            return finish(BOUNDED, f"time limit reached at horizon {horizon}")
        if not exists:
            return finish(PROVEN, f"every reachable state was searched (no path of "
                                  f"{horizon + 1} steps without a repeated state)")
    return finish(BOUNDED, f"searched up to horizon {horizon} (the maximal horizon)")
