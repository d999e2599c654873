"""The interactive prompt of ``ethasp dialogue`` (reads commands line by line)."""

from __future__ import annotations

import json
import textwrap
import threading
from collections.abc import Callable
from pathlib import Path
from typing import TextIO

from ethasp.errors import InputError
from ethasp.interfaces.progress import ProgressLine
from ethasp.interfaces.shortening import shorten_literal
from ethasp.principles.restriction import restricting_principles
from ethasp.questions.contrast import Answer
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


def answer_text(answer: Answer, naming) -> str:
    """An answer in words, then the plans, verdicts and constraints."""
    lines = [answer.explanation]
    if answer.impasse is not None:
        lines.append(answer.impasse.text)
    original = answer.original
    lines.append(
        f"  plan asked about: {naming.actions(original.plan) or '(empty)'} "
        f"({original.principle}: {_verdict(original)}{_cost(original.cost)})"
    )
    if answer.contrast is not None:
        contrast = answer.contrast
        lines.append(
            f"  contrast plan: {naming.actions(contrast.plan) or '(empty)'} "
            f"({contrast.principle}: {_verdict(contrast)}{_cost(contrast.cost)})"
        )
    elif answer.status == "bounded":
        lines.append(f"  no contrast plan found (bounded): {answer.proof}")
    else:
        lines.append(f"  no contrast plan: {answer.proof}")
    if answer.principle_dropped:
        lines.append(
            f"  the principle {answer.under} was dropped for the contrast: "
            f"{answer.dropped_because}; the contrast plan was made without it and "
            f"is judged under it"
        )
    if answer.note:
        lines.append(f"  note: {answer.note}")
    if answer.impasse is not None:
        lines += impasse_lines(answer.impasse, naming, answer.under)
    constraints = ", ".join(naming.constraint(c.term) for c in answer.constraints)
    lines.append(f"  constraints: {constraints}")
    if answer.conflict:
        lines.append(
            f"  conflicting constraints: "
            f"{', '.join(naming.constraint(c.term) for c in answer.conflict)}"
        )
    difference = answer.difference
    if difference["original_only"] or difference["contrast_only"]:
        lines.append(
            f"  reasons only for the plan asked about: "
            f"{_literals(difference['original_only'])}; "
            f"only for the contrast: {_literals(difference['contrast_only'])}"
        )
    return "\n".join(lines)


def _cost(cost: int | None) -> str:
    """``; cost 5`` for a plan of a model with action costs."""
    return f"; cost {cost}" if cost is not None else ""


def impasse_lines(impasse, naming, under: str) -> list[str]:
    """The conflicts of a dropped principle and the cheapest repair, in lines."""
    conflicts = impasse.conflicts

    def shown(items) -> str:
        return "{" + ", ".join(item.text(naming) for item in items) + "}"

    found = "; ".join(shown(conflict) for conflict in conflicts.conflicts) or "none"
    more = ", more may exist" if conflicts.conflicts_truncated else ""
    lines = [f"  conflicts under {under} ({conflicts.status}{more}): {found}"]
    result = impasse.repair
    if result is not None:
        if result.repairs:
            best = result.repairs[0]
            changes = "; ".join(change.text(naming) for change in best.changes)
            status = "least, proven" if result.status == "found" else "bounded"
            plan = naming.actions(best.plan) if best.plan is not None else "(none found)"
            lines.append(
                f"  cheapest repair (cost {best.cost}, {status}): {changes}; plan: "
                f"{plan or '(empty plan)'}"
            )
        else:
            lines.append(f"  no repair ({result.status}): {result.proof}")
    return lines


def _literals(literals: list[str]) -> str:
    """Literals of reasons, long ones shortened (``--json`` has them whole)."""
    return ", ".join(shorten_literal(literal) for literal in literals) or "none"


def unmeetable_text(answer: Answer, naming) -> str:
    """What the dialogue says when no plan can meet the questions imposed."""
    conflict = ", ".join(naming.constraint(c.term) for c in answer.conflict)
    return (
        "No plan can meet the questions asked so far together (conflicting constraints: "
        f"{conflict}); they stay imposed, so every later question would have no contrast "
        "plan either. Type drop to take back the last question."
    )


def _verdict(side) -> str:
    word = "permissible" if side.judgement.permissible else "impermissible"
    return word if side.judgement.status == "proven" else f"{word}, bounded"


class Prompt:
    """Runs a dialogue from lines of text; saves it when it ends to
    ``save_path`` (``-``: prints it on ``output``; None: not at all)."""

    def __init__(
        self,
        dialogue: Dialogue,
        save_path: Path | str | None,
        output: TextIO,
        load: Callable[[str], Dialogue],
        progress: ProgressLine | None = None,
    ):
        self.dialogue = dialogue
        self.save_path = save_path
        self.output = output
        self.load = load
        self.progress = progress
        self._saving = threading.Lock()  # an interrupt saves from another thread
        self._ended = False

    def say(self, text: str) -> None:
        if self.progress is not None:
            self.progress.clear()
        print(text, file=self.output, flush=True)

    def show_current(self) -> None:
        report = self.dialogue.current()
        judgement = report.judgements[0]
        naming = self.dialogue.model.naming
        text = judgement.explanation.text if judgement.explanation else ""
        verdict = "permissible" if judgement.permissible else "impermissible"
        self.say(
            f"current plan: {naming.actions(report.plan) or '(empty)'} "
            f"({judgement.principle}: {verdict})"
        )
        if text:
            self.say(text)
        self.say(f"next contrasts must satisfy: {self.dialogue.under}")

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
            step = step_question(line)
            explanation = self.dialogue.explain_step(step)
            self.say(explanation.step_text(step, self.dialogue.model))
        elif command == "why":
            answer = self.dialogue.ask(line.strip())
            self.say(answer_text(answer, self.dialogue.model.naming))
            if self.dialogue.unmeetable is not None:
                self.say(unmeetable_text(answer, self.dialogue.model.naming))
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
        elif command == "undo":
            step = self.dialogue.undo()
            self.say(f"took back: {step.question}")
            self.show_current()
        elif command == "drop":
            if self.dialogue.unmeetable is None:
                raise InputError(
                    "drop: the last question does not conflict (no question to "
                    "drop); undo takes back any last question"
                )
            step = self.dialogue.undo()
            self.say(f"dropped: {step.question} (its constraints are no longer imposed)")
            self.show_current()
        elif command == "save":
            if not rest:
                raise InputError("save: give a file name (- for standard output)")
            self.say(self._save(rest))
        elif command == "load":
            if not rest:
                raise InputError("load: give a file name")
            self.dialogue = self.load(rest)
            self.say(f"loaded {rest} ({len(self.dialogue.steps)} questions)")
            self.show_current()
        else:
            raise InputError(f"unknown command {command!r} (type help)")
        return True

    def run(self, read: Callable[[], str]) -> int:
        """Read and carry out commands until quit or end of input, then save the
        dialogue (InputError if it cannot be written).  On Ctrl-C (a
        KeyboardInterrupt here) the dialogue is saved and the interrupt raised on."""
        self.show_current()
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
