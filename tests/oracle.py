"""Brute-force reference semantics, written from the paper's definitions.

Explicit states (frozensets of true variables), breadth-first search, and a
generator of small random models.  Used only by tests, as an oracle.
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

    # -- semantics ------------------------------------------------------------

    def applicable(self, state: frozenset, action: str) -> bool:
        return all((var in state) == value for var, value in self.pre[action].items())

    def apply(self, state: frozenset, action: str) -> frozenset:
        result = set(state)
        for var, value in self.eff[action].items():
            if value:
                result.add(var)
            else:
                result.discard(var)
        return frozenset(result)

    def is_goal(self, state: frozenset) -> bool:
        return all((var in state) == value for var, value in self.goal.items())

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

    # -- ASP ------------------------------------------------------------------

    def to_asp(self) -> str:
        lines = [f"variable({v})." for v in self.variables]
        lines += [f"action({a})." for a in self.actions]
        for a in self.actions:
            lines += [f"pre({a},{v},{str(b).lower()})." for v, b in self.pre[a].items()]
            lines += [f"eff({a},{v},{str(b).lower()})." for v, b in self.eff[a].items()]
        lines += [f"init({v})." for v in sorted(self.init)]
        lines += [f"goal({v},{str(b).lower()})." for v, b in self.goal.items()]
        lines += [f"utility({a},{u})." for a, u in self.action_utility.items()]
        lines += [f"utility({v},{str(b).lower()},{u})." for (v, b), u in self.fact_utility.items()]
        return "\n".join(lines) + "\n"


def random_model(seed: int, max_variables: int = 4, max_actions: int = 4) -> RandomModel:
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
    return RandomModel(variables, actions, pre, eff, init, goal, action_utility, fact_utility)
