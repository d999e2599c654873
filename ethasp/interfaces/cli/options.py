"""The options that commands share, as parent parsers, and what they make.

Parent parsers (``argparse.ArgumentParser(add_help=False)``, a new one per
command): the plan (:func:`plan_options`), the limits of searches
(:func:`limit_options`, :func:`search_options`), ``--reasons-limit``,
``--satisficing``.  A command takes a parent's options where it lists them
(:func:`inherit`), so that its ``--help`` shows them in its own order.  Also
the types of the numeric options, and the :class:`Budget` a command's limits
make.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from ethasp.errors import InputError
from ethasp.interfaces.progress import ProgressLine
from ethasp.planning.budget import DEFAULT_TIME_LIMIT, Budget
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.planning.search import DEFAULT_MAX_HORIZON, DEFAULT_SATISFICING_HORIZON
from ethasp.planning.systems import AUTO_ACTIONS, CHOICES
from ethasp.planning.systems import DEFAULT as DEFAULT_SYSTEM
from ethasp.planning.terms import read_text
from ethasp.reasons import DEFAULT_LIMIT as DEFAULT_REASONS_LIMIT

# Bounds of the numeric options (a larger value is refused, not wrapped).
MAX_HORIZON = 1_000_000
MAX_SECONDS = 1_000_000.0
MAX_REASONS = 1_000_000


def seconds(text: str) -> float | None:
    """A --time-limit: seconds, a finite number from 0 to MAX_SECONDS; 0 means none."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number of seconds: {text!r}") from None
    if math.isnan(value) or value < 0 or value > MAX_SECONDS:
        raise argparse.ArgumentTypeError(
            f"must be a number of seconds from 0 to {MAX_SECONDS:,.0f} (0: no limit): {text!r}"
        )
    return value if value > 0 else None


def whole_number(name: str, largest: int, smallest: int = 0):
    """An argparse type: a whole number from ``smallest`` to ``largest``."""

    def parse(text: str) -> int:
        try:
            value = int(text.strip())
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
        if not smallest <= value <= largest:
            raise argparse.ArgumentTypeError(f"must be from {smallest} to {largest:,}: {text!r}")
        return value

    parse.__name__ = name
    return parse


horizon = whole_number("horizon", MAX_HORIZON)
reasons_number = whole_number("reasons limit", MAX_REASONS)
answer_reasons_number = whole_number("reasons limit", MAX_REASONS, smallest=1)  # answers need words


def budget(args: argparse.Namespace) -> Budget:
    """The command's budget: its time limit and a progress line on standard error
    (kept in ``args.limits``, for the memory limit of :func:`main`)."""
    args.progress = ProgressLine(enabled=False if getattr(args, "quiet", False) else None)
    args.limits = Budget(getattr(args, "time_limit", None), args.progress)
    return args.limits


def gigabytes(text: str) -> float | None:
    """A --memory-limit: gigabytes, a finite number from 0 to 1,000,000; 0 means none."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number of gigabytes: {text!r}") from None
    if math.isnan(value) or value < 0 or value > 1_000_000:
        raise argparse.ArgumentTypeError(
            f"must be a number of gigabytes from 0 to 1,000,000 (0: no limit): {text!r}"
        )
    return value if value > 0 else None


def port(text: str) -> int:
    """A --port: 0 (any free port) to 65535."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a port number: {text!r}") from None
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"must be 0 to 65535: {text!r}")
    return value


# The memory a command may use (gigabytes), its processes together (see
# ethasp.execution): near it its searches stop and answer bounded; where
# clingo cannot be stopped (a grounding), its worker is ended below it.
DEFAULT_MEMORY_LIMIT = 4.0
MEMORY_LIMIT_HELP = (
    "the memory (GB gigabytes) of the command's processes together stays below "
    "this: its searches stop near it and answer 'bounded' with what they found "
    f"(default {DEFAULT_MEMORY_LIMIT:g}; 0 for no limit)"
)
TIME_LIMIT_HELP = (
    f"stop searching after SECONDS and answer 'bounded' with what was found; the "
    f"command ends by then, plus a fraction of a second (default "
    f"{DEFAULT_TIME_LIMIT:g}; 0 for no limit)"
)
QUIET_HELP = "no progress line on standard error (shown on a terminal after 2 s)"


def inherit(parser: argparse.ArgumentParser, *parents: argparse.ArgumentParser) -> None:
    """Add the options of parent parsers to ``parser`` here, after those it
    has (what ``parents=`` does, but where the command lists them)."""
    for parent in parents:
        parser._add_container_actions(parent)


def _parent() -> argparse.ArgumentParser:
    return argparse.ArgumentParser(add_help=False)


def hide(parser: argparse.ArgumentParser, option: str) -> None:
    """Leave an option out of --help (it is still read, to be refused in words)."""
    for action in parser._actions:
        if option in action.option_strings:
            action.help = argparse.SUPPRESS


def plan_options(required: bool = True, what: str = "the plan") -> argparse.ArgumentParser:
    """``--plan`` or ``--plan-file`` (:func:`given_plan` reads them)."""
    parser = _parent()
    given = parser.add_mutually_exclusive_group(required=required)
    default = "" if required else " (default: the plan the model comes with, if any)"
    given.add_argument(
        "--plan", metavar='"A1 A2 ..."', help=f"{what}: action terms separated by spaces{default}"
    )
    given.add_argument(
        "--plan-file",
        metavar="FILE",
        help=f"read {what} from FILE (actions separated by white space)",
    )
    return parser


def given_plan(args: argparse.Namespace, model: Model | None = None) -> Plan:
    """The plan of --plan, or of --plan-file (for plans too long for a command
    line), or else the plan the model comes with (a HERA situation's)."""
    if args.plan_file is not None:
        return Plan.parse(read_text(Path(args.plan_file), "--plan-file"))
    if args.plan is not None:
        return Plan.parse(args.plan)
    own = model.own_plan() if model is not None else None
    if own is None and model is not None and model.is_cam:
        raise InputError(
            "no action given: use --plan ACTION to choose one of the causal agency model's actions"
        )
    if own is None:
        raise InputError(
            "no plan given: use --plan or --plan-file (the model comes with no plan of its own)"
        )
    return own


def reasons_option(
    what: str = "at most N reasons of each kind per judgement",
    answers: bool = False,
) -> argparse.ArgumentParser:
    """--reasons-limit; for contrastive answers at least 1 (their words come from reasons)."""
    parser = _parent()
    least = "at least 1" if answers else "0: no explanations"
    parser.add_argument(
        "--reasons-limit",
        type=answer_reasons_number if answers else reasons_number,
        default=None,
        metavar="N",
        help=f"{what} (default {DEFAULT_REASONS_LIMIT}; {least})",
    )
    return parser


def default_reasons_limit(args: argparse.Namespace) -> None:
    """--reasons-limit, by default ethasp.reasons.DEFAULT_LIMIT."""
    if args.reasons_limit is None:
        args.reasons_limit = DEFAULT_REASONS_LIMIT


def limit_options(per: str = "", quiet: str = QUIET_HELP) -> argparse.ArgumentParser:
    """--time-limit, --memory-limit and --quiet (``per``: for what the time limit holds)."""
    parser = _parent()
    parser.add_argument(
        "--time-limit",
        type=seconds,
        default=DEFAULT_TIME_LIMIT,
        metavar="SECONDS",
        help=TIME_LIMIT_HELP + per,
    )
    parser.add_argument(
        "--memory-limit",
        type=gigabytes,
        default=DEFAULT_MEMORY_LIMIT,
        metavar="GB",
        help=MEMORY_LIMIT_HELP,
    )
    parser.add_argument("--quiet", action="store_true", help=quiet)
    return parser


def search_options(
    per: str = "", satisficing: bool = False, quiet: str = QUIET_HELP
) -> argparse.ArgumentParser:
    """--max-horizon, then the limits (with ``satisficing``: its default names the
    larger horizon of any-plan searches)."""
    parser = _parent()
    default = (
        f"{DEFAULT_MAX_HORIZON}; {DEFAULT_SATISFICING_HORIZON} with --satisficing"
        if satisficing
        else f"{DEFAULT_MAX_HORIZON}"
    )
    parser.add_argument(
        "--max-horizon",
        type=horizon,
        default=None,
        metavar="N",
        help=f"search plans of at most N steps (default {default})",
    )
    inherit(parser, planner_option(), limit_options(per, quiet))
    return parser


def planner_option() -> argparse.ArgumentParser:
    """--planner: which planning system searches (ethasp.planning.systems)."""
    parser = _parent()
    parser.add_argument(
        "--planner",
        choices=CHOICES,
        default=DEFAULT_SYSTEM,
        help="the planning system that searches plans and states: clingo; fast-downward "
        "(Fast Downward, from pip install 'ethasp[planners]') where the search compiles "
        "for it, clingo elsewhere; auto: Fast Downward where it is installed, the "
        f"search compiles and the task has at least {AUTO_ACTIONS} usable actions, "
        "else clingo (default auto)",
    )
    return parser


def satisficing_option(what: str = "a plan") -> argparse.ArgumentParser:
    parser = _parent()
    parser.add_argument(
        "--satisficing",
        action="store_true",
        help=f"find {what} fast, without proving it shortest (status found, "
        '"optimal": false in JSON)',
    )
    return parser


def max_horizon(args: argparse.Namespace) -> int:
    """--max-horizon, or its default (larger for any-plan searches)."""
    if args.max_horizon is not None:
        return args.max_horizon
    return (
        DEFAULT_SATISFICING_HORIZON if getattr(args, "satisficing", False) else DEFAULT_MAX_HORIZON
    )
