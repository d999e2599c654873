"""``ethasp plan``: a shortest plan, or (``--principle``) a shortest plan a principle permits."""

from __future__ import annotations

import argparse

from ethasp.errors import InputError
from ethasp.interfaces.cli.judgements import explanation_text, judgement_text
from ethasp.interfaces.cli.models import load_model, model_options
from ethasp.interfaces.cli.options import (
    budget,
    default_reasons_limit,
    inherit,
    max_horizon,
    reasons_option,
    satisficing_option,
    search_options,
)
from ethasp.interfaces.cli.output import emit, no_picture, svg_option, write_picture
from ethasp.planning.model import Model
from ethasp.planning.plan import steps
from ethasp.planning.search import DEFAULT_MAX_HORIZON, FOUND, find_plan


def add_parser(commands) -> None:
    plan = commands.add_parser(
        "plan",
        help="find a shortest plan (or any plan, fast: --satisficing)",
        description="Find a shortest plan (with --satisficing: some plan, found fast and not "
        "proven shortest). Status: found, none (proven: no plan exists) "
        "or bounded (none up to the horizon or time limit; one may still exist).",
    )
    inherit(plan, model_options())
    inherit(plan, search_options(satisficing=True))
    plan.add_argument("--all", action="store_true", help="list all shortest plans")
    inherit(plan, satisficing_option())
    plan.add_argument(
        "--principle",
        action="append",
        metavar="NAME",
        help="find a plan permissible under the principle NAME (deontology, "
        "utilitarianism, do-no-harm, or one of HERA's with a restriction: "
        "hera-deontology, goal-deontology, avoid-any-harm, "
        "avoid-avoidable-harm, hera-utilitarianism; repeat it to "
        "require several)",
    )
    inherit(
        plan,
        reasons_option(
            "with --principle: compute at most N sufficient and N "
            "necessary reasons for the plan's judgement"
        ),
    )
    inherit(plan, svg_option("the plan found (with --principle: and its judgement)"))
    plan.set_defaults(run=run)


def _unproven(optimal: bool) -> str:
    """What a plan's text says when an any-plan search found it."""
    return "" if optimal else " (not proven shortest)"


def run(args: argparse.Namespace) -> int:
    model = load_model(args)
    if args.principle:
        return run_permissible(args, model)
    if model.is_cam:  # every action is a choice of its own
        from ethasp.principles.restriction import plan_with_principles

        result = plan_with_principles(model, [], all_plans=True)
        no_picture(args)
        choices = ", ".join(model.naming.actions(plan) for plan in result.plans)
        emit(args, result.to_json(), f"choices of one action each: {choices}")
        return 0
    if args.all and args.satisficing:
        raise InputError("--all lists all shortest plans; it cannot go with --satisficing")
    result = find_plan(
        model,
        max_horizon(args),
        all_plans=args.all,
        budget=budget(args),
        satisficing=args.satisficing,
    )
    if result.status == FOUND:
        if args.all:
            lines = [f"{len(result.plans)} shortest plans of {steps(result.horizon)}:"]
            lines += [
                f"  {model.naming.actions(plan)}" if len(plan) else "  (empty plan)"
                for plan in result.plans
            ]
            text = "\n".join(lines)
        else:
            text = (
                f"plan of {steps(len(result.plan))}{_unproven(result.optimal)}: "
                f"{model.naming.actions(result.plan)}"
                if len(result.plan)
                else "plan of 0 steps: the goal holds initially"
            )
    elif result.status == "none":
        text = f"no plan exists: {result.proof}"
    else:
        text = f"bounded: {result.proof}; a plan may still exist"
    if result.status == FOUND:
        write_picture(
            args,
            model,
            lambda pictures: pictures.plan(
                result.plan,
                f"plan of {steps(len(result.plan))}{_unproven(result.optimal)}: "
                f"{model.naming.actions(result.plan) or '(empty plan)'}",
            ),
        )
    else:
        no_picture(args)
    emit(args, result.to_json(), text)
    return 0


def run_permissible(args: argparse.Namespace, model: Model) -> int:
    """ethasp plan --principle: a shortest HPlan, then its judgement."""
    from ethasp.principles.restriction import plan_with_principles
    from ethasp.reasons.reasons import judge

    limits = budget(args)
    if args.all and args.satisficing:
        raise InputError("--all lists all shortest plans; it cannot go with --satisficing")
    result = plan_with_principles(
        model,
        args.principle,
        max_horizon(args),
        all_plans=args.all,
        budget=limits,
        satisficing=args.satisficing,
    )
    under = " and ".join(result.principles)
    data = result.to_json()
    if result.status == FOUND:
        shown = [
            model.naming.actions(plan) if len(plan) else "(empty plan)"
            for plan in (result.plans if args.all else [result.plan])
        ]
        head = (
            f"plan of {steps(len(result.plan))}{_unproven(result.optimal)} permissible "
            f"under {under}"
        )
        lines = (
            [f"{len(shown)} shortest plans of {steps(result.horizon)} permissible under {under}:"]
            + [f"  {plan}" for plan in shown]
            if args.all
            else [f"{head}: {shown[0]}"]
        )
        # The judgement of the (first) HPlan, as ethasp judge prints it, minus its plan line.
        default_reasons_limit(args)
        report = judge(
            model,
            result.plan,
            result.principles,
            DEFAULT_MAX_HORIZON if args.max_horizon is None else args.max_horizon,
            reasons_limit=args.reasons_limit,
            budget=limits,
        )
        data["judgements"] = report.to_json()["judgements"]
        lines += explanation_text(report) + judgement_text(report, model).split("\n")[1:]
        write_picture(args, model, lambda pictures: pictures.report(report, f"{head}: {shown[0]}"))
    elif result.status == "none":
        lines = [f"no permissible plan exists: {result.proof}"]
    elif result.plan is not None:
        # Permissible as far as searched: the search could not exclude what
        # would make it impermissible (a better reachable state).
        shown = model.naming.actions(result.plan) if len(result.plan) else "(empty plan)"
        lines = [
            f"bounded: plan of {steps(len(result.plan))}, permissible under {under} as far "
            f"as searched (not proven): {shown}",
            f"  final state utility {result.utility}; {result.proof}",
        ]
    else:
        lines = [f"bounded: {result.proof}; a permissible plan may still exist"]
    if result.status != FOUND and result.best is not None and result.best.utility is not None:
        lines.append(
            f"best reachable utility: {result.best.utility} ({result.best.status}: "
            f"{result.best.proof})"
        )
    if result.status != FOUND:
        no_picture(args)
    emit(args, data, "\n".join(lines))
    return 0
