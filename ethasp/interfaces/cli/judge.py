"""``ethasp judge``: a plan judged under principles, with reasons in words."""

from __future__ import annotations

import argparse

from ethasp.errors import InputError
from ethasp.interfaces.cli.judgements import explanation_text, judgement_text
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
    reasons_option,
)
from ethasp.interfaces.cli.output import emit, svg_option, write_picture
from ethasp.planning.search import DEFAULT_MAX_HORIZON


def add_parser(commands) -> None:
    judging = commands.add_parser(
        "judge",
        help="judge a plan under ethical principles",
        description="Judge a plan under ethical principles (default: the paper's three, "
        "deontology, do-no-harm and utilitarianism). Status: proven, or bounded "
        "(utilitarianism compared the final state only with the states searched; "
        "avoid-avoidable-harm did not learn whether the goal is reachable).",
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
        "kantian-humanity-2, double-effect, hera-utilitarianism; or a "
        "group: paper, hera, all",
    )
    judging.add_argument(
        "--max-horizon",
        type=horizon,
        default=DEFAULT_MAX_HORIZON,
        metavar="N",
        help="compare with the states reachable in at most N steps "
        f"(default {DEFAULT_MAX_HORIZON})",
    )
    inherit(judging, limit_options())
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
    report = judge(
        model,
        given_plan(args, model),
        args.principle,
        max_horizon(args),
        reasons_limit=args.reasons_limit,
        budget=budget(args),
        best=args.best,
    )
    lines = [*explanation_text(report), judgement_text(report, model)]
    write_picture(args, model, lambda pictures: pictures.report(report))
    emit(args, report.to_json(), "\n".join(lines))
    return 0
