"""Exact layers beside a plan search: lower bounds on the length, and plans.

A plan search over the encodings (:mod:`ethasp.planning.search`) refutes
one horizon after the other; near the length of a shortest plan each
refutation costs more than the one before.  Exact breadth-first layers of
the reachable states (:class:`ethasp.planning.engines.reachability.Reachability`)
prove the same bounds symbolically: no goal state in layers 0..k proves that
every plan has more than k steps, and the first layer with a goal state is
the length of a shortest plan, with a shortest path to read off.  By
default (:data:`BIDIRECTIONAL`) the layers grow from both ends, forward from
the initial state and backward from the goal states, and no meeting of
forward layers 0..i with backward layers 0..j proves that every plan has
more than i + j steps.  Diagrams do well where the encodings do badly (many
interchangeable objects, many independent actions) and badly where they do
well, so :class:`Layers` computes them in a process (or thread) of its own
while the solver works on the horizons, and the search takes whichever
proof comes first.

Models with exogenous events get explicit layers of configurations instead
(:mod:`ethasp.planning.engines.explicit`): the diagrams know no events.

The layers are computed over the *search model*: the actions that relaxed
reachability finds usable (``usable/1`` of ``encodings/planning/
relaxed.lp``) and the state variables that may take both values
(``reachable/2``).  Every other state variable keeps its initial value in
every reachable state, so conditions on it are decided once: preconditions
of usable actions on them hold (that is what usable means), and an effect
on one sets the value it has.  The engine reads the ground atoms; it does
not decide what a plan is: a plan read off the layers is checked by its
trace (``encodings/planning/trace.lp``) before anyone sees it.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import clingo

from ethasp.execution import spawner
from ethasp.planning.budget import Budget
from ethasp.planning.engines import (
    ALL_FEATURES,
    ground_features,
    handles,
    model_features,
    require,
)

if TYPE_CHECKING:  # imported in the thread that computes the layers
    from ethasp.planning.engines.reachability import GroundModel

# The model features this engine handles (ethasp.planning.engines): the
# diagrams' (ethasp.planning.engines.reachability), and the others with the
# explicit layers (ethasp.planning.engines.explicit).
FEATURES = ALL_FEATURES


# Live diagram nodes beyond which the layers give up (the search goes on
# without them).
NODE_LIMIT = 500_000
# Bidirectional layers (forward from the initial state, backward from the goal
# states, the smaller frontier expanded first, the least plan read off
# through both where they meet).  With a diagram variable per state variable
# the backward layers held states that no reachable state resembles and grew
# far faster than the forward ones (depots p2: 1.4 million nodes at backward
# layer 2); with each mutex group one variable in binary they hold no state
# with two members of a group true, and meet early: satellite p4 (17 steps) in
# 0.3 s where forward layers pass 500,000 nodes at layer 13, driverlog p4 (16
# steps) in 0.16 s where forward layers take 1.8 s.
BIDIRECTIONAL = True


def _value(symbol: clingo.Symbol) -> bool:
    return symbol.name == "true"


# The ground atoms the search model is made of.
MODEL_ATOMS = (
    ("variable", 1),
    ("action", 1),
    ("pre", 3),
    ("eff", 3),
    ("ceff", 4),
    ("cpre", 4),
    ("derived", 1),
    ("axiom", 2),
    ("axiom_pre", 4),
    ("init", 1),
    ("goal", 2),
    ("goal_utility", 1),
    ("event_at", 2),
    ("event_pre", 3),
    ("event_effect", 4),
    ("event_condition", 4),
)


class Atoms:
    """The ground atoms of a planner that the search model needs, read at once
    (the planner's control serves one thread at a time)."""

    def __init__(self, planner, weights: bool = False):
        self.usable = planner.search_atoms("usable", 1)
        self.reachable = planner.search_atoms("reachable", 2)
        self.model = {name: planner.get(name, arity) for name, arity in MODEL_ATOMS}
        # The utilities of facts, for a goal utility (an HModel's) or where
        # asked for (``weights``: searches for states of a utility).
        wanted = weights or self.model["goal_utility"]
        self.model["weight"] = planner.get("weight", 2) if wanted else []

    def get(self, name: str, arity: int) -> list[clingo.Symbol]:
        return self.model[name]

    @property
    def features(self) -> frozenset[str]:
        """The features of the ground model (as the planner's)."""
        return ground_features(self)


def search_model(atoms: Atoms) -> GroundModel:
    """The search model of a planner's ground atoms (see the module docstring)."""
    from ethasp.planning.engines.reachability import from_atoms

    # (A symbol's arguments are read once each: every read crosses into clingo.)
    usable = {atom.arguments[0] for atom in atoms.usable}
    reachable = set()
    for atom in atoms.reachable:
        variable, value = atom.arguments
        reachable.add((variable, _value(value)))
    derived = [atom.arguments[0] for atom in atoms.get("derived", 1)]
    variables = [atom.arguments[0] for atom in atoms.get("variable", 1)]
    fluents = [v for v in variables if (v, True) in reachable and (v, False) in reachable]
    moving = set(fluents) | set(derived)
    # The value every other state variable has in every reachable state.
    fixed = {}
    for variable in variables:
        if variable not in moving:
            for value in (True, False):
                if (variable, value) in reachable:
                    fixed[variable] = value

    def keeps(variable, value) -> bool | None:
        """True: the literal holds everywhere; False: nowhere; None: it depends."""
        if variable in moving:
            return None
        return fixed.get(variable) == value

    pre, eff, ceff, cpre, axiom_pre = [], [], [], [], []
    for atom in atoms.get("pre", 3):
        action, variable, value = atom.arguments
        if action in usable and keeps(variable, _value(value)) is None:
            pre.append((action, variable, _value(value)))
    for atom in atoms.get("eff", 3):
        action, variable, value = atom.arguments
        if action in usable and variable in moving:
            eff.append((action, variable, _value(value)))
    never: set = set()  # conditional effects whose condition never holds
    for atom in atoms.get("cpre", 4):
        action, key, variable, value = atom.arguments
        if action not in usable:
            continue
        holds = keeps(variable, _value(value))
        if holds is None:
            cpre.append((action, key, variable, _value(value)))
        elif not holds:
            never.add((action, key))
    for atom in atoms.get("ceff", 4):
        action, key, variable, value = atom.arguments
        if action in usable and variable in moving and (action, key) not in never:
            ceff.append((action, key, variable, _value(value)))
    impossible: set = set()  # axioms with a condition that never holds
    for atom in atoms.get("axiom_pre", 4):
        name, key, variable, value = atom.arguments
        holds = keeps(variable, _value(value))
        if holds is None:
            axiom_pre.append((name, key, variable, _value(value)))
        elif not holds:
            impossible.add((name, key))
    axioms = [
        (atom.arguments[0], atom.arguments[1])
        for atom in atoms.get("axiom", 2)
        if (atom.arguments[0], atom.arguments[1]) not in impossible
    ]
    axiom_pre = [entry for entry in axiom_pre if (entry[0], entry[1]) not in impossible]
    goal = [
        (atom.arguments[0], _value(atom.arguments[1]))
        for atom in atoms.get("goal", 2)
        if keeps(atom.arguments[0], _value(atom.arguments[1])) is None
    ]
    init = [atom.arguments[0] for atom in atoms.get("init", 1) if atom.arguments[0] in moving]
    actions = [atom.arguments[0] for atom in atoms.get("action", 1) if atom.arguments[0] in usable]
    # A goal utility: the fixed variables' utilities are a constant; the
    # fluents' utilities stay in the search model.
    bounds = [atom.arguments[0].number for atom in atoms.get("goal_utility", 1)]
    weights, fixed_utility = {}, 0
    for atom in atoms.get("weight", 2):
        element, utility = atom.arguments
        if element.name != "fact":
            continue
        variable, value = element.arguments[0], _value(element.arguments[1])
        if variable in moving:
            weights[(variable, value)] = utility.number
        elif fixed.get(variable) == value:
            fixed_utility += utility.number
    goal_utility = max(bounds) - fixed_utility if bounds else None
    ground = from_atoms(
        fluents,
        actions,
        pre,
        eff,
        ceff,
        cpre,
        init,
        goal,
        weights,
        axiom_pre,
        axioms,
        derived,
        goal_utility,
        _events(atoms, keeps, moving),
    )
    ground.fixed_utility = fixed_utility
    return ground


def _events(atoms, keeps=lambda variable, value: None, moving=None) -> list:
    """The exogenous events of a ground model (``atoms``: anything with the
    planner's ``get``); for the search model, conditions on variables that
    never change decided (``keeps``), effects on them dropped (relaxed
    reachability counts what events may set, so an effect on a variable not
    ``moving`` keeps its value).  ``moving`` None: every variable."""
    steps: dict = {}
    for atom in atoms.get("event_at", 2):
        if atom.arguments[1].type == clingo.SymbolType.Number:
            steps.setdefault(atom.arguments[0], []).append(atom.arguments[1].number)
    if not steps:
        return []
    from ethasp.planning.engines.explicit import GroundEvent  # (models with events only)

    never: set = set()  # events whose precondition never holds
    pre: dict = {}
    for atom in atoms.get("event_pre", 3):
        event, variable, value = atom.arguments
        holds = keeps(variable, _value(value))
        if holds is None:
            pre.setdefault(event, []).append((variable, _value(value)))
        elif not holds:
            never.add(event)
    conditions: dict = {}
    dead: set = set()  # effects whose condition never holds
    for atom in atoms.get("event_condition", 4):
        event, key, variable, value = atom.arguments
        holds = keeps(variable, _value(value))
        if holds is None:
            conditions.setdefault((event, key), []).append((variable, _value(value)))
        elif not holds:
            dead.add((event, key))
    effects: dict = {}
    for atom in atoms.get("event_effect", 4):
        event, key, variable, value = atom.arguments
        if (moving is None or variable in moving) and (event, key) not in dead:
            effects.setdefault(event, []).append(
                (
                    key,
                    tuple(sorted(conditions.get((event, key), []), key=str)),
                    variable,
                    _value(value),
                )
            )
    return [
        GroundEvent(
            event,
            tuple(sorted(set(times))),
            tuple(sorted(pre.get(event, []), key=str)),
            tuple(sorted(effects.get(event, []), key=str)),
        )
        for event, times in sorted(steps.items(), key=str)
        if event not in never
    ]


def _import_diagrams() -> None:
    """Import the diagram package without the optional graph library it would
    load on the way (a fifth of a second that plan search does not need)."""
    if "dd" in sys.modules or "networkx" in sys.modules:
        return
    sys.modules["networkx"] = None  # makes `import networkx` fail: dd goes without
    try:
        import dd.cudd  # noqa: F401
    except ImportError:
        pass
    finally:
        del sys.modules["networkx"]


@dataclass(frozen=True)
class Status:
    """What the layers have proven so far.

    ``bound``: every plan has at least this many steps; ``goal_layer``: the
    length of a shortest plan, once known; ``plan``: the actions of a
    shortest plan, once read off; ``complete``: no goal state is
    reachable (every reachable state is known and none is a goal state; or,
    bidirectionally, every state from which a goal state is reachable is
    known and the initial state is not one); ``stopped``: why the layers gave up
    (empty while they work or after they finished).  An engine for cheapest
    plans (:mod:`ethasp.planning.engines.cheapest`) also tells ``cost_bound``:
    every plan costs at least this much; and with its ``plan``, a cheapest
    one, its ``cost``."""

    bound: int = 0
    goal_layer: int | None = None
    plan: tuple[clingo.Symbol, ...] | None = None
    complete: bool = False
    stopped: str = ""
    cost_bound: int = 0
    cost: int | None = None

    @property
    def working(self) -> bool:
        return not (self.plan is not None or self.complete or self.stopped)


def can_fork() -> bool:
    """Whether the layers run in a child process (:mod:`ethasp.execution.spawner`)."""
    return sys.platform.startswith("linux")


class Layers:
    """Exact layers of a planner's search model (given by its :class:`Atoms`,
    or by a function that reads them, called by :meth:`start`: so only where
    the planner is not solving then), computed beside the search.

    :meth:`start` starts the work, :attr:`status` tells what is proven so
    far (:attr:`news` is set whenever it changes), :meth:`stop` ends the work.
    ``read_plan``: read a shortest plan off the layers once the goal layer is
    found.

    On Linux the layers are computed in a child process, which the search
    ends when it ends (started by this process's spawner,
    :mod:`ethasp.execution.spawner`, never by a fork of this process and its
    threads): the diagram library holds Python's interpreter lock for every
    operation, which a thread of this process would have to share with the
    solver's driver.  The child gets the atoms and reports through a pipe,
    one line a finding.  Elsewhere they run in a thread.
    """

    def __init__(
        self,
        atoms: Atoms | Callable[[], Atoms],
        budget: Budget,
        read_plan: bool = True,
        node_limit: int = NODE_LIMIT,
        bidirectional: bool | None = None,
    ):
        self._atoms = atoms
        self.bidirectional = BIDIRECTIONAL if bidirectional is None else bidirectional
        self.model: GroundModel | None = None
        self.read_plan = read_plan
        self.node_limit = node_limit
        self.status = Status()
        self.news = threading.Event()  # set whenever the status changes
        self._stop = threading.Event()
        self._budget = budget.until(self._stop.is_set)
        self._child: spawner.Child | None = None
        self._lock = threading.Lock()

    # What the engine is called in its refusals.
    NAME = "exact layers"

    def features(self) -> frozenset[str]:
        """The model features the engine handles (its module's ``FEATURES``)."""
        return FEATURES

    def start(self) -> Layers:
        """Start the work (:class:`ethasp.planning.engines.Unhandled` for a model
        with a feature the engine does not handle)."""
        if callable(self._atoms):  # read here, while the planner does not solve
            self._atoms = self._atoms()
        require(self.NAME, self.features(), self._atoms.features)
        if can_fork():
            self._start_child()
        else:
            threading.Thread(
                target=self._run, args=(self._publish,), name="ethasp-layers", daemon=True
            ).start()
        return self

    def stop(self) -> None:
        """End the work: the child process at once, the thread at its next check."""
        self._stop.set()
        with self._lock:
            child, self._child = self._child, None
        if child is not None:
            child.kill()

    def _publish(self, **changes) -> None:
        self.status = Status(**{**self.status.__dict__, **changes})
        self.news.set()

    # -- in a child process --------------------------------------------------------

    def _start_child(self) -> None:
        child = spawner.spawn(
            _compute,
            (
                type(self),
                self._atoms,
                self.read_plan,
                self.node_limit,
                self.bidirectional,
                self._budget.deadline,
            ),
        )
        self._child = child
        threading.Thread(
            target=self._listen, args=(child,), name="ethasp-layers", daemon=True
        ).start()

    def _listen(self, child: spawner.Child) -> None:
        """Read the child's reports into :attr:`status` (until it ends)."""
        for line in child.lines():
            changes = _parse_report(line)
            if changes:
                self._publish(**changes)
        if self.status.working:
            self._publish(stopped="exact reachability ended")

    # -- the work --------------------------------------------------------------------

    def _run(self, publish) -> None:
        try:
            self._work(publish)
        except Exception as error:
            publish(stopped=f"exact reachability failed: {type(error).__name__}: {error}")

    def _work(self, publish) -> None:
        atoms = self._atoms() if callable(self._atoms) else self._atoms
        self.model = search_model(atoms)
        from ethasp.planning.engines import reachability

        if not handles(reachability.FEATURES, model_features(self.model)):
            # Exogenous events: explicit layers of configurations (state, time).
            from ethasp.planning.engines import explicit

            explicit.search_with_events(
                self.model, self._budget, publish, self._stop.is_set, read_plan=self.read_plan
            )
            return
        _import_diagrams()
        from ethasp.planning.engines.reachability import Reachability

        engine = Reachability(self.model, node_limit=self.node_limit)
        goal = engine.goal()
        if self.bidirectional:
            self._both_ways(engine, goal, publish)
            return
        layer = 0
        while True:
            if self._stop.is_set():
                publish(stopped="stopped")
                return
            if engine.layers[layer] & goal != engine.bdd.false:
                publish(goal_layer=layer, bound=layer)
                if self.read_plan:
                    publish(plan=tuple(engine.least_path(goal, layer)))
                return
            publish(bound=layer + 1)
            if not engine.expand(self._budget):
                publish(stopped=engine.stopped)
                return
            if engine.complete:
                publish(complete=True)
                return
            layer += 1

    def _both_ways(self, engine, goal, publish) -> None:
        """Forward layers F_i and backward layers B_j (from the goal states), the
        direction with the smaller frontier diagram expanded first.  With
        F_0..F_I and B_0..B_J computed and no F_i meeting a B_j, every plan has
        more than I+J steps (a state at step i of a shortest plan of d <= I+J
        steps, i = max(0, d-J), is in F_i and in B_(d-i)); so the first time a
        new layer meets the last layer of the other direction, I+J is the
        length of a shortest plan, read off through both.  A direction that
        finds no new state proves that no goal state is reachable."""
        engine.start_backward(goal)
        forward = backward = 0
        while True:
            if self._stop.is_set():
                publish(stopped="stopped")
                return
            meeting = engine.layers[forward] & engine.back_layers[backward]
            if meeting != engine.bdd.false:
                length = forward + backward
                publish(goal_layer=length, bound=length)
                if self.read_plan:
                    # The least plan of that length, read off both directions.
                    publish(plan=tuple(engine.least_path_meeting(forward, backward)))
                return
            publish(bound=forward + backward + 1)
            ahead = len(engine.layers[forward]) <= len(engine.back_layers[backward])
            if not (engine.expand(self._budget) if ahead else engine.expand_backward(self._budget)):
                publish(stopped=engine.stopped)
                return
            if engine.complete or engine.back_complete:
                publish(complete=True)
                return
            if ahead:
                forward += 1
            else:
                backward += 1


def _compute(
    engine: type[Layers],
    atoms: Atoms,
    read_plan: bool,
    node_limit: int,
    bidirectional: bool,
    deadline: float | None,
    out,
) -> None:
    """In a child process: an engine's work, each finding a line on ``out``."""
    budget = Budget(None)
    budget.deadline = deadline
    layers = engine(
        atoms, budget, read_plan=read_plan, node_limit=node_limit, bidirectional=bidirectional
    )
    layers._run(lambda **changes: _report(out, changes))


def _report(pipe, changes: dict) -> None:
    """One line for the parent per finding (actions of a plan as terms, tab-separated)."""
    for key, value in changes.items():
        if key == "plan":
            value = "\t".join(str(action) for action in value)
        pipe.write(f"{key} {' '.join(str(value).split()) if key == 'stopped' else value}\n")


def _parse_report(line: str) -> dict:
    key, _, value = line.rstrip("\n").partition(" ")
    if key in ("bound", "goal_layer", "cost_bound", "cost"):
        return {key: int(value)}
    if key == "complete":
        return {"complete": value == "True"}
    if key == "stopped":
        return {"stopped": value or "stopped"}
    if key == "plan":
        return {"plan": tuple(clingo.parse_term(term) for term in value.split("\t") if term)}
    return {}
