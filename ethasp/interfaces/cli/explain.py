"""``ethasp explain``: a plan step by step (causal links, removable steps, moral side)."""

from __future__ import annotations

import argparse

from ethasp.errors import InputError
from ethasp.interfaces.cli.models import load_model, model_options
from ethasp.interfaces.cli.options import (
    budget,
    given_plan,
    inherit,
    max_horizon,
    plan_options,
    satisficing_option,
    search_options,
)
from ethasp.interfaces.cli.output import emit, svg_option, write_picture
from ethasp.planning.plan import steps
from ethasp.planning.search import find_plan


def add_parser(commands) -> None:
    explaining = commands.add_parser(
        "explain",
        help="explain a plan step by step: causal links, E-links and D-links, removable steps",
        description="Explain a plan step by step: which later steps and goal facts each step "
        "serves (causal links: step i links V=B to step j when step i sets V to "
        "B, step j's precondition needs it and no step or event between them "
        "sets V), which steps the plan does not need (removable: the plan "
        "without them is still a plan), and each step's moral side (utility, bad "
        "under deontology, the valued facts it causes); then, as plan-explainer "
        "(Lindner and Olz, RO-MAN 2022) gives them, the E-links (what enables each "
        "step: its producers, the initial state included) and the D-links (what "
        "requires it: a literal that, had it not held, would have let a "
        "subsequence of the later steps reach the goal without it). The plan is "
        "--plan, or else the plan the model comes with, or else the plan 'ethasp "
        "plan [--principle P]' makes. A HERA situation's plan may miss its goal: "
        "it is explained against the goal facts it reaches, and the ones it misses "
        "are named. See docs/questions.md.",
    )
    inherit(explaining, model_options())
    inherit(explaining, plan_options(required=False, what="the plan explained"))
    explaining.add_argument(
        "--principle",
        default=None,
        metavar="P",
        help="without --plan: explain the plan made under the principle "
        "P (default: the model's own plan, else a shortest plan)",
    )
    inherit(explaining, search_options(satisficing=True))
    inherit(explaining, satisficing_option("the plan explained, when it is searched"))
    inherit(explaining, svg_option("the plan with its E-links and D-links as arrows"))
    explaining.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """ethasp explain: a plan step by step (causal links, removable steps, moral side)."""
    from ethasp.questions.steps import explain_steps

    model = load_model(args)
    if args.plan is not None or args.plan_file is not None:
        plan = given_plan(args)
    elif args.principle is None and model.own_plan() is not None:
        plan = model.own_plan()
    elif args.principle is not None:
        from ethasp.principles.restriction import plan_with_principles

        result = plan_with_principles(
            model,
            [args.principle],
            max_horizon(args),
            budget=budget(args),
            satisficing=args.satisficing,
        )
        if result.plan is None:
            raise InputError(f"no plan to explain: {result.proof}")
        plan = result.plan
    else:
        result = find_plan(
            model, max_horizon(args), budget=budget(args), satisficing=args.satisficing
        )
        if result.plan is None:
            raise InputError(f"no plan to explain: {result.proof}")
        plan = result.plan
    explanation = explain_steps(model, plan)
    naming = model.naming
    removable = [str(step.step) for step in explanation.steps if step.removable]
    cost = f", cost {explanation.cost}" if explanation.cost is not None else ""
    lines = [f"plan of {steps(len(plan))}{cost}: {naming.actions(plan) or '(empty)'}"]
    lines += explanation.lines()
    lines.append(f"removable steps: {', '.join(removable) or 'none'}")
    if plan:
        lines.append("E-links and D-links (what enables and what requires each step):")
        lines += [f"  {line}" for line in explanation.link_lines()]
    write_picture(args, model, lambda pictures: pictures.explained(explanation))
    emit(args, explanation.to_json(naming), "\n".join(lines))
    return 0
