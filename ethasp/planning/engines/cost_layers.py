"""Symbolic uniform-cost search: the reachable states by the cost of their
cheapest paths, computed with decision diagrams.

The exact layers of :mod:`ethasp.planning.engines.reachability` hold the
states by the length of their shortest paths.  With action costs the layers
here hold them by cost (Dijkstra's algorithm over sets of states): layer g is
the set of states whose cheapest path costs exactly g, computed from a set of
candidates (states one action of cost c away from layer g - c, less those
reached for less) and closed under the actions of cost 0 (sublayers, one per
step of cost 0, so that paths can be read off).  Costs are never negative, so
the layers come in increasing cost:

* no goal state in the layers up to g: every plan costs more than g;
* the first layer with a goal state: its cost is the least cost of a plan,
  and a cheapest plan is read off backwards, sublayer by sublayer;
* no candidate left: every reachable state is known, and none is a goal
  state.

It reuses the diagrams of :class:`~ethasp.planning.engines.reachability.
Reachability` (the variable order, derived variables, the goal, the
relations of actions and their pre-images), with one transition relation per
cluster of actions of equal cost.  Like the exact layers it knows no
exogenous events, and it stops at a limit of diagram nodes, claiming nothing
then; :mod:`ethasp.planning.engines.cheapest` runs it, and the explicit
uniform-cost search where it cannot serve.
"""

from __future__ import annotations

from collections.abc import Iterator

import clingo

from ethasp.planning.budget import Budget
from ethasp.planning.engines import (
    CONDITIONAL_EFFECTS,
    DERIVED_VARIABLES,
    model_features,
    require,
)
from ethasp.planning.engines.reachability import (
    DEFAULT_NODE_LIMIT,
    GroundModel,
    Reachability,
    _clusters,
)

# The model features this engine handles (ethasp.planning.engines).
FEATURES = frozenset({CONDITIONAL_EFFECTS, DERIVED_VARIABLES})


class CostLayers(Reachability):
    """Layers of states by the cost of their cheapest paths (see the module
    docstring); :meth:`search` runs them to the first goal state."""

    def __init__(
        self,
        model: GroundModel,
        costs: dict[clingo.Symbol, int],
        node_limit: int = DEFAULT_NODE_LIMIT,
    ):
        require("cost layers", FEATURES, model_features(model))
        super().__init__(model, node_limit)
        self.costs = {action.name: costs.get(action.name, 0) for action in model.actions}
        by_cost: dict[int, list] = {}
        for action in model.actions:
            by_cost.setdefault(self.costs[action.name], []).append(action)
        # Per cost: its actions, and their cluster relations.
        self.by_cost = {
            cost: (
                actions,
                [self._cluster(group) for group in _clusters_of(model, actions, self.index)],
            )
            for cost, actions in sorted(by_cost.items())
        }
        # Layer g: its sublayers (by steps of cost 0 from its candidates).
        self.cost_layers: dict[int, list] = {}

    def search(self, budget: Budget | None) -> Iterator[dict]:
        """Layers in increasing cost until a goal state (``plan`` and ``cost``),
        no candidate left (``complete``) or a limit (``stopped``): a generator
        of these findings, and of ``cost_bound`` for each layer, as the exact
        layers report them (and of empty findings after each image, where
        another search may take a turn)."""
        goal = self.goal()
        bdd = self.bdd
        candidates: dict[int, object] = {0: self.layers[0]}
        reached = bdd.false
        zero = self.by_cost.get(0, ([], []))[1]
        while candidates:
            cost = min(candidates)
            entry = candidates.pop(cost) & ~reached
            if entry == bdd.false:
                continue
            yield {"cost_bound": cost}
            sublayers = [entry]
            reached |= entry
            while True:
                new = self._step(sublayers[-1], zero, budget)
                if new is None:
                    yield {"stopped": f"symbolic uniform-cost search: {self.stopped}"}
                    return
                yield {}
                new &= ~reached
                if new == bdd.false:
                    break
                sublayers.append(new)
                reached |= new
            self.cost_layers[cost] = sublayers
            for k, sublayer in enumerate(sublayers):
                met = sublayer & goal
                if met != bdd.false:
                    state = self.pick(met)
                    yield {"plan": tuple(self._path(state, cost, k)), "cost": cost}
                    return
            layer = bdd.false
            for sublayer in sublayers:
                layer |= sublayer
            for step_cost, (_, images) in self.by_cost.items():
                if step_cost == 0:
                    continue
                new = self._step(layer, images, budget)
                if new is None:
                    yield {"stopped": f"symbolic uniform-cost search: {self.stopped}"}
                    return
                yield {}
                new &= ~reached
                if new != bdd.false:
                    target = cost + step_cost
                    candidates[target] = candidates.get(target, bdd.false) | new
        yield {"complete": True}

    def _step(self, states, images, budget: Budget | None):
        """The states one action (of the given clusters) from ``states``; None at
        a limit."""
        if not images:
            return self.bdd.false
        if budget is not None and budget.expired():
            self.stopped = budget.why_stopped()
            return None
        new = self.bdd.false
        for parts in images:
            new |= self._image(states, parts)
        if self.nodes() > self.node_limit:
            self.stopped = f"more than {self.node_limit} diagram nodes"
            return None
        return new

    def _path(self, state: frozenset[clingo.Symbol], cost: int, k: int) -> list[clingo.Symbol]:
        """The actions of a cheapest path to a state of sublayer k of layer
        ``cost``: backwards, a step of cost 0 within the layer while k > 0, else
        an action of cost c from layer ``cost - c``."""
        actions: list[clingo.Symbol] = []
        while cost > 0 or k > 0:
            full = self.state(state)
            if k > 0:
                step = self._action_predecessor(
                    state, full, self.by_cost[0][0], self.cost_layers[cost][k - 1]
                )
                if step is None:
                    raise RuntimeError(f"no step of cost 0 to sublayer {k} of layer {cost}")
                k -= 1
            else:
                step = None
                for step_cost, (members, _) in self.by_cost.items():
                    before = cost - step_cost
                    if step_cost == 0 or before not in self.cost_layers:
                        continue
                    layer = self.bdd.false
                    for sublayer in self.cost_layers[before]:
                        layer |= sublayer
                    step = self._action_predecessor(state, full, members, layer)
                    if step is not None:
                        cost = before
                        break
                if step is None:
                    raise RuntimeError(f"no predecessor of a state of layer {cost}")
                k = next(
                    j
                    for j, sublayer in enumerate(self.cost_layers[cost])
                    if sublayer & self.state(step[1]) != self.bdd.false
                )
            actions.append(step[0])
            state = step[1]
        return actions[::-1]


def _clusters_of(model: GroundModel, actions: list, index) -> list[list]:
    """The clusters (as :func:`~ethasp.planning.engines.reachability._clusters`
    makes them) of some of a model's actions."""
    part = GroundModel(model.variables, actions, model.init, model.goal, axioms=model.axioms)
    return _clusters(part, index)
