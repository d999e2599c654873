"""Exact reachability of a planning model, with binary decision diagrams.

A proof engine beside the encodings: it reads the *ground* model (the atoms
of the vocabulary of ``encodings/planning/model.lp`` after clingo grounded
the model, :class:`GroundModel`) and computes, symbolically, breadth-first
layers of states: layer k holds the states whose shortest path from the
initial state has k actions.  When no new state appears, every reachable
state is known.  It answers what the searches of the encodings can only
bound:

* the best utility of a reachable state (and one such state), or of a
  reachable state within a set (goal states, states other than a given one);
* the first layer that meets a set of states: the length of a shortest path
  to it, so a plan search can start at that horizon;
* that no reachable state is in a set (``none``, proven).

Semantics (the paper's planning formalism, as ``encodings/planning/
transition.lp`` has it): an action is applicable when its preconditions
hold; its effects set their variables, every other variable keeps its
value.  A conditional effect (``ceff/4`` with conditions ``cpre/4``) fires
when its conditions hold in the state before the action; when effects that
fire set a variable both true and false, true wins (PDDL's delete-then-add).

States are sets of variables (true) over the model's variables.  In the
diagrams, each proven mutex group of the model (:mod:`ethasp.planning.engines.
groups`: at most one of its variables holds in every reachable state) is one
finite-domain variable written in binary, one diagram variable per bit (its
value: which member holds, or none), as symbolic planners encode the groups
of their tasks; every other variable is a diagram variable of its own
(:class:`Layout`).  A group has no member whose facts carry a utility (the
utility of a state is read off the diagrams one variable at a time).  The
diagrams come from the ``dd`` package: CUDD (``dd.cudd``) when its compiled
module is installed, else ``dd``'s own Python implementation.  The engine is
cross-checked against explicit breadth-first search by the tests
(``tests/test_reachability.py``).  A search stops, without a claim, when it
exceeds its node limit or the budget.
"""

from __future__ import annotations

import sys
import warnings
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field

import clingo

from ethasp.planning.budget import Budget
from ethasp.planning.engines import CONDITIONAL_EFFECTS, DERIVED_VARIABLES, model_features, require

# The model features this engine handles (ethasp.planning.engines).
FEATURES = frozenset({CONDITIONAL_EFFECTS, DERIVED_VARIABLES})


Literal = tuple[clingo.Symbol, bool]

# Live diagram nodes beyond which a search gives up (a proof engine of last
# resort must not eat the machine's memory).
DEFAULT_NODE_LIMIT = 4_000_000

# The most nodes whose best utility is remembered between queries.
UTILITY_MEMO_LIMIT = 2_000_000

# A cluster of actions shares one transition relation over the variables they
# write: one relational product per cluster instead of one image per action.
CLUSTER_VARIABLES = 16

# A cluster whose relation grows beyond this many nodes is split in two
# (satellite p5: 110 take_image actions over 16 variables made a relation of
# 1.1 million nodes, the layers gave up before their first image).
CLUSTER_NODES = 20_000

# On models whose cluster relations have at most this many nodes together,
# neighbouring clusters are merged while their joint relation stays within it
# (logistics p4: one relation for all 84 actions, 1981 nodes, layers 4.5x
# faster than with four clusters; on depots merging took longer than it saved).
MERGE_NODES = 5_000

# Rounds of the FORCE heuristic for the initial variable order; variables that
# more than one action in HUB_SHARE uses take no part in it.
FORCE_ROUNDS = 20
HUB_SHARE = 20


@dataclass(frozen=True)
class Effect:
    """An effect: ``variable`` becomes ``value`` if every literal of
    ``condition`` holds before the action (an empty condition always holds)."""

    variable: clingo.Symbol
    value: bool
    condition: tuple[Literal, ...] = ()


@dataclass(frozen=True)
class GroundAction:
    """An action with its preconditions and effects."""

    name: clingo.Symbol
    pre: tuple[Literal, ...]
    effects: tuple[Effect, ...]


@dataclass
class GroundModel:
    """A planning model after grounding: variables, actions, initial state,
    goal and the utilities of facts (``weight(fact(V,B),U)``)."""

    variables: list[clingo.Symbol]
    actions: list[GroundAction]
    init: frozenset[clingo.Symbol]
    goal: list[Literal]
    weights: dict[Literal, int] = field(default_factory=dict)
    # Derived variables: each holds in a state where all literals of one of its
    # axioms hold (the least fixpoint, stratified by negation).
    axioms: dict[clingo.Symbol, list[tuple[Literal, ...]]] = field(default_factory=dict)
    # An HModel's goal utility (goal_utility/1 of model.lp): goal states are
    # also worth at least this much (None: no such goal).
    goal_utility: int | None = None
    # Exogenous events (ethasp.planning.engines.explicit.GroundEvent): the engine of
    # this module knows none; ethasp.planning.engines.explicit serves models with them.
    events: list = field(default_factory=list)
    # The utility of the state variables a search model leaves out (they keep
    # one value in every reachable state; ethasp.planning.engines.layers).
    fixed_utility: int = 0

    def utility(self, state: Iterable[clingo.Symbol]) -> int:
        """u(s): the sum of the utilities of the facts of a state (true variables given)."""
        true = set(state)
        return sum(self.weights.get((v, v in true), 0) for v in self.variables)


@dataclass
class Best:
    """A best state of a set: its utility, its true variables, and the layer
    (shortest distance from the initial state) where it was found."""

    utility: int
    state: frozenset[clingo.Symbol]
    layer: int


def dependency_groups(depends: dict) -> list[list]:
    """The strongly connected groups of a dependency graph, dependencies first
    (Tarjan's algorithm, iterative)."""
    index: dict = {}
    low: dict = {}
    on_stack: set = set()
    stack: list = []
    groups: list[list] = []
    counter = 0
    for root in sorted(depends, key=str):
        if root in index:
            continue
        work = [(root, iter(sorted(depends[root], key=str)))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            advanced = False
            for child in children:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(depends[child], key=str))))
                    advanced = True
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            if advanced:
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                group = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    group.append(member)
                    if member == node:
                        break
                groups.append(group)
    return groups


def _order(
    model: GroundModel, index: dict[clingo.Symbol, int], rounds: int = FORCE_ROUNDS
) -> list[int]:
    """A variable order for the diagrams: variables that actions use together
    are placed near each other (the FORCE heuristic: each action pulls its
    variables towards their centre, for a few rounds)."""
    position = {i: float(i) for i in index.values()}

    def positions(literals) -> set[int]:
        return {index[v] for v, _ in literals if v in index}  # derived ones aside

    uses = []
    for action in model.actions:
        used = positions(action.pre) | {index[e.variable] for e in action.effects}
        used |= {i for e in action.effects for i in positions(e.condition)}
        uses.append(used)
    # Variables that most actions use (a robot's hands, a fuel level) would pull
    # everything together: they take no part in the pulling.
    degree: dict[int, int] = {}
    for used in uses:
        for i in used:
            degree[i] = degree.get(i, 0) + 1
    hub = max(4, len(uses) // HUB_SHARE)
    edges = [sorted(i for i in used if degree[i] <= hub) for used in uses]
    edges = [edge for edge in edges if len(edge) > 1]
    if not edges:
        return sorted(position)
    for _ in range(rounds):
        total = dict.fromkeys(position, 0.0)
        count = dict.fromkeys(position, 0)
        for edge in edges:
            centre = sum(position[i] for i in edge) / len(edge)
            for i in edge:
                total[i] += centre
                count[i] += 1
        moved = {i: (total[i] / count[i] if count[i] else position[i]) for i in position}
        ranked = sorted(position, key=lambda i: (moved[i], i))
        position = {i: float(rank) for rank, i in enumerate(ranked)}
    return sorted(position, key=position.__getitem__)


def _clusters(model: GroundModel, index: dict[clingo.Symbol, int]) -> list[list[GroundAction]]:
    """Actions in groups that share one transition relation: in the order of the
    variables they write, a group takes actions while they write at most
    :data:`CLUSTER_VARIABLES` variables together."""

    def written(action: GroundAction) -> list[int]:
        return sorted({index[e.variable] for e in action.effects})

    groups: list[list[GroundAction]] = []
    variables: set[int] = set()
    for action in sorted(model.actions, key=lambda a: (written(a), str(a.name))):
        own = set(written(action))
        if groups and len(variables | own) <= CLUSTER_VARIABLES:
            groups[-1].append(action)
            variables |= own
        else:
            groups.append([action])
            variables = own
    return groups


class Layout:
    """The diagram variables (bits) of a model's variables.

    Each mutex group (``groups``: disjoint lists of two or more variables, of
    which at most one holds in every reachable state) is one *unit*, a
    finite-domain variable written in binary: its member k (counted from 1)
    has the code k, code 0 says that no member holds, and its bits come most
    significant first.  Every other variable is a unit of its own, one bit
    (code 1: true).  Units take the places of their first variables in
    ``order`` (a list of variable numbers), their bits numbered in that
    order: the diagrams' order.
    """

    def __init__(self, variables: Sequence[clingo.Symbol], order: Sequence[int], groups=()):
        group_of = {v: number for number, group in enumerate(groups) for v in group}
        self.units: list[tuple[clingo.Symbol, ...]] = []  # unit -> its members
        self.bits: list[tuple[int, ...]] = []  # unit -> its bits
        self.owner: list[int] = []  # bit -> its unit
        self.place: dict[clingo.Symbol, tuple[int, int]] = {}  # variable -> (unit, code)
        placed: set[int] = set()
        width = 0
        for i in order:
            variable = variables[i]
            number = group_of.get(variable)
            if number is None:
                members: tuple[clingo.Symbol, ...] = (variable,)
            elif number in placed:
                continue
            else:
                placed.add(number)
                members = tuple(groups[number])
            unit = len(self.units)
            size = len(members).bit_length()  # codes 0 to len(members)
            self.units.append(members)
            self.bits.append(tuple(range(width, width + size)))
            self.owner += [unit] * size
            width += size
            for code, member in enumerate(members, start=1):
                self.place[member] = (unit, code)
        self.width = width

    def assignment(self, true, units: Iterable[int]) -> dict[int, bool] | None:
        """The bits of ``units`` in the state whose true variables are ``true``
        (None if it has two members of a group true: no reachable state)."""
        values: dict[int, bool] = {}
        for unit in units:
            held = [code for code, m in enumerate(self.units[unit], start=1) if m in true]
            if len(held) > 1:
                return None
            values.update(self.code_bits(unit, held[0] if held else 0))
        return values

    def code_bits(self, unit: int, code: int) -> dict[int, bool]:
        bits = self.bits[unit]
        last = len(bits) - 1
        return {b: bool(code >> (last - j) & 1) for j, b in enumerate(bits)}

    def state(self, value) -> frozenset[clingo.Symbol]:
        """The true variables of the state whose bit b has the value ``value(b)``."""
        true = []
        for unit, members in enumerate(self.units):
            code = 0
            for b in self.bits[unit]:
                code = 2 * code + bool(value(b))
            if 1 <= code <= len(members):
                true.append(members[code - 1])
        return frozenset(true)


def mutex_groups(model: GroundModel) -> list[list[clingo.Symbol]]:
    """The proven mutex groups of the model (:func:`ethasp.planning.engines.
    groups.groups`) less their members whose facts carry a utility (a subset
    of a group is a group), those of two or more variables kept."""
    from ethasp.planning.engines import groups as groups_module

    weighted = {variable for (variable, _), utility in model.weights.items() if utility}
    found = []
    for group in groups_module.groups(model):
        rest = [v for v in group if v not in weighted]
        if len(rest) > 1:
            found.append(rest)
    return found


def _backend():
    """The decision diagram module: ``dd.cudd`` (compiled), else ``dd.autoref``.

    dd imports networkx if it can, for drawing diagrams, which this module
    never does; that import alone took most of dd's start-up (about 0.13 s),
    so it is kept out while dd loads (a ``None`` entry in ``sys.modules``
    makes an import fail, and dd then goes without).
    """
    blocked = "networkx" not in sys.modules
    if blocked:
        sys.modules["networkx"] = None  # type: ignore[assignment]
    try:
        try:
            from dd import cudd

            return cudd, True
        except ImportError:  # the compiled module is optional
            from dd import autoref

            return autoref, False
    finally:
        if blocked and sys.modules.get("networkx", 0) is None:
            del sys.modules["networkx"]


class _Stopped(Exception):
    """A budget ran out while a transition relation was built."""


class _Split(Exception):
    """A cluster's transition relation grew beyond :data:`CLUSTER_NODES`."""


class _TooLarge(Exception):
    """A transition relation grew beyond the node limit while it was built."""


class Reachability:
    """Breadth-first layers of reachable states, computed symbolically.

    Call :meth:`expand` until it returns False (stopped: node limit or
    budget) or :attr:`complete` is True (every reachable state is in
    :attr:`layers`).  Queries read the layers computed so far and say how far
    they looked.
    """

    def __init__(
        self, model: GroundModel, node_limit: int = DEFAULT_NODE_LIMIT, grouped: bool = True
    ):
        require("exact reachability", FEATURES, model_features(model))
        self.model = model
        self.node_limit = node_limit
        module, compiled = _backend()
        self._compiled = compiled
        self._module = module
        self.bdd = module.BDD(memory_estimate=256 * 2**20) if compiled else module.BDD()
        self.index = {variable: i for i, variable in enumerate(model.variables)}
        # ``grouped``: mutex groups as finite-domain variables (else a bit per variable).
        groups = mutex_groups(model) if grouped else []
        self.layout = Layout(model.variables, _order(model, self.index), groups)
        names = []
        for b in range(self.layout.width):
            names += [f"x{b}", f"y{b}"]  # a bit's value before and after an action
        self.bdd.declare(*names)
        # The variables keep the order of _order: reordering them (sifting) cost
        # far more than it saved on the planning models measured.
        self.bdd.configure(reordering=False)
        self._members: dict = {}
        # The states whose groups have valid codes (every reachable one).
        self.valid = self.bdd.true
        for unit, members in enumerate(self.layout.units):
            if len(members) > 1:
                held = self._code(unit, 0)
                for member in members:
                    held |= self._member(member)
                self.valid &= held
        self._derived: dict = {}
        self._derive()
        self._groups = _clusters(model, self.index)
        # The clusters' transition relations, built by the first search that
        # needs them (:meth:`_build`, under its budget: one cluster after the
        # other, resumed where a budget stopped it).  Why they cannot be
        # built: more nodes than the limit (some orders of the variables make
        # a cluster's relation grow beyond any use; the engine then gives up
        # before its first layer, and the searches go on without it, as where
        # a layer grows too large).
        self._images: list = []
        self._built = False
        self.unbuilt = ""
        init = self.state(model.init)
        self.layers = [init]
        self._prefixes: list = []
        self._relations: dict = {}
        self._writes: dict = {}
        self._level_table = None
        # _max_utility's results by node, kept across calls (the sets asked
        # about share most of their nodes); each entry holds its node, so
        # that no key is freed and reused while it is remembered.
        self._utility_memo: dict[int, tuple] = {}
        self.reached = init
        self.back_layers: list = []
        self.back_reached = self.bdd.false
        self.back_complete = False
        self.complete = False
        self._next = None  # the next layer, computed by closed() but not yet added
        self.stopped = ""

    # -- diagrams of literals -----------------------------------------------------

    def _code(self, unit: int, code: int, after: bool = False):
        """The set of states where a unit has a code."""
        prefix = "y" if after else "x"
        bits = self.layout.code_bits(unit, code)
        return self.bdd.cube({f"{prefix}{b}": value for b, value in bits.items()})

    def _member(self, variable: clingo.Symbol, after: bool = False):
        """The set of states where a (non-derived) variable holds."""
        key = (variable, after)
        node = self._members.get(key)
        if node is None:
            node = self._members[key] = self._code(*self.layout.place[variable], after)
        return node

    def _literal(self, literal: Literal, after: bool = False):
        if literal[0] in self._derived:
            node = self._derived[literal[0]]
        else:
            node = self._member(literal[0], after)
        return node if literal[1] else ~node

    def _derive(self) -> None:
        """The set of states where each derived variable holds: strongly connected
        groups of derived variables in the order of their dependencies, each
        iterated from false to its least fixpoint."""
        axioms = self.model.axioms
        depends = {
            d: {v for body in bodies for v, _ in body if v in axioms}
            for d, bodies in axioms.items()
        }
        for group in dependency_groups(depends):
            for derived in group:
                self._derived[derived] = self.bdd.false
            changed = True
            while changed:
                changed = False
                for derived in group:
                    value = self.bdd.false
                    for body in axioms[derived]:
                        value |= self._cube(body)
                    if value != self._derived[derived]:
                        self._derived[derived] = value
                        changed = True

    def _cube(self, literals: Iterable[Literal], after: bool = False):
        node = self.bdd.true
        for literal in literals:
            node &= self._literal(literal, after)
        return node

    def condition(self, literals: Iterable[Literal]):
        """The set of states where every literal holds."""
        return self._cube(literals)

    def goal(self):
        """The goal states (worth at least the goal utility, if the model has one)."""
        states = self._cube(self.model.goal)
        if self.model.goal_utility is not None:
            states &= self.at_least(self.model.goal_utility)
        return states

    def at_least(self, bound: int):
        """The states worth at least ``bound``: a diagram over the weighted
        variables, built top down in the diagrams' order with the utility still
        needed (memoised; decided early where the variables below can no longer
        miss or reach it)."""
        by_level, _ = self._levels()
        weighted = [
            (f"x{entry[0]}", entry[1], entry[2])
            for entry in by_level
            if entry is not None and (entry[1] or entry[2])
        ]
        count = len(weighted)
        most, least = [0] * (count + 1), [0] * (count + 1)
        for i in range(count - 1, -1, -1):
            _, w_false, w_true = weighted[i]
            most[i] = most[i + 1] + max(w_false, w_true)
            least[i] = least[i + 1] + min(w_false, w_true)
        memo: dict[tuple[int, int], object] = {}

        def known(i: int, need: int):
            if need <= least[i]:
                return self.bdd.true
            if need > most[i]:
                return self.bdd.false
            return memo.get((i, need))

        # Iteratively (long orders would overflow Python's recursion).
        stack = [(0, bound)]
        while stack:
            i, need = stack[-1]
            if known(i, need) is not None:
                stack.pop()
                continue
            name, w_false, w_true = weighted[i]
            high, low = known(i + 1, need - w_true), known(i + 1, need - w_false)
            if high is None or low is None:
                if high is None:
                    stack.append((i + 1, need - w_true))
                if low is None:
                    stack.append((i + 1, need - w_false))
                continue
            stack.pop()
            memo[(i, need)] = self.bdd.ite(self.bdd.var(name), high, low)
        return known(0, bound)

    def state(self, true: Iterable[clingo.Symbol]):
        """The set holding one state (its true variables given; empty where two
        members of a group are true: no reachable state is)."""
        return self._values(set(true), range(len(self.layout.units)))

    def _values(self, true, units: Iterable[int], after: bool = False):
        """The cube giving the bits of ``units`` their values in a state (true
        variables given)."""
        values = self.layout.assignment(true, units)
        if values is None:
            return self.bdd.false
        prefix = "y" if after else "x"
        return self.bdd.cube({f"{prefix}{b}": value for b, value in values.items()})

    def _bit_values(self, true, bits: Iterable[int], after: bool = False):
        """The cube giving ``bits`` their values in a state (true variables given)."""
        owner = self.layout.owner
        return self._values(true, sorted({owner[b] for b in bits}), after)

    def pick(self, states) -> frozenset[clingo.Symbol]:
        """The true variables of one state of a (non-empty) set."""
        return next(self.states(states))

    def states(self, states) -> Iterator[frozenset[clingo.Symbol]]:
        """The true variables of every state of a set, one state after the other."""
        care = [f"x{b}" for b in range(self.layout.width)]
        for values in self.bdd.pick_iter(states, care_vars=care):
            yield self.layout.state(lambda b, values=values: values[f"x{b}"])

    def _written_units(self, actions: Iterable[GroundAction]) -> list[int]:
        place = self.layout.place
        return sorted({place[e.variable][0] for a in actions for e in a.effects})

    def _written_bits(self, actions: Iterable[GroundAction]) -> list[int]:
        bits = self.layout.bits
        return [b for unit in self._written_units(actions) for b in bits[unit]]

    # -- images -------------------------------------------------------------------

    def _after_values(self, action: GroundAction) -> dict[int, object]:
        """The value after the action of each bit it writes, over the values
        before.  A variable of its own is set where an effect setting it true
        fires, else kept where none setting it false fires.  A group takes the
        code of the member an effect makes true (at most one, unconditionally:
        the group's proof), else code 0 where an effect makes its member that
        holds false, else keeps its code."""
        bdd, layout = self.bdd, self.layout
        changes: dict[int, list] = {}
        for effect in action.effects:
            unit, code = layout.place[effect.variable]
            entry = changes.setdefault(unit, [bdd.false, bdd.false, None])
            fires = self._cube(effect.condition)
            if effect.value:
                entry[0] |= fires
                entry[2] = code
            else:
                entry[1] |= fires & self._member(effect.variable)
        after: dict[int, object] = {}
        for unit, (adds, deletes, added) in changes.items():
            bits = layout.bits[unit]
            if len(layout.units[unit]) == 1:
                (b,) = bits
                after[b] = adds | (bdd.var(f"x{b}") & ~deletes)
            elif added is not None:
                if adds != bdd.true:
                    raise ValueError(f"a conditional effect on the group of {layout.units[unit]}")
                for b, value in layout.code_bits(unit, added).items():
                    after[b] = bdd.true if value else bdd.false
            else:
                for b in bits:  # (code 0: every bit false)
                    after[b] = bdd.var(f"x{b}") & ~deletes
        return after

    def _build(self, budget: Budget | None) -> bool:
        """Build the transition relations not built yet; False (and
        :attr:`stopped` says why) if the budget or the node limit stopped it.
        A budget stops it between two actions: a later call goes on with the
        cluster it stopped in."""
        if self._built:
            return True
        if self.unbuilt:
            self.stopped = self.unbuilt
            return False
        while len(self._images) < len(self._groups):
            group = self._groups[len(self._images)]
            try:
                self._images.append(self._cluster(group, budget, split=True))
            except _Split:
                # Two clusters of half the actions each (split again if need be).
                half = len(group) // 2
                self._groups[len(self._images) : len(self._images) + 1] = [
                    group[:half],
                    group[half:],
                ]
            except _TooLarge:
                self._images = []
                self.unbuilt = (
                    f"more than {self.node_limit} diagram nodes in the transition relation"
                )
                self.stopped = self.unbuilt
                return False
            except _Stopped:
                assert budget is not None
                self.stopped = f"{budget.why_stopped()} while the transition relation was built"
                return False
        self._merge(MERGE_NODES)
        self._built = True
        return True

    def _cluster(
        self, actions: list[GroundAction], budget: Budget | None = None, split: bool = False
    ):
        """The transition relation of a cluster of actions over the bits they
        write (before: x, after: y), and what an image under it quantifies and
        renames.  ``split``: give up (:class:`_Split`) once the relation of two
        or more actions has more than :data:`CLUSTER_NODES` nodes."""
        bdd = self.bdd
        written = self._written_bits(actions)
        start = len(bdd)
        unchanged = {i: bdd.var(f"y{i}").equiv(bdd.var(f"x{i}")) for i in written}
        relation = bdd.false
        for action in actions:
            if budget is not None and budget.expired():
                raise _Stopped()
            after = self._after_values(action)
            step = self._cube(action.pre)
            for i in written:
                step &= bdd.var(f"y{i}").equiv(after[i]) if i in after else unchanged[i]
            relation |= step
            # (the manager's count of live nodes: a twentieth of the time of
            # nodes(), which counts dead ones not yet collected too, once an
            # action on models of hundreds of actions; the relation's own
            # size, a traversal, only once the manager has grown that much)
            grown = len(bdd)
            if (
                split
                and len(actions) > 1
                and grown - start > CLUSTER_NODES
                and len(relation) > CLUSTER_NODES
            ):
                raise _Split()
            if grown > self.node_limit:
                raise _TooLarge()
        qvars = [f"x{i}" for i in written]
        rename = {f"y{i}": f"x{i}" for i in written}
        return relation, qvars, rename

    def _merge(self, limit: int) -> None:
        """On models whose cluster relations have at most ``limit`` nodes together,
        merge neighbouring clusters while their joint relation has at most
        ``limit`` nodes: there fewer, larger products (often one relation for
        every action) cost less than many small ones."""
        if not self._images or sum(len(parts[0]) for parts in self._images) > limit:
            return  # large models: joining costs more than it saves (depots)
        groups, images = [self._groups[0]], [self._images[0]]
        for group, parts in zip(self._groups[1:], self._images[1:], strict=True):
            joint = self._joined(images[-1], parts)
            if len(joint[0]) <= limit:
                groups[-1] = groups[-1] + group
                images[-1] = joint
            else:
                groups.append(group)
                images.append(parts)
        self._groups, self._images = groups, images

    def _joined(self, first, second):
        """One relation for two clusters: each keeps the variables only the other writes."""

        def keep(parts, names):
            frame = self.bdd.true  # small: one equivalence per variable
            for x in names:
                frame &= self.bdd.var(f"y{x[1:]}").equiv(self.bdd.var(x))
            return parts[0] & frame

        written = sorted(set(first[1]) | set(second[1]), key=lambda x: int(x[1:]))
        relation = keep(first, [x for x in written if x not in first[1]]) | keep(
            second, [x for x in written if x not in second[1]]
        )
        return relation, written, {f"y{x[1:]}": x for x in written}

    def _renamed(self, renaming: dict[str, str], node):
        """``node`` with its variables renamed (an action that writes no
        variable renames none: dd warns on standard error of an empty
        renaming, so it is not asked for one)."""
        return self.bdd.let(renaming, node) if renaming else node

    def _image(self, states, parts):
        relation, qvars, rename = parts
        if self._compiled:
            moved = self._module.and_exists(states, relation, qvars)
        else:
            moved = self.bdd.exist(qvars, states & relation)
        return self._renamed(rename, moved)

    def nodes(self) -> int:
        """Diagram nodes of the manager (with CUDD: live ones and dead ones
        not yet collected)."""
        if self._compiled:
            with warnings.catch_warnings():  # dd warns of a changed unit of 'mem'
                warnings.simplefilter("ignore")
                return int(self.bdd.statistics()["n_nodes"])
        return len(self.bdd)

    def _next_layer(self, frontier, reached, image, budget: Budget | None):
        """The states one step from ``frontier`` by ``image`` (per cluster), less
        those ``reached``; None (and :attr:`stopped` says why) if the budget or
        the node limit stopped it."""
        if not self._build(budget):
            return None
        if budget is not None and budget.expired():
            self.stopped = budget.why_stopped()
            return None
        new = self.bdd.false
        for parts in self._images:
            new |= image(frontier, parts)
            # (after every image: one may take long, and a look at the clock is cheap;
            # the node count, which takes time of its own, once a layer)
            if budget is not None and budget.expired():
                self.stopped = budget.why_stopped()
                return None
        if self.nodes() > self.node_limit:
            self.stopped = f"more than {self.node_limit} diagram nodes"
            return None
        return new & ~reached

    def expand(self, budget: Budget | None = None) -> bool:
        """Compute the next layer; False (and :attr:`stopped` says why) if the
        budget or the node limit stopped it, True otherwise."""
        if self.complete:
            return True
        new, self._next = self._next, None
        if new is None:
            new = self._next_layer(self.layers[-1], self.reached, self._image, budget)
        if new is None:
            return False
        if new == self.bdd.false:
            self.complete = True
            return True
        self.reached |= new
        self.layers.append(new)
        return True

    def closed(self, budget: Budget | None = None) -> bool | None:
        """Are the states reached so far closed under every action (no state is
        one step beyond them)?  Then :attr:`complete` is set: every reachable
        state is known.  The next layer is computed to tell, kept for
        :meth:`expand` and not added: a search bounded by a horizon asks this
        at its last layer.  None if the budget or the node limit stopped it."""
        if self.complete:
            return True
        if self._next is None:
            self._next = self._next_layer(self.layers[-1], self.reached, self._image, budget)
            if self._next is None:
                return None
        if self._next == self.bdd.false:
            self._next = None
            self.complete = True
            return True
        return False

    # -- backward: pre-images from a set of states --------------------------------

    def _preimage(self, states, parts):
        """The states from which an action of a cluster leads into ``states``:
        the written variables renamed to their after-copies, then the
        relation's product over them (the others keep their values)."""
        relation, _qvars, rename = parts
        moved = self._renamed({x: y for y, x in rename.items()}, states)
        after = list(rename)
        if self._compiled:
            return self._module.and_exists(moved, relation, after)
        return self.bdd.exist(after, moved & relation)

    def start_backward(self, states) -> None:
        """Start backward layers from a set of states (the goal states, say):
        backward layer j holds the states whose shortest path into the set has
        j actions (states not reachable from the initial state included)."""
        states &= self.valid  # (the states of no reachable state's shape left out)
        self.back_layers = [states]
        self.back_reached = states
        self.back_complete = False

    def expand_backward(self, budget: Budget | None = None) -> bool:
        """Compute the next backward layer; as :meth:`expand`."""
        if self.back_complete:
            return True
        new = self._next_layer(self.back_layers[-1], self.back_reached, self._preimage, budget)
        if new is None:
            return False
        if new == self.bdd.false:
            self.back_complete = True
            return True
        self.back_reached |= new
        self.back_layers.append(new)
        return True

    def least_path(self, states, length: int) -> list[clingo.Symbol]:
        """The least path of ``length`` actions from the initial state into
        ``states`` (paths compared step by step, step 1 first, by their
        actions' terms), where ``length`` is the distance of ``states`` (the
        first layer that meets them): the sets of states from which the rest
        of such a path leads into ``states`` are computed backwards within the
        layers, then the least action into the next set is taken, step after
        step.  The same path whatever engine found the length first."""
        if length > 0:
            self._build(None)  # (built by the expansions that made the layers)
        return self._least_walk(self._within_layers(self.layers[length] & states, length))

    def least_path_meeting(self, forward: int, backward: int) -> list[clingo.Symbol]:
        """The least path of ``forward + backward`` actions from the initial
        state into the set the backward layers start from, where forward layer
        ``forward`` and backward layer ``backward`` are the first to meet (so
        that this is the length of a shortest path): as :meth:`least_path`,
        without the forward layers beyond ``forward``.  A state at step k of
        such a path is at distance k from the initial state and at distance
        ``forward + backward - k`` from the set: up to step ``forward`` the
        sets of states from which the rest leads into the meeting are
        computed backwards within the forward layers; after it, they are the
        backward layers themselves."""
        self._build(None)
        meeting = self.layers[forward] & self.back_layers[backward]
        targets = self._within_layers(meeting, forward)
        targets += [self.back_layers[backward - j] for j in range(1, backward + 1)]
        return self._least_walk(targets)

    def _within_layers(self, states, length: int) -> list:
        """For k up to ``length``: the states of forward layer k from which a
        path of ``length - k`` actions leads into ``states`` (of layer ``length``)."""
        targets = [self.bdd.false] * (length + 1)
        targets[length] = states
        for k in range(length - 1, -1, -1):
            before = self.bdd.false
            for parts in self._images:
                before |= self._preimage(targets[k + 1], parts)
            targets[k] = self.layers[k] & before
        return targets

    def _least_walk(self, targets: list) -> list[clingo.Symbol]:
        """From the initial state (in ``targets[0]``), the least action into
        ``targets[k]`` at each step k."""
        current = frozenset(self.model.init)
        actions: list[clingo.Symbol] = []
        for k in range(1, len(targets)):
            step = self._least_successor(current, targets[k])
            if step is None:
                raise RuntimeError(f"no successor of a state of layer {k - 1} in layer {k}")
            action, current = step
            actions.append(action)
        return actions

    def _least_successor(self, state: frozenset[clingo.Symbol], states):
        """The least action (by its term) that leads from ``state`` into
        ``states``, and the state it leads to; None if none does."""
        self._build(None)
        full = self.state(state)
        candidates: list[GroundAction] = []
        for group, parts in zip(self._groups, self._images, strict=True):
            if self._image(full, parts) & states != self.bdd.false:
                candidates += group
        for action in sorted(candidates, key=lambda candidate: candidate.name):
            relation, written = self._relation(action)
            qvars = [f"x{b}" for b in written]
            moved = self.bdd.exist(qvars, full & relation)
            renaming = {f"y{b}": f"x{b}" for b in written}
            after = self._renamed(renaming, moved) & states
            if after != self.bdd.false:
                return action.name, self.pick(after)
        return None

    def run(self, budget: Budget | None = None) -> bool:
        """Expand until every reachable state is known (True) or stopped (False)."""
        while not self.complete:
            if not self.expand(budget):
                return False
        return True

    # -- queries --------------------------------------------------------------------

    def path_to(self, state: frozenset[clingo.Symbol], layer: int) -> list[clingo.Symbol]:
        """The actions of a shortest path from the initial state to a state of
        ``layer`` (given by its true variables): backwards, layer by layer, an
        action and a predecessor in the layer before."""
        actions: list[clingo.Symbol] = []
        current = state
        for k in range(layer, 0, -1):
            step = self._predecessor(current, self.layers[k - 1])
            if step is None:
                raise RuntimeError(f"no predecessor of a state of layer {k} in layer {k - 1}")
            action, current = step
            actions.append(action)
        return actions[::-1]

    def _predecessor(self, state: frozenset[clingo.Symbol], layer):
        """An action and a state of ``layer`` from which the action leads to
        ``state``: first a cluster of actions that has one (one pre-image per
        cluster), then an action of it."""
        self._build(None)
        full = self.state(state)
        for group, (relation, qvars, rename) in zip(self._groups, self._images, strict=True):
            after = self._bit_values(state, [int(x[1:]) for x in qvars], after=True)
            before = self.bdd.exist(list(rename), relation & after)
            if before & self.bdd.exist(qvars, full) & layer == self.bdd.false:
                continue
            step = self._action_predecessor(state, full, group, layer)
            if step is not None:
                return step
        return None

    def _action_predecessor(
        self, state: frozenset[clingo.Symbol], full, actions: list[GroundAction], layer
    ):
        """An action of ``actions`` and a state of ``layer`` from which it leads
        to the state ``full``."""
        for action in actions:
            if not self._may_lead_to(action, state):
                continue
            relation, written = self._relation(action)
            after = self._bit_values(state, written, after=True)
            rest = self.bdd.exist([f"x{b}" for b in written], full)  # the bits it leaves alone
            before = self.bdd.exist([f"y{b}" for b in written], relation & after)
            before &= rest & layer
            if before != self.bdd.false:
                return action.name, self.pick(before)
        return None

    def _may_lead_to(self, action: GroundAction, state: frozenset[clingo.Symbol]) -> bool:
        """A necessary condition, on the state after it, for an action to lead to
        a state (a quick filter before the diagrams decide): its unconditional
        effects hold there unless another effect may undo them (true wins), and
        its preconditions on (state) variables it does not write hold there."""
        written = self._written(action)
        for variable, value in written["fixed"]:
            if (variable in state) != value:
                return False
        for variable, value in action.pre:
            if (
                variable in self.index
                and variable not in written["all"]
                and (variable in state) != value
            ):
                return False
        return True

    def _written(self, action: GroundAction) -> dict:
        """Per action: the variables it writes, and the values its effects surely set."""
        found = self._writes.get(action.name)
        if found is None:
            adds = {e.variable for e in action.effects if e.value}
            fixed = {
                (e.variable, e.value)
                for e in action.effects
                if not e.condition and (e.value or e.variable not in adds)
            }
            found = {"all": {e.variable for e in action.effects}, "fixed": fixed}
            self._writes[action.name] = found
        return found

    def _relation(self, action: GroundAction):
        """The transition relation of one action over the bits it writes, and those bits."""
        if action.name not in self._relations:
            written = self._written_bits([action])
            after = self._after_values(action)
            relation = self._cube(action.pre)
            for b in written:
                relation &= self.bdd.var(f"y{b}").equiv(after[b])
            self._relations[action.name] = (relation, written)
        return self._relations[action.name]

    def first_layer(self, states, start: int = 0) -> int | None:
        """The first computed layer (from ``start``) that meets the set, or None."""
        for k in range(start, len(self.layers)):
            if self.layers[k] & states != self.bdd.false:
                return k
        return None

    def prefix(self, k: int):
        """The states of layers 0..k (reached within k steps)."""
        if k >= len(self.layers) - 1:
            return self.reached
        while len(self._prefixes) <= k:
            j = len(self._prefixes)
            previous = self._prefixes[-1] if self._prefixes else self.bdd.false
            self._prefixes.append(previous | self.layers[j])
        return self._prefixes[k]

    def distance(self, state: frozenset[clingo.Symbol]) -> int | None:
        """The layer of a state (its shortest distance), if computed."""
        cube = self.state(state)
        for k, layer in enumerate(self.layers):
            if layer & cube != self.bdd.false:
                return k
        return None

    def best_of(self, states) -> Best | None:
        """A state of maximal utility in a set (of computed layers), at its distance."""
        if states == self.bdd.false:
            return None
        utility, true = self._max_utility(states)
        return Best(utility, true, self.distance(true))

    def best(self, within=None, start: int = 0) -> Best | None:
        """A state of maximal utility among the computed layers from ``start``
        (restricted to the set ``within``), from the earliest layer that has
        one; None if they have no such state."""
        found: Best | None = None
        for k in range(start, len(self.layers)):
            states = self.layers[k] if within is None else self.layers[k] & within
            if states == self.bdd.false:
                continue
            utility, true = self._max_utility(states)
            if found is None or utility > found.utility:
                found = Best(utility, true, k)
        return found

    def best_in_layer(self, k: int, within=None) -> Best | None:
        states = self.layers[k] if within is None else self.layers[k] & within
        if states == self.bdd.false:
            return None
        utility, true = self._max_utility(states)
        return Best(utility, true, k)

    def _levels(self):
        """Per level of the diagrams: (bit, w(false), w(true)) or None for an
        after-bit (the bit of a variable of its own: the utilities of its facts;
        a group's bits: 0, its members carry none); and free[l], the best
        utility of the bits at levels l and below, unconstrained.  (The order
        never changes: no reordering.)"""
        if self._level_table is None:
            bdd, weights, layout = self.bdd, self.model.weights, self.layout
            by_level: list[tuple[int, int, int] | None] = []
            for level in range(len(bdd.vars)):
                name = bdd.var_at_level(level)
                if name.startswith("x"):
                    b = int(name[1:])
                    members = layout.units[layout.owner[b]]
                    if len(members) == 1:
                        v = members[0]
                        by_level.append((b, weights.get((v, False), 0), weights.get((v, True), 0)))
                    else:
                        by_level.append((b, 0, 0))
                else:
                    by_level.append(None)
            free = [0] * (len(by_level) + 1)
            for level in range(len(by_level) - 1, -1, -1):
                entry = by_level[level]
                free[level] = free[level + 1] + (max(entry[1], entry[2]) if entry else 0)
            self._level_table = (by_level, free)
        return self._level_table

    def _max_utility(self, states) -> tuple[int, frozenset[clingo.Symbol]]:
        """A state of the (non-empty) set with maximal utility, by dynamic
        programming over the diagram (iterative: diagrams may be deep)."""
        bdd = self.bdd
        by_level, free = self._levels()
        levels = len(by_level)
        true_key, false_key = int(bdd.true), int(bdd.false)
        minus = float("-inf")
        # memo: node key -> (value, chosen value, child, child's level, node)
        memo = self._utility_memo
        if len(memo) > UTILITY_MEMO_LIMIT:
            memo.clear()
        memo[true_key] = (0.0, False, None, levels, bdd.true)
        memo[false_key] = (minus, False, None, levels, bdd.false)
        stack = [states]
        while stack:
            node = stack[-1]
            key = int(node)
            if key in memo:
                stack.pop()
                continue
            low, high = node.low, node.high
            if node.negated:
                low, high = ~low, ~high
            low_key, high_key = int(low), int(high)
            if low_key not in memo or high_key not in memo:
                if low_key not in memo:
                    stack.append(low)
                if high_key not in memo:
                    stack.append(high)
                continue
            stack.pop()
            level = node.level
            entry = by_level[level]
            low_level = levels if low_key in (true_key, false_key) else low.level
            high_level = levels if high_key in (true_key, false_key) else high.level
            w_false, w_true = (entry[1], entry[2]) if entry is not None else (0, 0)
            on_low = memo[low_key][0] + free[level + 1] - free[low_level] + w_false
            on_high = memo[high_key][0] + free[level + 1] - free[high_level] + w_true
            if on_high >= on_low:
                memo[key] = (on_high, True, high, high_level, node)
            else:
                memo[key] = (on_low, False, low, low_level, node)
        key = int(states)
        start_level = levels if key in (true_key, false_key) else states.level
        total = memo[key][0] + free[0] - free[start_level]
        # Read the state back: chosen values on the path, the better value elsewhere.
        chosen: dict[int, bool] = {}
        node = states
        while int(node) not in (true_key, false_key):
            _, value, child, _, _ = memo[int(node)]
            entry = by_level[node.level]
            if entry is not None:
                chosen[entry[0]] = value
            node = child
        best = {entry[0]: entry[2] > entry[1] for entry in by_level if entry is not None}
        return int(total), self.layout.state(lambda b: chosen.get(b, best[b]))


def _effect_order(effect: Effect) -> tuple:
    return effect.variable, effect.value, effect.condition


def from_atoms(
    variables: Sequence[clingo.Symbol],
    actions: Sequence[clingo.Symbol],
    pre: Iterable[tuple[clingo.Symbol, clingo.Symbol, bool]],
    eff: Iterable[tuple[clingo.Symbol, clingo.Symbol, bool]],
    ceff: Iterable[tuple[clingo.Symbol, clingo.Symbol, clingo.Symbol, bool]],
    cpre: Iterable[tuple[clingo.Symbol, clingo.Symbol, clingo.Symbol, bool]],
    init: Iterable[clingo.Symbol],
    goal: Iterable[Literal],
    weights: dict[Literal, int],
    axiom_pre: Iterable[tuple[clingo.Symbol, clingo.Symbol, clingo.Symbol, bool]] = (),
    axioms: Iterable[tuple[clingo.Symbol, clingo.Symbol]] = (),
    derived: Iterable[clingo.Symbol] = (),
    goal_utility: int | None = None,
    events: Sequence = (),
) -> GroundModel:
    """A ground model from the atoms of the model vocabulary (actions, then
    ``pre(A,V,B)``, ``eff(A,V,B)``, ``ceff(A,K,V,B)``, ``cpre(A,K,V,B)``, ...,
    ``axiom_pre(D,K,V,B)`` and ``axiom(D,K)`` of derived variables)."""
    pres: dict[clingo.Symbol, list[Literal]] = {a: [] for a in actions}
    effects: dict[clingo.Symbol, list[Effect]] = {a: [] for a in actions}
    for action, variable, value in pre:
        if action in pres:
            pres[action].append((variable, value))
    for action, variable, value in eff:
        if action in effects:
            effects[action].append(Effect(variable, value))
    conditions: dict[tuple[clingo.Symbol, clingo.Symbol], list[Literal]] = {}
    for action, key, variable, value in cpre:
        conditions.setdefault((action, key), []).append((variable, value))
    for action, key, variable, value in ceff:
        if action in effects:
            condition = tuple(sorted(conditions.get((action, key), [])))
            effects[action].append(Effect(variable, value, condition))
    # Sorted for a fixed order (clingo's own order of symbols: fast to compare).
    ground = [
        GroundAction(a, tuple(sorted(pres[a])), tuple(sorted(effects[a], key=_effect_order)))
        for a in actions
    ]
    bodies: dict[tuple[clingo.Symbol, clingo.Symbol], list[Literal]] = {
        (name, key): [] for name, key in axioms
    }
    for name, key, variable, value in axiom_pre:
        bodies.setdefault((name, key), []).append((variable, value))
    # A derived variable without axioms never holds.
    derived_axioms: dict[clingo.Symbol, list[tuple[Literal, ...]]] = {d: [] for d in derived}
    for (name, _), body in sorted(bodies.items(), key=str):
        derived_axioms.setdefault(name, []).append(tuple(sorted(body, key=str)))
    return GroundModel(
        list(variables),
        ground,
        frozenset(init),
        list(goal),
        dict(weights),
        derived_axioms,
        goal_utility,
        list(events),
    )
