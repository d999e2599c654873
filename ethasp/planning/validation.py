"""Validation of a given action sequence against a model (encodings/planning/trace.lp).

A PDDL task has only the action instances whose static preconditions hold
(:mod:`ethasp.planning.readers.pddl`); a plan naming another instance of an action
schema is told which static precondition fails, by a small program of its own
(encodings/planning/static.lp over the translation's rules for candidates).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import clingo
from clingo import ast
from clorm import unify

from ethasp.errors import InputError
from ethasp.planning.driver.planner import add_facts, occurrences
from ethasp.planning.messages import Messages
from ethasp.planning.model import Model
from ethasp.planning.naming import ASP_NAMING, Naming
from ethasp.planning.plan import Plan
from ethasp.planning.readers import SCHEMA_PREDICATES
from ethasp.resources import encoding
from ethasp.vocabulary import (
    Failure,
    Final,
    Invalid,
    IsPlan,
    NoSchemaInstance,
    StaticFailure,
    Unmet,
    UnmetGoal,
)

# The atoms of a plan's trace that a validation reads (planning/trace.lp).
TRACE_ATOMS = (
    ("invalid", 1),
    ("unmet", 4),
    ("failure", 1),
    ("final", 2),
    ("unmet_goal", 2),
    ("plan", 0),
)


def literal(variable: clingo.Symbol, value: str) -> str:
    """A fact as text: ``v`` for true, ``-v`` for false."""
    return str(variable) if value == "true" else f"-{variable}"


@dataclass
class Validation:
    """Whether a sequence of actions is a plan, and if not, why.

    ``failure_step`` is the first step (1-based) whose action is inapplicable,
    with ``failure_action`` and the ``unmet_preconditions`` there (literals
    ``v`` / ``-v``), ``static`` if they are static (no action changes them: the
    step names an instance of a PDDL action schema that is no action of the
    task); ``unmet_goals`` are the goal facts that the final state
    misses; ``final_state`` lists the final state's literals (when every step
    is applicable).
    """

    plan: Plan
    valid: bool
    failure_step: int | None = None
    failure_action: str | None = None
    unmet_preconditions: list[str] = field(default_factory=list)
    static: bool = False
    unmet_goals: list[str] = field(default_factory=list)
    final_state: list[str] = field(default_factory=list)
    cost: int | None = None  # the plan's cost, in a model with action costs

    def message(self, naming: Naming = ASP_NAMING) -> str:
        """One line saying why the sequence is not a plan ('' if it is one).

        ``naming`` shows actions and facts (a model's :attr:`Model.naming`).
        """
        if self.valid:
            return ""
        if self.failure_step is not None and self.failure_action is not None:
            unmet = self.unmet_preconditions
            static = (
                f" and no action changes {'it' if len(unmet) == 1 else 'them'}"
                if self.static
                else ""
            )
            return (
                f"step {self.failure_step}: action {naming.action(self.failure_action)} "
                f"is not applicable: precondition "
                f"{', '.join(map(naming.fact, unmet))} does not hold{static}"
            )
        return (
            f"the goal is not reached: {', '.join(map(naming.fact, self.unmet_goals))} "
            "does not hold at the end"
        )

    def to_json(self) -> dict:
        return {
            "plan": self.plan.to_list(),
            "valid": self.valid,
            "failure": None
            if self.failure_step is None
            else {
                "step": self.failure_step,
                "action": self.failure_action,
                "unmet_preconditions": self.unmet_preconditions,
                "static": self.static,
            },
            "unmet_goals": self.unmet_goals,
            "final_state": self.final_state,
            **({"cost": self.cost} if self.cost is not None else {}),
        }


def _problem(
    problem: clingo.Symbol, naming: Naming = ASP_NAMING, creative: frozenset = frozenset()
) -> str:
    args = problem.arguments
    if problem.name == "unknown_action" and args[0] in creative:
        return (
            f"action {naming.action(args[0])} at step {args[1]} is a creative alternative: "
            "it exists only where a repair adds it (ethasp repair)"
        )
    if problem.name == "unknown_action":
        return f"unknown action {naming.action(args[0])} at step {args[1]}"
    return str(problem)


def creative_alternatives(model: Model) -> frozenset:
    """The model's creative alternatives (actions that only repairs add)."""
    planner = model.planner
    return frozenset(
        atom.arguments[0] for arity in (1, 2) for atom in planner.get("creative", arity)
    )


def validate(model: Model, plan: Plan) -> Validation:
    """Validate a plan (its trace, computed once per plan by the model's
    planner); raise InputError if it names unknown actions."""
    model.require_planning("validating a plan")
    answer = model.planner.trace(plan)
    validation = read_validation(plan, answer.select(TRACE_ATOMS), model)
    if model.planner.has_costs:
        validation.cost = answer.get("plan_cost", 1)[0].arguments[0].number
    return validation


def plan_atoms(
    model: Model,
    plan: Plan,
    encodings,
    facts: Iterable[clingo.Symbol] = (),
    reach_goal: bool = True,
) -> list[clingo.Symbol]:
    """The shown atoms of programs about a plan (``encodings``, which include
    its trace, ``planning/trace.lp``), given further ``facts``, in one clingo
    call; InputError if the plan is not a plan of the model (without
    ``reach_goal``: if its actions cannot be executed one after the other)."""
    ctl = model.planner.program(encodings, symbols=[*occurrences(plan), *facts])
    symbols: list[clingo.Symbol] = []
    with ctl.solve(yield_=True) as handle:
        for answer in handle:
            symbols = list(answer.symbols(shown=True))
            break
    validation = read_validation(plan, symbols, model)
    executable = validation.failure_step is None and not validation.static
    if not validation.valid and (reach_goal or not executable):
        raise InputError(f"not a plan: {validation.message(model.naming)}")
    return symbols


def read_validation(
    plan: Plan, symbols: list[clingo.Symbol], model: Model | None = None
) -> Validation:
    """The validation of a plan from the shown atoms of a program with trace.lp
    (and, for a PDDL task's ``model``, of the instances of its action schemas
    that the plan names and that are no actions)."""
    facts = unify([Invalid, Unmet, Failure, Final, UnmetGoal, IsPlan], symbols)
    problems = [atom.problem.symbol for atom in facts.query(Invalid).all()]
    failures = sorted(atom.step for atom in facts.query(Failure).all())
    if problems:
        static = _static_failure(model, problems) if model is not None else None
        if static is None:
            naming = model.naming if model is not None else Naming()
            creative = creative_alternatives(model) if model is not None else frozenset()
            first = min(problems, key=lambda problem: _problem(problem))  # as ever: by text
            raise InputError(f"plan: {_problem(first, naming, creative)}")
        if not failures or static[0] < failures[0]:
            return Validation(plan, False, *static, static=True)
    if failures:
        step = failures[0]
        unmet = sorted(
            (atom for atom in facts.query(Unmet).all() if atom.step == step),
            key=lambda atom: str(atom.variable),
        )
        return Validation(
            plan,
            False,
            failure_step=step,
            failure_action=str(unmet[0].action),
            unmet_preconditions=[literal(a.variable.symbol, a.value) for a in unmet],
        )
    final = sorted(literal(atom.variable.symbol, atom.value) for atom in facts.query(Final).all())
    goals = sorted(
        literal(atom.variable.symbol, atom.value) for atom in facts.query(UnmetGoal).all()
    )
    valid = bool(list(facts.query(IsPlan).all()))
    return Validation(plan, valid, unmet_goals=goals, final_state=final)


def _static_failure(
    model: Model, problems: list[clingo.Symbol]
) -> tuple[int, str, list[str]] | None:
    """The first step whose term is an instance of a PDDL action schema that
    fails a static precondition: (step, action, failing preconditions); None
    if some problem is another one (an unknown action, a missing step)."""
    if any(problem.name != "unknown_action" for problem in problems):
        return None
    steps: dict[clingo.Symbol, int] = {}
    for problem in problems:
        action, step = problem.arguments
        steps[action] = min(step.number, steps.get(action, step.number))
    failing = static_failures(model, list(steps))
    if failing is None:
        return None
    action = min(steps, key=lambda action: steps[action])
    return steps[action], str(action), failing[action]


def static_failures(
    model: Model, terms: list[clingo.Symbol]
) -> dict[clingo.Symbol, list[str]] | None:
    """For terms that are no actions of a PDDL task: the static preconditions
    (literals ``v`` / ``-v``) that each fails, as an instance of its action
    schema; None if some term is no instance of any schema (with its equalities),
    or if the model has no schemas (it is no PDDL task)."""
    answer = _schema_program(model, terms)
    if list(answer.query(NoSchemaInstance).all()):
        return None
    failing: dict[clingo.Symbol, list[StaticFailure]] = {}
    for atom in answer.query(StaticFailure).all():
        failing.setdefault(atom.action.symbol, []).append(atom)
    if set(failing) != set(terms):
        return None
    return {
        term: [
            literal(a.variable.symbol, a.value)
            for a in sorted(atoms, key=lambda atom: str(atom.variable))
        ]
        for term, atoms in failing.items()
    }


def _schema_program(model: Model, candidates: list[clingo.Symbol]):
    """The answer set of static.lp over the model's rules for candidates (a
    PDDL translation's), the task's typing and initial state, and the
    candidates: a small program, in which no action of the task is grounded."""
    messages = Messages()
    ctl = clingo.Control(logger=messages, message_limit=20)
    try:
        with ast.ProgramBuilder(ctl) as builder:

            def keep(statement):
                if (
                    statement.ast_type == ast.ASTType.Rule
                    and _head_name(statement) in SCHEMA_PREDICATES
                ):
                    builder.add(statement)

            for source in model.sources:
                if source.path is not None:
                    ast.parse_files([str(source.path)], keep, logger=messages)
                else:
                    ast.parse_string(source.text, keep, logger=messages)
            ast.parse_files([str(encoding("planning/static.lp"))], builder.add)
        add_facts(
            ctl,
            [
                *model.planner.get("init", 1),
                *model.planner.get("has_type", 2),
                *(clingo.Function("pddl_candidate", [action]) for action in candidates),
            ],
        )
        ctl.ground([("base", [])])
    except RuntimeError:
        messages.raise_first("grounding failed")
    with ctl.solve(yield_=True) as handle:
        for answer in handle:
            return unify([NoSchemaInstance, StaticFailure], answer.symbols(shown=True))
    return unify([NoSchemaInstance, StaticFailure], [])


def _head_name(rule) -> str | None:
    head = rule.head
    if head.ast_type == ast.ASTType.Literal and head.atom.ast_type == ast.ASTType.SymbolicAtom:
        symbol = head.atom.symbol
        if symbol.ast_type == ast.ASTType.Function:
            return symbol.name
    return None
