"""Brute-force reference semantics of questions and step-by-step explanations,
written from their definitions (docs/questions.md) over the explicit states of
tests/oracle.py's RandomModel (its public methods only: applicable, step,
trajectory, successor, finish, firing, is_goal, is_plan, extended, caused,
permissible, ...).

Constraint terms are tuples named as in encodings/questions/questions.lp:
("used", a), ("unused", a), ("before", b, a), ("at", a, t), ("not_at", a, t),
("within", a, t1, t2), ("not_within", a, t1, t2), ("ends", f, value),
("fact_at", f, value, t), ("at_most", n).

Steps are the model's own (RandomModel.step: the action, then the exogenous
events due at that step), and a plan's states are RandomModel.trajectory:
the initial state, then the state after each step, up to the later of the
plan's end and the last event (idle steps after the plan).  So "the state
after step T" is the T-th state for a plan of at least T steps and the final
state (after every event) otherwise; ends(F,B) and the goal read the final
state.
"""

from __future__ import annotations

from collections import deque

from oracle import RandomModel


def trajectory(spec: RandomModel, plan: list[str]) -> list[frozenset] | None:
    """The states of a plan: the initial state, then the state after each step,
    events included, up to the later of the plan's end and the last event
    (its final state last); None if some step is not applicable."""
    return spec.trajectory(plan)


def after_step(states: list[frozenset], plan: list[str], step: int) -> frozenset:
    """The state after step ``step`` of a plan whose states are ``states``:
    after its action and the events of that step, or the final state for a
    plan of fewer steps."""
    return states[step] if step <= len(plan) else states[-1]


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
        # An X at some step, and no Y at a step before the first X.
        first, then = term[1], term[2]
        return first in plan and then not in plan[: plan.index(first)]
    if kind in ("at", "not_at"):
        there = term[2] <= n and plan[term[2] - 1] == term[1]
        return there if kind == "at" else not there
    if kind in ("within", "not_within"):
        inside = any(plan[t - 1] == term[1] for t in range(term[2], min(term[3], n) + 1))
        return inside if kind == "within" else not inside
    if kind == "ends":
        return value(spec, states[-1], term[1]) == term[2]
    if kind == "fact_at":
        return value(spec, after_step(states, plan, term[3]), term[1]) == term[2]
    if kind == "at_most":
        return n <= term[1]
    raise ValueError(term)


def _largest_step(terms) -> int:
    """The largest step a set of constraints names (an at_most bound counts)."""
    bound = 0
    for term in terms:
        if term[0] in ("at", "not_at"):
            bound = max(bound, term[2])
        elif term[0] in ("within", "not_within") or term[0] == "fact_at":
            bound = max(bound, term[3])
        elif term[0] == "at_most":
            bound = max(bound, term[1])
    return bound


def shortest_meeting(spec: RandomModel, terms, principles=()) -> int | None:
    """The length of a shortest plan that meets every constraint and is
    permissible under every principle (deontology, do-no-harm,
    utilitarianism), or None if there is none.

    Breadth-first search over nodes (state, time, memory, produced): the
    time counts the steps up to the later of the last event and one past
    the largest step the constraints name (exact below it); the memory holds
    what the constraints remember (the actions used, whether a Y came before
    the first X of a before(X,Y), the actions at named steps, the states
    after named steps); produced holds,
    for do-no-harm, the bad facts an action of the plan set (they held after
    it) that have held ever since (as tests/oracle.py's search).  A node is
    accepted on the plan's final state, after the events still due.  The
    nodes are finitely many, so None means no such plan of any length.
    """
    terms = list(terms)
    principles = set(principles)
    clock = _largest_step(terms) + 1
    top = max(clock, spec.last_event)
    limit = min((t[1] for t in terms if t[0] == "at_most"), default=None)
    watched = {
        t[1] for t in terms if t[0] in ("used", "unused", "at", "not_at", "within", "not_within")
    }
    watched |= {a for t in terms if t[0] == "before" for a in t[1:]}
    named_steps = {t[3] for t in terms if t[0] == "fact_at"}
    best = spec.best_reachable_utility() if "utilitarianism" in principles else None
    harmless = "do-no-harm" in principles

    def carry(state, produced):
        return frozenset(fact for fact in produced if (fact[0] in state) == fact[1])

    def accepted(node) -> bool:
        state, time, memory, produced = node
        for later in range(time + 1, spec.last_event + 1):
            state = spec.step(state, later, None)
            produced = carry(state, produced)
        if not spec.is_goal(state):
            return False
        if best is not None and spec.state_utility(state) < best:
            return False
        if harmless and produced:
            return False
        return all(_met(spec, term, state, time, memory) for term in terms)

    start = (spec.init, 0, frozenset(), frozenset())
    depth = {start: 0}
    queue = deque([start])
    while queue:
        node = queue.popleft()
        if accepted(node):
            return depth[node]
        state, time, memory, produced = node
        step = time + 1  # the step taken next (exact while below the top)
        if limit is not None and depth[node] + 1 > limit:
            continue
        for action in spec.actions:
            if not spec.applicable(state, action):
                continue
            if "deontology" in principles and spec.bad_action(action):
                continue
            after = spec.step(state, step, action)
            remember = set(memory)
            if action in watched:
                remember.add(("used", action))
            for _, first, then in (t for t in terms if t[0] == "before"):
                if action == then != first and ("used", first) not in memory:
                    remember.add(("early", first, then))  # a Y before the first X
            if step < clock:
                remember.add(("at", action, step))
                if step in named_steps:
                    remember.add(("after", step, spec.extended(after) if spec.derived else after))
            if harmless:
                acted = spec.apply(state, action)
                fired = {
                    (v, b)
                    for v, b in spec.firing(state, action)
                    if spec.bad_fact(v, b) and (v in acted) == b
                }
                produced_after = carry(after, produced | fired)
            else:
                produced_after = produced
            succ = (after, min(step, top), frozenset(remember), produced_after)
            if succ not in depth:
                depth[succ] = depth[node] + 1
                queue.append(succ)
    return None


def _met(spec: RandomModel, term: tuple, final: frozenset, time: int, memory) -> bool:
    """A constraint at the end of a plan of ``time`` steps (exact below the
    clock) whose final state is ``final`` and which remembers ``memory``."""
    kind = term[0]
    if kind == "used":
        return ("used", term[1]) in memory
    if kind == "unused":
        return ("used", term[1]) not in memory
    if kind == "before":
        return ("used", term[1]) in memory and ("early", term[1], term[2]) not in memory
    if kind in ("at", "not_at"):
        there = ("at", term[1], term[2]) in memory
        return there if kind == "at" else not there
    if kind in ("within", "not_within"):
        inside = any(("at", term[1], t) in memory for t in range(term[2], term[3] + 1))
        return inside if kind == "within" else not inside
    if kind == "ends":
        return value(spec, final, term[1]) == term[2]
    if kind == "fact_at":
        if time >= term[3]:
            after = next(s for tag, t, s in (m for m in memory if m[0] == "after") if t == term[3])
            return (term[1] in after) == term[2]
        return value(spec, final, term[1]) == term[2]
    if kind == "at_most":
        return time <= term[1]
    raise ValueError(term)


# -- step-by-step explanations ---------------------------------------------------------


def _sets(spec: RandomModel, state: frozenset, action: str) -> dict[str, bool]:
    """What the action sets in a state: its firing effects, true winning."""
    result: dict[str, bool] = {}
    for variable, setting in spec.firing(state, action):
        result[variable] = result.get(variable, False) or setting
    return result


def _support(
    spec: RandomModel, state: frozenset, variable: str, wanted: bool, seen=None
) -> set[tuple[str, bool]]:
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


def _event_sets(spec: RandomModel, state: frozenset, step: int) -> dict[str, dict[str, bool]]:
    """What each event of a step sets, from the state after that step's action:
    the events that happen (preconditions hold), each with the variables that
    one of its firing effects sets and wins on: no firing effect of that step
    (of any event) sets the variable the other way with a greater key, or
    with an equal key to true (so the greatest key wins, true between equal
    keys, as RandomModel.happen; an effect overridden by one that is in turn
    overridden sets nothing)."""
    happening = [
        event
        for event in spec.events
        if event.step == step and all((v in state) == b for v, b in event.pre.items())
    ]
    firing = {
        event.name: [
            (key, sets)
            for key, conditions, sets in event.effects
            if all((v in state) == b for v, b in conditions.items())
        ]
        for event in happening
    }
    every = [
        (key, variable, setting)
        for effects in firing.values()
        for key, sets in effects
        for variable, setting in sets.items()
    ]

    def wins(key: int, variable: str, setting: bool) -> bool:
        return not any(
            v == variable and b != setting and (k > key or (k == key and b)) for k, v, b in every
        )

    return {
        name: {
            variable: setting
            for key, sets in effects
            for variable, setting in sets.items()
            if wins(key, variable, setting)
        }
        for name, effects in firing.items()
    }


def _event_needs(spec: RandomModel, state: frozenset, step: int) -> dict[str, dict[str, bool]]:
    """The needs of the events of a step that happen, read in the state after
    that step's action: their preconditions and the conditions of their
    effects that fire."""
    needs = {}
    for event in spec.events:
        if event.step != step or not all((v in state) == b for v, b in event.pre.items()):
            continue
        needs[event.name] = dict(event.pre)
        for _, conditions, _ in event.effects:
            if all((v in state) == b for v, b in conditions.items()):
                needs[event.name].update(conditions)
    return needs


def links(spec: RandomModel, plan: list[str]) -> set[tuple]:
    """The causal links of a plan, as (provider, consumer, variable, value,
    kind, via): the provider a step number or ("event", step, name), the
    consumer a step number, ("event", step, name) or "goal"; kind
    precondition, condition (the effect's name), event or goal; via the
    derived variable or None.

    Things happen at points in order: the action of step T (point 2T), then
    the events of step T (point 2T+1), up to the later of the plan's end and
    the last event (N); the goal reads the final state (point 2N+2).  A need
    is linked from the last provider of the variable (either value) before
    the consumer's point, when that provider set the value needed."""
    states = trajectory(spec, plan)
    end = len(states) - 1
    providers: list[tuple[int, object, dict[str, bool]]] = []
    consumers: list[tuple[int, object, frozenset, dict[str, bool], object]] = []
    for j in range(1, end + 1):
        before = states[j - 1]
        mid = before
        if j <= len(plan):
            action = plan[j - 1]
            providers.append((2 * j, j, _sets(spec, before, action)))
            consumers.append((2 * j, j, before, spec.pre[action], "precondition"))
            for name, conditions, _ in spec.ceff.get(action, []):
                if spec.satisfies(before, conditions):
                    consumers.append((2 * j, j, before, conditions, ("condition", name)))
            mid = spec.apply(before, action)
        for name, sets in _event_sets(spec, mid, j).items():
            providers.append((2 * j + 1, ("event", j, name), sets))
        for name, needs in _event_needs(spec, mid, j).items():
            consumers.append((2 * j + 1, ("event", j, name), mid, needs, "event"))
    consumers.append((2 * end + 2, "goal", states[-1], spec.goal, "goal"))

    found = set()
    for point, consumer, state, needs, kind in consumers:
        for variable, wanted in needs.items():
            via = variable if variable in spec.derived else None
            for v, b in _support(spec, state, variable, wanted):
                earlier = [p for p in providers if p[0] < point and v in p[2]]
                if not earlier:
                    continue
                last = max(p[0] for p in earlier)
                for _, provider, sets in earlier:
                    if _ == last and sets[v] == b:
                        found.add((provider, consumer, v, b, kind, via))
    return found


def serving(found: set[tuple]) -> set:
    """The nodes (steps, events) from which links lead to the goal."""
    result = {link[0] for link in found if link[1] == "goal"}
    while True:
        more = {link[0] for link in found if link[1] in result} - result
        if not more:
            return result
        result |= more


def causes(spec: RandomModel, plan: list[str]) -> dict[int, set[tuple[str, bool, int]]]:
    """The valued facts each step causes: the step's action sets the fact (its
    winning effects) and the plan causes it (Caused); with their utility."""
    states = trajectory(spec, plan)
    caused = spec.caused(plan)
    result = {}
    for step, action in enumerate(plan, start=1):
        result[step] = {
            (v, b, spec.fact_utility[(v, b)])
            for v, b in _sets(spec, states[step - 1], action).items()
            if (v, b) in caused and spec.fact_utility.get((v, b), 0) != 0
        }
    return result


def removable(spec: RandomModel, plan: list[str]) -> set[int]:
    """The steps without which the plan is still a plan."""
    return {
        step for step in range(1, len(plan) + 1) if spec.is_plan(plan[: step - 1] + plan[step:])
    }
