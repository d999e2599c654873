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
"""

from __future__ import annotations

import random
from collections import deque
from dataclasses import dataclass, field


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
    ceff: dict[str, list[tuple[str, dict[str, bool], dict[str, bool]]]] = \
        field(default_factory=dict)
    # derived variables, in order: each with its axioms (conditions)
    derived: dict[str, list[dict[str, bool]]] = field(default_factory=dict)

    # -- semantics ------------------------------------------------------------

    def extended(self, state: frozenset) -> frozenset:
        """The state with the derived variables that hold in it."""
        result = set(state)
        for name, axioms in self.derived.items():
            if any(all((var in result) == value for var, value in axiom.items())
                   for axiom in axioms):
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

    def run(self, plan: list[str]) -> frozenset | None:
        state = self.init
        for action in plan:
            if not self.applicable(state, action):
                return None
            state = self.apply(state, action)
        return state

    def is_plan(self, plan: list[str]) -> bool:
        final = self.run(plan)
        return final is not None and self.is_goal(final)

    def distances(self) -> dict[frozenset, int]:
        """Every reachable state with its distance from the initial state."""
        dist = {self.init: 0}
        queue = deque([self.init])
        while queue:
            state = queue.popleft()
            for action in self.actions:
                if self.applicable(state, action):
                    succ = self.apply(state, action)
                    if succ not in dist:
                        dist[succ] = dist[state] + 1
                        queue.append(succ)
        return dist

    def shortest_plan_length(self) -> int | None:
        goals = [d for s, d in self.distances().items() if self.is_goal(s)]
        return min(goals) if goals else None

    def state_utility(self, state: frozenset) -> int:
        return sum(self.fact_utility.get((var, var in state), 0) for var in self.variables)

    # -- the ethical principles (Definitions 1-3 of the paper) ------------------

    def bad_action(self, action: str) -> bool:
        return self.action_utility.get(action, 0) < 0

    def bad_fact(self, var: str, value: bool) -> bool:
        return self.fact_utility.get((var, value), 0) < 0

    def effects_of(self, plan: list[str]) -> set[tuple[str, bool]]:
        """The effects of the plan's actions that fired (the plan applicable)."""
        state, effects = self.init, set()
        for action in plan:
            effects |= set(self.firing(state, action))
            state = self.apply(state, action)
        return effects

    def caused(self, plan: list[str]) -> set[tuple[str, bool]]:
        """Caused(p): p holds in the final state and some action of the plan has p
        as an effect (that fired)."""
        final = self.run(plan)
        return {(var, value) for var, value in self.effects_of(plan) if (var in final) == value}

    def best_reachable_utility(self) -> int:
        return max(self.state_utility(state) for state in self.distances())

    def permissible(self, plan: list[str], principle: str) -> bool:
        """Whether a plan is permissible under a principle, from the definitions."""
        if principle == "deontology":
            return not any(self.bad_action(action) for action in plan)
        if principle == "do-no-harm":
            return not any(self.bad_fact(var, value) for var, value in self.caused(plan))
        if principle == "utilitarianism":
            return self.state_utility(self.run(plan)) >= self.best_reachable_utility()
        raise ValueError(principle)

    def shortest_permissible_length(self, principles) -> int | None:
        """The length of a shortest plan permissible under all the principles, or None.

        Breadth-first search over pairs (state, bad facts some action so far
        had as effect); the pairs are finitely many, so None means no
        permissible plan of any length.
        """
        principles = set(principles)
        best = self.best_reachable_utility() if "utilitarianism" in principles else None

        def accepted(state, effected) -> bool:
            if not self.is_goal(state):
                return False
            if best is not None and self.state_utility(state) < best:
                return False
            if "do-no-harm" in principles:
                return not any((var in state) == value for var, value in effected)
            return True

        start = (self.init, frozenset())
        dist = {start: 0}
        queue = deque([start])
        while queue:
            node = queue.popleft()
            state, effected = node
            if accepted(state, effected):
                return dist[node]
            for action in self.actions:
                if not self.applicable(state, action):
                    continue
                if "deontology" in principles and self.bad_action(action):
                    continue
                succ = (self.apply(state, action),
                        effected | {(var, value) for var, value in self.firing(state, action)
                                    if self.bad_fact(var, value)})
                if succ not in dist:
                    dist[succ] = dist[node] + 1
                    queue.append(succ)
        return None

    # -- ASP ------------------------------------------------------------------

    def to_asp(self) -> str:
        lines = [f"variable({v})." for v in self.variables]
        lines += [f"action({a})." for a in self.actions]
        for a in self.actions:
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
                lines += [f"axiom_pre({d},{k},{v},{str(b).lower()})." for v, b in conditions.items()]
        lines += [f"init({v})." for v in sorted(self.init)]
        lines += [f"goal({v},{str(b).lower()})." for v, b in self.goal.items()]
        lines += [f"utility({a},{u})." for a, u in self.action_utility.items()]
        lines += [f"utility({v},{str(b).lower()},{u})." for (v, b), u in self.fact_utility.items()]
        return "\n".join(lines) + "\n"


def random_model(seed: int, max_variables: int = 4, max_actions: int = 4,
                 conditional: bool = False, derived: bool = False,
                 far_goal: bool = False) -> RandomModel:
    """A small random model; with ``conditional``, actions also get conditional
    effects, and with ``derived``, derived variables that preconditions,
    conditions and the goal may read (the model without them is the same).
    With ``far_goal`` the goal is made of literals of a reachable state
    farthest from the initial state (so that plans are longer)."""
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
    fact_utility = {(v, b): rng.randint(-3, 3) for v in variables for b in (True, False)
                    if rng.random() < 0.5}
    spec = RandomModel(variables, actions, pre, eff, init, goal, action_utility, fact_utility)
    if derived:
        _add_derived(spec, rng)
    if conditional:
        _add_conditional_effects(spec, rng)
    if far_goal:
        distances = spec.distances()
        far = max(distances.values())
        state = rng.choice(sorted((s for s, d in distances.items() if d == far), key=sorted))
        differ = [v for v in spec.variables if (v in state) != (v in spec.init)]
        chosen = rng.sample(differ, min(len(differ), rng.randint(1, 3))) or spec.variables[:1]
        spec.goal = {v: v in state for v in chosen}
    return spec


def _add_derived(spec: RandomModel, rng: random.Random) -> None:
    readable = list(spec.variables)
    for index in range(rng.randint(1, 2)):
        name = f"d{index}"
        spec.derived[name] = [
            {v: rng.random() < 0.5 for v in rng.sample(readable, rng.randint(0, min(2, len(readable))))}
            for _ in range(rng.randint(0 if rng.random() < 0.2 else 1, 2))]
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
            conditions = {v: rng.random() < 0.5
                          for v in rng.sample(readable, rng.randint(0, min(2, len(readable))))}
            sets = {v: rng.random() < 0.5
                    for v in rng.sample(spec.variables, rng.randint(1, min(2, len(spec.variables))))}
            effects.append((f"k{k}", conditions, sets))
        if effects:
            spec.ceff[a] = effects


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
            return ("geq", [fact() for _ in range(rng.randint(1, 3))],
                    [fact() for _ in range(rng.randint(1, 3))])
        element = (("action", rng.choice(spec.actions)) if rng.random() < 0.4
                   else ("fact", *fact()))
        return (kind, element)
    kind = rng.choice(["not", "and", "or", "imp"])
    if kind == "not":
        return ("not", random_formula(spec, rng, depth - 1))
    return (kind, random_formula(spec, rng, depth - 1), random_formula(spec, rng, depth - 1))


def plan_through(spec: RandomModel, rng: random.Random, walk: int) -> list[str] | None:
    """A plan: a random walk of at most ``walk`` applicable actions, then a
    shortest path to a goal state (None if no goal state is reachable from there)."""
    state, plan = spec.init, []
    for _ in range(walk):
        options = [a for a in spec.actions if spec.applicable(state, a)]
        if not options:
            break
        action = rng.choice(options)
        plan.append(action)
        state = spec.apply(state, action)
    parent = {state: None}
    queue = deque([state])
    while queue:
        current = queue.popleft()
        if spec.is_goal(current):
            tail = []
            while parent[current] is not None:
                current, action = parent[current]
                tail.append(action)
            return plan + tail[::-1]
        for action in spec.actions:
            if spec.applicable(current, action):
                succ = spec.apply(current, action)
                if succ not in parent:
                    parent[succ] = (current, action)
                    queue.append(succ)
    return None
