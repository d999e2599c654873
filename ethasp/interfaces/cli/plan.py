"""``ethasp plan``: a shortest plan, or (``--principle``) a shortest plan a principle permits;
with action costs, cheapest plans, and what the principle costs."""

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
from ethasp.interfaces.cli.output import (
    checkpoint,
    emit,
    no_picture,
    svg_option,
    write_picture,
)
from ethasp.planning.model import Model
from ethasp.planning.plan import steps
from ethasp.planning.search import DEFAULT_MAX_HORIZON, FOUND, find_plan


def add_parser(commands) -> None:
    plan = commands.add_parser(
        "plan",
        help="find a shortest plan (or any plan, fast: --satisficing)",
        description="Find a shortest plan (with --satisficing: some plan, found fast and not "
        "proven shortest); in a model with action costs (cost/2, or PDDL's :action-costs "
        "with (:metric minimize (total-cost))), a cheapest plan, and with --principle also "
        "what the principles cost. Status: found, none (proven: no plan exists) "
        "or bounded (none up to the horizon or time limit; one may still exist).",
    )
    inherit(plan, model_options())
    inherit(plan, search_options(satisficing=True))
    plan.add_argument(
        "--all",
        action="store_true",
        help="list all shortest plans (with action costs: all cheapest plans of fewest steps)",
    )
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


def _unproven(optimal: bool, cost: int | None = None) -> str:
    """What a plan's text says when an any-plan search found it."""
    return "" if optimal else f" (not proven {'shortest' if cost is None else 'cheapest'})"


def plan_head(length: int, cost: int | None, optimal: bool = True) -> str:
    """``plan of 3 steps``, with its cost in a model with action costs."""
    costs = f", cost {cost}" if cost is not None else ""
    return f"plan of {steps(length)}{costs}{_unproven(optimal, cost)}"


def _kind(cost: int | None) -> str:
    return "shortest" if cost is None else "cheapest"


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
            length = len(result.plan) if result.cost is not None else result.horizon
            costs = f", cost {result.cost}" if result.cost is not None else ""
            lines = [f"{len(result.plans)} {_kind(result.cost)} plans of {steps(length)}{costs}:"]
            lines += [
                f"  {model.naming.actions(plan)}" if len(plan) else "  (empty plan)"
                for plan in result.plans
            ]
            text = "\n".join(lines)
        else:
            text = (
                f"{plan_head(len(result.plan), result.cost, result.optimal)}: "
                f"{model.naming.actions(result.plan)}"
                if len(result.plan)
                else "plan of 0 steps: the goal holds initially"
            )
    elif result.status == "none":
        text = f"no plan exists: {result.proof}"
    elif result.plan is not None:
        # The cheapest plan found, not proven cheapest (a model with action costs).
        text = (
            f"bounded: {plan_head(len(result.plan), result.cost)} (not proven cheapest): "
            f"{model.naming.actions(result.plan) or '(empty plan)'}\n  {result.proof}"
        )
    else:
        text = f"bounded: {result.proof}; a plan may still exist"
    if result.plan is not None:
        write_picture(
            args,
            model,
            lambda pictures: pictures.plan(
                result.plan,
                f"{plan_head(len(result.plan), result.cost, result.optimal)}: "
                f"{model.naming.actions(result.plan) or '(empty plan)'}",
            ),
        )
    else:
        no_picture(args)
    emit(args, result.to_json(), text)
    return 0


def run_permissible(args: argparse.Namespace, model: Model) -> int:
    """ethasp plan --principle: a shortest HPlan, then its judgement."""
    from ethasp.principles.restriction import plan_with_principles, principle_cost
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
        comma = "," if result.cost is not None else ""
        head = (
            f"{plan_head(len(result.plan), result.cost, result.optimal)}{comma} permissible "
            f"under {under}"
        )
        length = len(result.plan) if result.cost is not None else result.horizon
        costs = f", cost {result.cost}" if result.cost is not None else ""
        lines = (
            [
                f"{len(shown)} {_kind(result.cost)} plans of {steps(length)}{costs} permissible "
                f"under {under}:"
            ]
            + [f"  {plan}" for plan in shown]
            if args.all
            else [f"{head}: {shown[0]}"]
        )
        checkpoint(data, "\n".join(lines), "the plan was judged")
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
        default_reasons_limit(args)
        if args.reasons_limit and not model.is_cam:  # a CAM has no goal to conflict with
            lines += conflict_lines(args, model, result.principles, data, limits)
    elif result.plan is not None and result.best is None:
        # A model with action costs: the cheapest permissible plan found, not
        # proven cheapest.
        shown = model.naming.actions(result.plan) if len(result.plan) else "(empty plan)"
        lines = [
            f"bounded: {plan_head(len(result.plan), result.cost)}, permissible under {under} "
            f"(not proven cheapest): {shown}",
            f"  {result.proof}",
        ]
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
    if model.planner.has_costs and not args.satisficing:
        price = principle_cost(model, result, max_horizon(args), limits)
        data["principle_cost"] = price.to_json()
        lines.append(price.text())
    if result.status != FOUND:
        no_picture(args)
    emit(args, data, "\n".join(lines))
    return 0


def conflict_lines(args, model: Model, principles, data: dict, limits) -> list[str]:
    """The minimal conflicts and maximal goal subsets of a model without a
    permissible plan, in words and as lists (their JSON added to ``data``)."""
    from ethasp.principles.conflict import goal_conflicts
    from ethasp.reasons.conflicts import explain_conflicts

    conflicts = goal_conflicts(
        model, principles, max_horizon=max_horizon(args), budget=limits, limit=args.reasons_limit
    )
    data.update(conflicts.to_json(model.naming))
    words = explain_conflicts(model, conflicts, max_horizon=max_horizon(args), budget=limits)
    data["conflicts_explanation"] = words.text
    return [words.text, *conflict_list_lines(model, conflicts)]


def conflict_list_lines(model: Model, conflicts) -> list[str]:
    """The conflicts and goal subsets, one a line."""

    def shown(items, conflict: bool = False) -> str:
        if not items and conflict:
            return "{} (even the empty goal)"
        return "{" + ", ".join(item.text(model.naming) for item in items) + "}"

    more = "limit reached, more may exist"
    cut = f"; {more}" if conflicts.conflicts_truncated else ""
    lines = [f"minimal conflicts ({conflicts.status}{cut}):"]
    lines += [f"  {shown(conflict, True)}" for conflict in conflicts.conflicts] or ["  none"]
    lines.append(
        "maximal goal subsets, each with a shortest permissible plan"
        f"{f' ({more})' if conflicts.goal_subsets_truncated else ''}:"
    )
    for subset in conflicts.goal_subsets:
        plan = (
            "(not found in time)"
            if subset.plan is None
            else (model.naming.actions(subset.plan) or "(empty plan)")
        )
        lines.append(f"  {shown(subset.items)}: {plan}")
    if not conflicts.goal_subsets:
        lines.append("  none")
    return lines
