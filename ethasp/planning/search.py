"""Plan search: shortest plans by increasing horizon, with multi-shot solving.

The encodings are grounded one step at a time (see :mod:`ethasp.planning.incremental`)
and never again.  Every result carries a status:

* ``found``: a plan was found (it is a shortest one: every smaller horizon has
  none);
* ``none``: there is no plan, with a proof: the goal is not even relaxed
  reachable (``encodings/planning/relaxed.lp``), or at some horizon no simple path of
  that length exists (``encodings/planning/loopfree.lp``), so every reachable
  state has been searched;
* ``bounded``: the search stopped at ``--max-horizon`` or ``--time-limit``
  without a plan; a plan may still exist.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Iterable, Sequence

import clingo
from clorm import unify

from ethasp.errors import InputError
from ethasp.planning.incremental import CHECK, CHECK_MARKER, STEP, add_encodings, time_parts
from ethasp.planning.model import Messages, Model
from ethasp.planning.plan import Plan
from ethasp.resources import encoding
from ethasp.vocabulary import Occurs

FOUND, NONE, BOUNDED = "found", "none", "bounded"

DEFAULT_MAX_HORIZON = 64

PLANNING = ("planning/model.lp", "planning/relaxed.lp", "planning/transition.lp")
LOOPFREE = "loopfree"

# Plain shortest-plan search: redundant mutex constraints and a solver
# configuration that did best on the PDDL benchmark and on held-out instances.
SHORTEST = ("planning/mutex.lp",)
SHORTEST_OPTIONS = ("--configuration=trendy",)


@dataclass
class SearchResult:
    """The outcome of a plan search.

    ``plan`` is a shortest plan (or None), ``plans`` all shortest plans when
    they were asked for, ``horizon`` the last horizon searched, and ``proof``
    says why there is no plan (status ``none``) or what cut the search short
    (status ``bounded``).
    """

    status: str
    plan: Plan | None = None
    horizon: int = 0
    proof: str = ""
    plans: list[Plan] = field(default_factory=list)

    def to_json(self) -> dict:
        return {
            "status": self.status,
            "plan": self.plan.to_list() if self.plan is not None else None,
            "horizon": self.horizon,
            "proof": self.proof,
            **({"plans": [plan.to_list() for plan in self.plans]} if self.plans else {}),
        }


def _powers_of_two(limit: int) -> set[int]:
    result, power = set(), 1
    while power <= limit:
        result.add(power)
        power *= 2
    return result


class Search:
    """A multi-shot search over a model, plus extra encodings and facts.

    ``encodings`` are further time-indexed encodings (restrictions, question
    constraints) written with the step(T)/horizon(T) convention; ``goal``
    says whether the goal must hold at the horizon; ``optimize`` asks for an
    optimal model (for ``#maximize``/``#minimize`` statements in the
    encodings), at the horizons a driver chooses with :meth:`solve_at`;
    ``options`` are further clingo command-line options.  :meth:`run` searches
    shortest plans, horizon after horizon.
    """

    def __init__(self, model: Model, encodings: Sequence[str] = (), facts: Iterable = (),
                 goal: bool = True, optimize: bool = False,
                 assumptions: Sequence[tuple[clingo.Symbol, bool]] = (),
                 options: Sequence[str] = ()):
        self.model = model
        self.goal = goal
        self.optimize = optimize
        self.assumptions = list(assumptions)
        self.messages = Messages()
        self.ctl = model.control((["--opt-mode=opt"] if optimize else []) + list(options),
                                 self.messages)
        files = list(PLANNING) + (["planning/goal.lp"] if goal else []) + list(encodings)
        try:
            self.ctl.add("base", [], time_parts())
            add_encodings(self.ctl, [encoding(name) for name in files], on_message=self.messages)
            add_encodings(self.ctl, [encoding("planning/loopfree.lp")], step_part=LOOPFREE,
                          on_message=self.messages)
            fact_text = "".join(f"{fact}.\n" for fact in facts)
            if fact_text:
                self.ctl.add("base", [], fact_text)
            self.ctl.ground([("base", []), (CHECK, [clingo.Number(0)])])
        except RuntimeError:
            self.messages.raise_first("grounding failed")
        self.grounded = 0
        self.loopfree_grounded = 0

    # -- helpers ----------------------------------------------------------------

    def _is_fact(self, name: str) -> bool:
        atom = self.ctl.symbolic_atoms[clingo.Function(name)]
        return atom is not None and atom.is_fact

    def _ground_to(self, horizon: int) -> None:
        parts = []
        for t in range(self.grounded + 1, horizon + 1):
            parts += [(STEP, [clingo.Number(t)]), (CHECK, [clingo.Number(t)])]
        if parts:
            self._ground(parts)
        self.grounded = max(self.grounded, horizon)

    def _ground(self, parts) -> None:
        try:
            self.ctl.ground(parts)
        except RuntimeError:
            self.messages.raise_first("grounding failed")

    def _solve(self, assumptions, deadline: float | None, collect_all: bool):
        """Solve; return (satisfiable or None if interrupted, models' symbols, optimum)."""
        models: list[list[clingo.Symbol]] = []
        costs: list[list[int]] = []

        def on_model(model: clingo.Model) -> None:
            symbols = list(model.symbols(shown=True))
            if self.optimize or not collect_all:
                models[:] = [symbols]
                costs[:] = [list(model.cost)]
            else:
                models.append(symbols)

        handle = self.ctl.solve(assumptions=assumptions, on_model=on_model, async_=True)
        with handle:
            timeout = None if deadline is None else max(0.0, deadline - time.monotonic())
            finished = handle.wait(timeout) if timeout is not None else handle.wait()
            if not finished:
                handle.cancel()
                handle.wait()
                return None, models, costs[0] if costs else None
            result = handle.get()
        if result.interrupted:
            return None, models, None
        return result.satisfiable, models, costs[0] if costs else None

    def _simple_path_exists(self, horizon: int, deadline: float | None) -> bool | None:
        parts = [(LOOPFREE, [clingo.Number(t)])
                 for t in range(self.loopfree_grounded + 1, horizon + 1)]
        if parts:
            self._ground(parts)
        self.loopfree_grounded = max(self.loopfree_grounded, horizon)
        saved = self.ctl.configuration.solve.models
        self.ctl.configuration.solve.models = "1"
        simple_path = clingo.Function("simple_path")
        self.ctl.assign_external(simple_path, True)
        optimize = self.optimize
        self.optimize = False
        try:
            satisfiable, _, _ = self._solve(self.assumptions, deadline, collect_all=False)
        finally:
            self.optimize = optimize
            self.ctl.assign_external(simple_path, False)
            self.ctl.configuration.solve.models = saved
        return satisfiable

    # -- single horizons (for drivers that choose their own horizons) -----------

    def solve_at(self, horizon: int, deadline: float | None = None
                 ) -> tuple[bool | None, list[clingo.Symbol], list[int] | None]:
        """Ground up to ``horizon`` and solve with that horizon, once.

        Returns (satisfiable, or None if the deadline interrupted the solve;
        the shown atoms of the last model found, an optimal one when
        ``optimize`` and not interrupted; that model's cost).  The horizon's
        external is released afterwards, so every horizon is solved at most once.
        """
        self._ground_to(horizon)
        self.ctl.configuration.solve.models = "0" if self.optimize else "1"
        query = clingo.Function(CHECK_MARKER, [clingo.Number(horizon)])
        self.ctl.assign_external(query, True)
        try:
            satisfiable, models, cost = self._solve(self.assumptions, deadline, False)
        finally:
            self.ctl.release_external(query)
        return satisfiable, (models[0] if models else []), cost

    def simple_path_exists(self, length: int, deadline: float | None = None) -> bool | None:
        """Is there a path of ``length`` actions without a repeated state?

        None if the deadline interrupted the check.  Call it between solves at
        single horizons (no horizon external may be true meanwhile).
        """
        self._ground_to(length)
        return self._simple_path_exists(length, deadline)

    # -- the search -------------------------------------------------------------

    def run(self, max_horizon: int = DEFAULT_MAX_HORIZON, time_limit: float | None = None,
            all_plans: bool = False) -> SearchResult:
        """Search horizons 0, 1, ... up to max_horizon for a shortest plan."""
        if self.optimize:
            raise ValueError("Search.run looks for plans, not optima: use solve_at")
        if max_horizon < 0:
            raise InputError("the maximal horizon must be at least 0")
        deadline = None if time_limit is None else time.monotonic() + time_limit
        if self.goal and self._is_fact("unreachable_goal"):
            return SearchResult(NONE, horizon=0,
                                proof="the goal is unreachable even ignoring delete effects")
        self.ctl.configuration.solve.models = "0" if all_plans else "1"
        checkpoints = _powers_of_two(max_horizon) | {max_horizon}
        for horizon in range(0, max_horizon + 1):
            self._ground_to(horizon)
            query = clingo.Function(CHECK_MARKER, [clingo.Number(horizon)])
            self.ctl.assign_external(query, True)
            satisfiable, models, _ = self._solve(self.assumptions, deadline, all_plans)
            if satisfiable is None:
                return SearchResult(BOUNDED, horizon=horizon,
                                    proof=f"time limit reached at horizon {horizon}")
            if satisfiable:
                return self._found(horizon, models, all_plans)
            self.ctl.release_external(query)
            if horizon in checkpoints and horizon > 0:
                exists = self._simple_path_exists(horizon, deadline)
                if exists is None:
                    return SearchResult(BOUNDED, horizon=horizon,
                                        proof=f"time limit reached at horizon {horizon}")
                if not exists:
                    return SearchResult(
                        NONE, horizon=horizon,
                        proof=f"no plan up to horizon {horizon}, and no path of {horizon} steps "
                              "without a repeated state: every reachable state was searched")
        return SearchResult(BOUNDED, horizon=max_horizon,
                            proof=f"no plan up to horizon {max_horizon} (the maximal horizon)")

    def _found(self, horizon: int, models, all_plans: bool) -> SearchResult:
        plans = [Plan.from_occurs(unify([Occurs], symbols).query(Occurs).all())
                 for symbols in models]
        unique = list(dict.fromkeys(plans))
        return SearchResult(FOUND, plan=unique[0], horizon=horizon,
                            plans=unique if all_plans else [])


def find_plan(model: Model, max_horizon: int = DEFAULT_MAX_HORIZON,
              time_limit: float | None = None, all_plans: bool = False) -> SearchResult:
    """A shortest plan for the model (all shortest plans with ``all_plans``)."""
    search = Search(model, SHORTEST, options=SHORTEST_OPTIONS)
    return search.run(max_horizon, time_limit, all_plans)
