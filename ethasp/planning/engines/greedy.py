"""Greedy forward search for any-plan search: some plan fast, not a shortest one.

Any-plan search (:func:`ethasp.planning.search.any_plan`) asks the solver
for plans at growing horizons; on tasks whose plans are long, proving that
nothing fits a horizon costs more than finding a plan.  This engine runs
beside it: a greedy best-first search over explicit states of the search
model (:func:`ethasp.planning.engines.layers.search_model`), guided by the FF
heuristic (the length of a relaxed plan that ignores delete effects) and
trying first the actions of that relaxed plan applicable in the state
(helpful actions), with lazy evaluation (a state is evaluated when it is
taken from the queue, with its parent's estimate until then).

It is a proposal engine, as the exact layers are: it reads the ground model
and proposes a sequence of actions; the search checks the plan by its trace
(``encodings/planning/trace.lp``) before anyone sees it, so what a plan is
stays decided by the encodings.  Its one other claim is that no goal state
is reachable, when it has expanded every reachable state (pruning only
repeated states and states from which even the relaxed goal is
unreachable); running out of time or of its state limit, it stops without
a claim.  Like the layers, it is started only where relaxed reachability
found the goal reachable (the search model leaves out the goal literals on
variables that never change).  It runs in a child process beside the
solver (see :class:`Greedy`).  It does not model exogenous events (its
states are states, not configurations of a state and a time): it refuses a
model with events, and the planner runs the exact layers beside any-plan
search on such a model instead (:mod:`ethasp.planning.engines.layers`,
explicit layers of configurations there, for the proof that no plan exists).

States are explicit ones of the search model, as bit masks
(:class:`ethasp.planning.engines.task.Task`, which also gives the heuristic).
"""

from __future__ import annotations

import heapq

import clingo

from ethasp.planning.budget import Budget
from ethasp.planning.engines import CONDITIONAL_EFFECTS, DERIVED_VARIABLES, require
from ethasp.planning.engines.layers import Layers, search_model
from ethasp.planning.engines.task import Task, path

# The model features this engine handles (ethasp.planning.engines): not
# exogenous events (the next state depends on the step, which the search does
# not track); on models with events the planner runs the exact layers instead
# (explicit layers of configurations, ethasp.planning.engines.explicit).
FEATURES = frozenset({CONDITIONAL_EFFECTS, DERIVED_VARIABLES})


# States generated beyond which the search gives up (memory).
STATE_LIMIT = 2_000_000
# Why a search without a plan stopped when it expanded every reachable state
# (but relaxed dead ends, from which no goal state is reachable either).
EXHAUSTED = "every reachable state expanded without a goal state"
# Expansions between two checks of the budget.
CHECK_EVERY = 64
# Turns in a row the queue of helpful actions gets whenever the estimate
# improves (progress is followed where the relaxed plan points).
BOOST = 1000


def greedy_plan(
    task: Task, budget: Budget | None = None, state_limit: int = STATE_LIMIT
) -> tuple[list[clingo.Symbol] | None, str]:
    """A plan by lazy greedy best-first search (helpful actions first), or None
    and why the search stopped (:class:`ethasp.planning.engines.Unhandled` for
    a task with exogenous events)."""
    require("greedy search", FEATURES, task.features)
    position = {id(s): i for i, s in enumerate(task.steps)}
    parents: dict[int, tuple[int, int] | None] = {task.init: None}
    # Two queues, taken in turn: every successor, and those by helpful actions.
    queues: list[list] = [[], []]
    counter = 0
    heapq.heappush(queues[0], (0, counter, task.init))
    closed: set[int] = set()
    turn = 0
    expansions = 0
    best = None
    boost = 0  # turns the helpful queue gets in a row (after progress)
    while queues[0] or queues[1]:
        if boost and queues[1]:
            turn, boost = 1, boost - 1
        elif not queues[turn]:
            turn = 1 - turn
        _, _, state = heapq.heappop(queues[turn])
        turn = 1 - turn
        if state in closed:
            continue
        closed.add(state)
        full = task.full(state)
        if task.is_goal(full):
            return path(task, parents, state), ""
        expansions += 1
        if expansions % CHECK_EVERY == 0 and budget is not None and budget.expired():
            return None, budget.why_stopped()
        h, helpful = task.heuristic(full)
        if h is None:
            continue  # a dead end, even relaxed
        if best is None or h < best:
            best, boost = h, boost + BOOST
        for step in task.applicable(full):
            successor = step.apply(full) & task.base
            if successor in parents:
                continue
            number = position[id(step)]
            parents[successor] = (state, number)
            counter += 1
            heapq.heappush(queues[0], (h, counter, successor))
            if number in helpful:
                heapq.heappush(queues[1], (h, counter, successor))
        if len(parents) > state_limit:
            return None, f"more than {state_limit} states"
    return None, EXHAUSTED


class Greedy(Layers):
    """Greedy forward search (:func:`greedy_plan`) beside a search, run as the
    exact layers are run (:class:`ethasp.planning.engines.layers.Layers`: a child
    process on Linux, else a thread); its :attr:`status` gets a ``plan`` (not
    a shortest one), ``complete`` (no goal state is reachable) or
    ``stopped``.  It refuses a model with exogenous events when started."""

    NAME = "greedy search"

    def features(self) -> frozenset[str]:
        return FEATURES

    def _work(self, publish) -> None:
        atoms = self._atoms() if callable(self._atoms) else self._atoms
        self.model = search_model(atoms)
        plan, why = greedy_plan(Task(self.model), self._budget)
        if plan is None and why == EXHAUSTED:
            publish(complete=True)
        elif plan is None:
            publish(stopped=f"greedy search: {why}")
        else:
            publish(plan=tuple(plan))
