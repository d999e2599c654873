"""Repairs: the cheapest changes of a model that admit a permissible plan.

A model declares the changes it allows, each with a cost
(``encodings/planning/model.lp``): a changeable initial value, a creative
alternative (an action that exists only where a repair adds it, HERA's
creative alternatives), a preventable event, and every goal fact that is not
fixed may be dropped.  A *repair* is a set of these changes; the *repaired
model* is the model after them (``encodings/repairs/repaired.lp``), a model
of its own.  A repair *admits* a permissible plan when the repaired model
has a plan that the principles permit there (judged in the repaired model:
utilitarianism compares with the states reachable in it).  Its cost is the
sum of its changes' costs; the answer is every repair of least cost (up to a
limit), each with a plan it admits, which the principles' judgement in the
repaired model confirms.

**The search.**  The changes other than dropped goal facts (the *model
changes*) are tried in increasing cost, each set once
(``encodings/repairs/changes.lp``, clingo optimisation).  For each set, the
cheapest goal facts to drop are the complements of the goal subsets of
greatest worth (worth: what dropping the goal facts costs), found by MARCO
with worths over the goal's items of the repaired model
(:class:`ethasp.principles.conflict.Exploration`), on one grounding of its
soft HModel.  Once a repair of total cost c is known, sets of model changes
costing more than c are not tried: dropped goal facts cost nothing less than
0, so every repair of cost c has been found when every set of model changes
of cost at most c was tried.  The answer is ``found`` (proven least) when
every decision was a proof and every cheaper set was tried, ``none`` when no
allowed change admits a permissible plan (proven), else ``bounded``.
Question constraints, where given, are kept: the repaired model's plan must
meet them.

**Repaired towards a plan.**  Given a plan, each repair's plan is one that
keeps as much of the given plan as it can: of least plan stability distance
to it (Fox, Gerevini, Long and Serina, ICAPS 2006: the actions of either plan
that the other lacks, counted with their repetitions), then shortest; the
repairs are listed by that distance.  A plan of distance d has at most d
steps more than the given plan, so a search to the horizon that the distance
of a shortest plan allows proves the least distance
(``encodings/repairs/towards.lp``, clingo optimisation).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import clingo

from ethasp.errors import InputError
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import MODEL_VOCABULARY, Constraint
from ethasp.planning.model import Model
from ethasp.planning.naming import Naming
from ethasp.planning.plan import Plan
from ethasp.planning.search import BOUNDED, DEFAULT_MAX_HORIZON, FOUND, NONE
from ethasp.principles.conflict import Exploration
from ethasp.principles.goal_items import GoalItems
from ethasp.principles.judgement import Judgement, judge
from ethasp.principles.restriction import chosen_principles

REPAIRED = ("planning/model.lp", "repairs/repaired.lp")
CHANGES = ("planning/model.lp", "repairs/changes.lp")
TOWARDS = (
    "planning/model.lp",
    "planning/relaxed.lp",
    "planning/transition.lp",
    "planning/events.lp",
    "planning/goal.lp",
    "repairs/towards.lp",
)
# At most this many repairs of least cost.
DEFAULT_LIMIT = 10
# What a model declares about the changes a repair may make (planning/model.lp).
DECLARATIONS = (
    ("changeable", 1),
    ("changeable", 2),
    ("creative", 1),
    ("creative", 2),
    ("preventable", 1),
    ("preventable", 2),
    ("goal_cost", 3),
    ("goal_fixed", 2),
)


@dataclass(frozen=True)
class Change:
    """One change a repair makes: ``initial(V)``, ``add(A)``, ``prevent(E)`` or
    ``drop(V,B)``, with its cost; ``initially`` is V's initial value in the
    model (for ``initial(V)``)."""

    term: clingo.Symbol
    cost: int
    initially: bool = False

    @property
    def kind(self) -> str:
        return self.term.name

    def text(self, naming: Naming) -> str:
        subject = self.term.arguments[0]
        if self.kind == "initial":
            return f"start with {naming.fact_of(subject, not self.initially)}"
        if self.kind == "add":
            return f"add the creative alternative {naming.action(subject)}"
        if self.kind == "prevent":
            return f"prevent the event {naming.name(subject)}"
        return f"drop the goal {naming.fact_of(subject, self.term.arguments[1].name == 'true')}"

    def to_json(self, naming: Naming) -> dict[str, Any]:
        subject = self.term.arguments[0]
        data: dict[str, Any] = {"kind": self.kind, "cost": self.cost}
        if self.kind == "initial":
            data["fact"] = naming.fact_of(subject, not self.initially)
        elif self.kind == "add":
            data["action"] = naming.action(subject)
        elif self.kind == "prevent":
            data["event"] = naming.name(subject)
        else:
            data["fact"] = naming.fact_of(subject, self.term.arguments[1].name == "true")
        data["text"] = self.text(naming)
        return data


@dataclass
class Repair:
    """A repair of least cost: its changes, the repaired model, a plan it
    admits (``optimal``: a shortest one, or with a given plan one of least
    ``distance`` to it, proven; None where the search was cut short) and the
    principles' judgements of that plan in the repaired model."""

    changes: list[Change]
    cost: int
    model: Model
    plan: Plan | None = None
    optimal: bool = True
    distance: int | None = None
    judgements: list[Judgement] = field(default_factory=list)

    def to_json(self, naming: Naming) -> dict[str, Any]:
        data: dict[str, Any] = {
            "changes": [change.to_json(naming) for change in self.changes],
            "cost": self.cost,
            "plan": self.plan.to_list() if self.plan is not None else None,
            "optimal": self.optimal,
            "judgements": [judgement.to_json() for judgement in self.judgements],
        }
        if self.distance is not None:
            data["distance"] = self.distance
        return data


@dataclass
class RepairResult:
    """The least repairs (see the module docstring).  ``status``: ``found``
    (the repairs are of least cost, proven), ``none`` (proven: no allowed
    change admits a permissible plan), ``bounded`` (a limit struck: cheaper
    repairs, or any repair, may exist); ``truncated``: more repairs of the
    least cost exist than listed; ``allowed``: every change the model
    allows; ``towards``: the given plan."""

    status: str
    principles: list[str]
    repairs: list[Repair]
    cost: int | None
    proof: str
    allowed: list[Change]
    truncated: bool = False
    towards: Plan | None = None

    def to_json(self, naming: Naming) -> dict[str, Any]:
        data: dict[str, Any] = {
            "status": self.status,
            "principles": list(self.principles),
            "cost": self.cost,
            "repairs": [repair.to_json(naming) for repair in self.repairs],
            "truncated": self.truncated,
            "proof": self.proof,
            "allowed": [change.to_json(naming) for change in self.allowed],
        }
        if self.towards is not None:
            data["towards"] = self.towards.to_list()
        return data


def allowed_changes(model: Model) -> list[Change]:
    """The changes the model allows (``repair_change/2``), each with its cost."""
    initially = {atom.arguments[0] for atom in model.planner.get("init", 1)}
    changes = []
    for atom in model.planner.get("repair_change", 2):
        term, cost = atom.arguments
        changes.append(Change(term, cost.number, term.arguments[0] in initially))
    return sorted(changes, key=lambda change: str(change.term))


def declares_changes(model: Model) -> bool:
    """Does the model declare what a repair may change (more than dropping goal
    facts at cost 1)?"""
    return any(model.planner.get(*signature) for signature in DECLARATIONS)


def repaired_model(model: Model, changes: Sequence[Change]) -> Model:
    """The model after the changes (``encodings/repairs/repaired.lp``): a
    model of facts of its own (the model itself without changes)."""
    if not changes:
        return model
    planner = model.planner
    inputs = [clingo.Function("repair", [change.term]) for change in changes]
    answer = planner.solve_program(REPAIRED, symbols=inputs)
    unknown = answer.get("repair_unknown", 1)
    if unknown:
        raise InputError(f"no change the model allows: {unknown[0].arguments[0]}")
    removed = {atom.arguments[0] for atom in answer.get("repair_removes", 1)}
    facts = [
        atom
        for signature in MODEL_VOCABULARY
        for atom in planner.get(*signature)
        if atom not in removed
    ]
    facts += [atom.arguments[0] for atom in answer.get("repair_adds", 1)]
    name = "<" + ", ".join(str(change.term) for change in changes) + ">"
    kind = "situation" if model.is_situation else "repaired"
    return Model.of_facts(f"{model_name(model)} repaired: {name}", facts, model.naming, kind)


def model_name(model: Model) -> str:
    return ", ".join(source.name for source in model.sources) or "<model>"


def _next_changes(
    model: Model, allowed: dict[clingo.Symbol, Change], tried: list[frozenset[clingo.Symbol]]
) -> tuple[frozenset[clingo.Symbol], int] | None:
    """The cheapest set of model changes not tried yet (changes.lp), or None."""
    symbols = []
    for index, changes in enumerate(tried):
        name = clingo.Number(index)
        symbols.append(clingo.Function("tried", [name]))
        symbols += [clingo.Function("tried_change", [name, term]) for term in sorted(changes)]
    ctl = model.planner.program(CHANGES, symbols=symbols)
    config = ctl.configuration.solve
    assert isinstance(config, clingo.Configuration)
    config.opt_mode = "opt"
    found: list[frozenset[clingo.Symbol]] = []

    def on_model(answer: clingo.Model) -> None:
        found[:] = [frozenset(atom.arguments[0] for atom in answer.symbols(shown=True))]

    if not ctl.solve(on_model=on_model).satisfiable:
        return None
    chosen = found[-1]
    return chosen, sum(allowed[term].cost for term in chosen)


@dataclass
class _Found:
    changes: frozenset[clingo.Symbol]
    drops: list[clingo.Symbol]
    items: GoalItems
    required: frozenset[int]


def repair(
    model: Model,
    principles: Sequence[str],
    plan: Plan | None = None,
    constraints: Sequence[Constraint] = (),
    max_horizon: int | None = None,
    time_limit: float | None = None,
    budget: Budget | None = None,
    limit: int = DEFAULT_LIMIT,
) -> RepairResult:
    """The repairs of least cost that admit a plan permissible under the
    principles (see the module docstring): at most ``limit`` of them, each with
    a plan (with ``plan``: the one that keeps the most of it); ``constraints``
    (of questions) are kept."""
    model.require_planning("repairing a model")
    budget = budget or Budget(time_limit)
    horizon = DEFAULT_MAX_HORIZON if max_horizon is None else max_horizon
    chosen = chosen_principles(principles)
    names = [principle.name for principle in chosen]
    terms = [constraint.term for constraint in constraints]
    allowed = allowed_changes(model)
    by_term = {change.term: change for change in allowed}
    tried: list[frozenset[clingo.Symbol]] = []
    least: int | None = None
    found: list[_Found] = []
    exact, complete = True, False
    while not budget.expired():
        candidate = _next_changes(model, by_term, tried)
        if candidate is None or (least is not None and candidate[1] > least):
            complete = True
            break
        changes, cost = candidate
        tried.append(changes)
        repaired = repaired_model(model, [by_term[term] for term in sorted(changes)])
        items = GoalItems(repaired, chosen, terms, budget, horizon)
        if not items.ready:
            exact = False
            continue
        worth, required = {}, set()
        for number, item in enumerate(items.items):
            fact = item.fact
            drop = _drop(fact) if fact is not None else None
            if drop is not None and drop in by_term:
                worth[number] = by_term[drop].cost
            else:
                required.add(number)
        whole = sum(worth.values())
        exploration = Exploration(items, sorted(worth), frozenset(required), worth)

        # Only goal subsets worth at least what the least repair so far allows.
        need = None if least is None else whole - (least - cost)

        def floor(exploration: Exploration = exploration, need: int | None = need) -> int | None:
            best = max((exploration.value(s) for s in exploration.subsets), default=None)
            return max((v for v in (best, need) if v is not None), default=None)

        exploration.run(floor=floor)
        exact = exact and exploration.exact and exploration.complete and items.proven_best
        if not exploration.subsets:
            continue
        kept = max(exploration.value(s) for s in exploration.subsets)
        total = cost + whole - kept
        if least is None or total < least:
            least, found = total, []
        if total == least:
            for subset in exploration.subsets:
                if exploration.value(subset) == kept:
                    drops = [_drop(items.items[n].fact) for n in sorted(set(worth) - subset)]
                    found.append(_Found(changes, drops, items, subset | frozenset(required)))
    repairs = [_made(model, entry, by_term, chosen, plan, budget, horizon) for entry in found]
    repairs.sort(key=lambda r: (_order(r), [str(c.term) for c in r.changes]))
    proven = exact and complete
    if not repairs:
        status = NONE if proven else BOUNDED
        proof = (
            "no change the model allows admits a permissible plan: every set of changes was tried"
            if proven
            else _cut(budget)
        )
        return RepairResult(status, names, [], None, proof, allowed, towards=plan)
    proof = (
        f"no repair costs less than {least}: every set of changes costing less was tried"
        if proven
        else f"repairs of cost {least} found, but a cheaper one is not excluded ({_cut(budget)})"
    )
    return RepairResult(
        FOUND if proven else BOUNDED,
        names,
        repairs[:limit],
        least,
        proof,
        allowed,
        truncated=len(repairs) > limit,
        towards=plan,
    )


def _cut(budget: Budget) -> str:
    if budget.expired():
        return budget.why_stopped()
    return "some repairs were not decided within the maximal horizon"


def _drop(fact) -> clingo.Symbol:
    variable, value = fact
    return clingo.Function("drop", [variable, clingo.Function("true" if value else "false")])


def _order(repair: Repair) -> tuple:
    distance = repair.distance if repair.distance is not None else 0
    length = len(repair.plan) if repair.plan is not None else 0
    return (distance, length)


def _made(
    model: Model,
    entry: _Found,
    by_term: dict[clingo.Symbol, Change],
    chosen,
    towards: Plan | None,
    budget: Budget,
    horizon: int,
) -> Repair:
    """A repair found: its changes, repaired model, plan and judgements."""
    changes = [by_term[term] for term in sorted(entry.changes)] + [
        by_term[term] for term in entry.drops
    ]
    cost = sum(change.cost for change in changes)
    repaired = repaired_model(model, changes)
    result = entry.items.shortest(entry.required)
    if result.status != FOUND:
        return Repair(changes, cost, repaired, None, False)
    plan, optimal, gap = result.plan, result.optimal, None
    assert plan is not None
    if towards is not None:
        plan, optimal, gap = _towards(entry.items, entry.required, plan, towards, budget)
    names = [principle.name for principle in chosen]
    report = judge(repaired, plan, names, horizon, budget=budget)
    if not all(judgement.permissible for judgement in report.judgements):
        raise RuntimeError(f"the plan {plan} of a repair is not permissible in the repaired model")
    return Repair(changes, cost, repaired, plan, optimal, gap, report.judgements)


def distance(plan: Plan, given: Plan) -> int:
    """The plan stability distance of two plans (see the module docstring)."""
    counts: dict[clingo.Symbol, int] = {}
    for action in plan:
        counts[action] = counts.get(action, 0) + 1
    for action in given:
        counts[action] = counts.get(action, 0) - 1
    return sum(abs(count) for count in counts.values())


def _towards(
    items: GoalItems, required: frozenset[int], shortest: Plan, given: Plan, budget: Budget
) -> tuple[Plan, bool, int]:
    """A plan that reaches the items, of least distance to the given plan, then
    shortest; whether that is proven; its distance."""
    first = distance(shortest, given)
    if first == 0 or items.searched_in_asp:
        return shortest, first == 0, first
    planner = items.soft.planner
    steps = len(given) + first - 1
    horizon = max(steps, planner.last_event)
    literals = {literal for n in required for literal in items.items[n].literals}
    facts = [f"time(0..{horizon}).", f"horizon({horizon})."]
    if horizon:
        facts.append(f"step(1..{horizon}).")
    if horizon > steps:
        facts.append(f":- acted(T), T > {steps}, step(T).")
    symbols = [
        clingo.Function("goal", [v, clingo.Function("true" if b else "false")])
        for v, b in sorted(literals)
    ]
    symbols += planner.get("goal_utility", 1)
    symbols += [
        clingo.Function("towards_step", [clingo.Number(step), action])
        for step, action in enumerate(given, start=1)
    ]
    ctl = planner.program(TOWARDS, "\n".join(facts) + "\n", symbols=symbols)
    config = ctl.configuration.solve
    assert isinstance(config, clingo.Configuration)
    config.opt_mode = "opt"
    best: list[list[clingo.Symbol]] = []

    def on_model(answer: clingo.Model) -> None:
        best[:] = [list(answer.symbols(atoms=True))]

    handle = ctl.solve(on_model=on_model, async_=True)
    with handle:
        finished = budget.wait(handle)
        if finished:
            handle.get()
    if not best:
        return shortest, finished, first
    occurs = sorted(
        (atom.arguments[1].number, atom.arguments[0])
        for atom in best[-1]
        if atom.name == "occurs" and len(atom.arguments) == 2
    )
    plan = Plan(tuple(action for _, action in occurs))
    if distance(plan, given) > first:  # no plan within the horizon is closer
        return shortest, finished, first
    return plan, finished, distance(plan, given)
