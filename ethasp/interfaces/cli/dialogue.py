"""``ethasp dialogue``: questions one after another at a prompt."""

from __future__ import annotations

import argparse
import functools
import os
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ethasp.errors import InputError
from ethasp.execution.limits import Limits
from ethasp.execution.worker import DONE, INPUT_ERROR, Outcome, Worker
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
        "help at the prompt. Each question is answered by a worker process that "
        "keeps the model grounded, under the limits below; Ctrl-C during a "
        "question ends its work and the dialogue goes on as it was. With --save "
        "FILE the dialogue is saved when it ends (also on Ctrl-C at the prompt, "
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
        default=None,
        metavar="FILE",
        help="save the dialogue (JSON) to FILE when it ends, also on Ctrl-C or "
        "end of input (- for standard output, after the conversation; "
        "default: not saved)",
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
    from ethasp.interfaces.prompt import STANDARD_OUTPUT, Prompt, opened

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
    save: Path | str | None = args.save
    if save is not None and save != STANDARD_OUTPUT:
        save = Path(save)
        writable(save, "--save")
    # This process reads the model; a worker grounds it and makes every move.
    model = load_model(args, check=False)
    options = {
        "max_horizon": max_horizon(args),
        "time_limit": args.time_limit,
        "reasons_limit": args.reasons_limit,
        "satisficing": args.satisficing,
    }
    progress = ProgressLine(enabled=False if args.quiet else None)
    files = model_files(args, resolve=True)
    plan = given_plan(args) if (args.plan is not None or args.plan_file is not None) else None
    moves = Moves(model, args, progress)
    try:
        dialogue, actions, facts, current = moves.first(
            opened, model, args.principle, plan, args.load, files, options
        )
        interactive = sys.stdin.isatty()
        # At a terminal: editing keys, a history across runs, Tab completion.
        editor = _line_editor(actions, facts) if interactive else None

        def read() -> str:
            line = editor.read("ethasp> ") if editor is not None else input("")
            # Bytes that are not UTF-8 become U+FFFD, so that messages can show them.
            return line.encode("utf-8", "surrogateescape").decode("utf-8", "replace")

        if interactive:
            print("ethasp dialogue: type help for the commands, quit to end.")
        prompt = Prompt(dialogue, save, sys.stdout, progress, moves, options, files)

        def on_interrupt() -> str:  # Ctrl-C at the prompt saves the dialogue first
            if editor is not None:
                editor.restore()
                print(file=sys.stderr)  # off the line being edited
            return prompt.save_now()

        args.on_interrupt = on_interrupt
        return prompt.run(read, current)
    finally:
        moves.close()


class Moves:
    """The dialogue's moves, made in a worker process that keeps the model
    grounded (:mod:`ethasp.execution.worker`), each under the command's
    limits.  Ctrl-C during a move, or a limit passed, ends the worker at
    once: the prompt says so and goes on with the dialogue as it was, and a
    new worker grounds the model while the next command is typed."""

    def __init__(self, model: Model, args: argparse.Namespace, progress: ProgressLine):
        from ethasp.interfaces.prompt import warm

        self.args = args
        self.progress = progress
        self.worker = Worker(functools.partial(warm, model), name="ethasp-dialogue")
        self.worker.start()

    def _limits(self) -> Limits:
        return Limits.of(self.args.time_limit, self.args.memory_limit)

    def _call(self, move: Callable[..., Any], args: tuple) -> Outcome:
        try:
            return self.worker.call(move, *args, limits=self._limits(), on_progress=self.progress)
        except KeyboardInterrupt:
            self._renew()
            raise
        finally:
            self.progress.clear()

    def _renew(self) -> None:
        self.worker.kill()
        self.worker.start()

    def first(self, move: Callable[..., Any], *args: Any) -> Any:
        """The dialogue's start: errors end the command (one line)."""
        outcome = self._call(move, args)
        if outcome.status == DONE:
            return outcome.value
        if outcome.status == INPUT_ERROR:
            raise InputError(outcome.message)
        if outcome.limited:
            raise InputError(f"no dialogue: {outcome.message} before it could start")
        raise RuntimeError(_failure(outcome))

    def __call__(self, move: Callable[..., Any], *args: Any) -> Any:
        """A move of the dialogue (see the class docstring)."""
        from ethasp.interfaces.prompt import Stopped

        unchanged = "the dialogue is as it was"
        try:
            outcome = self._call(move, args)
        except KeyboardInterrupt:
            raise Stopped(f"interrupted: the work was ended and {unchanged}") from None
        if outcome.status == DONE:
            return outcome.value
        if outcome.status == INPUT_ERROR:
            raise InputError(outcome.message)
        self._renew()
        if outcome.limited:
            raise Stopped(f"no answer: {outcome.message}; the work was ended and {unchanged}")
        raise Stopped(
            f"internal error: {_failure(outcome)} (please report it; ETHASP_DEBUG=1 shows "
            f"where); {unchanged}"
        )

    def close(self) -> None:
        self.worker.kill()


def _failure(outcome: Outcome) -> str:
    """The last line of a failed move (the whole trace with ETHASP_DEBUG)."""
    if os.environ.get("ETHASP_DEBUG"):
        print(outcome.message, file=sys.stderr, flush=True)
    lines = outcome.message.strip().splitlines()
    return lines[-1] if lines else outcome.status


def _line_editor(actions: list[str], facts: list[str]):
    """The dialogue's line editor (ethasp/interfaces/editing.py): it completes
    commands, the model's actions and variables, and principle names."""
    from ethasp.interfaces.completion import principle_names
    from ethasp.interfaces.editing import Completer, LineEditor, history_path

    return LineEditor(Completer(actions, facts, principle_names(restricting=True)), history_path())
