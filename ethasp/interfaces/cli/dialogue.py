"""``ethasp dialogue``: questions one after another at a prompt."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ethasp.errors import InputError
from ethasp.interfaces.cli.models import STDIN, load_model, model_files, model_options
from ethasp.interfaces.cli.options import (
    default_reasons_limit,
    given_plan,
    hide,
    inherit,
    max_horizon,
    plan_options,
    reasons_option,
    satisficing_option,
    search_options,
)
from ethasp.interfaces.cli.output import writable
from ethasp.interfaces.progress import ProgressLine
from ethasp.planning.model import Model


def add_parser(commands) -> None:
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
    inherit(talk, model_options(stdin=False))  # standard input carries the commands
    hide(talk, "--json")  # refused with a line that says why
    inherit(talk, plan_options(required=False, what="the first plan"))
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
    inherit(talk, search_options(" per question", satisficing=True))
    inherit(
        talk,
        satisficing_option(
            "the plans searched (the first plan unless --plan is given, and every contrast plan)"
        ),
    )
    inherit(talk, reasons_option(answers=True))
    talk.set_defaults(run=run, one_answer=False)


def run(args: argparse.Namespace) -> int:
    from ethasp.interfaces.prompt import Prompt
    from ethasp.questions.dialogue import Dialogue

    default_reasons_limit(args)
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
        writable(save, "--save")
    model = load_model(args)
    options = {
        "max_horizon": max_horizon(args),
        "time_limit": args.time_limit,
        "reasons_limit": args.reasons_limit,
        "satisficing": args.satisficing,
    }
    progress = ProgressLine(enabled=False if args.quiet else None)
    files = model_files(args, resolve=True)
    if args.load:
        dialogue = Dialogue.load(args.load, model, **options)
    else:
        plan = given_plan(args) if (args.plan or args.plan_file) else model.own_plan()
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
