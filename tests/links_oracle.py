"""Brute-force E-links and D-links (Lindner and Olz, RO-MAN 2022), written from
their definitions, over the explicit semantics of tests/oracle.py.  Used only
by tests, as an oracle.

Steps are numbered 1..n; the state before step t is the state after steps
1..t-1 and their events.  Points order what happens: the action of step i at
2i, the events of step i at 2i+1, the goal after the last step and event.

* A step i sets l = (v, b) when an effect of its action that fires sets v to
  b and wins (true wins between effects of one step); an event of step i
  sets l when one of its effects that fires sets v to b and wins (the
  greatest key, true between equal keys).
* Producers of l for step t (or the goal): every setter of l at a point
  before it with no setter of the opposite of l in between; and ``init`` if
  l holds initially and no setter of the opposite comes before it.
* Step t needs the preconditions of its action and the conditions of its
  conditional effects that fire; the goal needs its literals.  A need on a
  derived variable d is a need on the literals that give d its value: for d
  true, the conditions of every axiom of d that holds; for d false, each
  condition that fails (with the value its variable has); derived variables
  among them expanded likewise.
* l is demanded at step t when it holds before t and, with l flipped in that
  state, some subsequence of the steps t+1..n (order kept) is executable and
  reaches the goal, the kept steps taking the slots t, t+1, ... and the events
  staying at their steps (every subsequence is tried).
* D-link (p, l, t): l demanded at t, p a producer of l for t.  E-link
  (p, l, c): c needs l, p a producer of l for c, and (p, l, c) no D-link.

Without events, conditional effects and derived variables this is exactly
plan-explainer's definition.  Links are tuples (from, variable, value, to)
as ``ethasp explain --json`` writes them: from is "init", a step number or
``("event", name, step)``; to is a step number or "goal".
"""

from __future__ import annotations

from itertools import combinations

from oracle import RandomModel


def _states(spec: RandomModel, plan: list[str]) -> tuple[list, list, int]:
    """The states after each step (index 0: initial) and after the action of
    each step (mids, index t for step t), up to the later of the plan's end and
    the last event."""
    end = max(len(plan), spec.last_event)
    states, mids = [spec.init], [None]
    for t in range(1, end + 1):
        mid = spec.apply(states[-1], plan[t - 1]) if t <= len(plan) else states[-1]
        mids.append(mid)
        states.append(spec.happen(mid, t))
    return states, mids, end


def _action_sets(spec: RandomModel, state, action: str) -> dict[str, bool]:
    effects = spec.firing(state, action)
    adds = {v for v, b in effects if b}
    return {v: b for v, b in effects if b or v not in adds}


def _event_sets(spec: RandomModel, mid, t: int) -> list[tuple[str, str, bool]]:
    """(event, variable, value) that events of step t set and win."""
    firing = []
    for event in spec.events:
        if event.step != t or not all((v in mid) == b for v, b in event.pre.items()):
            continue
        for key, conditions, sets in event.effects:
            if all((v in mid) == b for v, b in conditions.items()):
                for var, value in sets.items():
                    firing.append((event.name, key, var, value))
    winners = []
    for name, key, var, value in firing:
        beaten = any(
            var2 == var and value2 != value and (key2 > key or (key2 == key and value2))
            for _, key2, var2, value2 in firing
        )
        if not beaten:
            winners.append((name, var, value))
    return sorted(set(winners))


def _expand(spec: RandomModel, state, variable: str, value: bool) -> set[tuple[str, bool]]:
    """The state literals a need on (variable, value) in ``state`` is a need on."""
    if variable not in spec.derived:
        return {(variable, value)}
    full = spec.extended(state)
    found: set[tuple[str, bool]] = set()
    for axiom in spec.derived[variable]:
        holding = all((v in full) == b for v, b in axiom.items())
        for v, b in axiom.items():
            if value and holding:
                found |= _expand(spec, state, v, b)
            elif not value and (v in full) != b:
                found |= _expand(spec, state, v, v in full)
    return found


def _demanded(spec: RandomModel, states, plan: list[str], t: int, variable: str) -> bool:
    flipped = set(states[t - 1]) ^ {variable}
    rest = plan[t:]
    for size in range(len(rest) + 1):
        for kept in combinations(rest, size):
            state = frozenset(flipped)
            ok = True
            for slot in range(t, max(t - 1 + size, spec.last_event) + 1):
                action = kept[slot - t] if slot - t < size else None
                if action is not None and not spec.applicable(state, action):
                    ok = False
                    break
                state = spec.step(state, slot, action)
            if ok and spec.is_goal(state):
                return True
    return False


def e_and_d_links(spec: RandomModel, plan: list[str]) -> tuple[set, set]:
    """The E-links and the D-links of a plan (see the module docstring)."""
    states, mids, end = _states(spec, plan)
    setters = []  # (point, producer, variable, value)
    for i in range(1, len(plan) + 1):
        for v, b in _action_sets(spec, states[i - 1], plan[i - 1]).items():
            setters.append((2 * i, i, v, b))
    for t in range(1, end + 1):
        for name, v, b in _event_sets(spec, mids[t], t):
            setters.append((2 * t + 1, ("event", name, t), v, b))

    def producers(variable: str, value: bool, point: int) -> set:
        found = set()
        cut = max(
            (p for p, _, v, b in setters if v == variable and b != value and p < point),
            default=-1,
        )
        if cut < 0 and (variable in spec.init) == value:
            found.add("init")
        for p, who, v, b in setters:
            if v == variable and b == value and cut < p < point:
                found.add(who)
        return found

    needs = set()  # (consumer, point, variable, value)
    for t in range(1, len(plan) + 1):
        before, action = states[t - 1], plan[t - 1]
        wanted = list(spec.pre[action].items())
        for _, conditions, _ in spec.ceff.get(action, []):
            if spec.satisfies(before, conditions):
                wanted += list(conditions.items())
        for v, b in wanted:
            for w, c in _expand(spec, before, v, b):
                needs.add((t, 2 * t, w, c))
    for v, b in spec.goal.items():
        for w, c in _expand(spec, states[end], v, b):
            needs.add(("goal", 2 * end + 2, w, c))

    demanded = {
        (t, v, v in states[t - 1])
        for t in range(1, len(plan) + 1)
        for v in spec.variables
        if _demanded(spec, states, plan, t, v)
    }
    d_links = {(p, v, b, t) for t, v, b in demanded for p in producers(v, b, 2 * t)}
    e_links = {
        (p, v, b, c)
        for c, point, v, b in needs
        for p in producers(v, b, point)
        if (c, v, b) not in demanded
    }
    return e_links, d_links


def links_of_json(links: list[dict]) -> set:
    """``e_links`` or ``d_links`` of ``ethasp explain --json`` as oracle tuples."""
    found = set()
    for link in links:
        source = link["from"]
        if isinstance(source, dict):
            source = ("event", source["event"], source["step"])
        found.add((source, link["variable"], link["value"], link["to"]))
    return found
