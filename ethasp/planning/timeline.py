"""A plan step by step, for pictures: what each action changes, what the plan
causes, and the moral values and words of the model's actions and facts.

The semantics come from answer sets: ``encodings/planning/steps.lp`` (with
``trace.lp``) gives the effects of each step, which of them change the state
and which produce a fact that the plan causes; ``judgement/judge.lp`` the
utility of the final state; the model's ``weight/2`` atoms (``model.lp``) the
moral values and its label facts (``encodings/reasons/labels.lp``) the words.
Python only reads the atoms back; :mod:`ethasp.interfaces.svg` draws them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import clingo
from clorm import unify

from ethasp.errors import InputError
from ethasp.planning.driver.planner import TRACE_EVENTS
from ethasp.planning.model import Model
from ethasp.planning.naming import ASP_NAMING, Naming
from ethasp.planning.plan import Plan
from ethasp.planning.validation import plan_atoms
from ethasp.vocabulary import (
    Action,
    ActionLabel,
    AgentLabel,
    Caused,
    Causing,
    Changed,
    EventChanged,
    FactLabel,
    Final,
    Goal,
    Happened,
    Init,
    Initially,
    PlanCost,
    SetAt,
    UtilityOfFinal,
    Variable,
    Weight,
)

STEPS = (
    "planning/model.lp",
    "planning/trace.lp",
    TRACE_EVENTS,
    "planning/steps.lp",
    "judgement/judge.lp",
)

# Every state of a plan is computed for its picture: longer plans are refused.
MAX_STEPS = 200


@dataclass(frozen=True)
class Fact:
    """A fact: a variable with a value (``v`` or ``-v`` as a literal)."""

    variable: clingo.Symbol
    value: bool

    def literal(self) -> str:
        return str(self.variable) if self.value else f"-{self.variable}"

    def shown(self, naming: Naming) -> str:
        return naming.fact(self.literal())

    @classmethod
    def of(cls, variable: clingo.Symbol, value: str) -> Fact:
        return cls(variable, value == "true")


def moral(utility: int) -> str:
    """The moral value of a utility: good, bad or neutral (Good/Bad/Neutral of L)."""
    return "good" if utility > 0 else "bad" if utility < 0 else "neutral"


def _element(kind: str, *arguments: clingo.Symbol) -> clingo.Symbol:
    return clingo.Function(kind, list(arguments))


@dataclass
class Valuation:
    """A model at a glance: its actions and variables, initial state and goal,
    the utility of every action and fact (``weight/2``) and their labels."""

    actions: list[clingo.Symbol]
    variables: list[clingo.Symbol]
    initial: set[clingo.Symbol]
    goal: list[Fact]
    weights: dict[clingo.Symbol, int]
    agent: tuple[str, str] | None = None
    action_labels: dict[clingo.Symbol, tuple[str, str]] = field(default_factory=dict)
    fact_labels: dict[Fact, str] = field(default_factory=dict)
    costs: dict[clingo.Symbol, int] = field(default_factory=dict)  # with action costs only

    @classmethod
    def of_model(cls, model: Model) -> Valuation:
        """Read from the model's facts (its rules grounded)."""
        facts = model.facts(
            [Action, Variable, Init, Goal, Weight, AgentLabel, ActionLabel, FactLabel]
        )
        agents = sorted((a.name, a.possessive) for a in facts.query(AgentLabel).all())
        return cls(
            actions=sorted((a.name.symbol for a in facts.query(Action).all()), key=str),
            variables=sorted((v.name.symbol for v in facts.query(Variable).all()), key=str),
            initial={i.variable.symbol for i in facts.query(Init).all()},
            goal=sorted(
                (Fact.of(g.variable.symbol, g.value) for g in facts.query(Goal).all()), key=_order
            ),
            weights={w.element.symbol: w.utility for w in facts.query(Weight).all()},
            agent=agents[0] if agents else None,
            action_labels={
                a.action.symbol: (a.phrase, a.gerund) for a in facts.query(ActionLabel).all()
            },
            fact_labels={
                Fact.of(f.variable.symbol, f.value): f.phrase for f in facts.query(FactLabel).all()
            },
            costs=model.planner.action_costs() if model.planner.has_costs else {},
        )

    def action_utility(self, action: clingo.Symbol) -> int:
        return self.weights.get(_element("action", action), 0)

    def fact_utility(self, fact: Fact) -> int:
        value = clingo.Function("true" if fact.value else "false")
        return self.weights.get(_element("fact", fact.variable, value), 0)

    def action_label(self, action: clingo.Symbol) -> str:
        return self.action_labels.get(action, ("", ""))[0]

    def action_cost(self, action: clingo.Symbol) -> int | None:
        """The cost of an action, in a model with action costs (else None)."""
        return self.costs.get(action, 0) if self.costs else None

    def fact_label(self, fact: Fact) -> str:
        return self.fact_labels.get(fact, "")

    def to_json(self, naming: Naming = ASP_NAMING) -> dict:
        """The model at a glance, named by ``naming``, each element with its
        utility, moral value and label."""

        def fact(variable: clingo.Symbol, value: bool) -> dict:
            item = Fact(variable, value)
            utility = self.fact_utility(item)
            return {
                "literal": item.literal(),
                "shown": item.shown(naming),
                "utility": utility,
                "moral": moral(utility),
                "label": self.fact_label(item),
            }

        return {
            "agent": None
            if self.agent is None
            else {"name": self.agent[0], "possessive": self.agent[1]},
            "actions": [
                {
                    "term": str(action),
                    "shown": naming.action(action),
                    "utility": self.action_utility(action),
                    "moral": moral(self.action_utility(action)),
                    "label": self.action_label(action),
                }
                for action in self.actions
            ],
            "variables": [
                {
                    "term": str(variable),
                    "shown": naming.fact(str(variable)),
                    "initial": variable in self.initial,
                    "true": fact(variable, True),
                    "false": fact(variable, False),
                }
                for variable in self.variables
            ],
            "goal": [fact(item.variable, item.value) for item in self.goal],
        }


@dataclass
class Column:
    """One step of a plan: its action, the effects that change the state
    (``changes``, the events' of the step included), those that set a value it
    already had (``kept``), and the effects that produce a fact the plan causes
    (``causing``); ``events`` happened at the step (exogenous events: a step
    after the end of the plan has only events, and its action is
    ``events(E,...)``)."""

    step: int
    action: clingo.Symbol
    changes: list[Fact]
    kept: list[Fact]
    causing: set[Fact]
    events: list[clingo.Symbol] = field(default_factory=list)


@dataclass
class Timeline:
    """A plan step by step: the initial values of the variables it changes,
    one column per step, its final state, the facts it causes (``Caused`` of
    L), the utility of the final state and, in a model with action costs, the
    plan's cost."""

    plan: Plan
    initial: list[Fact]
    columns: list[Column]
    final: list[Fact]
    caused: set[Fact]
    utility: int
    valuation: Valuation
    cost: int | None = None

    def changed_variables(self) -> list[clingo.Symbol]:
        return sorted(
            {fact.variable for column in self.columns for fact in column.changes}, key=str
        )


def _order(fact: Fact) -> tuple[str, bool]:
    return str(fact.variable), fact.value


def _facts(atoms, step: int | None = None) -> list[Fact]:
    chosen = [a for a in atoms if step is None or a.step == step]
    return sorted((Fact.of(a.variable.symbol, a.value) for a in chosen), key=_order)


def timeline(
    model: Model, plan: Plan, valuation: Valuation | None = None, reach_goal: bool = True
) -> Timeline:
    """The timeline of a plan (one clingo call); InputError if it is not a plan
    (without ``reach_goal``: a sequence of actions executable one after the
    other, such as a better plan of utilitarianism, which reaches a better
    state and perhaps not the goal) or has more than :data:`MAX_STEPS` steps."""
    if len(plan) > MAX_STEPS:
        raise InputError(
            f"the plan has {len(plan)} steps; pictures are drawn for plans of "
            f"at most {MAX_STEPS} steps"
        )
    valuation = valuation or Valuation.of_model(model)
    symbols = plan_atoms(model, plan, STEPS, reach_goal=reach_goal)
    atoms = unify(
        [
            Initially,
            SetAt,
            Changed,
            Causing,
            Caused,
            Final,
            UtilityOfFinal,
            EventChanged,
            Happened,
            PlanCost,
        ],
        symbols,
    )
    sets = list(atoms.query(SetAt).all())
    changes = list(atoms.query(Changed).all())
    causing = list(atoms.query(Causing).all())
    by_events = list(atoms.query(EventChanged).all())
    happened: dict[int, list[clingo.Symbol]] = {}
    for atom in sorted(atoms.query(Happened).all(), key=lambda a: (a.step, str(a.event))):
        happened.setdefault(atom.step, []).append(atom.event.symbol)
    columns = []
    for step, action in enumerate(plan, start=1):
        changed = _facts(changes, step)
        events = _facts(by_events, step)
        columns.append(
            Column(
                step,
                action,
                changed + [fact for fact in events if fact not in changed],
                [fact for fact in _facts(sets, step) if fact not in changed],
                set(_facts(causing, step)),
                happened.get(step, []),
            )
        )
    for step in sorted(s for s in happened if s > len(plan)):
        columns.append(
            Column(
                step,
                clingo.Function("events", happened[step]),
                _facts(by_events, step),
                [],
                set(),
                happened[step],
            )
        )
    moved = {fact.variable for column in columns for fact in column.changes}
    initial = [fact for fact in _facts(atoms.query(Initially).all()) if fact.variable in moved]
    final = _facts(atoms.query(Final).all())
    utility = next(iter(atoms.query(UtilityOfFinal).all())).utility
    costs = [atom.cost for atom in atoms.query(PlanCost).all()]
    return Timeline(
        plan,
        initial,
        columns,
        final,
        set(_facts(atoms.query(Caused).all())),
        utility,
        valuation,
        costs[0] if costs and valuation.costs else None,
    )
