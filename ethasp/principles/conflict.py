"""Minimal conflicts and maximal goal subsets: which goals no permissible plan
reaches together.

When principles permit no plan, the user learns that nothing is permissible,
but not why.  The goal's items (its facts, and the constraints of the
questions asked, :mod:`ethasp.principles.goal_items`) answer it over the whole
space of plans, as Eifler et al. (AAAI 2020) explain unsolvable planning
tasks:

* a *conflict* is a subset-minimal set of items that no permissible plan
  reaches (the empty set where no permissible plan exists even without a
  goal: the principles forbid every way the world may go);
* a *goal subset* is a subset-maximal set of items that a permissible plan
  reaches, given with a shortest such plan.

Both are enumerated together by MARCO (Liffiton et al., Constraints 2016):
the map of unexplored sets (``encodings/conflicts/map.lp``) proposes a
largest unexplored *seed*; a reachable seed grows into a goal subset (every
subset of it is then explored), an unreachable one shrinks into a conflict
(every superset of it is then explored): by deletion from clingo's core
where the decision gave one, else by insertion, which decides one
unreachable set per item of the conflict (a planner proves a set
unreachable by exhausting its states).  Every set is decided on the one
grounding of the soft HModel
(:class:`ethasp.principles.goal_items.GoalItems`), each decision a proof or
``bounded``.  With worths (what dropping each item costs) the seeds come in
decreasing worth, and the exploration can stop at the goal subsets of
greatest worth: the cheapest sets of items to drop
(:mod:`ethasp.principles.repair`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import clingo

from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import Constraint
from ethasp.planning.engines.best_state import BestReachable
from ethasp.planning.messages import Messages
from ethasp.planning.model import Model
from ethasp.planning.naming import Naming
from ethasp.planning.plan import Plan
from ethasp.planning.search import BOUNDED, DEFAULT_MAX_HORIZON, FOUND, NONE
from ethasp.principles.goal_items import GoalItems, Item, Reach
from ethasp.principles.restriction import chosen_principles
from ethasp.resources import encoding

MAP = "conflicts/map.lp"
PROVEN = "proven"
# At most this many conflicts and this many goal subsets (as many as reasons).
DEFAULT_LIMIT = 10


class Exploration:
    """MARCO over sets of items (see the module docstring).

    ``varied``: the numbers of the items that may be left out (the others,
    ``kept``, are in every set decided); ``worth``: what leaving out each
    varied item costs (positive), for the seeds of greatest worth first.
    After :meth:`run`, ``conflicts`` and ``subsets`` hold what was found (sets
    of varied items), ``exact`` says that every decision was a proof, and
    ``complete`` that every set was explored (with a ``floor`` of
    :meth:`run`: every set worth at least that much).
    """

    def __init__(
        self,
        items: GoalItems,
        varied: Sequence[int],
        kept: frozenset[int] = frozenset(),
        worth: dict[int, int] | None = None,
        unreachable: Sequence[frozenset[int]] = (),
    ):
        self.items = items
        # Sets of items (kept ones included) proven unreachable before.
        self.unreachable = set(unreachable)
        self.varied = list(varied)
        self.kept = kept
        self.worth = worth
        self.conflicts: list[frozenset[int]] = []
        self.subsets: list[frozenset[int]] = []
        self.undecided: list[frozenset[int]] = []
        self.exact = True
        self.complete = False

    def value(self, items: frozenset[int]) -> int:
        """The worth of a set of varied items (its size without worths)."""
        if self.worth is None:
            return len(items)
        return sum(self.worth[number] for number in items)

    def run(
        self,
        enough: Callable[[], bool] = lambda: False,
        floor: Callable[[], int | None] = lambda: None,
    ) -> None:
        """Explore until every set is explored, ``enough()`` says so, or the
        budget runs out; with ``floor()`` a worth, only the sets worth at
        least that much (the seeds come in decreasing worth)."""
        budget = self.items.budget
        while not budget.expired() and not enough():
            seed = self._seed()
            least = floor()
            if seed is None or (least is not None and self.value(seed) < least):
                self.complete = True
                return
            found = self._decide(seed)
            if found.status == FOUND:
                self.subsets.append(self._grow(seed))
            elif found.status == NONE:
                core = None if found.core is None else found.core & frozenset(self.varied)
                self.conflicts.append(self._shrink(seed, core))
            else:
                self.exact = False
                self.undecided.append(seed)

    # -- deciding sets ------------------------------------------------------------

    def _known(self, items: frozenset[int]) -> str | None:
        if any(conflict <= items for conflict in self.conflicts):
            return NONE
        if any(items <= subset for subset in self.subsets):
            return FOUND
        return None

    def _decide(self, items: frozenset[int]):
        if items | self.kept in self.unreachable:
            # (no search; relaxed reachability may still name a smaller core)
            return Reach(NONE, core=self.items.relaxed_core(items | self.kept))
        return self.items.reach(items | self.kept)

    def _status(self, items: frozenset[int]) -> tuple[str, frozenset[int] | None]:
        known = self._known(items)
        if known is not None:
            return known, None
        found = self._decide(items)
        if found.status == BOUNDED:
            self.exact = False
        core = None if found.core is None else found.core & frozenset(self.varied)
        return found.status, core

    def _grow(self, seed: frozenset[int]) -> frozenset[int]:
        """A goal subset that contains the reachable seed."""
        subset = seed
        for number in self.varied:
            if number in subset:
                continue
            status, _ = self._status(subset | {number})
            if status == FOUND:
                subset = subset | {number}
        return subset

    def _shrink(self, seed: frozenset[int], core: frozenset[int] | None) -> frozenset[int]:
        """A conflict within the unreachable seed: by deletion from its core
        where the decision gave one, else by insertion (:meth:`_insert`)."""
        if core is None:
            return self._insert(seed)
        conflict = seed & core
        for number in sorted(conflict):
            if number not in conflict:
                continue
            trial = conflict - {number}
            status, smaller = self._status(trial)
            if status == NONE:
                conflict = trial if smaller is None else trial & smaller
        return conflict

    def _insert(self, seed: frozenset[int]) -> frozenset[int]:
        """A conflict within the unreachable seed, item by item: the items are
        added in order to the conflict's items found so far until the set is
        unreachable; the last one added is in every conflict within that set
        (without it the set is reachable), so it joins the conflict, and the
        set becomes the seed of the next round.  The conflict is complete when
        it is unreachable itself.  Where a decision needs the whole state space
        (a planner's search that proves "none" exhausts it, and gives no core
        to start from), this decides about as many unreachable sets as the
        conflict has items, where deletion decides one for every item it
        leaves out; the reachable sets between are found fast."""
        conflict: frozenset[int] = frozenset()
        while True:
            if conflict == seed:
                return conflict  # (known unreachable)
            status, _ = self._status(conflict)
            if status == NONE:
                return conflict
            trial = conflict
            last = None
            for number in sorted(seed - conflict):
                trial = trial | {number}
                last = number
                # (the whole seed is known unreachable: no decision)
                status = NONE if trial == seed else self._status(trial)[0]
                if status == NONE:
                    break
            if last is None or status != NONE:
                # Unreachable sets only undecided (bounded) on the way: the seed
                # stands as the conflict, unproven minimal (exact is False).
                return seed
            conflict, seed = conflict | {last}, trial

    # -- the map -----------------------------------------------------------------

    def _seed(self) -> frozenset[int] | None:
        """A largest unexplored set (of greatest worth, with worths), or None."""
        ctl = clingo.Control(["--heuristic=Domain"], logger=Messages(), message_limit=20)
        ctl.load(str(encoding(MAP)))
        facts = [_atom("item", number) for number in self.varied]
        if self.worth is not None:
            facts += [_atom("worth", n, self.worth[n]) for n in self.varied]
        for index, conflict in enumerate(self.conflicts):
            name = clingo.Function("c", [clingo.Number(index)])
            facts.append(clingo.Function("conflict", [name]))
            facts += [_atom("in_conflict", name, n) for n in sorted(conflict)]
        for index, subset in enumerate(self.subsets + self.undecided):
            name = clingo.Function("s", [clingo.Number(index)])
            facts.append(clingo.Function("reached", [name]))
            facts += [_atom("in_reached", name, n) for n in sorted(subset)]
        # An undecided seed is blocked as if reached: the seeds below it are still
        # explored, and the answer is bounded (exact is False).
        with ctl.backend() as backend:
            for fact in facts:
                backend.add_rule([backend.add_atom(fact)])
        ctl.ground([("base", [])])
        config = ctl.configuration.solve
        assert isinstance(config, clingo.Configuration)
        if self.worth is None:
            config.enum_mode = "domRec"
        else:
            config.opt_mode = "opt"
        seeds: list[frozenset[int]] = []

        def on_model(model: clingo.Model) -> None:
            seeds[:] = [frozenset(s.arguments[0].number for s in model.symbols(shown=True))]

        result = ctl.solve(on_model=on_model)
        if not result.satisfiable:
            return None
        return seeds[-1]


def _atom(name: str, *arguments) -> clingo.Symbol:
    return clingo.Function(
        name,
        [clingo.Number(a) if isinstance(a, int) else a for a in arguments],
    )


# -- the answer --------------------------------------------------------------------


@dataclass
class GoalSubset:
    """A maximal set of items that a permissible plan reaches, with a shortest
    such plan (``optimal``: proven shortest; None where the search was cut
    short)."""

    items: list[Item]
    plan: Plan | None
    optimal: bool = True

    def to_json(self, naming: Naming) -> dict:
        return {
            "literals": [item.text(naming) for item in self.items],
            "plan": self.plan.to_list() if self.plan is not None else None,
        }


@dataclass
class Conflicts:
    """Which items of the goal no plan permissible under ``principles`` reaches
    together (see the module docstring).

    ``conflicts``: the minimal conflicts found (an empty conflict: no
    permissible plan exists even without a goal); ``goal_subsets``: the
    maximal goal subsets found, each with a shortest plan.  ``status`` is
    ``proven`` when every claim rests on a proof and every set was explored
    (up to the limit), else ``bounded``; ``*_truncated``: the list was cut
    at the limit (more may exist).  ``items`` are all the goal's items;
    ``best`` utilitarianism's best reachable state.
    """

    status: str
    principles: list[str]
    items: list[Item]
    conflicts: list[list[Item]] = field(default_factory=list)
    goal_subsets: list[GoalSubset] = field(default_factory=list)
    conflicts_truncated: bool = False
    goal_subsets_truncated: bool = False
    proof: str = ""
    best: BestReachable | None = None

    @property
    def empty_goal_fails(self) -> bool:
        """No permissible plan exists even without a goal (proven where
        ``status`` is proven)."""
        return any(not conflict for conflict in self.conflicts)

    def to_json(self, naming: Naming) -> dict[str, Any]:
        return {
            "conflicts": [[item.text(naming) for item in c] for c in self.conflicts],
            "goal_subsets": [subset.to_json(naming) for subset in self.goal_subsets],
            "conflicts_status": self.status,
            "conflicts_truncated": self.conflicts_truncated,
            "goal_subsets_truncated": self.goal_subsets_truncated,
            "conflicts_proof": self.proof,
        }


def goal_conflicts(
    model: Model,
    principles: Sequence[str],
    constraints: Sequence[Constraint] = (),
    max_horizon: int | None = None,
    time_limit: float | None = None,
    budget: Budget | None = None,
    limit: int = DEFAULT_LIMIT,
    unreachable: bool = False,
) -> Conflicts:
    """The minimal conflicts and maximal goal subsets of the model's goal (and
    the question ``constraints``, which count like goal facts) under the
    principles: at most ``limit`` of each (0: none computed).  ``budget`` (or
    else ``time_limit``) bounds the searches.  ``unreachable``: a search
    proved before that no plan permissible under the principles meets the
    goal and every constraint (the whole set of items is not decided again)."""
    model.require_planning("the conflicts of a goal")
    budget = budget or Budget(time_limit)
    horizon = DEFAULT_MAX_HORIZON if max_horizon is None else max_horizon
    chosen = chosen_principles(principles)
    names = [principle.name for principle in chosen]
    terms = [constraint.term for constraint in constraints]
    items = GoalItems(model, chosen, terms, budget, horizon)
    if not items.ready:
        assert items.best is not None
        return Conflicts(
            BOUNDED,
            names,
            [],
            conflicts_truncated=True,
            goal_subsets_truncated=True,
            proof=f"no reachable state valued yet: {items.best.proof}",
            best=items.best,
        )
    if limit <= 0:
        return Conflicts(
            PROVEN,
            names,
            items.items,
            conflicts_truncated=True,
            goal_subsets_truncated=True,
            proof="not computed (limit 0)",
            best=items.best,
        )
    every = frozenset(range(len(items.items)))
    exploration = Exploration(items, sorted(every), unreachable=[every] if unreachable else [])
    exploration.run(lambda: len(exploration.conflicts) > limit and len(exploration.subsets) > limit)
    subsets = []
    for subset in _ordered(exploration.subsets)[:limit]:
        if items.budget.expired():
            subsets.append(GoalSubset(_of(items, subset), None, False))
            continue
        result = items.shortest(subset)
        if result.status == FOUND:
            subsets.append(GoalSubset(_of(items, subset), result.plan, result.optimal))
        else:
            exploration.exact = False
            subsets.append(GoalSubset(_of(items, subset), None, False))
    exact = exploration.exact and items.proven_best
    status = PROVEN if exact and (exploration.complete or _cut(exploration, limit)) else BOUNDED
    return Conflicts(
        status,
        names,
        items.items,
        [_of(items, c) for c in _ordered(exploration.conflicts)[:limit]],
        subsets,
        len(exploration.conflicts) > limit or not exploration.complete,
        len(exploration.subsets) > limit or not exploration.complete,
        _proof(items, exploration, status),
        items.best,
    )


def _cut(exploration: Exploration, limit: int) -> bool:
    """Did the exploration stop at the limit (and not for lack of time)?"""
    return len(exploration.conflicts) > limit and len(exploration.subsets) > limit


def _ordered(sets: list[frozenset[int]]) -> list[frozenset[int]]:
    """Sets of items, smallest first, then by their items' numbers."""
    return sorted(sets, key=lambda s: (len(s), sorted(s)))


def _of(items: GoalItems, numbers: frozenset[int]) -> list[Item]:
    return [items.items[number] for number in sorted(numbers)]


def _proof(items: GoalItems, exploration: Exploration, status: str) -> str:
    """What the lists rest on, in words."""
    if status == BOUNDED:
        if not items.proven_best and items.best is not None:
            return (
                "plans reach the best utility found, but a better state is not excluded "
                f"({items.best.proof})"
            )
        if items.budget.expired():
            return f"{items.budget.why_stopped()} while the goal's items were explored"
        return "some sets of the goal's items were not decided within the maximal horizon"
    depth = items.known_depth
    if depth is not None and depth.horizon is not None and not items.searched_in_asp:
        return (
            f"each set of the goal's items decided by one search to horizon {depth.horizon} "
            f"({depth.proof})"
        )
    return "each set of the goal's items decided by plan search and its proofs"
