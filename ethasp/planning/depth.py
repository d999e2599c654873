"""The depth of a model's reachable configurations: a horizon within which every
reachable configuration lies.

A search to such a horizon (with idle steps after the plan's end) sees every
reachable configuration (state, and time up to the last event), so one solve
there decides whether any plan meets a condition on the final state, and an
unsatisfiable solve is a proof (searches that require subsets of a goal,
:mod:`ethasp.principles.conflict`, ask it once and then solve once per
subset).  Two proofs, the first that succeeds under the budget:

* **exact layers**: the diagrams of exact reachability (models without
  events, :mod:`ethasp.planning.engines.reachability`) or the explicit
  layers of configurations (models with events,
  :mod:`ethasp.planning.engines.explicit`) run until no new state appears;
  the number of layers less one is the depth;
* **the loop-free threshold** (``encodings/planning/loopfree.lp``): no path
  of h+1 steps without a repeated configuration, so every reachable
  configuration lies within h steps (a shortest path to it is such a path);
  h runs over powers of four up to the maximal horizon.

Either may be cut short (the budget, the engines' limits): then there is no
depth, and the caller proves what it needs otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass

from ethasp.memo import results
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import GroundingStopped, Planner, Setting
from ethasp.planning.plan import steps


@dataclass(frozen=True)
class Depth:
    """Every reachable configuration lies within ``horizon`` steps (``proof``
    says why), or ``horizon`` is None: not established (``proof`` says what
    stopped it)."""

    horizon: int | None
    proof: str


def reachable_depth(planner: Planner, budget: Budget, max_horizon: int) -> Depth:
    """The depth of the planner's reachable configurations (computed once per
    planner; a result cut short by the budget is not kept)."""
    kept = results(planner)
    if "depth" in kept:
        return kept["depth"]
    depth = _exact(planner, budget)
    if depth.horizon is None and not budget.expired():
        depth = _loopfree(planner, budget, max_horizon, depth.proof)
    if depth.horizon is not None or not budget.expired():
        kept["depth"] = depth
    return depth


def _exact(planner: Planner, budget: Budget) -> Depth:
    """The depth from the engines' exact layers, if they finish."""
    if planner.exact_reachability:
        engine = planner.reachability()
        name = "exact reachability"
    else:
        from ethasp.planning.engines.best_state import configurations

        engine = configurations(planner)
        name = "explicit layers of configurations"
    with planner.lock:
        while not engine.complete:
            if not engine.expand(budget):
                return Depth(None, f"{name} stopped: {engine.stopped}")
    depth = len(engine.layers) - 1
    return Depth(depth, f"{name}: no new state after {steps(depth)}")


def _loopfree(planner: Planner, budget: Budget, max_horizon: int, before: str) -> Depth:
    """The depth from the loop-free threshold, at powers of four up to the
    maximal horizon."""
    horizon = 0
    while horizon <= max_horizon:
        try:
            exists = planner.simple_path_exists(horizon + 1, Setting(goal=False), budget)
        except GroundingStopped:
            exists = None
        if exists is None:
            return Depth(None, f"{before}; {budget.why_stopped()}")
        if not exists:
            return Depth(
                horizon,
                f"no path of {steps(horizon + 1)} without a repeated state: every reachable "
                f"state lies within {steps(horizon)}",
            )
        if horizon == max_horizon:
            break
        horizon = min(max_horizon, max(1, horizon * 4))
    return Depth(None, f"{before}; paths without a repeated state reach the maximal horizon")
