"""The goal's items, and which sets of them a permissible plan reaches.

The *items* of a goal are the model's goal facts and the constraints of the
questions asked: a question's constraint counts like a goal fact.  For a set
S of items, the model Pi_S is the model with the goal facts of S (and the
constraints of S imposed); S is *reachable* under principles when Pi_S has a
plan that the principles permit.  Reachability is monotone: a plan that
reaches S reaches every subset of S, and is permitted there too (the
principles that read the goal read it item by item: goal-deontology forbids
the plans of a goal with a bad fact, and avoid-avoidable-harm's Avoidable
holds wherever a plan reaches the goal).

One HModel answers for every S: the *soft* HModel of the principles
(:attr:`ethasp.principles.hmodel.Restriction.soft`) has the principles'
restriction and records what the question constraints need, but requires
no item.  What an item requires at the end (``goal_of/3`` of
``encodings/restrictions/hmodel.lp``) becomes a question constraint
``ends(V,B)`` of the soft HModel's planner, switched by an assumption
(``encodings/questions/questions.lp``), so that a search requires any set of
items on the one grounding.

Whether S is reachable is decided, once the depth of the soft HModel's
reachable configurations is known (:mod:`ethasp.planning.depth`), by one
solve at that horizon: every reachable configuration lies within it, so an
unsatisfiable solve is a proof, and clingo's core of the assumptions names a
subset of S that is unreachable already.  Without the depth (cut short), by
plan search (:func:`ethasp.planning.search.shortest`) and its proofs, or
``bounded``.  Where plan search hands the soft HModel to an external planner
(:mod:`ethasp.planning.systems`: S's items are then goal facts of its
task), by its search for any plan (:func:`ethasp.planning.search.any_plan`)
without the depth: the planner proves "none" by exhausting the states, where
the depth would cost every reachable state.
A question constraint that the soft HModel cannot record (a fact after a
step, of a derived variable) is searched in ASP as it is, and its sets are
always decided by plan search.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import clingo

from ethasp.planning.budget import Budget
from ethasp.planning.depth import Depth, reachable_depth
from ethasp.planning.driver.planner import Constraint, Setting
from ethasp.planning.engines.best_state import PROVEN
from ethasp.planning.model import Model
from ethasp.planning.naming import Naming
from ethasp.planning.plan import Plan
from ethasp.planning.search import (
    BOUNDED,
    DEFAULT_MAX_HORIZON,
    FOUND,
    NONE,
    SearchResult,
    any_plan,
    plans_of,
    shortest,
)
from ethasp.principles.hmodel import Literal, goal_items, hmodel
from ethasp.principles.principle import Principle
from ethasp.principles.restriction import restriction_for

GOAL = "goal"


@dataclass(frozen=True)
class Item:
    """An item of the goal: a goal fact ``goal(V,B)`` of the model, or a
    question's constraint term; ``literals`` are what the soft HModel
    requires at the end for it (empty for a constraint searched in ASP)."""

    term: clingo.Symbol
    literals: tuple[Literal, ...] = ()

    @property
    def is_goal_fact(self) -> bool:
        return self.term.name == GOAL and len(self.term.arguments) == 2

    @property
    def fact(self) -> Literal | None:
        """The goal fact (variable, value) of a goal item, else None."""
        if not self.is_goal_fact:
            return None
        variable, value = self.term.arguments
        return variable, value.name == "true"

    def text(self, naming: Naming) -> str:
        """The goal fact as a literal (``done``, ``-safe``), or the constraint
        (``used(pull)``)."""
        fact = self.fact
        if fact is not None:
            return naming.fact_of(*fact)
        return naming.constraint(self.term)


@dataclass
class Reach:
    """Whether a set of items is reachable: ``found`` (``plan`` reaches it,
    not necessarily a shortest one), ``none`` (proven: ``core``, where
    known, is a subset already unreachable) or ``bounded``."""

    status: str
    plan: Plan | None = None
    core: frozenset[int] | None = None


class GoalItems:
    """The items of a model's goal under principles and question constraints,
    and the searches that require sets of them (see the module docstring).

    Items are numbered: the goal facts in the order of their terms, then the
    question constraints in the order given.  ``best`` is utilitarianism's
    best reachable state (None without utilitarianism); where no reachable
    state is valued yet, :attr:`ready` is False and nothing is decided.
    """

    def __init__(
        self,
        model: Model,
        principles: Sequence[Principle],
        terms: Sequence[clingo.Symbol] = (),
        budget: Budget | None = None,
        max_horizon: int = DEFAULT_MAX_HORIZON,
    ):
        self.model = model
        self.principles = list(principles)
        self.budget = budget or Budget()
        self.max_horizon = max_horizon
        restriction, self.best = restriction_for(
            model, principles, terms, self.budget, max_horizon, soft=True
        )
        self.ready = restriction is not None
        self.items: list[Item] = []
        self._constraints: list[frozenset[Constraint]] = []
        self._reached: dict[frozenset[int], Reach] = {}
        # The plans found, each with every item it reaches (a witness for each
        # set of them: no search is made for a set a plan found reaches).
        self._witnesses: list[tuple[frozenset[int], Plan]] = []
        self._depth: Depth | None = None
        self.searched_in_asp = False
        if restriction is None:
            return
        self.soft = hmodel(model, restriction)
        required = goal_items(model, restriction)
        goals = sorted((term for term in required if term.name == GOAL), key=str)
        self.items = [Item(term, tuple(required[term])) for term in goals]
        for term in dict.fromkeys(terms):
            self.items.append(Item(term, tuple(required.get(term, ()))))
        wanted: dict[int, list[clingo.Symbol]] = {}
        for number, item in enumerate(self.items):
            if item.literals or item.is_goal_fact:
                wanted[number] = [_ends(variable, value) for variable, value in item.literals]
            else:  # not recorded by the soft HModel: searched in ASP as it is
                wanted[number] = [item.term]
                self.searched_in_asp = True
        every = sorted({term for terms in wanted.values() for term in terms}, key=str)
        planner = self.soft.planner
        by_term = {c.term: c for c in planner.question(every)} if every else {}
        self._constraints = [
            frozenset(by_term[term] for term in wanted[number]) for number in range(len(self.items))
        ]

    @property
    def proven_best(self) -> bool:
        """Are the plans found permissible by a proof (utilitarianism's best
        reachable utility proven, where it is needed)?"""
        return self.best is None or self.best.status == PROVEN

    def setting(self, items: Iterable[int]) -> Setting:
        """The setting that requires the items."""
        constraints = frozenset(c for number in items for c in self._constraints[number])
        return Setting(constraints=constraints)

    def depth(self) -> Depth:
        """The depth of the soft HModel's reachable configurations (once)."""
        if self._depth is None or (self._depth.horizon is None and not self.budget.expired()):
            self._depth = reachable_depth(self.soft.planner, self.budget, self.max_horizon)
        return self._depth

    @property
    def known_depth(self) -> Depth | None:
        """The depth, where a decision computed it (None otherwise)."""
        return self._depth

    def reach(self, items: frozenset[int]) -> Reach:
        """Whether a permissible plan reaches the items (kept per set): by a
        plan found before that reaches them too, else by a decision (a plan
        found is checked against every item, :meth:`_reached_by`)."""
        if items not in self._reached:
            for reached, plan in self._witnesses:
                if items <= reached:
                    return Reach(FOUND, plan)
            found = self._reach(items)
            if found.status == FOUND and found.plan is not None:
                self._witnesses.append((self._reached_by(found.plan), found.plan))
            if found.status != BOUNDED or not self.budget.expired():
                self._reached[items] = found
            return found
        return self._reached[items]

    def _reached_by(self, plan: Plan) -> frozenset[int]:
        """The items a plan of the soft HModel reaches: those whose
        constraints it meets (``questions/questions.lp``, one program for
        every item's constraints)."""
        terms = sorted({c.term for constraints in self._constraints for c in constraints}, key=str)
        met = self.soft.planner.met(plan, terms) if terms else set()
        return frozenset(
            number
            for number, constraints in enumerate(self._constraints)
            if all(c.term in met for c in constraints)
        )

    def _reach(self, items: frozenset[int]) -> Reach:
        planner = self.soft.planner
        setting = self.setting(items)
        known = self._relaxed(items)
        if known is not None:
            return Reach(NONE, core=known)
        if not self.searched_in_asp and self._by_planner(setting):
            # Any plan decides it: the planner's greedy search finds one fast, and
            # exhausts the states (pruning only relaxed dead ends) to prove none.
            result = any_plan(planner, setting, self.budget, task="goal subsets", deciding=True)
            if result.status == FOUND:
                return Reach(FOUND, result.plan)
            return Reach(result.status)
        horizon = None if self.searched_in_asp else self.depth().horizon
        if horizon is None:
            result = self._search(setting)
            if result.status == FOUND:
                return Reach(FOUND, result.plan)
            return Reach(result.status)
        outcome = planner.solve(horizon, setting, self.budget)
        if outcome.satisfiable is None:
            return Reach(BOUNDED)
        if outcome.satisfiable:
            return Reach(FOUND, plans_of([outcome.symbols])[0])
        failed = set(outcome.core)
        core = frozenset(
            number
            for number in items
            if any(_active(c) in failed for c in self._constraints[number])
        )
        return Reach(NONE, core=core)

    def relaxed_core(self, items: frozenset[int]) -> frozenset[int] | None:
        """Items among ``items`` that no plan reaches even ignoring delete
        effects (see :meth:`_reach`), else None: no search is made."""
        return self._relaxed(items)

    def _by_planner(self, setting: Setting) -> bool:
        """Does plan search hand this setting to an external planner (its
        items are goal facts of the planner's task), which proves "none"
        without the depth of every reachable configuration?"""
        from ethasp.planning import systems

        return systems.usable(self.soft.planner, setting)

    def _relaxed(self, items: frozenset[int]) -> frozenset[int] | None:
        """Items that no plan reaches even ignoring delete effects (relaxed
        reachability: the soft HModel's own goal, or an item's condition),
        known before any search and before the depth; else None."""
        planner = self.soft.planner
        if not planner.prepare(self.budget):
            return None
        if planner.is_fact("unreachable_goal"):
            return frozenset()
        failing = {
            c for c, _ in planner.impossible(sorted(self.setting(items).constraints, key=str))
        }
        for number in sorted(items):
            if self._constraints[number] & failing:
                return frozenset({number})
        return None

    def shortest(self, items: Iterable[int]) -> SearchResult:
        """A shortest permissible plan that reaches the items."""
        return self._search(self.setting(items))

    def _search(self, setting: Setting) -> SearchResult:
        # A depth found already lets the search go beyond the maximal horizon;
        # none is computed for it: a shortest plan is proven by the horizons
        # refuted below it, and the depth would cost every reachable state
        # (on driverlog p4, 67 s of diagrams for an example plan of 16 steps).
        known = self._depth.horizon if self._depth is not None else None
        depth = None if self.searched_in_asp else known
        horizon = self.max_horizon if depth is None else max(self.max_horizon, depth)
        return shortest(
            self.soft.planner,
            setting,
            self.budget,
            horizon,
            task="goal subsets",
            threads=False,
        )


def _ends(variable: clingo.Symbol, value: bool) -> clingo.Symbol:
    return clingo.Function("ends", [variable, clingo.Function("true" if value else "false")])


def _active(constraint: Constraint) -> clingo.Symbol:
    return clingo.Function("active", [constraint.question, constraint.term])
