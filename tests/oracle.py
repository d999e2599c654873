"""Brute-force reference semantics, written from the paper's definitions.

Explicit states (frozensets of true variables), breadth-first search, and a
generator of small random models.  Used only by tests, as an oracle.

Models may also have conditional effects and derived variables (the model
vocabulary of encodings/planning/model.lp): an effect fires when its
conditions hold in the state before the action, and when firing effects set a
variable both ways, true wins; a derived variable holds in a state when all
conditions of one of its axioms hold there (axioms of a derived variable read
only state variables and derived variables defined before it).  An effect
counts for Caused(p) and for do-no-harm only when it fires.

Models may also have exogenous events (HERA's events at time points): an
event is due at a step T; after the action of step T, if its preconditions
hold, each of its effects whose conditions hold fires (both read the state
after the action); among the firing effects of one step on one variable, the
greatest key wins (true between equal keys), and an event overrides the
action.  Events happen after the plan's last action too: the final state is
the state after the later of the plan's end and the last event.  So the
search space is made of configurations (state, time), the time counting only
up to the last event.  Caused(p) with events: some action's effect that fired
and won at step S set p (p holds after the action), and p held after S (its
events included) and at every later step.
"""

from __future__ import annotations

import contextlib
import heapq
import io
import random
from collections import deque
from dataclasses import dataclass, field


@dataclass
class Event:
    """An exogenous event: due at ``step``; happens when ``pre`` holds after the
    action of that step; ``effects`` are (key, conditions, sets)."""

    name: str
    step: int
    pre: dict[str, bool]
    effects: list[tuple[int, dict[str, bool], dict[str, bool]]]


@dataclass
class RandomModel:
    variables: list[str]
    actions: list[str]
    pre: dict[str, dict[str, bool]]
    eff: dict[str, dict[str, bool]]
    init: frozenset
    goal: dict[str, bool]
    action_utility: dict[str, int] = field(default_factory=dict)
    fact_utility: dict[tuple[str, bool], int] = field(default_factory=dict)
    # conditional effects: per action, (name, conditions, effects)
    ceff: dict[str, list[tuple[str, dict[str, bool], dict[str, bool]]]] = field(
        default_factory=dict
    )
    # derived variables, in order: each with its axioms (conditions)
    derived: dict[str, list[dict[str, bool]]] = field(default_factory=dict)
    # exogenous events
    events: list[Event] = field(default_factory=list)
    # action costs (cost/2): empty, no costs (every action costs 1); else an
    # action without one costs 0
    action_cost: dict[str, int] = field(default_factory=dict)
    # what a repair may change, with costs: initial values of variables,
    # creative alternatives (actions with pre/eff like others, but not in
    # ``actions``), preventable events; goal facts dropped (cost 1 unless in
    # ``goal_cost``; never those in ``goal_fixed``)
    changeable: dict[str, int] = field(default_factory=dict)
    creative: dict[str, int] = field(default_factory=dict)
    preventable: dict[str, int] = field(default_factory=dict)
    goal_cost: dict[tuple[str, bool], int] = field(default_factory=dict)
    goal_fixed: set = field(default_factory=set)

    # -- semantics ------------------------------------------------------------

    @property
    def last_event(self) -> int:
        """The last step at which an event is due (0 without events)."""
        return max((event.step for event in self.events), default=0)

    def extended(self, state: frozenset) -> frozenset:
        """The state with the derived variables that hold in it."""
        result = set(state)
        for name, axioms in self.derived.items():
            if any(
                all((var in result) == value for var, value in axiom.items()) for axiom in axioms
            ):
                result.add(name)
        return frozenset(result)

    def satisfies(self, state: frozenset, conditions: dict[str, bool]) -> bool:
        full = self.extended(state) if self.derived else state
        return all((var in full) == value for var, value in conditions.items())

    def applicable(self, state: frozenset, action: str) -> bool:
        return self.satisfies(state, self.pre[action])

    def firing(self, state: frozenset, action: str) -> list[tuple[str, bool]]:
        """The effects of an action that fire in a state: unconditional ones
        and conditional ones whose conditions hold."""
        effects = list(self.eff[action].items())
        for _, conditions, sets in self.ceff.get(action, []):
            if self.satisfies(state, conditions):
                effects += list(sets.items())
        return effects

    def apply(self, state: frozenset, action: str) -> frozenset:
        effects = self.firing(state, action)
        adds = {var for var, value in effects if value}
        dels = {var for var, value in effects if not value}
        return frozenset((set(state) - dels) | adds)

    def is_goal(self, state: frozenset) -> bool:
        return self.satisfies(state, self.goal)

    def happen(self, state: frozenset, t: int) -> frozenset:
        """The state after the events due at step ``t``, from the state after
        that step's action (if any)."""
        winners: dict[str, tuple[int, bool]] = {}
        for event in self.events:
            if event.step != t or not all((v in state) == b for v, b in event.pre.items()):
                continue
            for key, conditions, sets in event.effects:
                if all((v in state) == b for v, b in conditions.items()):
                    for var, value in sets.items():
                        if var not in winners or (key, value) > winners[var]:
                            winners[var] = (key, value)
        if not winners:
            return state
        return frozenset(
            {v for v in state if v not in winners}
            | {v for v, (_, value) in winners.items() if value}
        )

    def step(self, state: frozenset, t: int, action: str | None) -> frozenset:
        """The state after step ``t``: its action (None: an idle step after the
        plan), then its events."""
        after = self.apply(state, action) if action is not None else state
        return self.happen(after, t)

    def trajectory(self, plan: list[str]) -> list[frozenset] | None:
        """The states of a plan: the initial one, then the state after each step,
        up to the later of the plan's end and the last event (idle steps after
        the plan); None if some action is inapplicable."""
        states = [self.init]
        for t in range(1, max(len(plan), self.last_event) + 1):
            action = plan[t - 1] if t <= len(plan) else None
            if action is not None and not self.applicable(states[-1], action):
                return None
            states.append(self.step(states[-1], t, action))
        return states

    def first_failure(self, plan: list[str]) -> int | None:
        """The first step (from 1) whose action is inapplicable, or None."""
        state = self.init
        for t, action in enumerate(plan, start=1):
            if not self.applicable(state, action):
                return t
            state = self.step(state, t, action)
        return None

    def run(self, plan: list[str]) -> frozenset | None:
        states = self.trajectory(plan)
        return states[-1] if states is not None else None

    def is_plan(self, plan: list[str]) -> bool:
        final = self.run(plan)
        return final is not None and self.is_goal(final)

    # Configurations (state, time): the time counts up to the last event only.

    def successor(self, config: tuple[frozenset, int], action: str) -> tuple[frozenset, int]:
        state, t = config
        return self.step(state, t + 1, action), min(t + 1, self.last_event)

    def finish(self, config: tuple[frozenset, int]) -> frozenset:
        """The final state of a plan that ends in this configuration (the events
        still due happen)."""
        state, t = config
        for later in range(t + 1, self.last_event + 1):
            state = self.happen(state, later)
        return state

    def configurations(self) -> dict[tuple[frozenset, int], int]:
        """Every reachable configuration with the length of a shortest action
        sequence to it."""
        start = (self.init, 0)
        dist = {start: 0}
        queue = deque([start])
        while queue:
            config = queue.popleft()
            for action in self.actions:
                if self.applicable(config[0], action):
                    succ = self.successor(config, action)
                    if succ not in dist:
                        dist[succ] = dist[config] + 1
                        queue.append(succ)
        return dist

    def distances(self) -> dict[frozenset, int]:
        """Every reachable state (final state of an action sequence) with the
        length of a shortest action sequence that ends in it."""
        dist: dict[frozenset, int] = {}
        for config, d in self.configurations().items():
            final = self.finish(config)
            if final not in dist or d < dist[final]:
                dist[final] = d
        return dist

    def shortest_plan_length(self) -> int | None:
        goals = [d for s, d in self.distances().items() if self.is_goal(s)]
        return min(goals) if goals else None

    def cost(self, action: str) -> int:
        """The cost of an action: 1 in a model without costs, else its cost or 0."""
        return self.action_cost.get(action, 0) if self.action_cost else 1

    def plan_cost(self, plan: list[str]) -> int:
        return sum(self.cost(action) for action in plan)

    def cheapest_plan_cost(self) -> int | None:
        """The least cost of a plan (Dijkstra over configurations), or None."""
        return self.cheapest_permissible_cost(())

    def least_cheapest_plan(self) -> list[str] | None:
        """The least of the cheapest plans of the fewest steps (compared step by
        step, step 1 first, by their actions in clingo's order of terms); None
        if there is no plan."""
        import clingo

        length, _, cost = self._permissible_search(set())
        if length is None or cost is None:
            return None
        order = sorted(self.actions, key=clingo.parse_term)
        dead: set = set()

        def search(config, depth: int, spent: int) -> list[str] | None:
            if depth == length:
                good = spent == cost and self.is_goal(self.finish(config))
                return [] if good else None
            if (config, depth, spent) in dead:
                return None
            for action in order:
                if self.applicable(config[0], action) and spent + self.cost(action) <= cost:
                    rest = search(
                        self.successor(config, action), depth + 1, spent + self.cost(action)
                    )
                    if rest is not None:
                        return [action, *rest]
            dead.add((config, depth, spent))
            return None

        return search((self.init, 0), 0, 0)

    def least_shortest_plan(self) -> list[str] | None:
        """The least shortest plan: plans of the shortest length compared step
        by step, step 1 first, by their actions in clingo's order of terms;
        None if there is no plan."""
        import clingo

        length = self.shortest_plan_length()
        if length is None:
            return None
        order = sorted(self.actions, key=clingo.parse_term)
        dead: set[tuple[tuple[frozenset, int], int]] = set()

        def search(config: tuple[frozenset, int], depth: int) -> list[str] | None:
            if depth == length:
                return [] if self.is_goal(self.finish(config)) else None
            if (config, depth) in dead:
                return None
            for action in order:
                if self.applicable(config[0], action):
                    rest = search(self.successor(config, action), depth + 1)
                    if rest is not None:
                        return [action, *rest]
            dead.add((config, depth))
            return None

        return search((self.init, 0), 0)

    def state_utility(self, state: frozenset) -> int:
        return sum(self.fact_utility.get((var, var in state), 0) for var in self.variables)

    # -- the ethical principles (Definitions 1-3 of the paper) ------------------

    def bad_action(self, action: str) -> bool:
        return self.action_utility.get(action, 0) < 0

    def bad_fact(self, var: str, value: bool) -> bool:
        return self.fact_utility.get((var, value), 0) < 0

    def effects_of(self, plan: list[str]) -> set[tuple[str, bool]]:
        """The effects of the plan's actions that fired (the plan applicable)."""
        states, effects = self.trajectory(plan), set()
        for t, action in enumerate(plan):
            effects |= set(self.firing(states[t], action))
        return effects

    def caused(self, plan: list[str]) -> set[tuple[str, bool]]:
        """Caused(p): p holds in the final state and an effect of an action of the
        plan that fired and won set p (p holds after the action), p holding
        from the end of that step (its events included) to the end."""
        states = self.trajectory(plan)
        result = set()
        for t, action in enumerate(plan, start=1):
            after = self.apply(states[t - 1], action)
            for var, value in self.firing(states[t - 1], action):
                if (var in after) == value and all((var in later) == value for later in states[t:]):
                    result.add((var, value))
        return result

    def best_reachable_utility(self) -> int:
        return max(self.state_utility(state) for state in self.distances())

    def permissible(self, plan: list[str], principle: str) -> bool:
        """Whether a plan is permissible under a principle, from the definitions:
        the paper's three, and HERA's principles that have a restriction (of
        HERA 0.22.3; hera-utilitarianism without alternatives permits every
        plan)."""
        if principle in ("deontology", "hera-deontology"):
            return not any(self.bad_action(action) for action in plan)
        if principle == "do-no-harm":
            return not any(self.bad_fact(var, value) for var, value in self.caused(plan))
        if principle == "utilitarianism":
            return self.state_utility(self.run(plan)) >= self.best_reachable_utility()
        if principle in ("avoid-any-harm", "avoid-avoidable-harm"):
            # Avoidable(p) of a final bad fact p holds iff the goal is reachable.
            if principle == "avoid-avoidable-harm" and self.shortest_plan_length() is None:
                return True
            return not self.final_harm(self.run(plan))
        if principle == "goal-deontology":
            return not self.bad_goal()
        if principle == "hera-utilitarianism":
            return True
        raise ValueError(principle)

    def final_harm(self, state: frozenset) -> bool:
        """Does a bad fact hold in the state?"""
        return any(self.bad_fact(var, var in state) for var in self.variables)

    def bad_goal(self) -> bool:
        """Is a fact of the goal bad?"""
        return any(
            var in self.variables and self.bad_fact(var, value) for var, value in self.goal.items()
        )

    def within(self, principles, horizon: int) -> str:
        """What a brute-force search of ``horizon`` steps settles about the
        plans permissible under the principles: "found" (one of at most
        ``horizon`` steps exists), "none" (every node of the search, and for
        utilitarianism every configuration of the model, is within
        ``horizon`` steps, and no permissible plan is among them) or "open"
        (the horizon cut it short)."""
        principles = set(principles)
        if "utilitarianism" in principles:
            depth = max(self.configurations().values())
            if depth > horizon:
                return "open"
        length, depth, _ = self._permissible_search(principles)
        if length is not None:
            return "found" if length <= horizon else "open"
        return "none" if depth <= horizon else "open"

    def shortest_permissible_length(self, principles) -> int | None:
        return self._permissible_search(set(principles))[0]

    def cheapest_permissible_cost(self, principles) -> int | None:
        """The least cost of a plan permissible under all the principles, or None."""
        return self._permissible_search(set(principles))[2]

    def _permissible_search(self, principles) -> tuple[int | None, int, int | None]:
        """The length of a shortest plan permissible under all the principles (of
        a cheapest one, with costs), or None; the depth of the deepest node
        searched; and the cost of that plan.

        Uniform-cost search over (configuration, produced): the bad facts that
        an action of the plan set and that have held since, by cost, then
        length (breadth-first without costs); the nodes are finitely many, so
        None means no permissible plan of any length.
        """
        best = self.best_reachable_utility() if "utilitarianism" in principles else None

        def carry(state, produced):
            return frozenset(fact for fact in produced if (fact[0] in state) == fact[1])

        if "goal-deontology" in principles and self.bad_goal():
            return None, 0, None
        harmless = bool({"avoid-any-harm", "avoid-avoidable-harm"} & principles)

        def accepted(node) -> bool:
            config, produced = node
            state = self.finish(config)
            if not self.is_goal(state):
                return False
            if best is not None and self.state_utility(state) < best:
                return False
            if harmless and self.final_harm(state):
                return False
            if "do-no-harm" in principles:
                # the flags that survive the events still due
                t = config[1]
                current = config[0]
                for later in range(t + 1, self.last_event + 1):
                    current = self.happen(current, later)
                    produced = carry(current, produced)
                return not produced
            return True

        start = ((self.init, 0), frozenset())
        key = {start: (0, 0)}
        queue = [(0, 0, 0, start)]
        done: set = set()
        counter = 0
        while queue:
            cost, length, _, node = heapq.heappop(queue)
            if node in done:
                continue
            done.add(node)
            config, produced = node
            if accepted(node):
                return length, length, cost
            for action in self.actions:
                if not self.applicable(config[0], action):
                    continue
                if {"deontology", "hera-deontology"} & principles and self.bad_action(action):
                    continue
                succ_config = self.successor(config, action)
                after = self.apply(config[0], action)
                fired = {
                    (var, value)
                    for var, value in self.firing(config[0], action)
                    if self.bad_fact(var, value) and (var in after) == value
                }
                succ = (succ_config, carry(succ_config[0], produced | fired))
                succ_key = (cost + self.cost(action), length + 1)
                if succ not in done and succ_key < key.get(succ, (succ_key[0] + 1, 0)):
                    key[succ] = succ_key
                    counter += 1
                    heapq.heappush(queue, (*succ_key, counter, succ))
        return None, max(length for _, length in key.values()), None

    # -- ASP ------------------------------------------------------------------

    def to_asp(self) -> str:
        lines = [f"variable({v})." for v in self.variables]
        lines += [f"action({a})." for a in self.actions]
        lines += [f"creative({a},{c})." for a, c in self.creative.items()]
        lines += [f"changeable({v},{c})." for v, c in self.changeable.items()]
        lines += [f"preventable({e},{c})." for e, c in self.preventable.items()]
        lines += [f"goal_cost({v},{str(b).lower()},{c})." for (v, b), c in self.goal_cost.items()]
        lines += [f"goal_fixed({v},{str(b).lower()})." for v, b in sorted(self.goal_fixed)]
        for a in list(self.actions) + list(self.creative):
            lines += [f"pre({a},{v},{str(b).lower()})." for v, b in self.pre[a].items()]
            lines += [f"eff({a},{v},{str(b).lower()})." for v, b in self.eff[a].items()]
        for a, effects in self.ceff.items():
            for k, conditions, sets in effects:
                lines += [f"ceff({a},{k},{v},{str(b).lower()})." for v, b in sets.items()]
                lines += [f"cpre({a},{k},{v},{str(b).lower()})." for v, b in conditions.items()]
        for d, axioms in self.derived.items():
            lines.append(f"derived({d}).")
            for k, conditions in enumerate(axioms):
                lines.append(f"axiom({d},{k}).")
                lines += [
                    f"axiom_pre({d},{k},{v},{str(b).lower()})." for v, b in conditions.items()
                ]
        for event in self.events:
            e = event.name
            lines += [f"event({e}).", f"event_at({e},{event.step})."]
            lines += [f"event_pre({e},{v},{str(b).lower()})." for v, b in event.pre.items()]
            for k, conditions, sets in event.effects:
                lines += [f"event_effect({e},{k},{v},{str(b).lower()})." for v, b in sets.items()]
                lines += [
                    f"event_condition({e},{k},{v},{str(b).lower()})." for v, b in conditions.items()
                ]
        lines += [f"init({v})." for v in sorted(self.init)]
        lines += [f"goal({v},{str(b).lower()})." for v, b in self.goal.items()]
        lines += [f"utility({a},{u})." for a, u in self.action_utility.items()]
        lines += [f"utility({v},{str(b).lower()},{u})." for (v, b), u in self.fact_utility.items()]
        lines += [f"cost({a},{c})." for a, c in self.action_cost.items()]
        return "\n".join(lines) + "\n"


def random_model(
    seed: int,
    max_variables: int = 4,
    max_actions: int = 4,
    conditional: bool = False,
    derived: bool = False,
    far_goal: bool = False,
    events: bool = False,
    costs: bool = False,
) -> RandomModel:
    """A small random model; with ``conditional``, actions also get conditional
    effects, with ``derived``, derived variables that preconditions,
    conditions and the goal may read, and with ``events``, one or two
    exogenous events at steps 1 to 3, with preconditions and conditional
    effects (the model without them is the same).
    With ``far_goal`` the goal is made of literals of a reachable state
    farthest from the initial state (so that plans are longer).  With
    ``costs``, actions get costs from 0 to 4 (most of them; the others cost
    0), drawn after everything else (the model without them is the same)."""
    rng = random.Random(seed)
    variables = [f"v{i}" for i in range(rng.randint(1, max_variables))]
    actions = [f"a{i}" for i in range(rng.randint(1, max_actions))]
    pre, eff = {}, {}
    for a in actions:
        pre[a] = {v: rng.random() < 0.5 for v in variables if rng.random() < 0.35}
        eff[a] = {v: rng.random() < 0.5 for v in variables if rng.random() < 0.45}
        if not eff[a]:
            eff[a] = {rng.choice(variables): rng.random() < 0.5}
    init = frozenset(v for v in variables if rng.random() < 0.4)
    goal = {v: rng.random() < 0.5 for v in variables if rng.random() < 0.5}
    if not goal:
        goal = {rng.choice(variables): rng.random() < 0.5}
    action_utility = {a: rng.randint(-2, 2) for a in actions if rng.random() < 0.6}
    fact_utility = {
        (v, b): rng.randint(-3, 3) for v in variables for b in (True, False) if rng.random() < 0.5
    }
    spec = RandomModel(variables, actions, pre, eff, init, goal, action_utility, fact_utility)
    if derived:
        _add_derived(spec, rng)
    if conditional:
        _add_conditional_effects(spec, rng)
    if events:
        _add_events(spec, rng)
    if far_goal:
        distances = spec.distances()
        far = max(distances.values())
        state = rng.choice(sorted((s for s, d in distances.items() if d == far), key=sorted))
        differ = [v for v in spec.variables if (v in state) != (v in spec.init)]
        chosen = rng.sample(differ, min(len(differ), rng.randint(1, 3))) or spec.variables[:1]
        spec.goal = {v: v in state for v in chosen}
    if costs:
        spec.action_cost = {
            a: rng.choice((0, 1, 1, 2, 3, 4)) for a in actions if rng.random() < 0.8
        }
        if not spec.action_cost:
            spec.action_cost = {actions[0]: rng.randint(0, 4)}
    return spec


def _add_derived(spec: RandomModel, rng: random.Random) -> None:
    readable = list(spec.variables)
    for index in range(rng.randint(1, 2)):
        name = f"d{index}"
        spec.derived[name] = [
            {
                v: rng.random() < 0.5
                for v in rng.sample(readable, rng.randint(0, min(2, len(readable))))
            }
            for _ in range(rng.randint(0 if rng.random() < 0.2 else 1, 2))
        ]
        readable.append(name)
    for a in spec.actions:
        if rng.random() < 0.3:
            spec.pre[a][rng.choice(list(spec.derived))] = rng.random() < 0.5
    if rng.random() < 0.3:
        spec.goal[rng.choice(list(spec.derived))] = rng.random() < 0.5


def _add_conditional_effects(spec: RandomModel, rng: random.Random) -> None:
    readable = list(spec.variables) + list(spec.derived)
    for a in spec.actions:
        effects = []
        for k in range(rng.randint(0, 2)):
            conditions = {
                v: rng.random() < 0.5
                for v in rng.sample(readable, rng.randint(0, min(2, len(readable))))
            }
            sets = {
                v: rng.random() < 0.5
                for v in rng.sample(spec.variables, rng.randint(1, min(2, len(spec.variables))))
            }
            effects.append((f"k{k}", conditions, sets))
        if effects:
            spec.ceff[a] = effects


def _add_events(spec: RandomModel, rng: random.Random) -> None:
    """One or two events at steps 1 to 3; conflicting effects (on one variable,
    of one step) are allowed: the greatest key wins."""
    for index in range(rng.randint(1, 2)):
        pre = {
            v: rng.random() < 0.5
            for v in rng.sample(spec.variables, rng.randint(0, min(1, len(spec.variables))))
        }
        effects = []
        for key in rng.sample(range(1, 4), rng.randint(1, 2)):
            conditions = {
                v: rng.random() < 0.5
                for v in rng.sample(spec.variables, rng.randint(0, min(1, len(spec.variables))))
            }
            sets = {
                v: rng.random() < 0.5
                for v in rng.sample(spec.variables, rng.randint(1, min(2, len(spec.variables))))
            }
            effects.append((key, conditions, sets))
        spec.events.append(Event(f"e{index}", rng.randint(1, 3), pre, effects))


def features(seed: int) -> dict[str, bool]:
    """Which features a random model of this seed draws: each of conditional
    effects, derived variables and events in half of the models (every
    combination alike), so that property tests cover every feature together."""
    return {
        "conditional": seed % 2 == 1,
        "derived": (seed // 2) % 2 == 1,
        "events": (seed // 4) % 2 == 1,
    }


# -- the language L, read literally (section "Moral Action Query Language") ------
#
# Formulas are tuples: ("good"|"bad"|"neutral", element), with element
# ("action", a) or ("fact", v, value); ("caused", v, value);
# ("geq", [(v, value), ...], [(v, value), ...]); ("not", f); ("and"|"or"|"imp", f, g).


def element_utility(spec: RandomModel, element: tuple) -> int:
    if element[0] == "action":
        return spec.action_utility.get(element[1], 0)
    return spec.fact_utility.get((element[1], element[2]), 0)


def holds(spec: RandomModel, plan: list[str], formula: tuple) -> bool:
    """<model, plan> |= formula, from the paper's definitions."""
    kind = formula[0]
    if kind == "good":
        return element_utility(spec, formula[1]) > 0
    if kind == "bad":
        return element_utility(spec, formula[1]) < 0
    if kind == "neutral":
        return element_utility(spec, formula[1]) == 0
    if kind == "caused":
        return (formula[1], formula[2]) in spec.caused(plan)
    if kind == "geq":

        def worth(facts):
            return sum(spec.fact_utility.get(fact, 0) for fact in set(facts))

        return worth(formula[1]) >= worth(formula[2])
    if kind == "not":
        return not holds(spec, plan, formula[1])
    if kind == "and":
        return holds(spec, plan, formula[1]) and holds(spec, plan, formula[2])
    if kind == "or":
        return holds(spec, plan, formula[1]) or holds(spec, plan, formula[2])
    if kind == "imp":
        return not holds(spec, plan, formula[1]) or holds(spec, plan, formula[2])
    raise ValueError(formula)


def random_formula(spec: RandomModel, rng: random.Random, depth: int = 3) -> tuple:
    """A random formula of L over the model's actions and variables."""

    def fact() -> tuple:
        return rng.choice(spec.variables), rng.random() < 0.5

    if depth == 0 or rng.random() < 0.3:
        kind = rng.choice(["good", "bad", "neutral", "caused", "geq"])
        if kind == "caused":
            return ("caused", *fact())
        if kind == "geq":
            return (
                "geq",
                [fact() for _ in range(rng.randint(1, 3))],
                [fact() for _ in range(rng.randint(1, 3))],
            )
        element = ("action", rng.choice(spec.actions)) if rng.random() < 0.4 else ("fact", *fact())
        return (kind, element)
    kind = rng.choice(["not", "and", "or", "imp"])
    if kind == "not":
        return ("not", random_formula(spec, rng, depth - 1))
    return (kind, random_formula(spec, rng, depth - 1), random_formula(spec, rng, depth - 1))


def plan_through(spec: RandomModel, rng: random.Random, walk: int) -> list[str] | None:
    """A plan: a random walk of at most ``walk`` applicable actions, then a
    shortest path to a goal state (None if no goal state is reachable from there)."""
    config, plan = (spec.init, 0), []
    for _ in range(walk):
        options = [a for a in spec.actions if spec.applicable(config[0], a)]
        if not options:
            break
        action = rng.choice(options)
        plan.append(action)
        config = spec.successor(config, action)
    parent = {config: None}
    queue = deque([config])
    while queue:
        current = queue.popleft()
        if spec.is_goal(spec.finish(current)):
            tail = []
            while parent[current] is not None:
                current, action = parent[current]
                tail.append(action)
            return plan + tail[::-1]
        for action in spec.actions:
            if spec.applicable(current[0], action):
                succ = spec.successor(current, action)
                if succ not in parent:
                    parent[succ] = (current, action)
                    queue.append(succ)
    return None


# -- goal subsets, conflicts and repairs (Eifler et al.'s explanations under a principle) --


def with_goal(spec: RandomModel, goal: dict) -> RandomModel:
    """The model with another goal."""
    from dataclasses import replace

    return replace(spec, goal=dict(goal))


def goal_reachable(spec: RandomModel, literals, principle: str) -> bool:
    """Does a plan permissible under the principle reach the goal facts
    ``literals`` ((variable, value) pairs), the model's goal replaced by them?"""
    return with_goal(spec, dict(literals)).shortest_permissible_length([principle]) is not None


def goal_structure(spec: RandomModel, principle: str):
    """The subset-minimal sets of goal facts that no permissible plan reaches
    (conflicts) and the subset-maximal ones that a permissible plan reaches
    (goal subsets), by trying every subset of the goal."""
    import itertools

    facts = sorted(spec.goal.items())
    reachable = {}
    for size in range(len(facts) + 1):
        for subset in itertools.combinations(facts, size):
            reachable[frozenset(subset)] = goal_reachable(spec, subset, principle)
    conflicts = [s for s, ok in reachable.items() if not ok and all(reachable[s - {f}] for f in s)]
    subsets = [
        s
        for s, ok in reachable.items()
        if ok and all(not reachable[s | {f}] for f in facts if f not in s)
    ]
    return set(conflicts), set(subsets)


def add_repairs(spec: RandomModel, rng: random.Random) -> None:
    """Declare what a repair may change: one or two creative alternatives (with
    preconditions, effects and maybe a utility), changeable initial values,
    preventable events, costs and fixed goal facts."""
    for index in range(rng.randint(1, 2)):
        name = f"c{index}"
        spec.pre[name] = {v: rng.random() < 0.5 for v in spec.variables if rng.random() < 0.3}
        spec.eff[name] = {v: rng.random() < 0.5 for v in spec.variables if rng.random() < 0.5}
        if not spec.eff[name]:
            spec.eff[name] = {rng.choice(spec.variables): rng.random() < 0.5}
        if rng.random() < 0.5:
            spec.action_utility[name] = rng.randint(-2, 2)
        spec.creative[name] = rng.randint(1, 3)
    for variable in rng.sample(spec.variables, rng.randint(0, min(2, len(spec.variables)))):
        spec.changeable[variable] = rng.randint(1, 3)
    for event in spec.events:
        if rng.random() < 0.5:
            spec.preventable[event.name] = rng.randint(1, 3)
    for fact in spec.goal.items():
        if fact[0] not in spec.variables:
            continue
        roll = rng.random()
        if roll < 0.3:
            spec.goal_cost[fact] = rng.randint(2, 3)
        elif roll < 0.45:
            spec.goal_fixed.add(fact)


def allowed_changes(spec: RandomModel) -> list[tuple[tuple, int]]:
    """The changes a repair may make, with their costs: ("initial", v),
    ("add", a), ("prevent", e), ("drop", v, b)."""
    changes = [(("initial", v), c) for v, c in spec.changeable.items()]
    changes += [(("add", a), c) for a, c in spec.creative.items()]
    changes += [(("prevent", e), c) for e, c in spec.preventable.items()]
    changes += [
        (("drop", v, b), spec.goal_cost.get((v, b), 1))
        for v, b in spec.goal.items()
        if (v, b) not in spec.goal_fixed
    ]
    return changes


def repaired(spec: RandomModel, changes) -> RandomModel:
    """The model after the changes."""
    from dataclasses import replace

    kinds = {change[0] for change in changes}
    assert kinds <= {"initial", "add", "prevent", "drop"}
    init = set(spec.init)
    for change in changes:
        if change[0] == "initial":
            init ^= {change[1]}
    dropped = {(c[1], c[2]) for c in changes if c[0] == "drop"}
    prevented = {c[1] for c in changes if c[0] == "prevent"}
    added = [c[1] for c in changes if c[0] == "add"]
    return replace(
        spec,
        actions=list(spec.actions) + sorted(added),
        init=frozenset(init),
        goal={v: b for v, b in spec.goal.items() if (v, b) not in dropped},
        events=[event for event in spec.events if event.name not in prevented],
        creative={},
        changeable={},
        preventable={},
        goal_cost={},
        goal_fixed=set(),
    )


def least_repairs(spec: RandomModel, principle: str) -> tuple[int | None, set]:
    """The least cost of a repair that admits a plan permissible under the
    principle (judged in the repaired model), and every repair of that cost,
    by trying every set of changes in increasing cost."""
    import itertools

    changes = allowed_changes(spec)
    subsets = []
    for size in range(len(changes) + 1):
        subsets += list(itertools.combinations(changes, size))
    subsets.sort(key=lambda subset: sum(cost for _, cost in subset))
    least, found = None, set()
    for subset in subsets:
        cost = sum(c for _, c in subset)
        if least is not None and cost > least:
            break
        model = repaired(spec, [change for change, _ in subset])
        if model.shortest_permissible_length([principle]) is not None:
            least = cost
            found.add(frozenset(change for change, _ in subset))
    return least, found


def assert_shortest(result, spec: RandomModel) -> None:
    """A plan search's result agrees with the oracle: "none" exactly where no
    plan exists, else a valid plan of the shortest length, proven shortest."""
    expected = spec.shortest_plan_length()
    if expected is None:
        assert result.status == "none", (result, spec)
        return
    assert result.status == "found", (result, spec)
    plan = [str(action) for action in result.plan]
    assert spec.is_plan(plan), (plan, spec)
    assert len(plan) == expected and result.optimal, (plan, expected, spec)


def answered(search):
    """The result of a search in which Fast Downward never failed (a failure
    falls back to clingo with a warning, which the oracle would not notice)."""
    from ethasp.planning import systems

    systems._warned.clear()  # (each warning is given once per process)
    said = io.StringIO()
    with contextlib.redirect_stderr(said):
        result = search()
    assert "Fast Downward failed" not in said.getvalue(), said.getvalue()
    return result
