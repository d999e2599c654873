"""Contrastive questions "Why A rather than B?" about a plan: its actions, when
they happen, its outcome and its length.

Grammar of typed questions (the words ``why``, ``not``, ``rather than``,
``before``, ``after``, ``at``, ``within``, ``in``, ``steps``, ``action`` and
``fact`` in any case; a final ``?`` is allowed).  A and B are actions, F a
state variable (or a derived variable), all written as ASP terms or, for
PDDL models, as PDDL expressions (``(move hall kitchen)``); T, T1, T2 and N
are whole numbers, and steps count from 1.  "The state after step T" is the
state after the T-th action and the events of step T; for a plan of fewer
than T steps it is the plan's final state::

    why A                    contrast: A is not used                unused(A)
    why not A                contrast: A is used                    used(A)
    why A rather than B      contrast: A is not used, B is used     unused(A), used(B)
    why A before B           contrast: B is used, no A before the first B   before(B,A)
    why A after B            contrast: A is used, no B before the first A   before(A,B)
    why A at T               contrast: A is not the action of step T  not_at(A,T)
    why not A at T           contrast: A is the action of step T    at(A,T)
    why A within T1..T2      contrast: A at no step from T1 to T2   not_within(A,T1,T2)
    why not A within T1..T2  contrast: A at some step T1 to T2      within(A,T1,T2)
    why F                    contrast: F is false at the end        ends(F,false)
    why not F                contrast: F is true at the end         ends(F,true)
    why F at T               contrast: F is false after step T      fact_at(F,false,T)
    why not F at T           contrast: F is true after step T       fact_at(F,true,T)
    why not in N steps       contrast: at most N steps              at_most(N)
    why not a cheaper plan   contrast: costs less than the plan,    cheaper_than(C)
                             C (a model with action costs)

``why X`` (with or without ``not``, ``at`` or ``within``) names an action or a
state variable; a name that is both is refused unless the question says which:
``why action X``, ``why fact X``.  "Before" means at an earlier step.
``why A before B`` presupposes that the plan uses B and an A before its first
B; ``why A after B`` that it uses A and a B before its first A.  ``why step
T`` is no contrastive question: it asks for the causal explanation of step T
of the plan (:func:`step_question`, :mod:`ethasp.questions.steps`).

A question becomes constraint facts ``contrast(Q,C)`` read by the fixed
encoding ``encodings/questions/questions.lp``; no rule text is generated.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import clingo

from ethasp.errors import InputError
from ethasp.planning.plan import split_terms

KINDS = ("why", "why-not", "rather-than", "before", "after", "length", "cheaper")
# The kinds whose subject may be an action or a state variable.
EITHER = ("why", "why-not")
# The kinds about two actions.
PAIRS = {"rather-than": "rather than", "before": "before", "after": "after"}
WHAT = ("action", "fact")

# The largest step number or length a question may name (clingo's numbers are
# 32-bit; no search goes anywhere near).
MAX_STEP = 1_000_000

FORMS = (
    "why A | why not A | why A rather than B | why A before B | why A after B | "
    "why [not] A at T | why [not] A within T1..T2 | why [not] F | why [not] F at T | "
    "why not in N steps | why not a cheaper plan"
)
_CHEAPER = re.compile(r"why\s+not\s+(a\s+)?cheaper(\s+plan)?", re.IGNORECASE)

_WINDOW = re.compile(r"(\d+)\s*\.\.\s*(\d+)")
_STEP_QUESTION = re.compile(r"\s*why\s+step\s+(\S+?)\s*\??\s*", re.IGNORECASE)


def _number(text: str, what: str, question: str, least: int = 1) -> int:
    if not re.fullmatch(r"\d+", text):
        raise InputError(
            f"question: expected {what} (a whole number), got {text!r} in {question!r}"
        )
    value = int(text)
    if value < least or value > MAX_STEP:
        raise InputError(
            f"question: {what} {value} in {question!r} must be from {least} to {MAX_STEP:,}"
        )
    return value


def step_question(text: str) -> int | None:
    """The step T of ``why step T`` (the causal explanation of a step), or None
    for any other text; InputError for ``why step`` with no step number."""
    match = _STEP_QUESTION.fullmatch(text)
    if match is None:
        return None
    return _number(match.group(1), "a step number", text.strip())


@dataclass(frozen=True)
class Question:
    """A contrastive question: its kind, what it names (as text) and the steps.

    ``action`` is the action or state variable named (``what`` says which
    when the question does: ``action`` or ``fact``), ``other`` the second
    action of ``rather-than``, ``before`` and ``after``; ``at`` a step,
    ``within`` a window of steps (first, last); ``steps`` the length N of
    ``why not in N steps`` (kind ``length``).  ``why not a cheaper plan``
    (kind ``cheaper``) names nothing: its contrast costs less than the plan
    asked about.
    """

    kind: str
    action: str | None = None
    other: str | None = None
    at: int | None = None
    within: tuple[int, int] | None = None
    steps: int | None = None
    what: str | None = None

    def __post_init__(self):
        if self.kind not in KINDS:
            raise InputError(f"question: unknown kind {self.kind!r} (one of {', '.join(KINDS)})")
        if self.what is not None and self.what not in WHAT:
            raise InputError(f"question: 'what' must be action or fact, not {self.what!r}")
        if self.kind == "cheaper":
            if any(
                value is not None
                for value in (self.action, self.other, self.at, self.within, self.steps)
            ):
                raise InputError("question: kind cheaper names nothing (why not a cheaper plan)")
            return
        if self.kind == "length":
            if (
                self.steps is None
                or self.action is not None
                or self.other is not None
                or self.at is not None
                or self.within is not None
            ):
                raise InputError("question: kind length needs 'steps' (a number) and nothing else")
            self._check_step(self.steps, "the number of steps", 0)
            return
        if self.action is None or self.steps is not None:
            raise InputError(
                f"question: kind {self.kind} needs an action"
                + (" or a state variable" if self.kind in EITHER else "")
                + " and no 'steps'"
            )
        if (self.kind in PAIRS) != (self.other is not None):
            raise InputError(
                f"question: kind {self.kind} needs "
                f"{'two actions' if self.other is None else 'one action'}"
            )
        if self.kind in PAIRS and (self.at is not None or self.within is not None):
            raise InputError(f"question: kind {self.kind} takes no step")
        if self.kind in PAIRS and self.what == "fact":
            raise InputError(f"question: kind {self.kind} is about actions, not facts")
        if self.at is not None and self.within is not None:
            raise InputError("question: 'at' and 'within' cannot go together")
        if self.at is not None:
            self._check_step(self.at, "step", 1)
        if self.within is not None:
            if len(self.within) != 2:
                raise InputError("question: 'within' needs two steps, the first and the last")
            first, last = self.within
            self._check_step(first, "step", 1)
            self._check_step(last, "step", 1)
            if first > last:
                raise InputError(
                    f"question: the window {first}..{last} is empty (the first "
                    "step comes after the last)"
                )
            if self.what == "fact":
                raise InputError(
                    "question: a window of steps applies to actions; ask about a "
                    "fact after one step: why [not] F at T"
                )

    @staticmethod
    def _check_step(value, what: str, least: int) -> None:
        if not isinstance(value, int) or isinstance(value, bool) or not least <= value <= MAX_STEP:
            raise InputError(
                f"question: {what} must be a whole number from {least} to "
                f"{MAX_STEP:,}, not {value!r}"
            )

    # -- text -----------------------------------------------------------------

    @classmethod
    def parse(cls, text: str) -> Question:
        """Read a typed question such as ``why refrain rather than pull`` (see
        the module docstring for the grammar)."""
        shown = text.strip()
        body = shown.rstrip("?").strip()
        words = body.split(None, 1)
        if not words or words[0].lower() != "why" or len(words) < 2:
            raise InputError(f"question: expected 'why ...', got {shown!r} (forms: {FORMS})")
        if _CHEAPER.fullmatch(body):
            return cls("cheaper")
        if step_question(shown) is not None:
            raise InputError(
                f"question {shown!r} asks for the causal explanation of a step "
                "(ethasp explain, or 'why step T' in the dialogue), not for a "
                "contrast"
            )
        tokens = split_terms(words[1])
        lower = [token.lower() for token in tokens]
        negated = lower[0] == "not"
        if negated:
            tokens, lower = tokens[1:], lower[1:]
            if not tokens:
                raise InputError(f"question: missing action after 'why not' in {shown!r}")
            if len(tokens) == 3 and lower[0] == "in" and lower[2] in ("steps", "step"):
                return cls("length", steps=_number(tokens[1], "a number of steps", shown, 0))

        def keyword_at(position: int) -> bool:
            word = lower[position]
            return word in ("before", "after", "at", "within") or (
                word == "rather" and lower[position + 1 : position + 2] == ["than"]
            )

        # The subject comes first, so keywords are looked for after it (an
        # action may be named "at": why at at 2).
        keyword, index = None, None
        for position in range(1, len(tokens)):
            if keyword_at(position):
                keyword, index = lower[position], position
                break
        if keyword is None:
            if keyword_at(0) and len(tokens) > 1:
                raise InputError(f"question: missing action before '{tokens[0]}' in {shown!r}")
            what, subject = cls._subject(tokens, shown)
            return cls("why-not" if negated else "why", subject, what=what)
        after = index + (2 if keyword == "rather" else 1)
        if after >= len(tokens):
            missing = "step" if keyword in ("at", "within") else "action"
            raise InputError(f"question: missing {missing} at the end of {shown!r}")
        what, subject = cls._subject(tokens[:index], shown)
        rest = tokens[after:]
        if keyword in ("at", "within"):
            kind = "why-not" if negated else "why"
            if keyword == "at":
                if len(rest) != 1:
                    raise InputError(f"question: expected one step number after 'at' in {shown!r}")
                return cls(kind, subject, at=_number(rest[0], "a step number", shown), what=what)
            window = _WINDOW.fullmatch("".join(rest))
            if window is None:
                raise InputError(
                    f"question: expected a window of steps T1..T2 after 'within' in {shown!r}"
                )
            return cls(
                kind,
                subject,
                what=what,
                within=(
                    _number(window.group(1), "a step number", shown),
                    _number(window.group(2), "a step number", shown),
                ),
            )
        kind = "rather-than" if keyword == "rather" else keyword
        if negated:
            raise InputError(
                f"question: 'why not' does not go with '{PAIRS[kind]}' "
                f"(in {shown!r}); forms: {FORMS}"
            )
        other_what, other = cls._subject(rest, shown)
        if "fact" in (what, other_what):
            raise InputError(
                f"question: '{PAIRS[kind]}' compares actions, not facts (in {shown!r})"
            )
        return cls(kind, subject, other, what="action" if what else None)

    @staticmethod
    def _subject(tokens: list[str], shown: str) -> tuple[str | None, str]:
        """What a question names: ``(what, text)``, ``what`` given by a leading
        ``action`` or ``fact``."""
        what = None
        if len(tokens) > 1 and tokens[0].lower() in WHAT:
            what, tokens = tokens[0].lower(), tokens[1:]
        if not tokens:
            raise InputError(f"question: missing action in {shown!r}")
        if len(tokens) > 1:
            raise InputError(
                f"question: expected one action or state variable, got "
                f"{' '.join(tokens)!r} in {shown!r} (forms: {FORMS})"
            )
        return what, tokens[0]

    def __str__(self) -> str:
        if self.kind == "cheaper":
            return "why not a cheaper plan"
        if self.kind == "length":
            return f"why not in {self.steps} {'step' if self.steps == 1 else 'steps'}"
        subject = f"{self.what} {self.action}" if self.what else self.action
        if self.kind in PAIRS:
            return f"why {subject} {PAIRS[self.kind]} {self.other}"
        text = f"why not {subject}" if self.kind == "why-not" else f"why {subject}"
        if self.at is not None:
            text += f" at {self.at}"
        if self.within is not None:
            text += f" within {self.within[0]}..{self.within[1]}"
        return text

    # -- JSON -----------------------------------------------------------------

    def to_json(self) -> dict:
        """The question as JSON: ``kind`` and, where given, ``action`` (the
        action or state variable named), ``other``, ``at``, ``within``
        (``[T1, T2]``), ``steps`` and ``what``."""
        data: dict = {"kind": self.kind}
        if self.action is not None:
            data["action"] = self.action
        for key in ("other", "at", "steps", "what"):
            if getattr(self, key) is not None:
                data[key] = getattr(self, key)
        if self.within is not None:
            data["within"] = list(self.within)
        return data

    @classmethod
    def from_json(cls, data: dict) -> Question:
        if not isinstance(data, dict) or "kind" not in data:
            raise InputError("question: a JSON question needs 'kind'")
        if data["kind"] not in ("length", "cheaper") and "action" not in data:
            raise InputError("question: a JSON question needs 'kind' and 'action'")

        def text(key):
            value = data.get(key)
            return None if value is None else str(value)

        within = data.get("within")
        if within is not None:
            if not isinstance(within, list) or len(within) != 2:
                raise InputError("question: 'within' must be a list of two steps")
            within = tuple(within)
        return cls(
            str(data["kind"]),
            text("action"),
            text("other"),
            data.get("at"),
            within,
            data.get("steps"),
            text("what"),
        )

    # -- constraints ----------------------------------------------------------

    def about_fact(self, fact: bool) -> Question:
        """The question with ``what`` decided (for a question that did not say)."""
        from dataclasses import replace

        return replace(self, what="fact" if fact else "action")

    def contrasts(
        self, subject: clingo.Symbol | None, other: clingo.Symbol | None = None, fact: bool = False
    ) -> list[clingo.Symbol]:
        """The constraint terms C of ``contrast(Q,C)`` for resolved terms
        (``fact``: the subject is a state variable)."""
        fn, num = clingo.Function, clingo.Number
        if self.kind == "cheaper":
            raise ValueError("the contrast of 'why not a cheaper plan' is the plan's cost")
        if self.kind == "length":
            return [fn("at_most", [num(self.steps)])]
        if self.kind == "rather-than":
            return [fn("unused", [subject]), fn("used", [other])]
        if self.kind == "before":
            return [fn("before", [other, subject])]
        if self.kind == "after":
            return [fn("before", [subject, other])]
        positive = self.kind == "why-not"
        if fact:
            value = fn("true" if positive else "false")
            if self.at is not None:
                return [fn("fact_at", [subject, value, num(self.at)])]
            return [fn("ends", [subject, value])]
        if self.at is not None:
            return [fn("at" if positive else "not_at", [subject, num(self.at)])]
        if self.within is not None:
            first, last = self.within
            return [fn("within" if positive else "not_within", [subject, num(first), num(last)])]
        return [fn("used" if positive else "unused", [subject])]

    def presupposes(
        self, subject: clingo.Symbol | None, other: clingo.Symbol | None = None
    ) -> list[clingo.Symbol]:
        """Constraint terms the plan asked about must meet, besides not meeting
        the contrast already: the questions about two actions ask about an A
        that the plan uses, and ``before`` and ``after`` about a B it uses too
        (not meeting the contrast then says that the order asked about holds)."""
        if self.kind == "rather-than":
            return [clingo.Function("used", [subject])]
        if self.kind in PAIRS:
            return [clingo.Function("used", [subject]), clingo.Function("used", [other])]
        return []
