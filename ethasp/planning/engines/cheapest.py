"""Uniform-cost search for cheapest plans, beside a plan search with action costs.

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

import clingo

from ethasp.planning.budget import Budget
from ethasp.planning.engines import ALL_FEATURES
from ethasp.planning.engines.explicit import Events
from ethasp.planning.engines.layers import Atoms, Layers, search_model
from ethasp.planning.engines.task import Task

# The model features this engine handles (ethasp.planning.engines).
FEATURES = ALL_FEATURES

# Configurations kept beyond which the search gives up (memory).
CONFIGURATION_LIMIT = 1_000_000
# Configurations expanded between two checks of the budget.
CHECK_EVERY = 256


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
    publish,
    limit: int = CONFIGURATION_LIMIT,
) -> None:
    """Uniform-cost search (see the module docstring), reporting through
    ``publish`` as the exact layers do (``cost_bound``, then ``plan`` with
    ``cost``, or ``complete``, or ``stopped``)."""
    step_cost = [costs.get(step.name, 0) for step in task.steps]
    position = {id(step): number for number, step in enumerate(task.steps)}
    last = events.last
    start = (task.init, 0)
    best: dict[tuple[int, int], tuple[int, int]] = {start: (0, 0)}
    parents: dict[tuple[int, int], tuple[tuple[int, int], int] | None] = {start: None}
    queue = [(0, 0, 0, start)]
    counter = 0
    closed: set[tuple[int, int]] = set()
    bound = 0
    while queue:
        cost, steps, _, configuration = heapq.heappop(queue)
        if configuration in closed:
            continue
        closed.add(configuration)
        if cost > bound:
            bound = cost
            publish(cost_bound=bound)
        if task.is_goal(task.full(events.finish(configuration))):
            publish(plan=tuple(_path(task, parents, configuration)), cost=cost)
            return
        if len(closed) % CHECK_EVERY == 0 and budget is not None and budget.expired():
            publish(stopped=f"uniform-cost search: {budget.why_stopped()}")
            return
        state, time = configuration
        full = task.full(state)
        step = time + 1
        for action in task.applicable(full):
            number = position[id(action)]
            after = action.apply(full) & task.base
            if step <= last:
                after = events.happen(after, step)
            successor = (after, min(step, last))
            key = (cost + step_cost[number], steps + 1)
            if successor in closed or key >= best.get(successor, (key[0] + 1, 0)):
                continue
            best[successor] = key
            parents[successor] = (configuration, number)
            counter += 1
            heapq.heappush(queue, (key[0], key[1], counter, successor))
        if len(best) > limit:
            publish(stopped=f"uniform-cost search: more than {limit} configurations")
            return
    publish(complete=True)


def _path(task: Task, parents: dict, configuration) -> list[clingo.Symbol]:
    actions = []
    while parents[configuration] is not None:
        configuration, number = parents[configuration]
        actions.append(task.steps[number].name)
    return actions[::-1]


class Cheapest(Layers):
    """Uniform-cost search (:func:`cheapest_plan`) beside a search, run as the
    exact layers are run (:class:`ethasp.planning.engines.layers.Layers`: a
    child process on Linux, else a thread), over :class:`CostAtoms`."""

    def _work(self, publish) -> None:
        atoms = self._atoms() if callable(self._atoms) else self._atoms
        assert isinstance(atoms, CostAtoms)
        self.model = search_model(atoms)
        task = Task(self.model)
        events = Events(self.model.events, task.index)
        cheapest_plan(task, events, atoms.costs, self._budget, publish)
