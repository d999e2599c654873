"""Brute-force reference semantics of questions and step-by-step explanations,
written from their definitions (docs/questions.md) over the explicit states of
tests/oracle.py's RandomModel (its public methods only: applicable, apply,
firing, run, is_goal, is_plan, extended, distances, permissible, ...).

Constraint terms are tuples named as in encodings/questions/questions.lp:
("used", a), ("unused", a), ("before", b, a), ("at", a, t), ("not_at", a, t),
("within", a, t1, t2), ("not_within", a, t1, t2), ("ends", f, value),
("fact_at", f, value, t), ("at_most", n).

A step is simulated in one function, :func:`step_state`, and the states a
plan passes are listed by :func:`trajectory`; both follow RandomModel's
actions (applicable, apply).  For models with exogenous events they are the
two places to switch to the model's own simulation of steps and events (and
the search of :func:`shortest_meeting` would count its steps up to the last
event as well).
"""

from __future__ import annotations

from collections import deque

from oracle import RandomModel


def step_state(spec: RandomModel, state: frozenset, step: int, action: str) -> frozenset:
    """The state after step ``step`` of a plan, its action applicable in ``state``."""
    return spec.apply(state, action)


def trajectory(spec: RandomModel, plan: list[str]) -> list[frozenset] | None:
    """The states of a plan: the initial state, then the state after each step
    (its final state last); None if some step is not applicable."""
    state, states = spec.init, [spec.init]
    for step, action in enumerate(plan, start=1):
        if not spec.applicable(state, action):
            return None
        state = step_state(spec, state, step, action)
        states.append(state)
    return states


def value(spec: RandomModel, state: frozenset, variable: str) -> bool:
    """A state or derived variable's value in a state."""
    return variable in (spec.extended(state) if spec.derived else state)


def meets(spec: RandomModel, plan: list[str], term: tuple) -> bool:
    """Does the plan (applicable) meet the constraint?"""
    states = trajectory(spec, plan)
    kind, n = term[0], len(plan)
    if kind == "used":
        return term[1] in plan
    if kind == "unused":
        return term[1] not in plan
    if kind == "before":
        first, then = term[1], term[2]
        return any(x == first and then in plan[i + 1:] for i, x in enumerate(plan))
    if kind in ("at", "not_at"):
        there = term[2] <= n and plan[term[2] - 1] == term[1]
        return there if kind == "at" else not there
    if kind in ("within", "not_within"):
        inside = any(plan[t - 1] == term[1] for t in range(term[2], min(term[3], n) + 1))
        return inside if kind == "within" else not inside
    if kind == "ends":
        return value(spec, states[-1], term[1]) == term[2]
    if kind == "fact_at":
        state = states[term[3]] if term[3] <= n else states[-1]
        return value(spec, state, term[1]) == term[2]
    if kind == "at_most":
        return n <= term[1]
    raise ValueError(term)


def _clock(terms) -> int:
    """The largest step a set of constraints names, plus one (the step count
    is remembered up to it), and one past an at_most bound."""
    bound = 0
    for term in terms:
        if term[0] in ("at", "not_at"):
            bound = max(bound, term[2])
        elif term[0] in ("within", "not_within"):
            bound = max(bound, term[3])
        elif term[0] == "fact_at":
            bound = max(bound, term[3])
        elif term[0] == "at_most":
            bound = max(bound, term[1])
    return bound + 1


def shortest_meeting(spec: RandomModel, terms, principles=()) -> int | None:
    """The length of a shortest plan that meets every constraint and is
    permissible under every principle (deontology, do-no-harm,
    utilitarianism), or None if there is none.

    Breadth-first search over nodes (state, step count up to the largest step
    the constraints name, what the constraints remember: the actions used,
    the actions at named steps, the values after named steps, the bad facts
    some action had as an effect); the nodes are finitely many, so None means
    no such plan of any length.
    """
    terms = list(terms)
    principles = set(principles)
    clock = _clock(terms)
    limit = min((t[1] for t in terms if t[0] == "at_most"), default=None)
    watched = {t[1] for t in terms if t[0] in ("used", "unused", "at", "not_at", "within",
                                              "not_within")}
    watched |= {a for t in terms if t[0] == "before" for a in t[1:]}
    named_steps = {t[3] for t in terms if t[0] == "fact_at"}
    best = spec.best_reachable_utility() if "utilitarianism" in principles else None

    def accepted(node) -> bool:
        state, count, memory, harms = node
        if not spec.is_goal(state):
            return False
        if best is not None and spec.state_utility(state) < best:
            return False
        if "do-no-harm" in principles and any((v in state) == b for v, b in harms):
            return False
        return all(_met(spec, term, state, count, memory) for term in terms)

    start = (spec.init, 0, frozenset(), frozenset())
    depth = {start: 0}
    queue = deque([start])
    while queue:
        node = queue.popleft()
        if accepted(node):
            return depth[node]
        state, count, memory, harms = node
        step = count + 1              # the step taken next (exact while below the clock)
        if limit is not None and depth[node] + 1 > limit:
            continue
        for action in spec.actions:
            if not spec.applicable(state, action):
                continue
            if "deontology" in principles and spec.bad_action(action):
                continue
            after = step_state(spec, state, step, action)
            remember = set(memory)
            if action in watched:
                remember.add(("used", action))
                for other in watched:
                    if ("used", other) in memory:
                        remember.add(("before", other, action))
            if step < clock:
                remember.add(("at", action, step))
                for t in named_steps:
                    if t == step:
                        remember.add(("after", step, frozenset(spec.extended(after)
                                                               if spec.derived else after)))
            effected = harms | {(v, b) for v, b in spec.firing(state, action)
                                if spec.bad_fact(v, b)} if "do-no-harm" in principles else harms
            succ = (after, min(step, clock), frozenset(remember), effected)
            if succ not in depth:
                depth[succ] = depth[node] + 1
                queue.append(succ)
    return None


def _met(spec: RandomModel, term: tuple, state: frozenset, count: int, memory) -> bool:
    """A constraint at the end of a plan of ``count`` steps (``count`` exact
    below the clock) that ends in ``state`` and remembers ``memory``."""
    kind = term[0]
    if kind == "used":
        return ("used", term[1]) in memory
    if kind == "unused":
        return ("used", term[1]) not in memory
    if kind == "before":
        return ("before", term[1], term[2]) in memory
    if kind in ("at", "not_at"):
        there = ("at", term[1], term[2]) in memory
        return there if kind == "at" else not there
    if kind in ("within", "not_within"):
        inside = any(("at", term[1], t) in memory for t in range(term[2], term[3] + 1))
        return inside if kind == "within" else not inside
    if kind == "ends":
        return value(spec, state, term[1]) == term[2]
    if kind == "fact_at":
        if count >= term[3]:
            after = next(s for tag, t, s in (m for m in memory if m[0] == "after")
                         if t == term[3])
            return (term[1] in after) == term[2]
        return value(spec, state, term[1]) == term[2]
    if kind == "at_most":
        return count <= term[1]
    raise ValueError(term)


# -- step-by-step explanations ---------------------------------------------------------

def _sets(spec: RandomModel, state: frozenset, action: str) -> dict[str, bool]:
    """What the action sets in a state: its firing effects, true winning."""
    result: dict[str, bool] = {}
    for variable, setting in spec.firing(state, action):
        result[variable] = result.get(variable, False) or setting
    return result


def _support(spec: RandomModel, state: frozenset, variable: str, wanted: bool,
             seen=None) -> set[tuple[str, bool]]:
    """The state variables (with values) that give a derived variable its value
    in a state: for true, the conditions of every axiom that holds; for false,
    every condition that fails; derived conditions expanded in turn."""
    seen = set() if seen is None else seen
    if variable not in spec.derived:
        return {(variable, wanted)}
    if (variable, wanted) in seen:
        return set()
    seen.add((variable, wanted))
    full = spec.extended(state)
    result: set[tuple[str, bool]] = set()
    for axiom in spec.derived[variable]:
        holds = all((v in full) == b for v, b in axiom.items())
        for v, b in axiom.items():
            if wanted and holds:
                result |= _support(spec, state, v, b, seen)
            elif not wanted and (v in full) != b:
                result |= _support(spec, state, v, not b, seen)
    return result


def links(spec: RandomModel, plan: list[str]) -> set[tuple]:
    """The causal links of a plan, as (provider step, consumer, variable,
    value, kind, via): consumer a step number or "goal", kind precondition,
    condition (the effect's name) or goal, via the derived variable or None."""
    states = trajectory(spec, plan)
    setters = [_sets(spec, states[i], action) for i, action in enumerate(plan)]

    def provider(variable: str, before: int) -> int | None:
        for step in range(before - 1, 0, -1):
            if variable in setters[step - 1]:
                return step
        return None

    found = set()

    def need(consumer, before: int, state, variable, wanted, kind):
        via = variable if variable in spec.derived else None
        for v, b in _support(spec, state, variable, wanted):
            step = provider(v, before)
            if step is not None and setters[step - 1][v] == b:
                found.add((step, consumer, v, b, kind, via))

    for j, action in enumerate(plan, start=1):
        before = states[j - 1]
        for variable, wanted in spec.pre[action].items():
            need(j, j, before, variable, wanted, "precondition")
        for name, conditions, _ in spec.ceff.get(action, []):
            if spec.satisfies(before, conditions):
                for variable, wanted in conditions.items():
                    need(j, j, before, variable, wanted, ("condition", name))
    for variable, wanted in spec.goal.items():
        need("goal", len(plan) + 1, states[-1], variable, wanted, "goal")
    return found


def removable(spec: RandomModel, plan: list[str]) -> set[int]:
    """The steps without which the plan is still a plan."""
    return {step for step in range(1, len(plan) + 1)
            if spec.is_plan(plan[:step - 1] + plan[step:])}
