"""``ethasp judge``: a plan judged under principles, with reasons in words."""

from __future__ import annotations

import argparse

from ethasp.errors import InputError
from ethasp.interfaces.cli.judgements import choices_table, explanation_text, judgement_text
from ethasp.interfaces.cli.models import load_model, model_options
from ethasp.interfaces.cli.options import (
    budget,
    default_reasons_limit,
    given_plan,
    horizon,
    inherit,
    limit_options,
    max_horizon,
    plan_options,
    planner_option,
    reasons_option,
)
from ethasp.interfaces.cli.output import checkpoint, emit, no_picture, svg_option, write_picture
from ethasp.planning.search import DEFAULT_MAX_HORIZON


def add_parser(commands) -> None:
    judging = commands.add_parser(
        "judge",
        help="judge a plan under ethical principles",
        description="Judge a plan under ethical principles (default: the paper's three, "
        "deontology, do-no-harm and utilitarianism). Status: proven, or bounded "
        "(utilitarianism compared the final state only with the states searched; "
        "avoid-avoidable-harm did not learn whether the goal is reachable). In a "
        "causal agency model, --plan ACTION judges the choice of ACTION (default: "
        "HERA's principles for such models); without --plan, a table gives every "
        "action under every principle.",
    )
    inherit(judging, model_options())
    inherit(judging, plan_options(required=False))
    judging.add_argument(
        "--principle",
        action="append",
        metavar="NAME",
        help="a principle of encodings/principles/ (repeatable): the paper's "
        "deontology, do-no-harm, utilitarianism; HERA's hera-deontology, "
        "goal-deontology, avoid-any-harm, avoid-avoidable-harm, "
        "hera-do-no-harm, do-no-instrumental-harm, kantian-humanity, "
        "kantian-humanity-2, double-effect, hera-utilitarianism; for causal "
        "agency models also intention-deontology, "
        "do-no-instrumental-harm-without-intentions, minimize-harm, "
        "minimax-harm, pareto, discourse, universality; or a group: paper, "
        "hera, all",
    )
    judging.add_argument(
        "--max-horizon",
        type=horizon,
        default=DEFAULT_MAX_HORIZON,
        metavar="N",
        help="compare with the states reachable in at most N steps "
        f"(default {DEFAULT_MAX_HORIZON})",
    )
    inherit(judging, planner_option(), limit_options())
    judging.add_argument(
        "--best",
        action="store_true",
        help="also find a best reachable state (utilitarianism; by default "
        "the search stops at the first state that decides the verdict)",
    )
    inherit(
        judging,
        reasons_option("compute at most N sufficient and N necessary reasons per judgement"),
    )
    inherit(judging, svg_option("the plan and its judgements"))
    judging.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ethasp.reasons.reasons import judge

    model = load_model(args)
    default_reasons_limit(args)
    if args.reasons_limit < 0:
        raise InputError("--reasons-limit must be at least 0")
    if model.is_cam and args.plan is None and args.plan_file is None:
        return run_table(args, model)
    plan = given_plan(args, model)
    limits = budget(args)
    if args.reasons_limit:
        # The verdicts first (kept for the judgement with reasons below): what
        # is printed if the reasons do not come within the limits.
        verdicts = judge(
            model,
            plan,
            args.principle,
            max_horizon(args),
            reasons_limit=0,
            budget=limits,
            best=args.best,
        )
        checkpoint(verdicts.to_json(), judgement_text(verdicts, model), "the reasons were found")
    report = judge(
        model,
        plan,
        args.principle,
        max_horizon(args),
        reasons_limit=args.reasons_limit,
        budget=limits,
        best=args.best,
    )
    lines = [*explanation_text(report), judgement_text(report, model)]
    write_picture(args, model, lambda pictures: pictures.report(report))
    emit(args, report.to_json(), "\n".join(lines))
    return 0


def run_table(args: argparse.Namespace, model) -> int:
    """Every action of a causal agency model judged under every principle asked."""
    from ethasp.planning.plan import Plan
    from ethasp.principles.causal import actions
    from ethasp.reasons.reasons import judge

    reports = [
        judge(
            model,
            Plan((action,)),
            args.principle,
            reasons_limit=args.reasons_limit if args.json else 0,
        )
        for action in actions(model)
    ]
    no_picture(args)
    emit(
        args,
        {"choices": [report.to_json() for report in reports]},
        choices_table(reports, model),
    )
    return 0
