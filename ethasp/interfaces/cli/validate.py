"""``ethasp validate``: whether a sequence of actions is a plan."""

from __future__ import annotations

import argparse

from ethasp.interfaces.cli.judgements import state_text
from ethasp.interfaces.cli.models import load_model, model_options
from ethasp.interfaces.cli.options import given_plan, inherit
from ethasp.interfaces.cli.output import emit
from ethasp.planning.plan import steps


def add_parser(commands) -> None:
    check = commands.add_parser(
        "validate",
        help="check that an action sequence is a plan",
        description="Check a plan: the first inapplicable step and its failing precondition, "
        "or the goal facts left unmet. Exit code 0 for a plan, 2 otherwise.",
    )
    inherit(check, model_options())
    check.add_argument(
        "--plan",
        metavar='"A1 A2 ..."',
        help='action terms separated by spaces, e.g. "pull" or "go(a,b) pick(x)", '
        'or PDDL actions, e.g. "(go a b) (pick x)" (default: the plan '
        "the model comes with, if any)",
    )
    check.set_defaults(plan_file=None)
    check.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ethasp.planning.validation import validate

    model = load_model(args)
    if model.is_cam:
        return run_choice(args, model)
    validation = validate(model, given_plan(args, model))
    if validation.valid:
        cost = f", cost {validation.cost}" if validation.cost is not None else ""
        text = (
            f"valid plan of {steps(len(validation.plan))}{cost}; "
            f"final state: {state_text(model, validation.final_state)}"
        )
    else:
        text = f"not a plan: {validation.message(model.naming)}"
    emit(args, validation.to_json(), text)
    return 0 if validation.valid else 2


def run_choice(args: argparse.Namespace, model) -> int:
    """A causal agency model: is the plan one of its actions, and its world."""
    from ethasp.principles import causal

    plan = given_plan(args, model)
    causal.chosen_action(model, plan)  # one line and exit code 2 if not
    world, utility, caused = causal.world(model, causal.evaluation(model, plan))
    text = (
        f"valid choice: {model.naming.actions(plan)}; world: {model.naming.facts(world)} "
        f"(utility of the consequences {utility})"
    )
    data = {"plan": plan.to_list(), "valid": True, "final_state": world, "caused": caused}
    emit(args, data, text)
    return 0
