"""Explicit breadth-first layers over configurations: every model feature.

The exact layers of :mod:`ethasp.planning.engines.reachability` are symbolic and
know actions, conditional effects and derived variables, not exogenous
events.  With events the next state depends on the step as well (events are
due at given steps, and happen after the plan too), so the layers here are
layers of *configurations* (state, time), the time counted up to the last
event (from there on no event lies ahead, and equal states are equal
configurations), over explicit states: Python integers, one bit a state
variable, as in the greedy search (:class:`ethasp.planning.engines.greedy.Task`,
whose actions and derived variables they use).  A configuration of layer k
is reached by k actions; the final state of a plan that ends there is the
state after the events still due (the steps between idle).

They serve models with events, which are small in practice (HERA's
situations): breadth-first, with a limit on the configurations kept.  They
claim only what they computed: no goal state among the final states of
layers 0..k (a lower bound: every plan has more than k steps), a shortest
plan (checked by its trace, like every engine's plans), that no goal state
is reachable (no new configuration: every one is known), and, for
utilitarianism, the best final state of every configuration (every one
known) or the first layer with a better one.
"""

from __future__ import annotations

from dataclasses import dataclass

import clingo

from ethasp.planning.budget import Budget
from ethasp.planning.engines import ALL_FEATURES
from ethasp.planning.engines.task import Task, bit_masks

# The model features this engine handles (ethasp.planning.engines).
FEATURES = ALL_FEATURES


# Configurations kept beyond which the layers give up (memory: a few hundred
# bytes each).
CONFIGURATION_LIMIT = 400_000
# Configurations expanded between two checks of the budget.
CHECK_EVERY = 256

Configuration = tuple[int, int]  # (state bits, time up to the last event)


@dataclass(frozen=True)
class GroundEvent:
    """An exogenous event: the steps it is due at, its preconditions and its
    effects (key, condition, variable, value)."""

    name: clingo.Symbol
    steps: tuple[int, ...]
    pre: tuple[tuple[clingo.Symbol, bool], ...]
    effects: tuple[
        tuple[clingo.Symbol, tuple[tuple[clingo.Symbol, bool], ...], clingo.Symbol, bool], ...
    ]


class Events:
    """The events of a model over the state bits of a task: what happens after
    the action of each step (the greatest key wins on a variable, true
    between equal keys; conditions read the state after the action)."""

    def __init__(self, events: list[GroundEvent], index: dict[clingo.Symbol, int]):
        keys = sorted({key for event in events for key, _, _, _ in event.effects})
        rank = {key: number for number, key in enumerate(keys)}

        def masks(literals) -> tuple[int, int]:
            return bit_masks(literals, index)

        self.due: dict[int, list] = {}
        for event in events:
            pre = masks(event.pre)
            effects = [
                (rank[key], masks(condition), 1 << index[variable], value)
                for key, condition, variable, value in event.effects
            ]
            for step in event.steps:
                self.due.setdefault(step, []).append((pre, effects))
        self.last = max(self.due, default=0)

    def happen(self, state: int, step: int) -> int:
        """The state after the events due at ``step`` (from the state after its action)."""
        due = self.due.get(step)
        if not due:
            return state
        winners: dict[int, tuple[int, bool]] = {}
        for (pos, neg), effects in due:
            if state & pos != pos or state & neg:
                continue
            for key, (cpos, cneg), bit, value in effects:
                held = state & cpos == cpos and not state & cneg
                if held and (bit not in winners or (key, value) > winners[bit]):
                    winners[bit] = (key, value)
        for bit, (_, value) in winners.items():
            state = state | bit if value else state & ~bit
        return state

    def finish(self, configuration: Configuration) -> int:
        """The final state of a plan that ends in the configuration."""
        state, time = configuration
        for step in range(time + 1, self.last + 1):
            state = self.happen(state, step)
        return state


class Configurations:
    """Breadth-first layers of configurations (see the module docstring).

    :meth:`expand` adds a layer (False: a limit stopped it, :attr:`stopped`
    says why); :attr:`complete` once no new configuration appears.
    """

    def __init__(self, task, events: Events, limit: int | None = None):
        self.task = task
        self.events = events
        self.limit = CONFIGURATION_LIMIT if limit is None else limit
        start = (task.init, 0)
        self.parents: dict[Configuration, tuple[Configuration, int] | None] = {start: None}
        self.layers: list[list[Configuration]] = [[start]]
        self.complete = False
        self.stopped = ""
        self._next: list[Configuration] | None = None

    def final(self, configuration: Configuration) -> int:
        """The final state (derived variables computed) of a plan ending there."""
        return self.task.full(self.events.finish(configuration))

    def successors(self, configuration: Configuration):
        """The applicable actions of a configuration, each with the configuration
        it leads to (the events of its step included)."""
        task, events = self.task, self.events
        state, time = configuration
        full = task.full(state)
        step = time + 1
        for action in task.applicable(full):
            after = action.apply(full) & task.base
            if step <= events.last:
                after = events.happen(after, step)
            yield action, (after, min(step, events.last))

    def _next_layer(self, budget: Budget | None) -> list[Configuration] | None:
        task, parents = self.task, self.parents
        position = {id(step): number for number, step in enumerate(task.steps)}
        found: list[Configuration] = []
        for count, configuration in enumerate(self.layers[-1], start=1):
            if count % CHECK_EVERY == 0 and budget is not None and budget.expired():
                self.stopped = budget.why_stopped()
                return None
            for action, successor in self.successors(configuration):
                if successor not in parents:
                    parents[successor] = (configuration, position[id(action)])
                    found.append(successor)
            if len(parents) > self.limit:
                self.stopped = f"more than {self.limit} configurations"
                return None
        return found

    def expand(self, budget: Budget | None = None) -> bool:
        if self.complete:
            return True
        found, self._next = self._next, None
        if found is None:
            found = self._next_layer(budget)
        if found is None:
            return False
        if not found:
            self.complete = True
            return True
        self.layers.append(found)
        return True

    def closed(self, budget: Budget | None = None) -> bool | None:
        """Is no configuration one step beyond the layers so far?  (As
        :meth:`ethasp.planning.engines.reachability.Reachability.closed`.)"""
        if self.complete:
            return True
        if self._next is None:
            self._next = self._next_layer(budget)
            if self._next is None:
                return None
        if not self._next:
            self._next = None
            self.complete = True
            return True
        return False

    def path(self, configuration: Configuration) -> list[clingo.Symbol]:
        """The actions of a shortest path to a configuration."""
        actions = []
        while self.parents[configuration] is not None:
            configuration, number = self.parents[configuration]
            actions.append(self.task.steps[number].name)
        return actions[::-1]

    def least_path(self, layer: int) -> list[clingo.Symbol]:
        """The least path (actions compared step by step by their terms) of
        ``layer`` actions to a configuration of that layer whose final state
        is a goal state, where ``layer`` is the first such layer: the
        configurations from which the rest of such a path leads there are
        found backwards within the layers, then the least action into the
        next set is taken, step after step."""
        targets: list[set[Configuration]] = [set() for _ in range(layer + 1)]
        targets[layer] = {c for c in self.layers[layer] if self.task.is_goal(self.final(c))}
        for k in range(layer - 1, -1, -1):
            targets[k] = {
                c
                for c in self.layers[k]
                if any(after in targets[k + 1] for _, after in self.successors(c))
            }
        current = self.layers[0][0]
        actions = []
        for k in range(1, layer + 1):
            name, current = min(
                (
                    (action.name, after)
                    for action, after in self.successors(current)
                    if after in targets[k]
                ),
                key=lambda pair: pair[0],
            )
            actions.append(name)
        return actions

    def first_goal(self, layer: int) -> Configuration | None:
        """A configuration of a layer whose final state is a goal state."""
        for configuration in self.layers[layer]:
            if self.task.is_goal(self.final(configuration)):
                return configuration
        return None


def search_with_events(model, budget: Budget, publish, stop, read_plan: bool = True) -> None:
    """:func:`search` over a search model with exogenous events
    (:func:`ethasp.planning.engines.layers.search_model`): its task and events."""
    task = Task(model)
    search(task, Events(model.events, task.index), budget, publish, stop, read_plan)


def search(task, events: Events, budget: Budget, publish, stop, read_plan: bool = True) -> None:
    """Plan search over the layers, reporting as the exact layers do
    (:class:`ethasp.planning.engines.layers.Status`): bounds, a shortest plan (only
    with ``read_plan``: a search whose setting the layers do not know, such
    as question constraints imposed in ASP, must not take it), or that no
    goal state is reachable."""
    layers = Configurations(task, events)
    k = 0
    while True:
        if stop():
            publish(stopped="stopped")
            return
        goal = layers.first_goal(k)
        if goal is not None:
            publish(goal_layer=k, bound=k)
            if read_plan:
                publish(plan=tuple(layers.least_path(k)))
            return
        publish(bound=k + 1)
        if not layers.expand(budget):
            publish(stopped=layers.stopped)
            return
        if layers.complete:
            publish(complete=True)
            return
        k += 1
