"""Mutex groups: sets of state variables of which at most one is true in
every reachable state, found on the search model and proven there.

Planners search tasks over finite-domain variables: where at most one of the
variables ``at(truck,l1)``, ``at(truck,l2)``, ... holds at a time, one
variable with a value per location (and one for "none of them") replaces
them all, and a search over it explores fewer states (LM-cut, for one, gives
higher estimates on it).  Fast Downward's translator finds such groups on
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
    """What the proof reads of an action."""

    needs: frozenset  # variables its preconditions need true
    adds: frozenset  # variables it makes true unconditionally
    deletes: frozenset  # variables it makes false unconditionally (and not true)
    may_add: frozenset  # variables a conditional effect may make true


def _actions(model) -> list[_Action]:
    actions = []
    for action in model.actions:
        needs = frozenset(v for v, b in action.pre if b)
        adds = frozenset(e.variable for e in action.effects if e.value and not e.condition)
        deletes = frozenset(e.variable for e in action.effects if not e.value and not e.condition)
        may_add = frozenset(e.variable for e in action.effects if e.value and e.condition)
        actions.append(_Action(needs, adds, deletes - adds, may_add))
    return actions


class _Prover:
    """The proof of :func:`at_most_one`, with the actions indexed by the
    variables they (may) make true."""

    def __init__(self, model):
        self.init = model.init
        self.adders: dict[clingo.Symbol, list[_Action]] = defaultdict(list)
        self.conditional: set[clingo.Symbol] = set()
        for action in _actions(model):
            for variable in action.adds:
                self.adders[variable].append(action)
            self.conditional |= action.may_add

    def unbalanced(self, members: frozenset) -> list[_Action] | None:
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

    def proves(self, members: frozenset) -> bool:
        return self.unbalanced(members) == []


def at_most_one(model, members) -> bool:
    """Is at most one variable of ``members`` true in every state reachable
    by the actions of the search model ``model`` (see the module docstring)?"""
    require("the proof of mutex groups", FEATURES, model_features(model))
    return _Prover(model).proves(frozenset(members))


def _shape(variable: clingo.Symbol) -> tuple[str, tuple[clingo.Symbol, ...]] | None:
    if variable.type != clingo.SymbolType.Function or not variable.name:
        return None
    return variable.name, tuple(variable.arguments)


def _fixed(arguments: tuple, counted: int | None) -> tuple:
    return arguments if counted is None else arguments[:counted] + arguments[counted + 1 :]


def groups(model) -> list[list[clingo.Symbol]]:
    """Disjoint proven groups of two or more of the search model's variables,
    largest first, each sorted (see the module docstring)."""
    require("the proof of mutex groups", FEATURES, model_features(model))
    variables = [v for v in model.variables if _shape(v) is not None]
    # part -> fixed arguments -> variables
    index: dict[Part, dict[tuple, set]] = defaultdict(lambda: defaultdict(set))
    parts_of: dict[clingo.Symbol, list[tuple[Part, tuple]]] = {}
    for variable in variables:
        name, arguments = _shape(variable)  # type: ignore[misc]
        found = []
        for counted in (None, *range(len(arguments))):
            part = (name, len(arguments), counted)
            fixed = _fixed(arguments, counted)
            index[part][fixed].add(variable)
            found.append((part, fixed))
        parts_of[variable] = found
    prover = _Prover(model)
    proven: set[frozenset] = set()
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
        for fixed in sorted(keys, key=str):
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
    return cover(proven)


def cover(proven) -> list[list[clingo.Symbol]]:
    """Disjoint groups from proven ones: largest first (ties by their text),
    each without the variables of the groups taken before it, kept while two
    or more variables remain."""
    chosen: list[list[clingo.Symbol]] = []
    taken: set = set()
    ordered = sorted((sorted(group, key=str) for group in proven), key=lambda g: (-len(g), str(g)))
    while ordered:
        group = ordered.pop(0)
        rest = [v for v in group if v not in taken]
        if len(rest) < len(group):  # shrunk by an earlier group: back in line
            if len(rest) > 1:
                ordered.append(rest)
                ordered.sort(key=lambda g: (-len(g), str(g)))
            continue
        chosen.append(rest)
        taken.update(rest)
    return chosen
