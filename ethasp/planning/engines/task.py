"""Explicit states of a search model: actions and derived variables over bit
masks, and the FF heuristic (the length of a relaxed plan that ignores delete
effects).

States are Python integers (bit i: variable i is true), so a state is hashed
and compared as one number.  Derived variables take the bits after the state
variables: a state keeps only its state variables, and the derived ones are
computed where a state is expanded (:meth:`Task.full`), group by group of
mutually dependent variables in the order of their dependencies, each from
false to its least fixpoint (the stratified semantics the encodings give
them, ``encodings/planning/transition.lp``).  In the relaxed task an axiom is
a relaxed action of no cost, and so is its negation: a derived variable
becomes false once each of its axioms has a literal whose opposite is
reached (every reachable state where it is false has such literals, so a
relaxed dead end stays a real one).

The greedy search (:mod:`ethasp.planning.engines.greedy`) and the explicit layers
of configurations (:mod:`ethasp.planning.engines.explicit`) search over it.
"""

from __future__ import annotations

from dataclasses import dataclass

import clingo

from ethasp.planning.engines import model_features
from ethasp.planning.engines.reachability import dependency_groups

# The step of a relaxed action that is an axiom (no action, no cost).
AXIOM = -1


def bit_masks(literals, index: dict[clingo.Symbol, int]) -> tuple[int, int]:
    """The bits of the variables that literals (variable, value) make true and
    those they make false."""
    pos = neg = 0
    for variable, value in literals:
        if value:
            pos |= 1 << index[variable]
        else:
            neg |= 1 << index[variable]
    return pos, neg


def path(task: Task, parents: dict, key) -> list[clingo.Symbol]:
    """The actions of a path found by a search over a task: ``parents`` maps
    a state (or configuration) to its parent and the number of the step that
    led there, None for the start."""
    actions = []
    while parents[key] is not None:
        key, number = parents[key]
        actions.append(task.steps[number].name)
    return actions[::-1]


@dataclass(frozen=True)
class Step:
    """An action over state bits: preconditions (bits that must be 1, bits that
    must be 0), unconditional effects (bits set, bits cleared; set wins), and
    conditional effects (condition masks and their set/clear masks)."""

    name: clingo.Symbol
    pos: int
    neg: int
    add: int
    delete: int
    conditional: tuple[tuple[int, int, int, int], ...]  # (pos, neg, add, delete)

    def applicable(self, state: int) -> bool:
        return state & self.pos == self.pos and not state & self.neg

    def apply(self, state: int) -> int:
        add, delete = self.add, self.delete
        for pos, neg, cadd, cdelete in self.conditional:
            if state & pos == pos and not state & neg:
                add |= cadd
                delete |= cdelete
        return (state & ~delete) | add


class Task:
    """A ground model as bit masks, and its FF heuristic.

    Relaxed facts are literals: ``2*i + 1`` for "variable i is true",
    ``2*i`` for "variable i is false"; a relaxed action (an action, or one
    conditional effect of it with its condition) needs its literals and adds
    its effects' literals.
    """

    def __init__(self, model):
        # The model's features (ethasp.planning.engines): an engine that
        # searches over the task refuses those it does not handle.
        self.features = model_features(model)
        self.variables = list(model.variables)
        self.derived = sorted(model.axioms, key=str)
        index = {v: i for i, v in enumerate(self.variables + self.derived)}
        self.index = index
        self.base = (1 << len(self.variables)) - 1  # the bits of the state variables
        # A goal utility (an HModel's): the utility of the state where every
        # variable is false, and what each true variable adds to it.
        self.goal_utility = model.goal_utility
        self.utility_base = sum(model.weights.get((v, False), 0) for v in self.variables)
        self.utility_gain = [
            (1 << i, model.weights.get((v, True), 0) - model.weights.get((v, False), 0))
            for i, v in enumerate(self.variables)
            if model.weights.get((v, True), 0) != model.weights.get((v, False), 0)
        ]
        self.steps: list[Step] = []
        # (needs, adds, step); step AXIOM for an axiom
        relaxed: list[tuple[tuple[int, ...], tuple[int, ...], int]] = []

        def literal(variable, value: bool) -> int:
            return 2 * index[variable] + (1 if value else 0)

        def masks(literals) -> tuple[int, int]:
            return bit_masks(literals, index)

        for number, action in enumerate(model.actions):
            pos, neg = masks(action.pre)
            add = delete = 0
            conditional = []
            needs = tuple(literal(v, b) for v, b in action.pre)
            plain_adds = []
            for effect in action.effects:
                bit = 1 << index[effect.variable]
                if effect.condition:
                    cpos, cneg = masks(effect.condition)
                    conditional.append(
                        (cpos, cneg, bit if effect.value else 0, 0 if effect.value else bit)
                    )
                    relaxed.append(
                        (
                            needs + tuple(literal(v, b) for v, b in effect.condition),
                            (literal(effect.variable, effect.value),),
                            number,
                        )
                    )
                else:
                    if effect.value:
                        add |= bit
                    else:
                        delete |= bit
                    plain_adds.append(literal(effect.variable, effect.value))
            relaxed.append((needs, tuple(plain_adds), number))
            self.steps.append(Step(action.name, pos, neg, add, delete, tuple(conditional)))
        # Derived variables by groups, dependencies first: (bit, axioms' masks).
        depends = {
            d: {v for body in bodies for v, _ in body if v in model.axioms}
            for d, bodies in model.axioms.items()
        }
        self.strata = [
            [(1 << index[d], [masks(body) for body in model.axioms[d]]) for d in group]
            for group in dependency_groups(depends)
        ]
        # Relaxed axioms: a derived variable becomes true by one of its axioms,
        # and false once every axiom has a literal whose opposite is reached
        # (an extra literal per axiom, numbered after the variables' ones).
        self.literals = 2 * len(index)
        for derived in self.derived:
            falsified = []
            for body in model.axioms[derived]:
                relaxed.append(
                    (tuple(literal(v, b) for v, b in body), (literal(derived, True),), AXIOM)
                )
                falsified.append(self.literals)
                for v, b in body:
                    relaxed.append(((literal(v, not b),), (self.literals,), AXIOM))
                self.literals += 1
            relaxed.append((tuple(falsified), (literal(derived, False),), AXIOM))
        self.relaxed = relaxed
        self.needs_count = [len(set(needs)) for needs, _, _ in relaxed]
        self.needed_by: list[list[int]] = [[] for _ in range(self.literals)]
        for r, (needs, _, _) in enumerate(relaxed):
            for lit in set(needs):
                self.needed_by[lit].append(r)
        self.free = [r for r, count in enumerate(self.needs_count) if count == 0]
        self.init = sum(1 << index[v] for v in model.init)
        self.goal = [literal(v, b) for v, b in model.goal]
        self.goal_pos, self.goal_neg = masks(model.goal)
        # Actions by a precondition bit, to find the applicable ones fast.
        self._unconditioned = [s for s in self.steps if not s.pos]
        self._by_bit: dict[int, list[Step]] = {}
        for s in self.steps:
            if s.pos:
                low = (s.pos & -s.pos).bit_length() - 1
                self._by_bit.setdefault(low, []).append(s)

    def full(self, state: int) -> int:
        """A state with the bits of its derived variables set (see the module
        docstring)."""
        for group in self.strata:
            changed = True
            while changed:
                changed = False
                for bit, bodies in group:
                    if state & bit:
                        continue
                    for pos, neg in bodies:
                        if state & pos == pos and not state & neg:
                            state |= bit
                            changed = True
                            break
        return state

    def utility(self, state: int) -> int:
        """u(s) of a state (its bits), from the model's utilities of facts."""
        return self.utility_base + sum(gain for bit, gain in self.utility_gain if state & bit)

    def is_goal(self, state: int) -> bool:
        if state & self.goal_pos != self.goal_pos or state & self.goal_neg:
            return False
        if self.goal_utility is None:
            return True
        return (
            self.utility_base + sum(gain for bit, gain in self.utility_gain if state & bit)
            >= self.goal_utility
        )

    def applicable(self, state: int) -> list[Step]:
        found = [s for s in self._unconditioned if not state & s.neg]
        bits = state
        while bits:
            low = bits & -bits
            for s in self._by_bit.get(low.bit_length() - 1, ()):
                if state & s.pos == s.pos and not state & s.neg:
                    found.append(s)
            bits ^= low
        return found

    def heuristic(self, state: int) -> tuple[int | None, set[int]]:
        """The FF estimate of a (full) state (None: the goal is relaxed
        unreachable) and the helpful actions: those of the relaxed plan
        applicable in the state."""
        reached = bytearray(self.literals)
        supporter = [-1] * self.literals
        frontier = []
        for i in range(len(self.index)):
            lit = 2 * i + ((state >> i) & 1)
            reached[lit] = 1
            frontier.append(lit)
        counts = list(self.needs_count)
        relaxed, needed_by = self.relaxed, self.needed_by
        open_goals = sum(1 for g in self.goal if not reached[g])
        goal_set = set(self.goal)
        pending = list(self.free)
        while open_goals:
            # One layer: the relaxed actions enabled so far add their literals.
            for lit in frontier:
                for r in needed_by[lit]:
                    counts[r] -= 1
                    if counts[r] == 0:
                        pending.append(r)
            if not pending:
                return None, set()
            frontier = []
            for r in pending:
                for lit in relaxed[r][1]:
                    if not reached[lit]:
                        reached[lit] = 1
                        supporter[lit] = r
                        frontier.append(lit)
                        if lit in goal_set:
                            open_goals -= 1
            pending = []
        # Extract a relaxed plan backwards from the goal.
        chosen: set[int] = set()
        agenda = [g for g in self.goal if supporter[g] >= 0]
        seen = set(agenda)
        while agenda:
            lit = agenda.pop()
            r = supporter[lit]
            if r < 0 or r in chosen:
                continue
            chosen.add(r)
            for need in relaxed[r][0]:
                if supporter[need] >= 0 and need not in seen:
                    seen.add(need)
                    agenda.append(need)
        actions = {relaxed[r][2] for r in chosen} - {AXIOM}
        helpful = {a for a in actions if self.steps[a].applicable(state)}
        return len(actions), helpful
