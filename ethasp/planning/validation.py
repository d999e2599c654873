"""Validation of a given action sequence against a model (encodings/planning/trace.lp)."""

from __future__ import annotations

from dataclasses import dataclass, field

import clingo
from clorm import unify

from ethasp.errors import InputError
from ethasp.planning.model import Model
from ethasp.planning.naming import Naming
from ethasp.planning.plan import Plan
from ethasp.vocabulary import Failure, Final, Invalid, IsPlan, Unmet, UnmetGoal

# The atoms of a plan's trace that a validation reads (planning/trace.lp).
TRACE_ATOMS = (("invalid", 1), ("unmet", 4), ("failure", 1), ("final", 2), ("unmet_goal", 2),
               ("plan", 0))


def literal(variable: clingo.Symbol, value: str) -> str:
    """A fact as text: ``v`` for true, ``-v`` for false."""
    return str(variable) if value == "true" else f"-{variable}"


@dataclass
class Validation:
    """Whether a sequence of actions is a plan, and if not, why.

    ``failure_step`` is the first step (1-based) whose action is inapplicable,
    with ``failure_action`` and the ``unmet_preconditions`` there (literals
    ``v`` / ``-v``); ``unmet_goals`` are the goal facts that the final state
    misses; ``final_state`` lists the final state's literals (when every step
    is applicable).
    """

    plan: Plan
    valid: bool
    failure_step: int | None = None
    failure_action: str | None = None
    unmet_preconditions: list[str] = field(default_factory=list)
    unmet_goals: list[str] = field(default_factory=list)
    final_state: list[str] = field(default_factory=list)

    def message(self, naming: Naming = Naming()) -> str:
        """One line saying why the sequence is not a plan ('' if it is one).

        ``naming`` shows actions and facts (a model's :attr:`Model.naming`).
        """
        if self.valid:
            return ""
        if self.failure_step is not None:
            return (f"step {self.failure_step}: action {naming.action(self.failure_action)} "
                    f"is not applicable: precondition "
                    f"{', '.join(map(naming.fact, self.unmet_preconditions))} does not hold")
        return (f"the goal is not reached: {', '.join(map(naming.fact, self.unmet_goals))} "
                "does not hold at the end")

    def to_json(self) -> dict:
        return {
            "plan": self.plan.to_list(),
            "valid": self.valid,
            "failure": None if self.failure_step is None else {
                "step": self.failure_step,
                "action": self.failure_action,
                "unmet_preconditions": self.unmet_preconditions,
            },
            "unmet_goals": self.unmet_goals,
            "final_state": self.final_state,
        }


def _problem(problem: clingo.Symbol) -> str:
    args = problem.arguments
    if problem.name == "unknown_action":
        return f"unknown action {args[0]} at step {args[1]}"
    return str(problem)


def validate(model: Model, plan: Plan) -> Validation:
    """Validate a plan (its trace, computed once per plan by the model's
    planner); raise InputError if it names unknown actions."""
    return read_validation(plan, model.planner.trace(plan).select(TRACE_ATOMS))


def read_validation(plan: Plan, symbols: list[clingo.Symbol]) -> Validation:
    """The validation of a plan from the shown atoms of a program with trace.lp."""
    facts = unify([Invalid, Unmet, Failure, Final, UnmetGoal, IsPlan], symbols)
    invalid = sorted(str(_problem(atom.problem.symbol)) for atom in facts.query(Invalid).all())
    if invalid:
        raise InputError(f"plan: {invalid[0]}")
    failures = list(facts.query(Failure).all())
    if failures:
        step = failures[0].step
        unmet = sorted((atom for atom in facts.query(Unmet).all() if atom.step == step),
                       key=lambda atom: str(atom.variable))
        return Validation(plan, False, failure_step=step, failure_action=str(unmet[0].action),
                          unmet_preconditions=[literal(a.variable.symbol, a.value) for a in unmet])
    final = sorted(literal(atom.variable.symbol, atom.value) for atom in facts.query(Final).all())
    goals = sorted(literal(atom.variable.symbol, atom.value) for atom in facts.query(UnmetGoal).all())
    valid = bool(list(facts.query(IsPlan).all()))
    return Validation(plan, valid, unmet_goals=goals, final_state=final)
