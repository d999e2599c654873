"""Uniform-cost search for cheapest plans, beside a plan search with action costs.

On models without exogenous events it runs symbolic uniform-cost search
(:mod:`ethasp.planning.engines.cost_layers`, decision diagrams) in turns
with the explicit search below (:func:`race`): the first that settles the
question answers.

With action costs (``cost/2``, :mod:`ethasp.planning.cost_search`) the solver
finds the cheapest plan of each horizon, but a cheaper plan may have more
steps, and with actions of cost 0 nothing bounds its length.  This engine
answers the question by itself: a uniform-cost search (Dijkstra's algorithm)
over the explicit configurations of the search model
(:func:`ethasp.planning.engines.layers.search_model`; a configuration is a
state and the time up to the last exogenous event, as in
:mod:`ethasp.planning.engines.explicit`), in order of the cost of the
cheapest known path to them, then of its number of steps.  Costs are never
negative, so:

* when a configuration is taken from the queue, no cheaper path to it
  exists; every plan not yet found costs at least its cost (``cost_bound``);
* the first configuration taken whose final state (the events still due
  happen) is a goal state ends a cheapest plan, of the fewest steps among
  the cheapest (``plan`` and ``cost``);
* with no configuration left, no goal state is reachable (``complete``).

It is a proposal engine like the others: it reads the ground model (the
actions' costs are ``action_cost/2`` of ``encodings/planning/model.lp``), and
its plan is checked by its trace before anyone sees it.  Its claims are
tested against a brute-force oracle (``tests/test_properties_costs.py``).
It runs in a child process beside the solver (see
:class:`ethasp.planning.engines.layers.Layers`) and stops at a limit on the
configurations kept, claiming nothing then.
"""

from __future__ import annotations

import heapq
from collections.abc import Iterator

import clingo

from ethasp.planning.budget import Budget
from ethasp.planning.engines import ALL_FEATURES, handles, model_features
from ethasp.planning.engines.explicit import Events
from ethasp.planning.engines.layers import Atoms, Layers, _import_diagrams, search_model
from ethasp.planning.engines.task import Task, path

# The model features this engine handles (ethasp.planning.engines).
FEATURES = ALL_FEATURES

# Configurations kept beyond which the search gives up (memory).
CONFIGURATION_LIMIT = 1_000_000
# Configurations expanded between two checks of the budget.
CHECK_EVERY = 256
# A key in the queue is cost * STEPS + steps (more steps than this: never kept).
STEPS = 1 << 32


class CostAtoms(Atoms):
    """The atoms of the search model and the costs of the actions."""

    def __init__(self, planner):
        super().__init__(planner)
        self.costs = {
            atom.arguments[0]: atom.arguments[1].number for atom in planner.get("action_cost", 2)
        }


def cheapest_plan(
    task: Task,
    events: Events,
    costs: dict[clingo.Symbol, int],
    budget: Budget | None,
    limit: int = CONFIGURATION_LIMIT,
) -> Iterator[dict]:
    """Uniform-cost search (see the module docstring), as a generator of its
    findings as the exact layers report them (``cost_bound``, then ``plan``
    with ``cost``, or ``complete``, or ``stopped``), and of empty findings
    every :data:`CHECK_EVERY` configurations (where another search may take
    a turn).

    A configuration is the number ``state * (last + 1) + time`` (the time up
    to the last event, 0 without events), and its key in the queue is
    ``cost * STEPS + steps``: one integer each, compared and hashed fast."""
    cost_of = {id(step): costs.get(step.name, 0) for step in task.steps}
    number_of = {id(step): number for number, step in enumerate(task.steps)}
    last = events.last
    span = last + 1
    derived = bool(task.strata)
    start = task.init * span
    best: dict[int, int] = {start: 0}
    parents: dict[int, tuple[int, int] | None] = {start: None}
    queue = [(0, 0, start)]
    counter = 0
    closed: set[int] = set()
    bound = 0
    while queue:
        key, _, configuration = heapq.heappop(queue)
        if configuration in closed:
            continue
        closed.add(configuration)
        cost = key // STEPS
        if cost > bound:
            bound = cost
            yield {"cost_bound": bound}
        state, time = divmod(configuration, span)
        final = events.finish((state, time)) if last else state
        if task.is_goal(task.full(final) if derived else final):
            yield {"plan": tuple(path(task, parents, configuration)), "cost": cost}
            return
        if len(closed) % CHECK_EVERY == 0:
            if budget is not None and budget.expired():
                yield {"stopped": f"uniform-cost search: {budget.why_stopped()}"}
                return
            yield {}
        full = task.full(state) if derived else state
        step = time + 1
        for action in task.applicable(full):
            after = action.apply(full) & task.base
            if step <= last:
                after = events.happen(after, step)
            successor = after * span + (step if step < last else last)
            if successor in closed:
                continue
            successor_key = key + cost_of[id(action)] * STEPS + 1
            if successor_key >= best.get(successor, successor_key + 1):
                continue
            best[successor] = successor_key
            parents[successor] = (configuration, number_of[id(action)])
            counter += 1
            heapq.heappush(queue, (successor_key, counter, successor))
        if len(best) > limit:
            yield {"stopped": f"uniform-cost search: more than {limit} configurations"}
            return
    yield {"complete": True}


def race(searches: list[Iterator[dict]], publish) -> None:
    """Run searches in turns (a turn: until a search yields), publishing what
    settles the question (a plan, or that no goal state is reachable) from
    the first that tells, and the greatest cost bound of them all; a search
    that stops leaves the others on; when all have stopped, the first's
    reason is published."""
    bounds: dict[int, int] = {}
    stopped: list[str] = []
    running = dict(enumerate(searches))
    while running:
        for number, search in list(running.items()):
            changes = next(search, {"stopped": "ended"})
            if "plan" in changes or "complete" in changes:
                publish(**changes)
                return
            if "stopped" in changes:
                stopped.append(changes["stopped"])
                del running[number]
            elif "cost_bound" in changes:
                bounds[number] = changes["cost_bound"]
                publish(cost_bound=max(bounds.values()))
    publish(stopped="; ".join(stopped) or "stopped")


class Cheapest(Layers):
    """Uniform-cost search (:func:`cheapest_plan`) beside a search, run as the
    exact layers are run (:class:`ethasp.planning.engines.layers.Layers`: a
    child process on Linux, else a thread), over :class:`CostAtoms`."""

    NAME = "uniform-cost search"

    def features(self) -> frozenset[str]:
        return FEATURES

    def _work(self, publish) -> None:
        atoms = self._atoms() if callable(self._atoms) else self._atoms
        assert isinstance(atoms, CostAtoms)
        self.model = search_model(atoms)
        task = Task(self.model)
        searches = [
            cheapest_plan(task, Events(self.model.events, task.index), atoms.costs, self._budget)
        ]
        from ethasp.planning.engines import cost_layers

        if handles(cost_layers.FEATURES, model_features(self.model)):
            # Symbolic layers too where they model the task (no events), in
            # turns with the explicit search: each does well where the other
            # does badly.
            from ethasp.planning.engines.cost_layers import CostLayers

            _import_diagrams()
            layers = CostLayers(self.model, atoms.costs, self.node_limit)
            searches.append(layers.search(self._budget))
        race(searches, publish)
