"""The ethasp command line: a thin layer over the Python API."""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import re
import shutil
import sys
import threading
import time
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from ethasp.errors import InputError
from ethasp.interfaces.progress import ProgressLine
from ethasp.interfaces.version import package_version
from ethasp.planning.budget import DEFAULT_TIME_LIMIT, Budget
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan, steps
from ethasp.planning.search import (
    DEFAULT_MAX_HORIZON,
    DEFAULT_SATISFICING_HORIZON,
    FOUND,
    find_plan,
)
from ethasp.planning.terms import read_text
from ethasp.reasons import DEFAULT_LIMIT as DEFAULT_REASONS_LIMIT
from ethasp.resources import MODELS

if TYPE_CHECKING:
    from ethasp.principles.judgement import JudgementReport

# Judgements, reasons, formulas and restrictions are imported by the commands
# that use them, so that ethasp plan starts quickly.

DESCRIPTION = """\
Ethical plan explanation with Answer Set Programming (clingo), after Krarup,
Lindner, Krivic and Long, "Understanding a Robot's Guiding Ethical Principles
via Automatically Generated Explanations" (IEEE CASE 2021).

MODEL is one or more ASP files in the vocabulary variable/1, action/1, pre/3,
eff/3, ceff/4, cpre/4, init/1, goal/2, utility/2, utility/3 (derived variables:
derived/1, axiom/2, axiom_pre/4; events: event/1, event_at/2, ...), or a PDDL
domain and problem (STRIPS, ADL, derived predicates) with ASP annotation files,
or a HERA situation (.yaml, .json); the name of a bundled model (e.g. trolley)
also works, and - reads an ASP model from standard input.  A model that comes
with a plan (a situation's) is judged on it when --plan is not given.  Bad
input gets one line on standard error and exit code 2; Ctrl-C one line and exit
code 130."""

# Bounds of the numeric options (a larger value is refused, not wrapped).
MAX_HORIZON = 1_000_000
MAX_SECONDS = 1_000_000.0
MAX_REASONS = 1_000_000


def model_paths(names: Sequence[str]) -> list[Path]:
    """Model files: paths as given, or else the bundled model of that name.

    Bundled PDDL files and their annotations are in the folder ``pddl``, HERA
    situations in the folder ``hera``.
    """
    paths = []
    for name in names:
        path = Path(name)
        try:
            exists = path.exists()
        except (OSError, ValueError):  # a name too long, ...: read_text says so
            exists = True
        if not exists:
            bundled = MODELS / (name if name.endswith(".lp") else name + ".lp")
            if "/" not in name and not bundled.is_file():
                bundled = MODELS / "pddl" / name
            if "/" not in name and not bundled.is_file():
                bundled = MODELS / "hera" / name
            if "/" not in name and bundled.is_file():
                path = bundled
        paths.append(path)
    return paths


STDIN = "-"  # as a model file: read the model from standard input
STDIN_NAME = "<stdin>"  # its name in messages


def read_stdin_model() -> str:
    """An ASP model from standard input (one line of error if it is not ASP text)."""
    try:
        data = (
            sys.stdin.buffer.read()
            if hasattr(sys.stdin, "buffer")
            else sys.stdin.read().encode("utf-8", "surrogateescape")
        )
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise InputError(
            f"{STDIN_NAME}: cannot be read (not UTF-8 text: byte {error.start + 1})"
        ) from None
    except (OSError, ValueError) as error:  # closed, or not readable
        raise InputError(
            f"{STDIN_NAME}: cannot be read ({getattr(error, 'strerror', None) or error})"
        ) from None
    head = text.lstrip()
    if head[:1] in ("(", ";") and "(define" in head[:4096].lower():
        raise InputError(
            f"{STDIN_NAME}: this looks like PDDL; standard input takes an ASP "
            "model (give a PDDL domain and problem as files)"
        )
    if re.match(r'\{\s*"|---', head):
        raise InputError(
            f"{STDIN_NAME}: this looks like a HERA situation; standard input "
            "takes an ASP model (give a situation as a .yaml or .json file)"
        )
    return text


def load_model(args: argparse.Namespace) -> Model:
    """The model of the command's MODEL arguments; ``-`` reads ASP text from
    standard input (at most once)."""
    names = list(args.model)
    if names.count(STDIN) > 1:
        raise InputError("standard input (-) can be given only once as a model file")
    if STDIN not in names:
        return Model.load(model_paths(names), allow_scripts=args.allow_scripts)
    names.remove(STDIN)
    return Model.load(
        model_paths(names),
        allow_scripts=args.allow_scripts,
        texts=[(STDIN_NAME, read_stdin_model())],
    )


def model_files(args: argparse.Namespace, resolve: bool = False) -> list[str]:
    """The model's files as a dialogue or the page names them (``<stdin>`` for -)."""
    return [
        STDIN_NAME if name == STDIN else str(path.resolve() if resolve else path)
        for name, path in zip(args.model, model_paths(args.model), strict=True)
    ]


def _seconds(text: str) -> float | None:
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


def _count(name: str, largest: int, smallest: int = 0):
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


_horizon = _count("horizon", MAX_HORIZON)
_reasons = _count("reasons limit", MAX_REASONS)
_answer_reasons = _count("reasons limit", MAX_REASONS, smallest=1)  # answers need words


def budget(args: argparse.Namespace) -> Budget:
    """The command's budget: its time limit and a progress line on standard error
    (kept in ``args.limits``, for the memory limit of :func:`main`)."""
    args.progress = ProgressLine(enabled=False if getattr(args, "quiet", False) else None)
    args.limits = Budget(getattr(args, "time_limit", None), args.progress)
    return args.limits


def _memory() -> int:
    """This process's resident memory in bytes (0 where it cannot be read)."""
    try:
        with open("/proc/self/statm") as statm:
            return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


def _gigabytes(text: str) -> float | None:
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


def _port(text: str) -> int:
    """A --port: 0 (any free port) to 65535."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a port number: {text!r}") from None
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"must be 0 to 65535: {text!r}")
    return value


def emit(args: argparse.Namespace, data: dict, text: str) -> None:
    """Print the answer (text, or JSON with --json) on standard output, or on
    standard error when the picture goes to standard output (--svg -)."""
    progress = getattr(args, "progress", None)
    if progress is not None:
        progress.clear()
    out = sys.stderr if getattr(args, "svg", None) == STDIN else sys.stdout
    print(json.dumps(data, indent=2) if args.json else text, file=out, flush=True)


def _add_svg_argument(parser: argparse.ArgumentParser, what: str) -> None:
    parser.add_argument(
        "--svg",
        metavar="FILE",
        help=f"also draw {what} as an SVG picture in FILE (- for standard "
        "output; the answer then goes to standard error)",
    )


def _draw(args: argparse.Namespace, model: Model, draw) -> None:
    """--svg FILE: write the picture that ``draw(Pictures)`` makes
    (ethasp/interfaces/pictures.py); --svg -: to standard output."""
    if args.svg is not None:
        from ethasp.interfaces.pictures import Pictures, write

        svg = draw(Pictures(model))
        if args.svg == STDIN:
            sys.stdout.write(svg)
            sys.stdout.flush()
        else:
            write(args.svg, svg)


def _no_picture(args: argparse.Namespace) -> None:
    if args.svg is not None:
        where = "standard output" if args.svg == STDIN else args.svg
        print(f"ethasp: no plan found, so no picture was written to {where}", file=sys.stderr)


# -- commands -----------------------------------------------------------------


def _unproven(optimal: bool) -> str:
    """What a plan's text says when an any-plan search found it."""
    return "" if optimal else " (not proven shortest)"


def command_plan(args: argparse.Namespace) -> int:
    model = load_model(args)
    if args.principle:
        return command_plan_permissible(args, model)
    if args.all and args.satisficing:
        raise InputError("--all lists all shortest plans; it cannot go with --satisficing")
    result = find_plan(
        model,
        _max_horizon(args),
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
        _draw(
            args,
            model,
            lambda pictures: pictures.plan(
                result.plan,
                f"plan of {steps(len(result.plan))}{_unproven(result.optimal)}: "
                f"{model.naming.actions(result.plan) or '(empty plan)'}",
            ),
        )
    else:
        _no_picture(args)
    emit(args, result.to_json(), text)
    return 0


def command_plan_permissible(args: argparse.Namespace, model: Model) -> int:
    """ethasp plan --principle: a shortest HPlan, then its judgement."""
    from ethasp.principles.restriction import plan_with_principles
    from ethasp.reasons.reasons import judge

    limits = budget(args)
    if args.all and args.satisficing:
        raise InputError("--all lists all shortest plans; it cannot go with --satisficing")
    result = plan_with_principles(
        model,
        args.principle,
        _max_horizon(args),
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
        _reasons_limit(args)
        report = judge(
            model,
            result.plan,
            result.principles,
            DEFAULT_MAX_HORIZON if args.max_horizon is None else args.max_horizon,
            reasons_limit=args.reasons_limit,
            budget=limits,
        )
        data["judgements"] = report.to_json()["judgements"]
        lines += _explanation_text(report) + _judgement_text(report, model).split("\n")[1:]
        _draw(args, model, lambda pictures: pictures.report(report, f"{head}: {shown[0]}"))
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
        _no_picture(args)
    emit(args, data, "\n".join(lines))
    return 0


def _state_text(model: Model, literals: list[str]) -> str:
    """A whole state in words: for a PDDL task the atoms that hold (PDDL's
    closed world), for other models every variable's value."""
    from ethasp.planning.naming import PddlNaming

    if isinstance(model.naming, PddlNaming):
        literals = [literal for literal in literals if not literal.startswith("-")]
    return model.naming.facts(literals)


def command_validate(args: argparse.Namespace) -> int:
    from ethasp.planning.validation import validate

    model = load_model(args)
    validation = validate(model, _given_plan(args, model))
    if validation.valid:
        text = (
            f"valid plan of {steps(len(validation.plan))}; "
            f"final state: {_state_text(model, validation.final_state)}"
        )
    else:
        text = f"not a plan: {validation.message(model.naming)}"
    emit(args, validation.to_json(), text)
    return 0 if validation.valid else 2


def _judgement_text(report: JudgementReport, model: Model) -> str:
    naming = model.naming
    lines = [
        f"plan: {naming.actions(report.plan)}" if len(report.plan) else "plan: (empty)",
        f"final state: {_state_text(model, report.final_state)} (utility {report.utility})",
    ]
    for judgement in report.judgements:
        verdict = "permissible" if judgement.permissible else "impermissible"
        if judgement.status == "bounded":
            verdict = f"{verdict} as far as searched (bounded, not proven)"
        else:
            verdict = f"{verdict} (proven)"
        if judgement.compared is None and judgement.best_reachable is None:
            lines.append(f"{judgement.principle}: {verdict}")
            continue
        lines.append(f"{judgement.principle}: {verdict}: {judgement.proof}")
        compared, best = judgement.compared, judgement.best_reachable
        final = set(report.final_state)
        if compared is not None and (best is None or best.found is not compared):
            kind = "a better reachable state" if not judgement.permissible else "compared with"
            lines.append(
                f"  {kind}: {_state_words(compared.literals, final, naming)} "
                f"(utility {compared.utility}, {steps(compared.distance)} away)"
            )
        if best is not None and best.found is not None:
            lines.append(
                f"  best reachable state: {_state_words(best.state, final, naming)} "
                f"(utility {best.utility}, {steps(best.horizon)} away; "
                f"{best.status}: {best.proof})"
            )
    return "\n".join(lines)


def _state_words(literals: list[str], final: set[str], naming) -> str:
    """A state, as its difference from the final state when that is shorter."""
    if set(literals) == final:
        return "the final state"
    differing = [literal for literal in literals if literal not in final]
    if len(differing) * 2 < len(literals):
        return f"the final state but {naming.facts(differing)}"
    return naming.facts(literals)


def _given_plan(args: argparse.Namespace, model: Model | None = None) -> Plan:
    """The plan of --plan, or of --plan-file (for plans too long for a command
    line), or else the plan the model comes with (a HERA situation's)."""
    if args.plan_file is not None:
        return Plan.parse(read_text(Path(args.plan_file), "--plan-file"))
    if args.plan is not None:
        return Plan.parse(args.plan)
    own = model.own_plan() if model is not None else None
    if own is None:
        raise InputError(
            "no plan given: use --plan or --plan-file (the model comes with no plan of its own)"
        )
    return own


def _add_plan_arguments(
    parser: argparse.ArgumentParser, required: bool = True, what: str = "the plan"
) -> None:
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


def _explanation_text(report: JudgementReport) -> list[str]:
    """Each judgement's explanation, then its reasons (ethasp/reasons/reasons.py),
    long ones shortened (ethasp/interfaces/shortening.py; --json has them whole)."""
    from ethasp.interfaces.shortening import WIDTH, reasons_lines

    width = WIDTH
    if sys.stdout.isatty():
        width = max(WIDTH, shutil.get_terminal_size((WIDTH, 24)).columns - 1)
    lines, shortened = [], False
    for judgement in report.judgements:
        explanation = judgement.explanation
        if explanation is None:
            continue
        lines.append(f"{judgement.principle}: {explanation.text}")
        for kind, reasons, truncated in (
            ("necessary", explanation.necessary_reasons, explanation.necessary_truncated),
            ("sufficient", explanation.sufficient_reasons, explanation.sufficient_truncated),
        ):
            kind_lines, cut = reasons_lines(kind, reasons, truncated, width)
            lines += kind_lines
            shortened = shortened or cut
    if shortened:
        lines.append("(long reasons are shortened here; --json prints them whole)")
    return lines


def _reasons_limit(args: argparse.Namespace) -> None:
    """--reasons-limit, by default ethasp.reasons.DEFAULT_LIMIT."""
    if args.reasons_limit is None:
        args.reasons_limit = DEFAULT_REASONS_LIMIT


def command_judge(args: argparse.Namespace) -> int:
    from ethasp.reasons.reasons import judge

    model = load_model(args)
    _reasons_limit(args)
    if args.reasons_limit < 0:
        raise InputError("--reasons-limit must be at least 0")
    report = judge(
        model,
        _given_plan(args, model),
        args.principle,
        _max_horizon(args),
        reasons_limit=args.reasons_limit,
        budget=budget(args),
        best=args.best,
    )
    lines = [*_explanation_text(report), _judgement_text(report, model)]
    _draw(args, model, lambda pictures: pictures.report(report))
    emit(args, report.to_json(), "\n".join(lines))
    return 0


def command_ask(args: argparse.Namespace) -> int:
    from ethasp.interfaces.prompt import answer_text
    from ethasp.questions.contrast import ask

    _reasons_limit(args)
    model = load_model(args)
    plan = _given_plan(args) if (args.plan or args.plan_file) else model.own_plan()
    answer = ask(
        model,
        args.question,
        plan,
        args.principle,
        args.under,
        _max_horizon(args),
        reasons_limit=args.reasons_limit,
        budget=budget(args),
        satisficing=args.satisficing,
    )
    _draw(args, model, lambda pictures: pictures.answer(answer))
    emit(args, answer.to_json(), answer_text(answer, model.naming))
    return 0


def command_explain(args: argparse.Namespace) -> int:
    """ethasp explain: a plan step by step (causal links, removable steps, moral side)."""
    from ethasp.questions.steps import explain_steps

    model = load_model(args)
    if args.plan or args.plan_file:
        plan = _given_plan(args)
    elif args.principle is None and model.own_plan() is not None:
        plan = model.own_plan()
    elif args.principle is not None:
        from ethasp.principles.restriction import plan_with_principles

        result = plan_with_principles(
            model,
            [args.principle],
            _max_horizon(args),
            budget=budget(args),
            satisficing=args.satisficing,
        )
        if result.plan is None:
            raise InputError(f"no plan to explain: {result.proof}")
        plan = result.plan
    else:
        result = find_plan(
            model, _max_horizon(args), budget=budget(args), satisficing=args.satisficing
        )
        if result.plan is None:
            raise InputError(f"no plan to explain: {result.proof}")
        plan = result.plan
    explanation = explain_steps(model, plan)
    naming = model.naming
    removable = [str(step.step) for step in explanation.steps if step.removable]
    lines = [f"plan of {steps(len(plan))}: {naming.actions(plan) or '(empty)'}"]
    lines += explanation.lines()
    lines.append(f"removable steps: {', '.join(removable) or 'none'}")
    _draw(args, model, lambda pictures: pictures.explained(explanation))
    emit(args, explanation.to_json(naming), "\n".join(lines))
    return 0


def _writable(path: Path, what: str) -> None:
    """Refuse a file that cannot be written before any work is done."""
    try:
        if path.is_dir():
            raise InputError(f"{what} {path}: is a directory, not a file")
        parent = path.parent if str(path.parent) else Path(".")
        if not parent.is_dir():
            raise InputError(f"{what} {path}: cannot be written (no directory {parent})")
        if not os.access(parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
            raise InputError(f"{what} {path}: cannot be written (permission denied)")
        if len(path.name.encode()) > os.pathconf(parent, "PC_NAME_MAX"):
            raise InputError(f"{what} {path}: cannot be written (file name too long)")
    except (OSError, ValueError) as error:
        reason = getattr(error, "strerror", None) or str(error)
        raise InputError(f"{what} {path}: cannot be written ({reason})") from None


def command_dialogue(args: argparse.Namespace) -> int:
    from ethasp.interfaces.prompt import Prompt
    from ethasp.questions.dialogue import Dialogue

    _reasons_limit(args)
    if args.json:
        raise InputError(
            "the dialogue prints text, not JSON: its answers are saved as JSON "
            "when it ends (--save FILE), and ethasp ask --json answers questions "
            "as JSON"
        )
    if STDIN in args.model:
        raise InputError(
            "the dialogue reads its commands from standard input, so its model "
            "cannot come from there (-): give the model as a file"
        )
    save = None if args.save == "-" else Path(args.save)
    if save is not None:
        _writable(save, "--save")
    model = load_model(args)
    options = {
        "max_horizon": _max_horizon(args),
        "time_limit": args.time_limit,
        "reasons_limit": args.reasons_limit,
        "satisficing": args.satisficing,
    }
    progress = ProgressLine(enabled=False if args.quiet else None)
    files = model_files(args, resolve=True)
    if args.load:
        dialogue = Dialogue.load(args.load, model, **options)
    else:
        plan = _given_plan(args) if (args.plan or args.plan_file) else model.own_plan()
        dialogue = Dialogue.start(model, args.principle, plan, files, **options)
    dialogue.model_files = files
    dialogue.on_progress = progress
    interactive = sys.stdin.isatty()
    # At a terminal: editing keys, a history across runs, Tab completion.
    editor = _line_editor(model) if interactive else None

    def read() -> str:
        line = editor.read("ethasp> ") if editor is not None else input("")
        # Bytes that are not UTF-8 become U+FFFD, so that messages can show them.
        return line.encode("utf-8", "surrogateescape").decode("utf-8", "replace")

    def load(path: str) -> Dialogue:
        loaded = Dialogue.load(path, model, **options)
        loaded.model_files = files
        loaded.on_progress = progress
        return loaded

    if interactive:
        print("ethasp dialogue: type help for the commands, quit to end.")
    prompt = Prompt(dialogue, save, sys.stdout, load, progress)

    def on_interrupt() -> str:  # Ctrl-C saves the dialogue first
        if editor is not None:
            editor.restore()
            print(file=sys.stderr)  # off the line being edited
        return prompt.save_now()

    args.on_interrupt = on_interrupt
    return prompt.run(read)


def _line_editor(model: Model):
    """The dialogue's line editor (ethasp/interfaces/editing.py): it completes
    commands, the model's actions and variables, and principle names."""
    from ethasp.interfaces.completion import principle_names
    from ethasp.interfaces.editing import Completer, LineEditor, history_path

    naming, planner = model.naming, model.planner
    actions = [naming.action(atom.arguments[0]) for atom in planner.get("action", 1)]
    facts = [naming.fact(str(atom.arguments[0])) for atom in planner.get("variable", 1)]
    return LineEditor(Completer(actions, facts, principle_names(restricting=True)), history_path())


def command_serve(args: argparse.Namespace) -> int:
    """ethasp serve: the dialogue as a local web page (ethasp/interfaces/web/)."""
    try:
        from ethasp.interfaces.web.server import serve
        from ethasp.interfaces.web.workspace import Options, Workspace
    except ImportError as error:  # a broken installation without Flask
        raise InputError(
            f"ethasp serve needs the package {error.name} (pip install flask)"
        ) from None

    _reasons_limit(args)
    model = load_model(args)
    files = model_files(args)
    workspace = Workspace(
        model,
        files,
        args.principle,
        Options(_max_horizon(args), args.time_limit, args.reasons_limit),
    )
    if args.quiet and args.log_requests:
        raise InputError("--log-requests cannot go with --quiet")
    return serve(
        workspace, args.host, args.port, args.open, log_requests=args.log_requests, quiet=args.quiet
    )


def command_completion(args: argparse.Namespace) -> int:
    """ethasp completion bash|zsh: the completion script (ethasp/interfaces/completion.py)."""
    from ethasp.interfaces.completion import script

    sys.stdout.write(script(args.shell, build_parser()))
    return 0


def command_query(args: argparse.Namespace) -> int:
    from ethasp.principles.judgement import query

    model = load_model(args)
    result = query(model, _given_plan(args, model), args.formula)
    emit(args, result.to_json(), "true" if result.value else "false")
    return 0


def command_batch(args: argparse.Namespace) -> int:
    """ethasp batch: many cases on warm local workers or a Dask cluster (ethasp/batch/)."""
    from ethasp.batch.progress import BatchProgress
    from ethasp.batch.report import write_report
    from ethasp.batch.run import batch

    _writable(Path(args.output), "--output")
    if args.report is not None:
        _writable(Path(args.report), "--report")
    run = batch(
        [str(path) for path in model_paths(args.cases)],
        args.principle,
        task=args.task,
        questions=args.question or (),
        under=args.under,
        output=args.output,
        workers=args.workers,
        scheduler=args.scheduler,
        time_limit=args.time_limit,
        max_horizon=args.max_horizon,
        reasons_limit=args.reasons_limit,
        satisficing=args.satisficing,
        allow_scripts=args.allow_scripts,
        glob=args.glob,
        retry_errors=args.retry_errors,
    )
    progress = BatchProgress(len(run.cases), run.skipped, run.cases_failed, enabled=not args.quiet)

    def interrupted() -> str:
        run.close()
        return (
            f"{run.lines_written} new lines written to {args.output}; run the same "
            "command again to compute the rest"
        )

    args.on_interrupt = interrupted
    run.start()
    for _ in run:
        progress.update(run.cases_done, run.cases_failed)
    computed = run.cases_done - run.skipped
    before = f", {run.skipped} done before" if run.skipped else ""
    progress.finish(
        f"ethasp batch: {len(run.cases)} cases ({computed} computed now{before}), "
        f"{run.cases_failed} failed; {run.lines_written} new lines in "
        f"{args.output} ({run.seconds:.1f} s)"
    )
    if args.report is not None:
        write_report(args.output, args.report)
        if not args.quiet:
            print(f"ethasp batch: report written to {args.report}", file=sys.stderr)
    return 1 if run.cases_failed else 0


def command_report(args: argparse.Namespace) -> int:
    """ethasp report: the HTML page of a batch's results."""
    from ethasp.batch.report import write_report

    destination = Path(args.output) if args.output else Path(args.results).with_suffix(".html")
    if destination.resolve() == Path(args.results).resolve():
        raise InputError(f"--output {destination}: would overwrite the results file")
    _writable(destination, "--output")
    write_report(args.results, destination)
    print(f"report written to {destination}")
    return 0


# -- parser -------------------------------------------------------------------

MODEL_FILES_HELP = (
    "model files (ASP), or a PDDL domain and problem (.pddl) with ASP "
    "annotation files, or a HERA situation (.yaml, .json), or the name of a "
    "bundled model"
)
MODEL_HELP = MODEL_FILES_HELP + "; - reads an ASP model from standard input"


def _add_model_arguments(parser: argparse.ArgumentParser, stdin: bool = True) -> None:
    parser.add_argument(
        "model", nargs="+", metavar="MODEL", help=MODEL_HELP if stdin else MODEL_FILES_HELP
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument(
        "--allow-scripts",
        action="store_true",
        help="run #script blocks in model files (refused by default)",
    )


def _hide(parser: argparse.ArgumentParser, option: str) -> None:
    """Leave an option out of --help (it is still read, to be refused in words)."""
    for action in parser._actions:
        if option in action.option_strings:
            action.help = argparse.SUPPRESS


# The memory a command may use (gigabytes): beyond it its searches stop and
# answer bounded; beyond MEMORY_HARD times it, where clingo cannot be stopped
# (a grounding), the command ends with one line.
DEFAULT_MEMORY_LIMIT = 4.0
MEMORY_HARD = 1.5
MEMORY_LIMIT_HELP = (
    f"stop searching when the process uses more than GB gigabytes of memory "
    f"and answer 'bounded'; end with one line at {MEMORY_HARD:g} times "
    f"that (default {DEFAULT_MEMORY_LIMIT:g}; 0 for no limit)"
)
TIME_LIMIT_HELP = (
    f"stop searching after SECONDS and answer 'bounded' (default "
    f"{DEFAULT_TIME_LIMIT:g}; 0 for no limit)"
)
QUIET_HELP = "no progress line on standard error (shown on a terminal after 2 s)"


def _add_reasons_limit(
    parser: argparse.ArgumentParser,
    what: str = "at most N reasons of each kind per judgement",
    answers: bool = False,
) -> None:
    """--reasons-limit; for contrastive answers at least 1 (their words come from reasons)."""
    least = "at least 1" if answers else "0: no explanations"
    parser.add_argument(
        "--reasons-limit",
        type=_answer_reasons if answers else _reasons,
        default=None,
        metavar="N",
        help=f"{what} (default {DEFAULT_REASONS_LIMIT}; {least})",
    )


def _add_limits(parser: argparse.ArgumentParser, per: str = "", quiet: str = QUIET_HELP) -> None:
    parser.add_argument(
        "--time-limit",
        type=_seconds,
        default=DEFAULT_TIME_LIMIT,
        metavar="SECONDS",
        help=TIME_LIMIT_HELP + per,
    )
    parser.add_argument(
        "--memory-limit",
        type=_gigabytes,
        default=DEFAULT_MEMORY_LIMIT,
        metavar="GB",
        help=MEMORY_LIMIT_HELP,
    )
    parser.add_argument("--quiet", action="store_true", help=quiet)


def _add_search_arguments(
    parser: argparse.ArgumentParser,
    per: str = "",
    satisficing: bool = False,
    quiet: str = QUIET_HELP,
) -> None:
    default = (
        f"{DEFAULT_MAX_HORIZON}; {DEFAULT_SATISFICING_HORIZON} with --satisficing"
        if satisficing
        else f"{DEFAULT_MAX_HORIZON}"
    )
    parser.add_argument(
        "--max-horizon",
        type=_horizon,
        default=None,
        metavar="N",
        help=f"search plans of at most N steps (default {default})",
    )
    _add_limits(parser, per, quiet)


def _add_satisficing_argument(parser: argparse.ArgumentParser, what: str = "a plan") -> None:
    parser.add_argument(
        "--satisficing",
        action="store_true",
        help=f"find {what} fast, without proving it shortest (status found, "
        '"optimal": false in JSON)',
    )


def _max_horizon(args: argparse.Namespace) -> int:
    """--max-horizon, or its default (larger for any-plan searches)."""
    if args.max_horizon is not None:
        return args.max_horizon
    return (
        DEFAULT_SATISFICING_HORIZON if getattr(args, "satisficing", False) else DEFAULT_MAX_HORIZON
    )


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="ethasp", description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.set_defaults(one_answer=True)
    parser.add_argument(
        "-V",
        "--version",
        action=_Version,
        nargs=0,
        help="show the program's version number and exit",
    )
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    plan = commands.add_parser(
        "plan",
        help="find a shortest plan (or any plan, fast: --satisficing)",
        description="Find a shortest plan (with --satisficing: some plan, found fast and not "
        "proven shortest). Status: found, none (proven: no plan exists) "
        "or bounded (none up to the horizon or time limit; one may still exist).",
    )
    _add_model_arguments(plan)
    _add_search_arguments(plan, satisficing=True)
    plan.add_argument("--all", action="store_true", help="list all shortest plans")
    _add_satisficing_argument(plan)
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
    _add_reasons_limit(
        plan,
        "with --principle: compute at most N sufficient and N "
        "necessary reasons for the plan's judgement",
    )
    _add_svg_argument(plan, "the plan found (with --principle: and its judgement)")
    plan.set_defaults(run=command_plan)

    check = commands.add_parser(
        "validate",
        help="check that an action sequence is a plan",
        description="Check a plan: the first inapplicable step and its failing precondition, "
        "or the goal facts left unmet. Exit code 0 for a plan, 2 otherwise.",
    )
    _add_model_arguments(check)
    check.add_argument(
        "--plan",
        metavar='"A1 A2 ..."',
        help='action terms separated by spaces, e.g. "pull" or "go(a,b) pick(x)", '
        'or PDDL actions, e.g. "(go a b) (pick x)" (default: the plan '
        "the model comes with, if any)",
    )
    check.set_defaults(plan_file=None)
    check.set_defaults(run=command_validate)

    judging = commands.add_parser(
        "judge",
        help="judge a plan under ethical principles",
        description="Judge a plan under ethical principles (default: the paper's three, "
        "deontology, do-no-harm and utilitarianism). Status: proven, or bounded "
        "(utilitarianism compared the final state only with the states searched; "
        "avoid-avoidable-harm did not learn whether the goal is reachable).",
    )
    _add_model_arguments(judging)
    _add_plan_arguments(judging, required=False)
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
        type=_horizon,
        default=DEFAULT_MAX_HORIZON,
        metavar="N",
        help="compare with the states reachable in at most N steps "
        f"(default {DEFAULT_MAX_HORIZON})",
    )
    _add_limits(judging)
    judging.add_argument(
        "--best",
        action="store_true",
        help="also find a best reachable state (utilitarianism; by default "
        "the search stops at the first state that decides the verdict)",
    )
    _add_reasons_limit(
        judging, "compute at most N sufficient and N necessary reasons per judgement"
    )
    _add_svg_argument(judging, "the plan and its judgements")
    judging.set_defaults(run=command_judge)

    asking = commands.add_parser(
        "query",
        help="evaluate a formula of the moral action query language",
        description="Evaluate a formula of the language L for a plan and print true or "
        "false, e.g. 'Caused(one_will_die) and not Bad(pull)'.",
    )
    _add_model_arguments(asking)
    asking.add_argument("formula", metavar="FORMULA", help="the formula (syntax: docs/formulas.md)")
    _add_plan_arguments(asking, required=False)
    asking.set_defaults(run=command_query)

    contrast = commands.add_parser(
        "ask",
        help="answer a contrastive question 'why A rather than B?' about a plan",
        description="Answer contrastive questions about a plan: the plan of --plan, or else "
        "the plan the model comes with, or else the plan that 'ethasp plan "
        "--principle P' makes. The question's constraints and the principle Q "
        "(--under, default P; one that can restrict plan search) restrict the "
        "model; its plan (the contrast) is judged and explained beside the "
        "original. The principle is dropped only when no plan meeting the "
        "question is proven permissible under Q; a search cut short answers "
        "bounded. Questions (A, B actions, F a state variable, T, T1, T2, N whole "
        "numbers, steps from 1): 'why A', 'why not A', 'why A rather than B', "
        "'why A before B', 'why A after B', 'why A at T', 'why not A at T', "
        "'why A within T1..T2', 'why not A within T1..T2', 'why F', 'why not F' "
        "(the final state), 'why F at T', 'why not F at T' (the state after step "
        "T), 'why not in N steps'; 'why action X' / 'why fact X' for a name that "
        "is both. See docs/questions.md.",
    )
    _add_model_arguments(contrast)
    contrast.add_argument(
        "--question",
        action="append",
        required=True,
        metavar='"why ..."',
        help="the question (repeatable: all are imposed together)",
    )
    _add_plan_arguments(contrast, required=False, what="the plan asked about")
    contrast.add_argument(
        "--principle",
        default="deontology",
        metavar="P",
        help="the principle the plan is made and judged under (default deontology)",
    )
    contrast.add_argument(
        "--under",
        default=None,
        metavar="Q",
        help="the principle the contrast plan must satisfy (default P)",
    )
    _add_search_arguments(contrast, satisficing=True)
    _add_satisficing_argument(
        contrast,
        "the plans searched (the contrast plan, and the plan asked about when --plan is not given)",
    )
    _add_reasons_limit(contrast, answers=True)
    _add_svg_argument(contrast, "the contrast plan aligned with the plan asked about")
    contrast.set_defaults(run=command_ask)

    explaining = commands.add_parser(
        "explain",
        help="explain a plan step by step: causal links, removable steps",
        description="Explain a plan step by step: which later steps and goal facts each step "
        "serves (causal links: step i links V=B to step j when step i sets V to "
        "B, step j's precondition needs it and no step or event between them "
        "sets V), which steps the plan does not need (removable: the plan "
        "without them is still a plan), and each step's moral side (utility, bad "
        "under deontology, the valued facts it causes). The plan is --plan, or "
        "else the plan the model comes with, or else the plan 'ethasp plan "
        "[--principle P]' makes. See docs/questions.md.",
    )
    _add_model_arguments(explaining)
    _add_plan_arguments(explaining, required=False, what="the plan explained")
    explaining.add_argument(
        "--principle",
        default=None,
        metavar="P",
        help="without --plan: explain the plan made under the principle "
        "P (default: the model's own plan, else a shortest plan)",
    )
    _add_search_arguments(explaining, satisficing=True)
    _add_satisficing_argument(explaining, "the plan explained, when it is searched")
    _add_svg_argument(explaining, "the plan with its causal links as arrows")
    explaining.set_defaults(run=command_explain)

    talk = commands.add_parser(
        "dialogue",
        help="explore contrastive questions interactively",
        description="An interactive dialogue (the paper's iterative process): ask questions "
        "about the current plan (the forms of 'ethasp ask'); their constraints "
        "accumulate; 'why step T' explains a step of the current plan; undo, "
        "drop a question no plan can meet, switch principle, save and load. Type "
        "help at the prompt. The dialogue is saved when it ends (also on Ctrl-C "
        "or end of input).",
    )
    _add_model_arguments(talk, stdin=False)  # standard input carries the commands
    _hide(talk, "--json")  # refused with a line that says why
    _add_plan_arguments(talk, required=False, what="the first plan")
    talk.add_argument(
        "--principle",
        default="deontology",
        metavar="P",
        help="the principle the first plan is made (without --plan and a "
        "plan of the model's own) and judged under, and the first "
        "principle contrast plans must satisfy (default deontology; one "
        "that can restrict plan search)",
    )
    talk.add_argument("--load", metavar="FILE", help="resume a saved dialogue")
    talk.add_argument(
        "--save",
        default="ethasp-dialogue.json",
        metavar="FILE",
        help="where the dialogue is saved when it ends "
        "(default ethasp-dialogue.json; - for nowhere)",
    )
    _add_search_arguments(talk, " per question", satisficing=True)
    _add_satisficing_argument(
        talk, "the plans searched (the first plan unless --plan is given, and every contrast plan)"
    )
    _add_reasons_limit(talk, answers=True)
    talk.set_defaults(run=command_dialogue, one_answer=False)

    web = commands.add_parser(
        "serve",
        help="explore the dialogue on a local web page",
        description="Serve the dialogue as a web page on this machine: the model at a glance, "
        "the current plan judged under every principle with its reasons, "
        "questions typed or clicked, contrast plans side by side with pictures, "
        "history, undo, save and load. Only the model given here is served. "
        "The server binds 127.0.0.1 unless --host is given, and prints the "
        "page's URL.",
    )
    web.add_argument("model", nargs="+", metavar="MODEL", help=MODEL_HELP)
    web.add_argument(
        "--allow-scripts",
        action="store_true",
        help="run #script blocks in model files (refused by default)",
    )
    web.add_argument(
        "--principle",
        default="deontology",
        metavar="P",
        help="the principle the first plan is made and judged under (default deontology)",
    )
    web.add_argument(
        "--port",
        type=_port,
        default=8765,
        metavar="N",
        help="the port (default 8765; 0: any free port)",
    )
    web.add_argument(
        "--host",
        default=None,
        metavar="H",
        help="the address to bind (default 127.0.0.1; an address beyond "
        "loopback serves the page to other machines)",
    )
    web.add_argument(
        "--open",
        action="store_true",
        help="open the page in the default web browser (one line on standard "
        "error if none can be started)",
    )
    _add_search_arguments(
        web,
        quiet="no log lines from the web server on standard error "
        "(the page's URL is still printed)",
    )
    web.add_argument(
        "--log-requests",
        action="store_true",
        help="print a line per HTTP request on standard error (off by default)",
    )
    _add_reasons_limit(web, answers=True)
    web.set_defaults(run=command_serve, one_answer=False)

    shells = commands.add_parser(
        "completion",
        help="print a shell completion script (bash, zsh)",
        description="Print a script that completes ethasp's commands, options, principle "
        "names, bundled models and file names in bash or zsh. Install: "
        "'ethasp completion bash > ~/.local/share/bash-completion/completions/"
        "ethasp', or 'ethasp completion zsh > ~/.zfunc/_ethasp' with "
        "fpath+=(~/.zfunc) before compinit in ~/.zshrc (see docs/cli.md).",
    )
    shells.add_argument("shell", choices=("bash", "zsh"), help="the shell: bash or zsh")
    shells.set_defaults(run=command_completion)

    many = commands.add_parser(
        "batch",
        help="judge, plan or ask about many cases at once, on all cores or a cluster",
        description="Compute many cases at once on warm worker processes (all local cores "
        "by default, or the workers of a Dask cluster with --scheduler) and "
        "append one JSON line per case and principle (and question) to --output "
        "as each case finishes. Running the same command again skips the lines "
        "already there and computes only the missing ones. Task (default per "
        "case): ask the questions when there are any, judge the case's own plan "
        "when it has one, else plan under each principle. A bad case gets a line "
        "with its error and the batch goes on. Exit code 0 when every case "
        "succeeded, 1 when some case has an error line, 2 for bad options, "
        "130 on Ctrl-C. See docs/batch.md.",
    )
    many.add_argument(
        "cases",
        nargs="+",
        metavar="CASE",
        help="a model file (.lp, HERA .yaml/.json; a PDDL domain and problem "
        "side by side, with their .lp annotation files after them), a "
        "bundled model's name, a folder (searched recursively), or a "
        "manifest (.csv, or .yaml with a list 'cases') listing cases with "
        "their own files, plans, principles and questions",
    )
    many.add_argument(
        "--output",
        "-o",
        required=True,
        metavar="FILE",
        help="the JSON lines file the results are appended to (and resumed from)",
    )
    many.add_argument(
        "--principle",
        action="append",
        metavar="NAME",
        help="a principle or group as for 'ethasp judge' (repeatable; default "
        "the paper's three; groups: paper, hera, all)",
    )
    many.add_argument(
        "--task",
        choices=["judge", "plan", "ask"],
        default=None,
        help="judge: the case's plan under each principle; plan: a shortest "
        "plan permissible under each principle; ask: each question about "
        "the case's plan (default: per case, see above)",
    )
    many.add_argument(
        "--question",
        action="append",
        metavar='"why ..."',
        help="a contrastive question for every case (repeatable: one line per "
        "case, principle and question)",
    )
    many.add_argument(
        "--under",
        default=None,
        metavar="Q",
        help="with questions: the principle the contrast plan must satisfy "
        "(default: the principle of the line)",
    )
    many.add_argument(
        "--glob",
        default=None,
        metavar="PATTERN",
        help="in folders, only file names matching PATTERN, e.g. 'case-*.lp' "
        "(default: every .lp, .pddl, .yaml, .yml and .json file)",
    )
    many.add_argument(
        "--workers",
        type=_count("number of workers", 4096),
        default=None,
        metavar="N",
        help="local worker processes (default: one per core)",
    )
    many.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="compute on a Dask cluster, e.g. tcp://10.0.0.5:8786 (needs "
        "pip install 'ethasp[cluster]' here and on the workers)",
    )
    many.add_argument(
        "--time-limit",
        type=_seconds,
        default=DEFAULT_TIME_LIMIT,
        metavar="SECONDS",
        help="per case: searches stop after SECONDS and answer 'bounded' "
        f"(default {DEFAULT_TIME_LIMIT:g}; 0 for no limit); a case still "
        "running at twice the limit plus 10 s is stuck in grounding: its "
        "worker is ended and the case gets an error line",
    )
    many.add_argument(
        "--max-horizon",
        type=_horizon,
        default=None,
        metavar="N",
        help=f"search plans and states of at most N steps (default "
        f"{DEFAULT_MAX_HORIZON}; {DEFAULT_SATISFICING_HORIZON} for plans "
        "with --satisficing)",
    )
    many.add_argument(
        "--reasons-limit",
        type=_reasons,
        default=None,
        metavar="N",
        help="judge: add the explanation and at most N reasons of each kind to "
        "each line (default 0: verdicts only); ask: at most N reasons "
        "per judgement (default: ethasp.reasons.DEFAULT_LIMIT)",
    )
    many.add_argument(
        "--satisficing",
        action="store_true",
        help="plans searched are found fast, not proven shortest",
    )
    many.add_argument(
        "--allow-scripts",
        action="store_true",
        help="run #script blocks in model files (refused by default: such a "
        "case gets an error line)",
    )
    many.add_argument(
        "--retry-errors",
        action="store_true",
        help="compute the lines with an error again (they are removed from --output first)",
    )
    many.add_argument(
        "--report", metavar="FILE", help="also write the HTML report of --output to FILE at the end"
    )
    many.add_argument(
        "--quiet", action="store_true", help="no progress bar or summary on standard error"
    )
    many.set_defaults(run=command_batch, one_answer=False)  # each case has its own limit

    drawing = commands.add_parser(
        "report",
        help="draw the HTML report of a batch's results",
        description="Write one self-contained HTML page about a results file of 'ethasp "
        "batch': verdict counts per principle, the pairwise agreement of the "
        "principles with the cases on which they disagree, the distribution of "
        "times, the slowest and the failed cases, and every case.",
    )
    drawing.add_argument("results", metavar="RESULTS", help="the JSON lines of ethasp batch")
    drawing.add_argument(
        "--output",
        "-o",
        default=None,
        metavar="FILE",
        help="the page (default: RESULTS with the suffix .html)",
    )
    drawing.set_defaults(run=command_report)
    return parser


class _Version(argparse.Action):
    """--version, read from the package's metadata only when asked for."""

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"ethasp {package_version()}")
        parser.exit()


class _Parser(argparse.ArgumentParser):
    """Usage errors in one line, like every other error."""

    def error(self, message: str):
        command = self.prog if self.prog.startswith("ethasp ") else "ethasp"
        self.exit(2, f"ethasp: error: {' '.join(message.split())} (see {command} --help)\n")


def _command(args: argparse.Namespace) -> int:
    """Run a command; errors become one line on standard error and an exit code."""
    try:
        code = args.run(args)
        sys.stdout.flush()
        return code
    except InputError as error:
        _error(str(error))
        return 2
    except BrokenPipeError:
        # The reader went away (e.g. ethasp ... | head): stop quietly.
        sys.stderr.close()
        return 1
    except OSError as error:
        if error.filename is not None:  # a file named by the user
            _error(f"{error.filename}: {error.strerror or error}")
            return 2
        # Standard output cannot be written (a full disk).
        with contextlib.suppress(OSError):  # nothing more to flush at exit
            sys.stdout = open(os.devnull, "w")  # noqa: SIM115 (until the process ends)
        _error(f"cannot write the answer ({error.strerror or error})")
        return 1
    except RecursionError:
        _error("the input is nested too deeply to read")
        return 2
    except MemoryError:
        _error("out of memory: the input is too large")
        return 2


def _error(message: str) -> None:
    print(f"ethasp: error: {' '.join(message.split())}", file=sys.stderr, flush=True)


# A command that has not answered this long after its time limit is stuck where
# clingo cannot be stopped (the searches' groundings stop at the limit, but
# not a model's own grounding, nor a program over one plan): seconds = limit + this.
# Only commands that give one answer are watched (``one_answer``): the dialogue
# and the web page run jobs, each under the time limit of its own budget, and
# stay up however long they are used.
OVERRUN_GRACE = 10.0


def _end(code: int, end_process: bool) -> int:
    """Leave with ``code`` while the command's thread may still be inside clingo
    (or reading input): the process ends at once when it is the command line's."""
    if end_process:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(OSError, ValueError):
                stream.flush()
        os._exit(code)
    return code


def _interrupted(args: argparse.Namespace, done: threading.Event, end_process: bool) -> int:
    """Ctrl-C: one line (after saving a dialogue), exit code 130."""
    hook = getattr(args, "on_interrupt", None)
    note = ""
    if hook is not None:
        try:
            note = f"; {hook()}"
        except Exception as error:
            note = f"; dialogue not saved: {error}"
    print(f"ethasp: interrupted{note}", file=sys.stderr, flush=True)
    return 130 if done.is_set() else _end(130, end_process)


def main(argv: Sequence[str] | None = None) -> int:
    """The ethasp command line (``argv`` None: the process's arguments).

    The command runs in a worker thread, so that Ctrl-C is handled at once even
    while clingo grounds or solves, and so that a command still running long
    after its time limit (clingo cannot interrupt grounding) is ended with an
    error.  Called with ``argv`` from Python, main returns in these cases and
    leaves the worker behind; as the command line, it ends the process.
    """
    end_process = argv is None
    args = None
    try:
        parser = build_parser()
        try:
            args = parser.parse_args(argv)
        except SystemExit as done:  # --help, or a usage error already printed
            return done.code if isinstance(done.code, int) else (0 if done.code is None else 2)
        outcome: dict = {}
        done = threading.Event()

        def work() -> None:
            try:
                outcome["code"] = _command(args)
            except BaseException as error:
                outcome["error"] = error
            finally:
                done.set()

        limit = getattr(args, "time_limit", None)
        overrun = limit + OVERRUN_GRACE if limit and args.one_answer else None
        started = time.monotonic()
        # (An Event, not Thread.join: an interrupted join can mark a running
        # thread as stopped.)
        threading.Thread(target=work, name="ethasp-command", daemon=True).start()
        memory = getattr(args, "memory_limit", None)
        memory = memory * 2**30 if memory else None
        try:
            while not done.wait(0.5):
                if memory is not None and args.one_answer:
                    used = _memory()
                    limits = getattr(args, "limits", None)
                    if used > memory and limits is not None and not limits.cancelled:
                        limits.cancel(f"the memory limit of {args.memory_limit:g} GB was reached")
                    if used > MEMORY_HARD * memory:
                        _error(
                            f"out of memory: {used / 2**30:.1f} GB in use, more than "
                            f"{MEMORY_HARD:g} times the memory limit of "
                            f"{args.memory_limit:g} GB, where clingo cannot be stopped "
                            "(--memory-limit GB raises it)"
                        )
                        return _end(2, end_process)
                if overrun is not None and time.monotonic() - started > overrun:
                    _error(
                        f"no answer within the time limit of {limit:g} s: still working "
                        f"after {overrun:g} s, where clingo cannot be stopped (the model's "
                        "own grounding, or a program over one plan; does it end?)"
                    )
                    return _end(2, end_process)
        except KeyboardInterrupt:
            return _interrupted(args, done, end_process)
        if "error" in outcome:
            error = outcome["error"]
            if isinstance(error, KeyboardInterrupt):
                return _interrupted(args, done, end_process)
            if os.environ.get("ETHASP_DEBUG"):
                raise error
            _error(
                f"internal error: {type(error).__name__}: {error} (please report it; "
                "ETHASP_DEBUG=1 shows where)"
            )
            return 70
        # The command is done and its output written: the process ends at
        # once, without tearing down clingo's grounding (tens of milliseconds).
        return _end(outcome["code"], end_process)
    except KeyboardInterrupt:
        print("ethasp: interrupted", file=sys.stderr, flush=True)
        return 130


if __name__ == "__main__":
    sys.exit(main())
