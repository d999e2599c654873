"""The ethasp command line: a thin layer over the Python API."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Sequence

from ethasp.errors import InputError
from ethasp.model import Model
from ethasp.plan import Plan
from ethasp.resources import MODELS
from ethasp.search import DEFAULT_MAX_HORIZON, FOUND, find_plan
from ethasp.validation import validate

DESCRIPTION = """\
Ethical plan explanation with Answer Set Programming (clingo), after Krarup,
Lindner, Krivic and Long, "Understanding a Robot's Guiding Ethical Principles
via Automatically Generated Explanations" (IEEE CASE 2021).

MODEL is one or more ASP files in the vocabulary variable/1, action/1, pre/3,
eff/3, init/1, goal/2, utility/2, utility/3; the name of a bundled model
(e.g. trolley) also works."""


def model_paths(names: Sequence[str]) -> list[Path]:
    """Model files: paths as given, or else the bundled model of that name."""
    paths = []
    for name in names:
        path = Path(name)
        if not path.exists():
            bundled = MODELS / (name if name.endswith(".lp") else name + ".lp")
            if "/" not in name and bundled.is_file():
                path = bundled
        paths.append(path)
    return paths


def load_model(args: argparse.Namespace) -> Model:
    return Model.load(model_paths(args.model), allow_scripts=args.allow_scripts)


def emit(args: argparse.Namespace, data: dict, text: str) -> None:
    print(json.dumps(data, indent=2) if args.json else text)


# -- commands -----------------------------------------------------------------

def command_plan(args: argparse.Namespace) -> int:
    model = load_model(args)
    result = find_plan(model, args.max_horizon, args.time_limit, all_plans=args.all)
    if result.status == FOUND:
        if args.all:
            lines = [f"{len(result.plans)} shortest plans of {result.horizon} steps:"]
            lines += [f"  {plan}" if len(plan) else "  (empty plan)" for plan in result.plans]
            text = "\n".join(lines)
        else:
            text = (f"plan of {result.horizon} steps: {result.plan}" if len(result.plan)
                    else "plan of 0 steps: the goal holds initially")
    elif result.status == "none":
        text = f"no plan exists: {result.proof}"
    else:
        text = f"bounded: {result.proof}; a plan may still exist"
    emit(args, result.to_json(), text)
    return 0


def command_validate(args: argparse.Namespace) -> int:
    model = load_model(args)
    validation = validate(model, Plan.parse(args.plan))
    if validation.valid:
        text = f"valid plan of {len(validation.plan)} steps; final state: {' '.join(validation.final_state)}"
    else:
        text = f"not a plan: {validation.message()}"
    emit(args, validation.to_json(), text)
    return 0 if validation.valid else 2


# -- parser -------------------------------------------------------------------

def _add_model_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("model", nargs="+", metavar="MODEL", help="model files (ASP)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--allow-scripts", action="store_true",
                        help="run #script blocks in model files (refused by default)")


def _add_search_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--max-horizon", type=int, default=DEFAULT_MAX_HORIZON, metavar="N",
                        help=f"search plans of at most N steps (default {DEFAULT_MAX_HORIZON})")
    parser.add_argument("--time-limit", type=float, default=None, metavar="SECONDS",
                        help="stop searching after SECONDS and report 'bounded'")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="ethasp", description=DESCRIPTION,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    plan = commands.add_parser(
        "plan", help="find a shortest plan",
        description="Find a shortest plan. Status: found, none (proven: no plan exists) "
                    "or bounded (none up to the horizon or time limit; one may still exist).")
    _add_model_arguments(plan)
    _add_search_arguments(plan)
    plan.add_argument("--all", action="store_true", help="list all shortest plans")
    plan.set_defaults(run=command_plan)

    check = commands.add_parser(
        "validate", help="check that an action sequence is a plan",
        description="Check a plan: the first inapplicable step and its failing precondition, "
                    "or the goal facts left unmet. Exit code 0 for a plan, 2 otherwise.")
    _add_model_arguments(check)
    check.add_argument("--plan", required=True, metavar='"A1 A2 ..."',
                       help="action terms separated by spaces, e.g. \"pull\" or \"go(a,b) pick(x)\"")
    check.set_defaults(run=command_validate)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except InputError as error:
        print(f"ethasp: error: {error}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("ethasp: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
