"""The planner: a planning model grounded once, and every search over it.

One :class:`Planner` belongs to one loaded model (:attr:`Model.planner`).  It
owns one clingo control that holds the model and every search encoding,
grounded once, horizon by horizon (multi-shot solving, see
:mod:`ethasp.planning.driver.incremental`), and answers every search a command or
a dialogue needs from it: plans, HPlans under any set of principles, best
reachable states, states of a given utility, contrast plans under any set of
question constraints, and the loop-free completeness checks.  What a search
asks for is a :class:`Setting`: the switches (external atoms and
assumptions) that a solve sets, never a new grounding.

Program parts of the control (``t`` a time, ``x`` an input value):

* ``base``: the model's files, ``planning/model.lp`` and ``planning/check.lp``;
  the model's defects (``error/1``) and its ground vocabulary are read from
  it;
* ``relaxed``: relaxed reachability (``planning/relaxed.lp``), grounded
  first: what an engine beside the solver reads of the searches (the usable
  actions, the relaxed reachable facts) and the first proofs ("the goal is
  unreachable"), without the rest of the searches' encodings;
* ``search``: what the searches need once (the static part of the
  encodings below);
* ``step(t)`` and ``check(t)``: the time-indexed rules of
  ``planning/transition.lp``, ``planning/goal.lp`` (switched by
  ``require(goal)``), ``planning/satisficing.lp`` (a decision heuristic,
  switched by ``require(satisficing)``), ``judgement/best.lp`` and
  ``reasons/other_state.lp``;
* ``mutex`` and ``mutex_step(t)``: the h^2 mutexes of ``planning/mutex.lp``
  and their constraints, grounded (for every step so far and from then on)
  once a solve has been slow (:meth:`Planner.use_mutexes`);
* ``state_check(t)``: the state at the horizon (``judgement/state.lp``), an
  atom per variable and horizon, grounded (for every time so far and from
  then on) once a search reads that state (:meth:`Planner.use_state`);
* ``canonical`` and ``canonical_step(t)``: the canonical order of
  independent consecutive actions of ``planning/canonical.lp`` (switched by
  ``require(canonical)``), grounded once a search that may use it has been
  slow (:meth:`Planner.use_canonical`);
* ``question(x)``, ``question_step(x,t)``, ``question_check(x,t)``: one
  question of ``questions/questions.lp``, grounded when it is asked;
* ``at_least(x)``, ``other_state(x)`` and their ``_check`` parts: a utility
  threshold or a state to avoid, grounded when needed;
* ``loopfree(t)`` and ``simple_path_step(x,t)``: the completeness threshold
  (``planning/loopfree.lp``), grounded when a proof needs it, for each set of
  questions asked.

A given plan is evaluated once (:meth:`Planner.trace`) by its own small
program over the ground model's facts (``planning/trace.lp``): a plan's
trace is not a search, and a long plan would not fit the search's grounding.
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import clingo

from ethasp.errors import InputError
from ethasp.memo import results
from ethasp.planning.budget import Budget
from ethasp.planning.driver import incremental, namespace
from ethasp.planning.driver.incremental import CHECK, STEP, TIME_MARKER
from ethasp.planning.messages import Messages
from ethasp.resources import encoding

if TYPE_CHECKING:  # imported when used: plain plan search starts without them
    from clorm import FactBase

    from ethasp.planning.engines.reachability import GroundModel, Reachability

# What a model defines (encodings/planning/model.lp and reasons/labels.lp):
# programs about a plan or a formula read these atoms of the ground model.
MODEL_VOCABULARY = tuple(namespace.MODEL_VOCABULARY)
# The predicates of the vocabulary about one action (its first argument): a
# plan's trace reads them for the plan's actions only.
ACTION_VOCABULARY = (
    ("action", 1),
    ("pre", 3),
    ("eff", 3),
    ("cpre", 4),
    ("ceff", 4),
    ("utility", 2),
    ("cost", 2),
    ("override", 4),
    ("action_label", 3),
)

# The trace of a plan under exogenous events: it extends trace.lp, and every
# rule of it starts from an event that is due (event_at/2), so it is left out
# of the programs of a model without events (their grounding costs a few
# milliseconds even where nothing is derived).
TRACE_EVENTS = "planning/trace_events.lp"
TRACE_ENCODINGS = (
    "planning/model.lp",
    "planning/trace.lp",
    TRACE_EVENTS,
    "judgement/judge.lp",
)

# What tells whether a given plan meets question constraints
# (``questions/questions.lp``'s ``met/3``): the plan's actions, and for
# constraints about facts its states (``questions/given.lp``).
QUESTIONS = "questions/questions.lp"
GIVEN = (
    "planning/model.lp",
    "planning/trace.lp",
    TRACE_EVENTS,
    "planning/steps.lp",
    "questions/given.lp",
    QUESTIONS,
)
# Constraint terms about the plan's actions only (no states needed to check them).
ACTION_TERMS = ("used", "unused", "before", "at", "not_at", "within", "not_within", "at_most")

LOOPFREE = "loopfree"
SEARCH = "search"

# Parts of the model's own base part and of the searches (relative to encodings/).
MODEL_ENCODINGS = ("planning/model.lp", "planning/check.lp")
RELAXED_ENCODING = "planning/relaxed.lp"
RELAXED = "relaxed"
# The atoms of relaxed.lp that the searches read (search_atoms, is_fact).
RELAXED_ATOMS = frozenset(
    {
        ("usable", 1),
        ("reachable", 2),
        ("unreachable_goal", 0),
        ("upper_bound", 1),
        ("best_fact", 2),
        ("best_value", 2),
    }
)
SEARCH_ENCODINGS = (
    "planning/transition.lp",
    "planning/events.lp",
    "reasons/other_state.lp",
    "questions/questions.lp",
)
# The utility of the state at the horizon (an objective, a threshold),
# switched on for the searches that read it: a search for a cheapest plan
# optimises the cost alone.
UTILITY_ENCODING = "judgement/best.lp"
UTILITY_SWITCH = clingo.Function("require", [clingo.Function("utility")])
# The cost of a plan, then its number of steps (objectives of a lower and a
# higher priority than the utility's), switched on for the searches for
# cheapest plans; grounded for models with action costs only.
COST_ENCODING = "planning/cost.lp"
# What the first level of optimisation of planning/cost.lp carries beyond a
# plan's cost (a constant 1, so that the level exists where every action
# grounded costs 0): a bound on the cost is given plus this.
COST_LEVEL_OFFSET = 1
COST_SWITCH = clingo.Function("require", [clingo.Function("cost")])
GOAL_ENCODING = "planning/goal.lp"
# The h^2 mutexes are redundant constraints: they speed up hard horizons, but
# their fixpoint grows with the square of the facts.  So they are grounded only
# once a solve has met MUTEX_AFTER conflicts (easy searches end before; work,
# not seconds, decides, so that the same search grounds the same program on
# every run, at any load), and
# only for models of at most MUTEX_MAX_FLUENTS state variables that change and
# at most MUTEX_MAX_PAIRS pairs of a usable action and such a variable (what
# the grounding of the fixpoint takes grows with them: 30 to 65 microseconds a
# pair; IPC freecell p1, 3,408 actions and 74 such variables, took 16 s, which
# the grounding cannot be interrupted in, after a 0.3 s solve).
MUTEX_ENCODING = "planning/mutex.lp"
MUTEX = "mutex"
MUTEX_STEP = "mutex_step"
MUTEX_MAX_FLUENTS = 400
MUTEX_MAX_PAIRS = 150_000
MUTEX_AFTER = 1000
# The canonical order of independent actions (partial-order reduction): its
# pairs of independent actions grow with the square of the actions, so it is
# grounded (with the mutexes) only for models of at most this many usable ones.
CANONICAL_ENCODING = "planning/canonical.lp"
CANONICAL = "canonical"
CANONICAL_STEP = "canonical_step"
CANONICAL_MAX_ACTIONS = 1000
# ... and once a solve that may use it has met this many conflicts (its
# grounding, per step, costs more than it saves on easier horizons).
CANONICAL_AFTER = 10_000
CANONICAL_SWITCH = clingo.Function("require", [clingo.Function("canonical")])
# The least plan of a length (the reported plan of a search, whichever engine
# found its length): a decision heuristic, grounded when first needed.
LEAST_ENCODING = "planning/lexicographic.lp"
LEAST = "lexicographic"
LEAST_STEP = "lexicographic_step"
LEAST_SWITCH = clingo.Function("require", [clingo.Function("lexicographic")])
LOOPFREE_ENCODING = "planning/loopfree.lp"
# The state at the horizon (at_horizon/3), for the searches that read it (an
# optimisation, a utility threshold): an atom per variable and horizon, which
# plain plan search on a PDDL task with many variables would pay for at every
# horizon.
STATE_ENCODING = "judgement/state.lp"
STATE_CHECK = "state_check"

# The solver configuration of every search (it did best on the planning benchmarks).
OPTIONS = ("--configuration=trendy", "--heuristic=Domain")

GOAL_SWITCH = clingo.Function("require", [clingo.Function("goal")])
# The decision heuristic of any-plan searches (planning/satisficing.lp).
SATISFICING_ENCODING = "planning/satisficing.lp"
SATISFICING_SWITCH = clingo.Function("require", [clingo.Function("satisficing")])

# past(t): step t comes after the end of the plan or path searched (it idles).
PAST = "past"


@functools.cache
def _time_atom(name: str, t: int) -> clingo.Symbol:
    """``horizon(t)`` or ``past(t)`` (made once)."""
    return clingo.Function(name, [clingo.Number(t)])


def add_facts(ctl: clingo.Control, facts: Iterable) -> None:
    """Add facts to a control object's base program.

    Clingo symbols and clorm facts are added as atoms through clingo's backend:
    no text is written, so no name (an action, a formula) can become a rule.
    Strings are program text that ethasp itself writes (``time(0..1)``), never
    user input; they are added as text.
    """
    symbols, texts = [], []
    for fact in facts:
        if isinstance(fact, str):
            texts.append(fact if fact.rstrip().endswith(".") else fact + ".")
        else:
            symbols.append(fact if isinstance(fact, clingo.Symbol) else fact.raw)
    if texts:
        ctl.add("base", [], "\n".join(texts))
    if symbols:
        with ctl.backend() as backend:
            for symbol in symbols:
                backend.add_rule([backend.add_atom(symbol)])


def solve_configuration(ctl: clingo.Control) -> clingo.Configuration:
    """The ``solve`` group of a control's configuration (models, enum_mode...)."""
    config = ctl.configuration.solve
    assert isinstance(config, clingo.Configuration)
    return config


def occurrences(plan) -> list[clingo.Symbol]:
    """A plan's ``occurs(A,T)`` atoms."""
    return [
        clingo.Function("occurs", [action, clingo.Number(step)])
        for step, action in enumerate(plan, start=1)
    ]


class Answer:
    """The shown atoms of an answer set, indexed by predicate, with their text
    as facts made once (programs that read an answer set are given it as facts)."""

    def __init__(self, symbols: list[clingo.Symbol]):
        self.symbols = symbols
        self._by_name: dict[str, list[clingo.Symbol]] | None = None
        self._texts: dict[tuple[tuple[str, int], ...] | None, str] = {}

    def get(self, name: str, arity: int) -> list[clingo.Symbol]:
        """The atoms of one predicate."""
        if self._by_name is None:
            self._by_name = {}
            for symbol in self.symbols:
                self._by_name.setdefault(symbol.name, []).append(symbol)
        return [s for s in self._by_name.get(name, []) if len(s.arguments) == arity]

    def select(self, signatures: Iterable[tuple[str, int]]) -> list[clingo.Symbol]:
        """The atoms of several predicates."""
        return [symbol for signature in signatures for symbol in self.get(*signature)]

    def text(self, signatures: Sequence[tuple[str, int]] | None = None) -> str:
        """The atoms (of the given predicates, else all) as facts."""
        key = None if signatures is None else tuple(signatures)
        if key not in self._texts:
            chosen = self.symbols if key is None else self.select(key)
            self._texts[key] = "".join(f"{symbol}.\n" for symbol in chosen)
        return self._texts[key]


@dataclass(frozen=True)
class Constraint:
    """One constraint of a question: ``contrast(Q,C)``."""

    question: clingo.Symbol
    term: clingo.Symbol

    def __str__(self) -> str:
        return str(self.term)


def final_facts(constraints) -> list[tuple[clingo.Symbol, bool]] | None:
    """The facts that constraints ask of the final state, where each is
    ``ends(F,B)`` (the final state has F = B, ``questions/questions.lp``):
    a classical goal; else None."""
    facts = []
    for constraint in sorted(constraints, key=str):
        term = constraint.term
        if term.name != "ends" or len(term.arguments) != 2:
            return None
        variable, value = term.arguments
        facts.append((variable, value.name == "true"))
    return facts


@dataclass(frozen=True)
class Setting:
    """What one solve asks of the model.

    ``goal``: the goal must hold at the horizon; ``constraints``: the question
    constraints imposed (of questions made by :meth:`Planner.question`; the
    restrictions of principles, and the question constraints that compile,
    are HModels of their own: :mod:`ethasp.principles.hmodel`);
    ``at_least``: the state at the horizon must be worth at least this much;
    ``other_state``: a state (:meth:`Planner.avoid`) the state at the horizon
    must differ from; ``optimize``: find an optimal model of the
    objective (the utility of the state at the horizon, then goal states);
    ``cheapest``: find a plan of least cost, then of fewest steps (the
    objectives of ``planning/cost.lp``, for models with action costs; a
    solve for all models lists every one within ``max_cost`` instead);
    ``max_cost``: the plan must cost at most this much (a bound of the
    cost objective); ``satisficing``: the solver's decision heuristic for any-plan searches
    (``planning/satisficing.lp``; it changes which plan is found first, not
    which plans exist); ``canonical``: independent consecutive actions in the
    order of their terms (``planning/canonical.lp``, once grounded): for
    searches that want one plan of a length, whatever its order (it removes
    plans, but never all plans of a length); ``least``: with ``optimize``,
    the least plan of the horizon in the order of the actions' terms is the
    optimum (``planning/lexicographic.lp``, grounded by
    :meth:`Planner.use_least`).
    """

    goal: bool = True
    constraints: frozenset[Constraint] = frozenset()
    at_least: int | None = None
    other_state: int | None = None
    optimize: bool = False
    satisficing: bool = False
    canonical: bool = False
    least: bool = False
    cheapest: bool = False
    max_cost: int | None = None


@dataclass
class Outcome:
    """The result of one solve: ``satisfiable`` (None when the budget stopped
    it), the shown atoms of the last model found (an optimal one when
    optimising and not stopped) and that model's cost; for an unsatisfiable
    solve, ``core``: question constraints imposed (``active(Q,C)`` atoms)
    that already make it unsatisfiable together (clingo's core of the
    assumptions)."""

    satisfiable: bool | None
    symbols: list[clingo.Symbol] = field(default_factory=list)
    cost: list[int] = field(default_factory=list)
    models: list[list[clingo.Symbol]] = field(default_factory=list)
    core: list[clingo.Symbol] = field(default_factory=list)


class GroundingStopped(Exception):
    """The budget ran out while clingo was grounding: the grounding goes on in
    the background (clingo cannot interrupt it), and the planner waits for it
    before its next use of the control."""


def _locked(method):
    """Run a method under the planner's lock: clingo controls and diagram
    managers serve one thread at a time (the web page runs searches in
    threads)."""

    @functools.wraps(method)
    def run(self, *args, **kwargs):
        with self.lock:
            return method(self, *args, **kwargs)

    return run


class Planner:
    """A model's one grounding and every search over it (see the module docstring).

    Created by :attr:`ethasp.planning.model.Model.planner`; the model's base
    part is grounded at once (its defects raise InputError), the searches'
    parts when a search first needs them.
    """

    def __init__(self, model):
        self.model = model
        self.lock = threading.RLock()
        self.messages = Messages()
        self.ctl = model.control(OPTIONS, self.messages)
        self._parts: dict[str, tuple[str, ...]] = {}
        self._searching = False
        self._relaxed = False  # the part relaxed grounded
        self._mutexes: bool | None = False  # grounded (True), not yet, or never (None)
        self._canonical: bool | None = False  # the same for the canonical order
        self._least = False  # the heuristic of least plans grounded
        self._state = False  # the state at the horizon grounded (use_state)
        self._mutex_size: tuple[int, int] | None = None  # (fluents, pairs)
        self._threads = 1  # solver threads (see threads())
        self._solve_limit = "umax"  # conflicts a solve may meet
        self.grounded = -1  # step and check parts grounded up to this time
        self._loopfree = 0  # loopfree parts grounded up to this time
        self._inputs: dict[str, list[clingo.Symbol]] = {name: [] for name in incremental.INPUTS}
        self._questions: dict[clingo.Symbol, list[Constraint]] = {}
        self._question_ids: dict[tuple[clingo.Symbol, ...], clingo.Symbol] = {}
        # Questions named but not grounded yet (their ``contrast/2`` facts): a
        # question is grounded when a search or impossible() first needs it.
        self._ungrounded: dict[clingo.Symbol, list[clingo.Symbol]] = {}
        self._configurations: dict[tuple[clingo.Symbol, ...], tuple[clingo.Symbol, int]] = {}
        self._avoided: dict[frozenset, int] = {}
        self._reachability: Reachability | None = None
        self._ground_model: GroundModel | None = None
        self._fact_weights: dict[tuple[clingo.Symbol, bool], int] | None = None
        self._externals: dict[clingo.Symbol, bool] = {}  # values assigned so far
        self._model_symbols: list[clingo.Symbol] | None = None
        self._action_atoms: dict[clingo.Symbol, list[clingo.Symbol]] | None = None
        self._state_symbols: list[clingo.Symbol] | None = None
        self._bound: Answer | None = None
        # A grounding left running when a budget ran out: (done, failure).
        self._pending: tuple[threading.Event, list] | None = None
        try:
            self._add_encodings(MODEL_ENCODINGS, "base")
            self.ctl.ground([("base", [])])
        except RuntimeError:
            self.messages.raise_first("grounding failed")
        self._atoms: dict[tuple[str, int], list[clingo.Symbol]] = {}

    # -- the ground model -----------------------------------------------------------

    @_locked
    def base_answers(self) -> list[list[clingo.Symbol]]:
        """The shown atoms (``error/1`` of check.lp) of up to two answer sets of
        the model's base part: a model must have exactly one."""
        if self._searching or self._relaxed:
            raise RuntimeError("the model is checked before any search")
        solve_configuration(self.ctl).models = "2"
        answers: list[list[clingo.Symbol]] = []
        with self.ctl.solve(yield_=True) as handle:
            for answer in handle:
                answers.append(list(answer.symbols(shown=True)))
        return answers

    @_locked
    def signatures(self) -> list[tuple[str, int]]:
        """The signatures of the predicates of the model's base grounding."""
        return [(name, arity) for name, arity, _ in self.ctl.symbolic_atoms.signatures]

    @_locked
    def get(self, name: str, arity: int) -> list[clingo.Symbol]:
        """The ground atoms of a predicate of the model's base part (model.lp's
        too), in the grounder's order (the same for the same model).  Under
        the lock: read while another thread grounds, clingo's atoms could be
        read half-made (and kept so)."""
        key = (name, arity)
        if key not in self._atoms:
            self._settle(None)
            self._atoms[key] = [
                atom.symbol for atom in self.ctl.symbolic_atoms.by_signature(name, arity)
            ]
        return self._atoms[key]

    @_locked
    def defines(self, name: str, argument: clingo.Symbol) -> bool:
        """Is ``name(argument)`` an atom of the model's base grounding (e.g. is
        a term an ``action/1`` or a ``variable/1`` of the model)?"""
        return self.ctl.symbolic_atoms[clingo.Function(name, [argument])] is not None

    @_locked
    def bound(self) -> Answer:
        """``upper_bound/1`` and ``best_fact/2`` of planning/relaxed.lp: no reachable
        state is worth more than the upper bound (read off relaxed reachability's
        part of the grounding: no search needs to be grounded for it)."""
        if self._bound is None:
            self._bound = Answer(
                self.search_atoms("upper_bound", 1) + self.search_atoms("best_fact", 2)
            )
        return self._bound

    def facts(self, predicates) -> FactBase:
        """The base part's atoms of the given clorm predicates (the model's
        vocabulary, its rules grounded, and model.lp's)."""
        from clorm import unify

        return unify(
            list(predicates),
            [
                symbol
                for predicate in predicates
                for symbol in self.get(predicate.meta.name, predicate.meta.arity)
            ],
        )

    def vocabulary_text(self, signatures: Iterable[tuple[str, int]]) -> str:
        """The ground atoms of these predicates as facts (for programs over a plan)."""
        return "".join(
            f"{symbol}.\n" for signature in signatures for symbol in self.get(*signature)
        )

    @_locked
    def fact_weights(self) -> dict[tuple[clingo.Symbol, bool], int]:
        """The utility of each fact (``weight(fact(V,B),U)`` of model.lp) by
        (V, value): what a state is worth, without the whole ground model."""
        if self._fact_weights is None:
            weights = {}
            for atom in self.get("weight", 2):
                element, utility = atom.arguments
                if element.name == "fact":
                    variable, value = element.arguments
                    weights[(variable, value.name == "true")] = utility.number
            self._fact_weights = weights
        return self._fact_weights

    @_locked
    def ground_model(self) -> GroundModel:
        """The model for the reachability engine, from the ground vocabulary."""
        if self._ground_model is None:
            from ethasp.planning.engines.layers import _events
            from ethasp.planning.engines.reachability import from_atoms

            def value(symbol: clingo.Symbol) -> bool:
                return symbol.name == "true"

            weights = dict(self.fact_weights())
            self._ground_model = from_atoms(
                [a.arguments[0] for a in self.get("variable", 1)],
                [a.arguments[0] for a in self.get("action", 1)],
                [
                    (a.arguments[0], a.arguments[1], value(a.arguments[2]))
                    for a in self.get("pre", 3)
                ],
                [
                    (a.arguments[0], a.arguments[1], value(a.arguments[2]))
                    for a in self.get("eff", 3)
                ],
                [
                    (a.arguments[0], a.arguments[1], a.arguments[2], value(a.arguments[3]))
                    for a in self.get("ceff", 4)
                ],
                [
                    (a.arguments[0], a.arguments[1], a.arguments[2], value(a.arguments[3]))
                    for a in self.get("cpre", 4)
                ],
                [a.arguments[0] for a in self.get("init", 1)],
                [(a.arguments[0], value(a.arguments[1])) for a in self.get("goal", 2)],
                weights,
                [
                    (a.arguments[0], a.arguments[1], a.arguments[2], value(a.arguments[3]))
                    for a in self.get("axiom_pre", 4)
                ],
                [(a.arguments[0], a.arguments[1]) for a in self.get("axiom", 2)],
                [a.arguments[0] for a in self.get("derived", 1)],
                max((a.arguments[0].number for a in self.get("goal_utility", 1)), default=None),
                _events(self),
            )
        return self._ground_model

    def reachability_pending(self) -> bool:
        """Whether the exact reachability engine of this model is still to be made."""
        return self._reachability is None

    @property
    def has_costs(self) -> bool:
        """Does the model have action costs (``cost/2``; plans are then cheapest
        ones, not shortest ones)?"""
        return bool(self.get("costs_given", 0))

    def action_costs(self) -> dict[clingo.Symbol, int]:
        """The cost of every action (``action_cost/2`` of planning/model.lp)."""
        return {atom.arguments[0]: atom.arguments[1].number for atom in self.get("action_cost", 2)}

    @property
    def has_events(self) -> bool:
        """Does the model have exogenous events (``event_at/2``)?"""
        return bool(self.get("event_at", 2))

    @property
    def last_event(self) -> int:
        """The last step at which an event is due (0 without events): a plan of
        fewer steps ends there, after the events."""
        steps = [
            atom.arguments[1].number
            for atom in self.get("event_at", 2)
            if atom.arguments[1].type == clingo.SymbolType.Number
        ]
        return max(steps, default=0)

    @property
    def features(self) -> frozenset[str]:
        """The features of the ground model that not every engine handles
        (:data:`ethasp.planning.engines.ALL_FEATURES`)."""
        from ethasp.planning.engines import ground_features

        return ground_features(self)

    def handles(self, features: frozenset[str]) -> bool:
        """Does an engine that handles ``features`` (its module's ``FEATURES``)
        handle this model?  Asked before any engine is used
        (:mod:`ethasp.planning.engines`)."""
        from ethasp.planning.engines import handles

        return handles(features, self.features)

    @property
    def exact_reachability(self) -> bool:
        """Does the exact reachability engine apply?  It knows actions,
        conditional effects and derived variables, not exogenous events:
        models with events get the explicit layers instead."""
        from ethasp.planning.engines import reachability

        return self.handles(reachability.FEATURES)

    @_locked
    def reachability(self) -> Reachability:
        """The exact reachability engine over this model (created once, expanded
        by whoever needs more layers).  Models with exogenous events have none
        (:attr:`exact_reachability`)."""
        from ethasp.planning.engines import reachability, require

        require("exact reachability", reachability.FEATURES, self.features)
        if self._reachability is None:
            self._reachability = reachability.Reachability(
                self.ground_model(), reachability.DEFAULT_NODE_LIMIT
            )
        return self._reachability

    # -- grounding ------------------------------------------------------------------

    def _start_relaxed(self, budget: Budget | None = None) -> None:
        """Add and ground relaxed reachability (once, before the searches)."""
        self._settle(budget)
        if self._relaxed:
            return
        try:
            self._add_encodings((RELAXED_ENCODING,), RELAXED)
        except RuntimeError:
            self.messages.raise_first("grounding failed")
        self._relaxed = True  # (noted before: see _start_search)
        self._ground([(RELAXED, [])], budget)

    def _add_encodings(self, names, part: str) -> None:
        """Add encodings whose rules all go into ``part``: as text where no
        marker can be in them (:func:`incremental.plain_text`), else split."""
        split = [name for name in names if incremental.plain_text(encoding(name)) is None]
        if split:
            with clingo.ast.ProgramBuilder(self.ctl) as builder:
                for name in split:
                    incremental.add_encoding(
                        builder, encoding(name), on_message=self.messages, base_part=part
                    )
        for name in names:
            text = incremental.plain_text(encoding(name))
            if text is not None:
                self.ctl.add(part, [], text)

    def _start_search(self, budget: Budget | None = None) -> None:
        """Add and ground the searches' encodings (once, on the first search)."""
        self._start_relaxed(budget)
        self._settle(budget)
        if self._searching:
            return
        switches = [
            GOAL_SWITCH,
            SATISFICING_SWITCH,
            CANONICAL_SWITCH,
            LEAST_SWITCH,
            UTILITY_SWITCH,
            COST_SWITCH,
        ]
        try:
            with clingo.ast.ProgramBuilder(self.ctl) as builder:
                files = [(name, STEP, None, SEARCH) for name in SEARCH_ENCODINGS]
                # Grounded when a search is found hard (see use_mutexes).
                files.append((MUTEX_ENCODING, MUTEX_STEP, None, MUTEX))
                files.append((CANONICAL_ENCODING, CANONICAL_STEP, None, CANONICAL))
                files.append((LEAST_ENCODING, LEAST_STEP, LEAST_SWITCH, LEAST))
                self._parts.update(
                    incremental.add_encoding(
                        builder,
                        encoding(STATE_ENCODING),
                        on_message=self.messages,
                        base_part=SEARCH,
                        check_part=STATE_CHECK,
                    )
                )
                files.append((GOAL_ENCODING, STEP, GOAL_SWITCH, SEARCH))
                files.append((UTILITY_ENCODING, STEP, UTILITY_SWITCH, SEARCH))
                if self.has_costs:
                    files.append((COST_ENCODING, STEP, COST_SWITCH, SEARCH))
                files.append((SATISFICING_ENCODING, STEP, SATISFICING_SWITCH, SEARCH))
                files.append((LOOPFREE_ENCODING, LOOPFREE, None, SEARCH))
                for name, step_part, switch, base_part in files:
                    self._parts.update(
                        incremental.add_encoding(
                            builder,
                            encoding(name),
                            step_part=step_part,
                            switch=switch,
                            on_message=self.messages,
                            base_part=base_part,
                        )
                    )
            for part, (parameters, text) in incremental.time_parts().items():
                self.ctl.add(part, parameters, text)
            self.ctl.add(SEARCH, [], "time(0).\n" + "".join(f"#external {s}.\n" for s in switches))
        except RuntimeError:
            self.messages.raise_first("grounding failed")
        # What is grounded is noted before: a grounding stopped by the budget
        # still completes in the background (see _ground).
        self._searching = True
        self.grounded = 0
        self._loopfree = 0
        self._ground([(SEARCH, []), (CHECK, [clingo.Number(0)])], budget)

    def _ground(self, parts, budget: Budget | None = None) -> None:
        """Ground program parts.  Under a budget the grounding runs in a thread
        of its own, so that the budget's limit holds while clingo grounds
        (which it cannot interrupt): when the budget runs out first,
        GroundingStopped is raised and the grounding completes in the
        background (the callers note what is grounded before, and every use of
        the control waits for it first, :meth:`_settle`)."""
        self._settle(budget)
        if budget is None:
            try:
                self.ctl.ground(parts)
            except RuntimeError:
                self.messages.raise_first("grounding failed")
            return
        done, failure = threading.Event(), []

        def work() -> None:
            try:
                self.ctl.ground(parts)
            except RuntimeError as error:
                failure.append(error)
            finally:
                done.set()

        self._pending = (done, failure)
        # Not a daemon: clingo cannot be stopped while it grounds, and a thread
        # still in clingo when the interpreter shuts down would crash it; the
        # interpreter waits for the grounding to end instead.
        threading.Thread(target=work, name="ethasp-grounding").start()
        self._settle(budget)

    def _settle(self, budget: Budget | None) -> None:
        """Wait for a grounding left running (without a budget: as long as it
        takes); GroundingStopped if the budget runs out first."""
        pending = self._pending
        if pending is None:
            return
        done, failure = pending
        if budget is None:
            done.wait()
        elif not budget.wait_event(done):
            raise GroundingStopped()
        self._pending = None
        if failure:
            self.messages.raise_first("grounding failed")

    def _input_parts(self, name: str, value: clingo.Symbol, times: Iterable[int]) -> list:
        parts = []
        for t in times:
            for kind in (STEP, CHECK):
                part = incremental.part_name(kind, name)
                if part in self._parts:
                    parts.append((part, [value, clingo.Number(t)]))
        return parts

    @_locked
    def ground_to(self, horizon: int, budget: Budget | None = None) -> None:
        """Ground the step and check parts (and those of every input) up to
        ``horizon`` (GroundingStopped if the budget runs out first)."""
        self._start_search(budget)
        parts = []
        for t in range(self.grounded + 1, horizon + 1):
            parts += [(STEP, [clingo.Number(t)]), (CHECK, [clingo.Number(t)])]
            if self._mutexes:
                parts.append((MUTEX_STEP, [clingo.Number(t)]))
            if self._canonical:
                parts.append((CANONICAL_STEP, [clingo.Number(t)]))
            if self._least:
                parts.append((LEAST_STEP, [clingo.Number(t)]))
            if self._state:
                parts.append((STATE_CHECK, [clingo.Number(t)]))
            for name, values in self._inputs.items():
                if name == "simple_path":
                    continue
                for value in values:
                    parts += self._input_parts(name, value, [t])
        grounded, self.grounded = self.grounded, max(self.grounded, horizon)
        if parts:
            try:
                self._ground(parts, budget)
            except InputError:
                self.grounded = grounded
                raise

    @_locked
    def use_mutexes(self, budget: Budget | None = None) -> bool:
        """Ground the h^2 mutexes (``planning/mutex.lp``) for every step so far
        and from now on, unless the model has more than MUTEX_MAX_FLUENTS state
        variables that may change or more than MUTEX_MAX_PAIRS pairs of such a
        variable and a usable action; whether they are in use."""
        self._start_search(budget)
        if self._mutexes:
            return True
        if self._mutexes is None:
            return False
        if self.has_events:
            # The mutexes are computed from the actions alone: events may break them.
            self._mutexes = None
            return False
        fluents, pairs = self.mutex_size()
        if fluents > MUTEX_MAX_FLUENTS or pairs > MUTEX_MAX_PAIRS:
            self._mutexes = None  # never
            return False
        self._mutexes = True
        self._ground_from_now(MUTEX, MUTEX_STEP, budget)
        return True

    @_locked
    def mutex_size(self) -> tuple[int, int]:
        """The state variables that may change (both values relaxed reachable),
        and their number times the usable actions: what the grounding of the
        h^2 mutexes grows with."""
        if self._mutex_size is None:
            reachable: dict[clingo.Symbol, int] = {}
            for atom in self.search_atoms("reachable", 2):
                reachable[atom.arguments[0]] = reachable.get(atom.arguments[0], 0) + 1
            fluents = sum(1 for count in reachable.values() if count == 2)
            self._mutex_size = (fluents, fluents * len(self.search_atoms("usable", 1)))
        return self._mutex_size

    @_locked
    def use_canonical(self, budget: Budget | None = None) -> bool:
        """Ground the canonical order of independent actions
        (``planning/canonical.lp``) for every step so far and from now on,
        unless the model has exogenous events or more than
        CANONICAL_MAX_ACTIONS usable actions; whether it is in use (a search
        imposes it with :attr:`Setting.canonical`)."""
        self._start_search(budget)
        if self._canonical is not False:
            return bool(self._canonical)
        if self.has_events or len(self.search_atoms("usable", 1)) > CANONICAL_MAX_ACTIONS:
            self._canonical = None  # never
            return False
        self._canonical = True
        self._ground_from_now(CANONICAL, CANONICAL_STEP, budget)
        return True

    @_locked
    def use_least(self, budget: Budget | None = None) -> None:
        """Ground the heuristic of least plans (``planning/lexicographic.lp``)
        for every step so far and from now on, the usable actions ranked by
        their terms."""
        self._start_search(budget)
        if self._least:
            return
        actions = sorted(atom.arguments[0] for atom in self.search_atoms("usable", 1))
        facts = [
            clingo.Function("lex_rank", [action, clingo.Number(rank)])
            for rank, action in enumerate(actions)
        ]
        facts.append(clingo.Function("lex_width", [clingo.Number(max(1, len(actions)))]))
        add_facts(self.ctl, facts)
        self._least = True
        self._ground_from_now(LEAST, LEAST_STEP, budget)

    @_locked
    def use_state(self, budget: Budget | None = None) -> None:
        """Ground the state at the horizon (``judgement/state.lp``) for every
        time so far and from now on (:meth:`ground_to` grounds later ones)."""
        self._start_search(budget)
        if not self._state:
            self._state = True
            self._ground(
                [(STATE_CHECK, [clingo.Number(t)]) for t in range(self.grounded + 1)], budget
            )

    def _ground_from_now(self, part: str, step_part: str, budget: Budget | None = None) -> None:
        """Ground an optional part and its step part for every step so far
        (:meth:`ground_to` grounds the step part of later steps)."""
        self._ground(
            [(part, [])] + [(step_part, [clingo.Number(t)]) for t in range(1, self.grounded + 1)],
            budget,
        )

    def _register(
        self,
        name: str,
        value: clingo.Symbol,
        facts: Sequence[clingo.Symbol] = (),
        budget: Budget | None = None,
    ) -> None:
        """Ground the parts of one input value up to the horizon grounded so far."""
        self._start_search(budget)
        if value in self._inputs[name]:
            return
        parts = [(name, [value])]
        add_facts(self.ctl, facts)  # seen by the parts grounded next
        times = range(1, self._loopfree + 1) if name == "simple_path" else range(self.grounded + 1)
        parts += self._input_parts(name, value, times)
        self._inputs[name].append(value)
        self._ground(parts, budget)

    # -- inputs ----------------------------------------------------------------------

    @_locked
    def question(self, terms: Sequence[clingo.Symbol]) -> list[Constraint]:
        """The constraints of a question (its ``contrast`` terms); the same terms
        give the same question (named ``q(N)``).  It is grounded when a search
        of this planner or :meth:`impossible` first needs it: a question whose
        plans another planner searches (an HModel's) grounds nothing here."""
        key = tuple(sorted(set(terms), key=str))
        if key not in self._question_ids:
            name = clingo.Function("q", [clingo.Number(len(self._question_ids) + 1)])
            self._questions[name] = [Constraint(name, term) for term in key]
            self._ungrounded[name] = [clingo.Function("contrast", [name, term]) for term in key]
            self._question_ids[key] = name
        return list(self._questions[self._question_ids[key]])

    def _ground_questions(self, names: Iterable[clingo.Symbol], budget: Budget | None) -> None:
        """Ground the questions named (those not grounded yet), in the order
        they were asked."""
        wanted = set(names)
        for name in [name for name in self._ungrounded if name in wanted]:
            self._register("question", name, self._ungrounded[name], budget)
            del self._ungrounded[name]

    @_locked
    def impossible(self, constraints: Iterable[Constraint]) -> list[tuple[Constraint, str]]:
        """The question constraints that no plan can meet, known from the grounding
        (``questions/questions.lp``): each with why (``goal``: it contradicts the
        goal; ``relaxed``: relaxed reachability excludes what it needs).  Their
        rules read the question's input atom and facts of the model and of
        relaxed reachability only, so an atom is grounded exactly when its
        rule holds for the question (the grounder drops a rule with a false
        body)."""
        constraints = list(constraints)
        self._ground_questions([c.question for c in constraints], None)
        found = []
        for constraint in constraints:
            for name, why in (
                ("question_against_goal", "goal"),
                ("question_unreachable", "relaxed"),
            ):
                atom = self.ctl.symbolic_atoms[
                    clingo.Function(name, [constraint.question, constraint.term])
                ]
                if atom is not None:
                    found.append((constraint, why))
                    break
        return found

    @_locked
    def avoid(self, state: Iterable[tuple[clingo.Symbol, bool]]) -> int:
        """An id for a state that searches may be asked to avoid (``other_state``)."""
        key = frozenset(state)
        if key not in self._avoided:
            number = len(self._avoided) + 1
            facts = [
                clingo.Function(
                    "other_than",
                    [clingo.Number(number), variable, clingo.Function(str(value).lower())],
                )
                for variable, value in sorted(key, key=str)
            ]
            self._register("other_state", clingo.Number(number), facts)
            self._avoided[key] = number
        return self._avoided[key]

    def _threshold(self, name: str, value: int, budget: Budget | None = None) -> None:
        self._register(name, clingo.Number(value), budget=budget)

    # -- solving ---------------------------------------------------------------------

    def _set(
        self,
        setting: Setting,
        horizon: int | None,
        end: int,
        simple_path: clingo.Symbol | None = None,
    ) -> list[tuple[clingo.Symbol, bool]]:
        """Assign the externals of a setting (``horizon``: the time whose check
        part applies, None for none; ``end``: the steps after it idle); return
        the assumptions on the question constraints."""
        assign = self._assign
        for t in range(self.grounded + 1):
            assign(_time_atom(TIME_MARKER, t), t == horizon)
            if t > 0:
                assign(_time_atom(PAST, t), t > end)
        assign(GOAL_SWITCH, setting.goal and horizon is not None)
        assign(SATISFICING_SWITCH, setting.satisficing)
        assign(
            UTILITY_SWITCH,
            (setting.optimize and not setting.least) or setting.at_least is not None,
        )
        assign(COST_SWITCH, setting.cheapest)
        # Paths compare the states between the actions, which a swap changes.
        assign(CANONICAL_SWITCH, setting.canonical and simple_path is None)
        assign(LEAST_SWITCH, setting.least and self._least)
        wanted = {
            "question": {c.question for c in setting.constraints},
            "at_least": (
                {clingo.Number(setting.at_least)} if setting.at_least is not None else set()
            ),
            "other_state": (
                {clingo.Number(setting.other_state)} if setting.other_state is not None else set()
            ),
            "simple_path": {simple_path} if simple_path is not None else set(),
        }
        for name, values in wanted.items():
            for value in self._inputs[name]:
                assign(clingo.Function(name, [value]), value in values)
        assumptions = []
        for question in sorted(wanted["question"], key=str):
            for constraint in self._questions[question]:
                atom = clingo.Function("active", [question, constraint.term])
                assumptions.append((atom, constraint in setting.constraints))
        return assumptions

    def _assign(self, atom: clingo.Symbol, value: bool) -> None:
        """Set an external atom, calling clingo only when its value changes."""
        if self._externals.get(atom) is not value:
            self.ctl.assign_external(atom, value)
            self._externals[atom] = value

    def _prepare(self, setting: Setting, budget: Budget | None = None) -> None:
        for constraint in setting.constraints:
            if constraint not in self._questions.get(constraint.question, ()):
                raise ValueError(
                    f"constraint {constraint} of an unknown question "
                    f"{constraint.question} (see Planner.question)"
                )
        self._ground_questions([c.question for c in setting.constraints], budget)
        if setting.at_least is not None:
            self._threshold("at_least", setting.at_least, budget)
        if (setting.optimize and not setting.least) or setting.at_least is not None:
            self.use_state(budget)  # their answers are read as states

    @_locked
    def solve(
        self,
        horizon: int,
        setting: Setting,
        budget: Budget,
        models: int = 1,
        mutex_after: float = MUTEX_AFTER,
        moot: Callable[[], bool] | None = None,
        conflicts: int | None = None,
    ) -> Outcome:
        """Solve at one horizon under a setting (grounding what it needs first),
        for at most ``conflicts`` conflicts if given (then ``satisfiable`` is
        None when they run out); a solve that meets more than ``mutex_after``
        conflicts has the h^2 mutexes grounded for the next ones
        (:meth:`use_mutexes`), and one under a canonical setting that meets
        more than CANONICAL_AFTER (and ``mutex_after``) the canonical order
        (:meth:`use_canonical`); neither when ``moot`` says, after a solve the
        budget stopped, that the search needs no more solves (another engine
        proved what it sought: the groundings would only delay its end)."""
        try:
            self._prepare(setting, budget)
            # A plan shorter than the last event ends after it: the goal and the
            # state at the horizon are checked there (the steps between idle).
            check = max(horizon, self.last_event)
            self.ground_to(check, budget)
        except GroundingStopped:
            return Outcome(None)  # the budget ran out while grounding
        assumptions = self._set(setting, check, horizon)
        # (Asked for every model, a search for cheapest plans lists those within max_cost.)
        optimize = setting.optimize or (setting.cheapest and models == 1)
        outcome = self._solve(assumptions, budget, optimize, models, conflicts, setting.max_cost)
        work = self._conflicts()
        if outcome.satisfiable is None and moot is not None and moot():
            return outcome
        try:
            if work > mutex_after and self._mutexes is False:
                self.use_mutexes(budget)  # a hard search: the next solves get them
            if (
                work > max(mutex_after, CANONICAL_AFTER)
                and setting.canonical
                and self._canonical is False
            ):
                self.use_canonical(budget)  # a harder one: worth its grounding
        except GroundingStopped:
            pass  # the next solve waits for it, or stops
        return outcome

    def _conflicts(self) -> float:
        """The conflicts the last solve met (0 where clingo does not say)."""
        try:
            return float(self.ctl.statistics["solving"]["solvers"]["conflicts"])
        except (KeyError, RuntimeError, TypeError):
            return 0.0

    def _solve(
        self,
        assumptions,
        budget: Budget,
        optimize: bool,
        models: int,
        conflicts: int | None = None,
        bound: int | None = None,
    ) -> Outcome:
        """Solve under assumptions: the first ``models`` models (0: all), or with
        ``optimize`` an optimal one; ``bound``: only models whose first
        objective (a plan's cost) is at most this."""
        if budget.expired():
            return Outcome(None)  # cancelled or out of time: no solve starts
        try:
            self._settle(budget)
        except GroundingStopped:
            return Outcome(None)
        config = solve_configuration(self.ctl)
        if bound is not None:
            bound += COST_LEVEL_OFFSET
        if optimize:
            config.opt_mode = "opt" if bound is None else f"opt,{bound}"
        else:
            config.opt_mode = "ignore" if bound is None else f"enum,{bound}"
        config.models = "0" if optimize else str(models)
        limit = "umax" if conflicts is None else str(max(1, conflicts))
        if limit != self._solve_limit:
            config.solve_limit = limit
            self._solve_limit = limit
        found: list[list[clingo.Symbol]] = []
        costs: list[list[int]] = []

        def on_model(model: clingo.Model) -> None:
            symbols = list(model.symbols(shown=True))
            if optimize or models == 1:
                found[:] = [symbols]
                costs[:] = [list(model.cost)]
            else:
                found.append(symbols)

        handle = self.ctl.solve(assumptions=assumptions, on_model=on_model, async_=True)
        with handle:
            if not budget.wait(handle):
                return Outcome(None, found[-1] if found else [], costs[0] if costs else [])
            result = handle.get()
            core = set(handle.core()) if result.unsatisfiable and assumptions else set()
        if result.interrupted or result.unknown:
            return Outcome(None, found[-1] if found else [], costs[0] if costs else [])
        return Outcome(
            result.satisfiable,
            found[-1] if found else [],
            costs[0] if costs else [],
            found,
            self._core(assumptions, core),
        )

    def _core(self, assumptions, core: set[int]) -> list[clingo.Symbol]:
        """The atoms assumed true whose literals are in a core."""
        found = []
        for atom, value in assumptions:
            symbolic = self.ctl.symbolic_atoms[atom] if value else None
            if symbolic is not None and symbolic.literal in core:
                found.append(atom)
        return found

    @_locked
    def threads(self, count: int) -> None:
        """Solve with this many threads from now on (clasp's competing
        portfolio: the first thread to decide a horizon decides it).  More
        than one makes the plan found depend on the race, so searches that
        promise the same answer every time (restrictions, questions) keep one."""
        if count != self._threads:
            self._settle(None)
            solve_configuration(self.ctl).parallel_mode = str(count)
            self._threads = count

    @_locked
    def simple_path_exists(self, length: int, setting: Setting, budget: Budget) -> bool | None:
        """Is there a path of ``length`` actions without a repeated state, under
        the setting's question constraints (their step constraints; what holds
        only at a horizon does not apply to a path), the state extended by what
        its questions track, and (with ``cheapest`` and ``max_cost``) costing
        at most ``max_cost``?  None if the budget stopped the check.
        """
        try:
            self._prepare(setting, budget)
            self.ground_to(length, budget)
            if self._loopfree < length:
                times = range(self._loopfree + 1, length + 1)
                parts = [(LOOPFREE, [clingo.Number(t)]) for t in times]
                for value in self._inputs["simple_path"]:
                    parts += self._input_parts("simple_path", value, times)
                self._loopfree = length
                self._ground(parts, budget)
            # One set of tracked facts per set of questions grounded so far (a question
            # grounded later adds tracked facts, so it needs comparisons of its own).
            key = tuple(sorted(self._inputs["question"], key=str))
            if key not in self._configurations:
                self._configurations[key] = clingo.Number(len(self._configurations) + 1)
                self._register("simple_path", self._configurations[key], budget=budget)
        except GroundingStopped:
            return None
        assumptions = self._set(setting, None, length, self._configurations[key])
        bound = setting.max_cost if setting.cheapest else None
        return self._solve(assumptions, budget, False, 1, bound=bound).satisfiable

    # -- programs over the ground model (given plans, formulas, reasons) --------------

    def model_symbols(self) -> list[clingo.Symbol]:
        """The ground model's vocabulary (made once)."""
        if self._model_symbols is None:
            self._model_symbols = [
                symbol for signature in MODEL_VOCABULARY for symbol in self.get(*signature)
            ]
        return self._model_symbols

    @_locked
    def prepare_traces(self) -> None:
        """Index the facts about actions by action (for :meth:`plan_model_symbols`;
        made once, and early by a search that waits for an engine)."""
        if self._action_atoms is None:
            by_action: dict[clingo.Symbol, list[clingo.Symbol]] = {}
            for signature in ACTION_VOCABULARY:
                for symbol in self.get(*signature):
                    by_action.setdefault(symbol.arguments[0], []).append(symbol)
            self._state_symbols = [
                symbol
                for signature in MODEL_VOCABULARY
                if signature not in ACTION_VOCABULARY
                for symbol in self.get(*signature)
            ]
            if self.has_costs:  # (costs of other actions than the plan's are left out)
                self._state_symbols.append(clingo.Function("costs_given"))
            self._action_atoms = by_action

    def plan_model_symbols(self, plan) -> list[clingo.Symbol]:
        """The ground model's vocabulary, the facts about actions
        (:data:`ACTION_VOCABULARY`) for the plan's actions only: all that a
        trace of the plan reads (``planning/trace.lp`` joins every fact about
        an action with its occurrence), and much less than the whole model."""
        self.prepare_traces()
        assert self._state_symbols is not None and self._action_atoms is not None
        return self._state_symbols + [
            symbol
            for action in dict.fromkeys(plan)
            for symbol in self._action_atoms.get(action, ())
        ]

    def program(
        self,
        encodings: Sequence[str],
        facts: str = "",
        arguments: Sequence[str] = (),
        model: bool = True,
        symbols: Iterable[clingo.Symbol] = (),
        budget: Budget | None = None,
    ) -> clingo.Control:
        """A grounded control with the ground model's facts (unless ``model`` is
        False), the encodings and further facts: programs about one plan or one
        formula, which read the model but do not search it.  ``facts`` is text
        that clingo itself printed (atoms of answer sets); the ground model and
        ``symbols`` (plans, terms users gave) go in through the backend (no
        text to write and parse again).  Under a ``budget`` the grounding runs
        in a thread of its own, and GroundingStopped is raised if the budget
        runs out first (the control, of no other use, is left to finish its
        grounding and is dropped).  :data:`TRACE_EVENTS` is left out where the
        model has no events (nothing of it would hold)."""
        if not self.has_events:
            encodings = [name for name in encodings if name != TRACE_EVENTS]
        messages = Messages()
        ctl = clingo.Control(list(arguments), logger=messages, message_limit=20)
        try:
            for name in encodings:
                ctl.load(str(encoding(name)))
            if facts:
                ctl.add("base", [], facts)
            add_facts(ctl, self.model_symbols() if model else ())
            add_facts(ctl, symbols)
            if budget is None:
                ctl.ground([("base", [])])
                return ctl
        except RuntimeError:
            messages.raise_first("grounding failed")
        done, failure = threading.Event(), []

        def work() -> None:
            try:
                ctl.ground([("base", [])])
            except RuntimeError as error:
                failure.append(error)
            finally:
                done.set()

        threading.Thread(target=work, name="ethasp-program").start()  # (not a daemon: above)
        if not budget.wait_event(done):
            raise GroundingStopped()
        if failure:
            messages.raise_first("grounding failed")
        return ctl

    @_locked
    def trace(self, plan, encodings: Sequence[str] = ()) -> Answer:
        """A plan's evaluation (its shown atoms): its trace (``planning/trace.lp``:
        validity, final state, Caused; ``judgement/judge.lp``: the final state's
        utility), plus what further ``encodings`` over it show.

        Each plan is evaluated once: a request whose encodings an earlier
        evaluation of the plan covers reuses that one.  (The evaluations are
        kept in :mod:`ethasp.memo` by the planner, not in it: the encodings
        may be those of the layers above.)
        """
        wanted = set(encodings)
        traces = results(self).setdefault("traces", {})
        for done, answer in traces.get(plan, []):
            if wanted <= done:
                return answer
        if encodings:  # further programs may read any action of the model
            answer = self.solve_program(
                list(TRACE_ENCODINGS) + list(encodings), symbols=occurrences(plan)
            )
        else:
            answer = self.solve_program(
                TRACE_ENCODINGS,
                model=False,
                symbols=self.plan_model_symbols(plan) + occurrences(plan),
            )
        traces.setdefault(plan, []).append((wanted, answer))
        return answer

    def met(self, plan, terms: Sequence[clingo.Symbol]) -> set[clingo.Symbol]:
        """The question constraint terms that a plan meets (``met/3`` of
        ``questions/questions.lp`` run on the plan: its actions only, or its
        states too, ``questions/given.lp``, when a term is about facts; over
        :meth:`plan_model_symbols`, all that the plan's states read)."""
        from clorm import unify

        from ethasp.vocabulary import Met

        name = clingo.Function("q")
        symbols = [clingo.Function("contrast", [name, term]) for term in terms]
        symbols += self.plan_model_symbols(plan) + occurrences(plan)
        if all(term.name in ACTION_TERMS for term in terms):
            horizon = len(plan)
            facts = [f"time(0..{horizon}).", f"horizon({horizon})."]
            if horizon:
                facts += [f"step(1..{horizon}).", f"acted(1..{horizon})."]
            answer = self.solve_program(
                [QUESTIONS], "\n".join(facts) + "\n", model=False, symbols=symbols
            )
        else:
            answer = self.solve_program(GIVEN, model=False, symbols=symbols)
        found = unify([Met], answer.get("met", 3))
        return {atom.constraint.symbol for atom in found.query(Met).all()}

    def solve_program(
        self,
        encodings: Sequence[str],
        facts: str = "",
        model: bool = True,
        symbols: Iterable[clingo.Symbol] = (),
        arguments: Sequence[str] = (),
    ) -> Answer:
        """The first answer set of :meth:`program` (empty if there is none)."""
        ctl = self.program(encodings, facts, arguments, model=model, symbols=symbols)
        with ctl.solve(yield_=True) as handle:
            for answer in handle:
                return Answer(list(answer.symbols(shown=True)))
        return Answer([])

    @property
    def grounding(self) -> bool:
        """Is a grounding left running in the background (a budget ran out)?"""
        return self._pending is not None and not self._pending[0].is_set()

    @_locked
    def prepare(self, budget: Budget | None = None, relaxed: bool = False) -> bool:
        """Ground what every search needs first (relaxed reachability, the
        searches' static part; with ``relaxed``, relaxed reachability only)
        under the budget; False if it ran out first (the grounding then
        completes in the background)."""
        try:
            if relaxed:
                self._start_relaxed(budget)
            else:
                self._start_search(budget)
        except GroundingStopped:
            return False
        return True

    def _start_for(self, name: str, arity: int) -> None:
        if (name, arity) in RELAXED_ATOMS:
            self._start_relaxed()
        else:
            self._start_search()

    @_locked
    def search_atoms(self, name: str, arity: int) -> list[clingo.Symbol]:
        """The ground atoms of a predicate of the searches' static part (e.g.
        ``upper_bound/1`` of planning/relaxed.lp)."""
        self._start_for(name, arity)
        return sorted(atom.symbol for atom in self.ctl.symbolic_atoms.by_signature(name, arity))

    @_locked
    def is_fact(self, name: str) -> bool:
        """Whether a nullary atom is a fact of the grounded searches (e.g. unreachable_goal)."""
        self._start_for(name, 0)
        atom = self.ctl.symbolic_atoms[clingo.Function(name)]
        return atom is not None and atom.is_fact
