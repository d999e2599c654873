"""``ethasp query``: a formula of the moral action query language L, true or false of a plan."""

from __future__ import annotations

import argparse

from ethasp.interfaces.cli.models import load_model, model_options
from ethasp.interfaces.cli.options import given_plan, inherit, plan_options
from ethasp.interfaces.cli.output import emit


def add_parser(commands) -> None:
    asking = commands.add_parser(
        "query",
        help="evaluate a formula of the moral action query language",
        description="Evaluate a formula of the language L for a plan and print true or "
        "false, e.g. 'Caused(one_will_die) and not Bad(pull)'.",
    )
    inherit(asking, model_options())
    asking.add_argument("formula", metavar="FORMULA", help="the formula (syntax: docs/formulas.md)")
    inherit(asking, plan_options(required=False))
    asking.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ethasp.principles.judgement import query

    model = load_model(args)
    result = query(model, given_plan(args, model), args.formula)
    emit(args, result.to_json(), "true" if result.value else "false")
    return 0
