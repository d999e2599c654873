"""The interactive prompt of ``ethasp dialogue`` (reads commands line by line).

The prompt keeps the dialogue; the moves that need clingo (questions, the
current plan in words, undo, load) are module-level functions that it runs
through a function given to it: ``ethasp dialogue`` runs them in a worker
process that keeps the model grounded (:mod:`ethasp.interfaces.cli.dialogue`),
so that Ctrl-C or a limit ends a move at once and the dialogue goes on as it
was before the move.
"""

from __future__ import annotations

import contextlib
import json
import textwrap
import threading
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any, TextIO

from ethasp.errors import InputError
from ethasp.interfaces.answer_words import answer_text, unmeetable_text
from ethasp.interfaces.progress import ProgressLine
from ethasp.planning.model import Model, kept
from ethasp.planning.plan import Plan
from ethasp.principles.restriction import restricting_principles
from ethasp.questions.dialogue import Dialogue
from ethasp.questions.question import step_question

HELP = """\
Commands:
  why A | why not A | why A rather than B | why A before B | why A after B
  why A at T | why not A at T | why A within T1..T2 | why not A within T1..T2
  why F | why not F | why F at T | why not F at T | why not in N steps
  why not a cheaper plan (a model with action costs)
                     ask about the current plan (A, B actions, F a state
                     variable, T, N step numbers; 'why action X' or 'why
                     fact X' for a name that is both); the question's
                     constraints stay imposed on later contrast plans
  why step T         how step T of the current plan serves later steps
                     and the goal (causal links), and whether it is needed
  principle NAME     the principle later contrast plans must satisfy, one
                     that can restrict plan search:
{principles}
  plan               show the current plan and its explanation
  history            the questions asked so far, with their principles
  undo               take back the last question
  drop               take back the last question when no plan can meet it
  save FILE          save the whole dialogue to FILE (JSON)
  save -             print the whole dialogue (JSON) on standard output
  load FILE          load a dialogue saved before
  help               this text
  quit               end the dialogue (saved with --save FILE)"""

STANDARD_OUTPUT = "-"  # as a file to save to: print the JSON instead


# -- the moves that need clingo, as a worker process makes them -----------------------
#
# Each takes the dialogue (its model a reference to the model the worker keeps
# warm: ethasp.planning.model) and returns what the prompt prints, with the
# dialogue after the move where it changes.


def warm(model: Model) -> None:
    """A new worker's first work: keep the model and ground it (an error is
    left to the first move, which meets it again and says it)."""
    with contextlib.suppress(Exception):
        kept(model).planner  # noqa: B018 (grounds the model)


def opened(
    model: Model,
    principle: str,
    plan: Plan | None,
    saved: str | None,
    files: list[str],
    options: dict,
) -> tuple[Dialogue, list[str], list[str], str]:
    """The dialogue's start: the model checked, the dialogue loaded from
    ``saved`` or started about ``plan`` (else the model's own plan, else the
    plan made under ``principle``); the names the line editor completes
    (actions, facts) and the current plan in words."""
    model = kept(model)
    if not model.checked:
        model.check()
    if saved is not None:
        dialogue = Dialogue.load(saved, model, **options)
    else:
        own = plan if plan is not None else model.own_plan()
        dialogue = Dialogue.start(model, principle, own, files, **options)
    dialogue.model_files = list(files)
    naming, planner = model.naming, model.planner
    actions = [naming.action(atom.arguments[0]) for atom in planner.get("action", 1)]
    facts = [naming.fact(str(atom.arguments[0])) for atom in planner.get("variable", 1)]
    return dialogue, actions, facts, current_text(dialogue)


def current_text(dialogue: Dialogue) -> str:
    """The current plan judged and explained under its principle, in words."""
    report = dialogue.current()
    judgement = report.judgements[0]
    naming = dialogue.model.naming
    text = judgement.explanation.text if judgement.explanation else ""
    verdict = "permissible" if judgement.permissible else "impermissible"
    lines = [
        f"current plan: {naming.actions(report.plan) or '(empty)'} "
        f"({judgement.principle}: {verdict})"
    ]
    if text:
        lines.append(text)
    lines.append(f"next contrasts must satisfy: {dialogue.under}")
    return "\n".join(lines)


def asked(dialogue: Dialogue, question: str) -> tuple[Dialogue, str]:
    """A question asked about the current plan, and its answer in words."""
    answer = dialogue.ask(question)
    lines = [answer_text(answer, dialogue.model.naming)]
    if dialogue.unmeetable is not None:
        lines.append(unmeetable_text(answer, dialogue.model.naming))
    return dialogue, "\n".join(lines)


def step_text(dialogue: Dialogue, step: int) -> str:
    """``why step T``: how a step of the current plan serves the goal."""
    return dialogue.explain_step(step).step_text(step, dialogue.model)


def taken_back(dialogue: Dialogue, dropped: bool) -> tuple[Dialogue, str]:
    """The last question taken back (``dropped``: one no plan can meet), and
    the current plan after."""
    step = dialogue.undo()
    said = (
        f"dropped: {step.question} (its constraints are no longer imposed)"
        if dropped
        else f"took back: {step.question}"
    )
    return dialogue, f"{said}\n{current_text(dialogue)}"


def loaded(path: str, model: Model, files: list[str], options: dict) -> tuple[Dialogue, str]:
    """A saved dialogue, its questions asked again; what the prompt says."""
    dialogue = Dialogue.load(path, kept(model), **options)
    dialogue.model_files = list(files)
    return dialogue, (f"loaded {path} ({len(dialogue.steps)} questions)\n{current_text(dialogue)}")


class Stopped(Exception):
    """A move ended without an answer (interrupted, or at a limit): the
    prompt says why and goes on with the dialogue as it was."""


def here(move: Callable[..., Any], *args: Any) -> Any:
    """Make a move in this process."""
    return move(*args)


class Prompt:
    """Runs a dialogue from lines of text; saves it when it ends to
    ``save_path`` (``-``: prints it on ``output``; None: not at all).

    The moves that need clingo go through ``run`` (``run(move, *args)``
    returns what ``move(*args)`` returns; :func:`here` by default, a worker
    process for ``ethasp dialogue``), each on a copy of the dialogue: the
    dialogue changes only when a move ends with an answer.  ``options`` are
    those of dialogues loaded (``max_horizon``, ...), ``files`` the model's
    files they record.
    """

    def __init__(
        self,
        dialogue: Dialogue,
        save_path: Path | str | None,
        output: TextIO,
        progress: ProgressLine | None = None,
        run: Callable[..., Any] = here,
        options: dict | None = None,
        files: Sequence[str] = (),
    ):
        self.dialogue = dialogue
        self.save_path = save_path
        self.output = output
        self.progress = progress
        self.options = dict(options or {})
        self.files = list(files)
        self._run = run
        self._saving = threading.Lock()  # an interrupt saves from another thread
        self._ended = False

    def say(self, text: str) -> None:
        if self.progress is not None:
            self.progress.clear()
        print(text, file=self.output, flush=True)

    def move(self, move: Callable[..., Any], *args: Any) -> Any:
        """Make a move on a copy of the dialogue (see the class docstring)."""
        if self._run is here:
            args = tuple(copy(arg) if isinstance(arg, Dialogue) else arg for arg in args)
        return self._run(move, *args)

    def show_current(self) -> None:
        self.say(self.move(current_text, self.dialogue))

    def handle(self, line: str) -> bool:
        """Carry out one command; False when the dialogue should end."""
        words = line.strip().split(None, 1)
        if not words:
            return True
        command, rest = words[0].lower(), (words[1].strip() if len(words) > 1 else "")
        if command in ("quit", "exit"):
            return False
        if command == "help":
            self.say(
                HELP.format(
                    principles=textwrap.fill(
                        ", ".join(restricting_principles()),
                        74,
                        initial_indent=" " * 21,
                        subsequent_indent=" " * 21,
                        break_on_hyphens=False,
                    )
                )
            )
        elif command == "why" and step_question(line) is not None:
            self.say(self.move(step_text, self.dialogue, step_question(line)))
        elif command == "why":
            self.dialogue, text = self.move(asked, self.dialogue, line.strip())
            self.say(text)
        elif command == "principle":
            if not rest:
                self.say(f"next contrasts must satisfy: {self.dialogue.under}")
            else:
                self.say(f"next contrasts must satisfy: {self.dialogue.switch_principle(rest)}")
        elif command in ("plan", "show"):
            self.show_current()
        elif command == "history":
            if not self.dialogue.steps:
                self.say("no question asked yet")
            for number, step in enumerate(self.dialogue.steps, start=1):
                own = [
                    c
                    for c in step.answer.constraints
                    if c.question == step.answer.constraints[-1].question
                ]
                naming = self.dialogue.model.naming
                self.say(
                    f"{number}. {step.question} (under {step.under}): "
                    f"{', '.join(naming.constraint(c.term) for c in own)}"
                )
        elif command in ("undo", "drop"):
            if command == "drop" and self.dialogue.unmeetable is None:
                raise InputError(
                    "drop: the last question does not conflict (no question to "
                    "drop); undo takes back any last question"
                )
            self.dialogue, text = self.move(taken_back, self.dialogue, command == "drop")
            self.say(text)
        elif command == "save":
            if not rest:
                raise InputError("save: give a file name (- for standard output)")
            self.say(self._save(rest))
        elif command == "load":
            if not rest:
                raise InputError("load: give a file name")
            self.dialogue, text = self.move(
                loaded, rest, self.dialogue.model, self.files, self.options
            )
            self.say(text)
        else:
            raise InputError(f"unknown command {command!r} (type help)")
        return True

    def run(self, read: Callable[[], str], current: str | None = None) -> int:
        """Say ``current`` (the current plan in words; else it is made), read
        and carry out commands until quit or end of input, then save the
        dialogue (InputError if it cannot be written).  On Ctrl-C (a
        KeyboardInterrupt here: at the prompt, or during a move made in this
        process) the dialogue is saved and the interrupt raised on; a move
        that ``run`` stopped (:class:`Stopped`) leaves the dialogue as it was."""
        if current is None:
            self.show_current()
        else:
            self.say(current)
        try:
            while True:
                try:
                    line = read()
                except EOFError:
                    break
                try:
                    if not self.handle(line):
                        break
                except InputError as error:
                    self.say(f"error: {error}")
                except Stopped as stopped:
                    self.say(str(stopped))
        except KeyboardInterrupt:
            self.say("")
            self.say(self.save_now())
            raise
        with self._saving:
            if self._ended:  # saved on an interrupt meanwhile
                return 130
            self._ended = True
            if self.save_path is not None:
                said = self._save(self.save_path)
                if self.save_path != STANDARD_OUTPUT:  # the JSON ends standard output
                    self.say(said)
        return 0

    def _save(self, path: Path | str) -> str:
        """Save the dialogue to a file, or print it (``-``); what happened, in words."""
        if str(path) == STANDARD_OUTPUT:
            self.say(json.dumps(self.dialogue.to_json(), indent=2))
            return "dialogue written to standard output"
        self.dialogue.save(path)
        return f"dialogue saved to {path}"

    def _saved(self) -> str:
        if self.save_path is None:
            return "dialogue not saved (--save FILE saves it)"
        if str(self.save_path) == STANDARD_OUTPUT:
            return "dialogue written to standard output"
        return f"dialogue saved to {self.save_path}"

    def save_now(self) -> str:
        """Save the dialogue as it stands and end it (on an interrupt, from any
        thread); what happened, in words."""
        with self._saving:
            if self._ended:  # it ended meanwhile, and saved itself
                return self._saved()
            self._ended = True
            if self.save_path is None:
                return self._saved()
            try:
                return self._save(self.save_path)
            except InputError as error:
                return f"dialogue not saved: {error}"


def copy(dialogue: Dialogue) -> Dialogue:
    """A dialogue whose questions can change without changing the original's."""
    return replace(dialogue, steps=list(dialogue.steps))
