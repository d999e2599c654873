"""Mutex groups: sets of state variables of which at most one is true in
every reachable state, found on the search model and proven there.

Planners search tasks over finite-domain variables: where at most one of the
variables ``at(truck,l1)``, ``at(truck,l2)``, ... holds at a time, one
variable with a value per location (and one for "none of them") replaces
them all, and a search over it stores and compares smaller states (Fast
Downward on satellite p7: the same states expanded, in three quarters of the
time).  Fast Downward's translator finds such groups on
the lifted PDDL task; here they are found on the ground search model
(:func:`ethasp.planning.engines.layers.search_model`), so that every model
gets them, whatever its source, and each group is proven before it is used.

**Candidates** come from the shape of the variables' names, as the
translator's invariants do: a *part* is a name and arity with one argument
*counted* (or none), and a candidate is a set of parts; a ground group of a
candidate is the set of variables that agree on their other, *fixed*,
arguments (``at(T,L)`` with ``L`` counted: one group per ``T``).  Every part
alone is a candidate; a candidate whose group fails because an action adds a
variable of it without deleting one is extended by the parts of that
action's deleted preconditions that have the same fixed arguments
(``at(D,L)`` and ``driving(D,T)``: a driver is at one place or in one truck).

**Proof** (:func:`at_most_one`), by induction over the applicable actions
from the initial state: at most one variable of the group holds initially;
and every action that makes one true (unconditionally; a conditional effect
that may make one true fails the group) makes exactly one true and needs
another of the group true before, which it makes false (it *moves* the
group's one true variable).  So no action raises the number of true
variables of the group above one.  Only the search model's actions count:
the usable ones (those that relaxed reachability does not rule out); events
are not modelled here (the tasks that read groups have none).

The groups used (:func:`groups`) cover each variable at most once: proven
groups of two or more variables, largest first (a part of a proven group is
a proven group).  Everything is ordered by the symbols' text, so the same
model gives the same groups on every run.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass

import clingo

from ethasp.planning.engines import (
    CONDITIONAL_EFFECTS,
    DERIVED_VARIABLES,
    model_features,
    require,
)

# The model features the proof handles (ethasp.planning.engines): a
# conditional effect that may make a member true fails its group; derived
# variables are no members.  Exogenous events are not modelled.
FEATURES = frozenset({CONDITIONAL_EFFECTS, DERIVED_VARIABLES})
# A part: (name, arity, the counted argument's position or None).
Part = tuple[str, int, int | None]
# Candidates tried beyond the single parts (a fixed amount of work: the same
# groups on every run, at any load).
MAX_EXTENSIONS = 2_000
# Parts of a candidate at most.
MAX_PARTS = 4


@dataclass(frozen=True)
class _Action:
    """What the proof reads of an action (variables by their number)."""

    needs: frozenset[int]  # variables its preconditions need true
    adds: frozenset[int]  # variables it makes true unconditionally
    deletes: frozenset[int]  # variables it makes false unconditionally (and not true)
    may_add: frozenset[int]  # variables a conditional effect may make true


class _Prover:
    """The proof of :func:`at_most_one`, over the variables by their number
    (each symbol is hashed once: clingo's symbols hash slowly), with the
    actions indexed by the variables they make true."""

    def __init__(self, model):
        self.number: dict[clingo.Symbol, int] = {v: i for i, v in enumerate(model.variables)}
        self.adders: dict[int, list[_Action]] = defaultdict(list)
        self.conditional: set[int] = set()
        for action in model.actions:
            needs = frozenset(self._number(v) for v, b in action.pre if b)
            adds, deletes, may_add = set(), set(), set()
            for effect in action.effects:
                number = self._number(effect.variable)
                if effect.condition:
                    if effect.value:
                        may_add.add(number)
                elif effect.value:
                    adds.add(number)
                else:
                    deletes.add(number)
            moved = _Action(needs, frozenset(adds), frozenset(deletes - adds), frozenset(may_add))
            for number in adds:
                self.adders[number].append(moved)
            self.conditional |= may_add
        self.init = frozenset(self.number[v] for v in model.init if v in self.number)

    def _number(self, variable: clingo.Symbol) -> int:
        number = self.number.get(variable)
        if number is None:  # (not a variable of the search model: a derived one)
            number = self.number[variable] = len(self.number)
        return number

    def unbalanced(self, members: frozenset[int]) -> list[_Action] | None:
        """The actions that make a member true without moving the group's
        true variable (None where the group fails otherwise: more than one
        member true initially, a conditional effect that may make one true,
        an action that makes two true)."""
        if len(members & self.init) > 1 or members & self.conditional:
            return None
        failing = []
        for variable in members:
            for action in self.adders[variable]:
                if len(action.adds & members) > 1:
                    return None
                if not (action.needs & action.deletes & members):
                    failing.append(action)
        return failing


def at_most_one(model, members) -> bool:
    """Is at most one variable of ``members`` true in every state reachable
    by the actions of the search model ``model`` (see the module docstring)?"""
    require("the proof of mutex groups", FEATURES, model_features(model))
    prover = _Prover(model)
    return prover.unbalanced(frozenset(prover._number(v) for v in members)) == []


def _fixed(arguments: tuple, counted: int | None) -> tuple:
    return arguments if counted is None else arguments[:counted] + arguments[counted + 1 :]


def groups(model, names=None) -> list[list]:
    """Disjoint proven groups of two or more of the search model's variables,
    largest first, each sorted (see the module docstring).  ``names``: the
    variables' symbols where the model's variables are their numbers (the
    candidates come from the names)."""
    require("the proof of mutex groups", FEATURES, model_features(model))
    prover = _Prover(model)
    names = list(model.variables) if names is None else list(names)
    # part -> fixed arguments (their text) -> variables
    index: dict[Part, dict[tuple, set[int]]] = defaultdict(lambda: defaultdict(set))
    parts_of: dict[int, list[tuple[Part, tuple]]] = {}
    for number, variable in enumerate(names):
        if variable.type != clingo.SymbolType.Function or not variable.name:
            continue
        arguments = tuple(str(argument) for argument in variable.arguments)
        found = []
        for counted in (None, *range(len(arguments))):
            part = (variable.name, len(arguments), counted)
            fixed = _fixed(arguments, counted)
            index[part][fixed].add(number)
            found.append((part, fixed))
        parts_of[number] = found
    proven: set[frozenset[int]] = set()
    tried: set[tuple[Part, ...]] = set()
    queue: list[tuple[Part, ...]] = sorted(((part,) for part in index), key=str)
    extensions = 0
    while queue:
        candidate = queue.pop(0)
        if candidate in tried:
            continue
        tried.add(candidate)
        keys = set().union(*(index[part].keys() for part in candidate))
        wanted: set[tuple[Part, ...]] = set()
        for fixed in sorted(keys):
            members = frozenset().union(*(index[part].get(fixed, ()) for part in candidate))
            failing = prover.unbalanced(members)
            if failing == []:
                if len(members) > 1:
                    proven.add(members)
                continue
            if failing is None or len(candidate) >= MAX_PARTS:
                continue
            # Extend by the parts of the deleted preconditions with these fixed arguments.
            for action in failing:
                for variable in action.needs & action.deletes:
                    for part, other in parts_of.get(variable, ()):
                        if other == fixed and part not in candidate:
                            wanted.add(tuple(sorted((*candidate, part), key=str)))
        for extended in sorted(wanted, key=str):
            if extended not in tried and extensions < MAX_EXTENSIONS:
                extensions += 1
                queue.append(extended)
    chosen = cover(proven, names)
    return [[model.variables[v] for v in group] for group in chosen]


def cover(proven, names) -> list[list[int]]:
    """Disjoint groups from proven ones (of variables by their number; their
    ``names``): largest first (ties by their text), each without the
    variables of the groups taken before it, kept while two or more variables
    remain."""

    def text(v: int) -> str:
        return str(names[v])

    def key(group: list[int]) -> tuple:
        return (-len(group), [text(v) for v in group])

    chosen: list[list[int]] = []
    taken: set[int] = set()
    ordered = sorted((sorted(group, key=text) for group in proven), key=key)
    while ordered:
        group = ordered.pop(0)
        rest = [v for v in group if v not in taken]
        if len(rest) < len(group):  # shrunk by an earlier group: back in line
            if len(rest) > 1:
                ordered.append(rest)
                ordered.sort(key=key)
            continue
        chosen.append(rest)
        taken.update(rest)
    return chosen
