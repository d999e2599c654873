"""``ethasp repair``: the cheapest changes of a model that admit a permissible plan."""

from __future__ import annotations

import argparse

from ethasp.interfaces.cli.models import load_model, model_options
from ethasp.interfaces.cli.options import (
    budget,
    given_plan,
    inherit,
    max_horizon,
    plan_options,
    search_options,
    whole_number,
)
from ethasp.interfaces.cli.output import emit
from ethasp.planning.model import Model
from ethasp.planning.plan import steps

MAX_REPAIRS = 1000


def add_parser(commands) -> None:
    repairing = commands.add_parser(
        "repair",
        help="find the cheapest changes of a model that admit a permissible plan",
        description="Find every repair of least cost (up to --limit): a set of the changes "
        "the model allows (changeable initial values, creative alternatives, "
        "preventable events, dropped goal facts; each with a cost, see "
        "docs/repairs.md) after which a plan permissible under the principles "
        "exists, each with such a plan, judged in the repaired model. Status: found "
        "(proven least), none (proven: no allowed change helps) or bounded. With "
        "--plan, each repair's plan keeps as much of that plan as it can (least "
        "plan stability distance), and the repairs are listed by that distance.",
    )
    inherit(repairing, model_options())
    repairing.add_argument(
        "--principle",
        action="append",
        required=True,
        metavar="NAME",
        help="a principle that can restrict plan search (repeatable: all must permit the plan)",
    )
    inherit(
        repairing,
        plan_options(required=False, what="a plan to repair towards (without it: none)"),
    )
    repairing.add_argument(
        "--limit",
        type=whole_number("repair limit", MAX_REPAIRS, smallest=1),
        default=10,
        metavar="N",
        help="list at most N repairs of least cost (default 10)",
    )
    inherit(repairing, search_options())
    repairing.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ethasp.principles.repair import repair

    model = load_model(args)
    towards = None
    if args.plan is not None or args.plan_file is not None:
        towards = given_plan(args, model)
    result = repair(
        model,
        args.principle,
        plan=towards,
        max_horizon=max_horizon(args),
        budget=budget(args),
        limit=args.limit,
    )
    emit(args, result.to_json(model.naming), repair_text(model, result))
    return 0


def repair_text(model: Model, result) -> str:
    """The repairs in lines: the status, then each repair, its plan and cost."""
    naming = model.naming
    under = " and ".join(result.principles)
    if not result.repairs:
        if result.status == "none":
            allowed = "; ".join(change.text(naming) for change in result.allowed) or "none"
            return f"no repair: {result.proof}\nchanges the model allows: {allowed}"
        return f"bounded: no repair found: {result.proof}"
    if result.cost == 0:
        plan = result.repairs[0].plan
        shown = naming.actions(plan) if plan else "the empty plan"
        head = f"no change needed: {shown} is permissible under {under}"
        if result.towards is not None:
            head += f" (distance {result.repairs[0].distance} from the plan given)"
        return head
    status = "least, proven" if result.status == "found" else "bounded"
    count = len(result.repairs)
    more = " (more exist)" if result.truncated else ""
    lines = [
        f"{count} repair{'s' if count != 1 else ''} of cost {result.cost} ({status}){more}: "
        f"{result.proof}"
    ]
    for number, found in enumerate(result.repairs, start=1):
        changes = "; ".join(f"{c.text(naming)} ({c.cost})" for c in found.changes)
        lines.append(f"  {number}. {changes}")
        if found.plan is None:
            lines.append("     no plan found in time")
            continue
        shown = naming.actions(found.plan) or "(empty plan)"
        proven = "" if found.optimal else " (not proven)"
        what = "shortest plan" if found.distance is None else f"distance {found.distance}"
        lines.append(
            f"     plan of {steps(len(found.plan))} permissible under {under} "
            f"({what}{proven}): {shown}"
        )
    return "\n".join(lines)
