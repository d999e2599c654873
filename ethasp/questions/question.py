"""Contrastive questions "Why A rather than B?" about the actions of a plan.

Grammar of typed questions (case of ``why``, ``not``, ``rather than`` and
``before`` does not matter; a final ``?`` is allowed; actions are ASP terms,
or PDDL action expressions for PDDL models)::

    why A                  contrast: A is not used
    why not A              contrast: A is used
    why A rather than B    contrast: A is not used, B is used
    why A before B         contrast: B is used before A

A question becomes constraint facts ``contrast(Q,C)`` read by the fixed
encoding ``encodings/questions/questions.lp``; no rule text is generated.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import clingo

from ethasp.errors import InputError

KINDS = ("why", "why-not", "rather-than", "before")

_WORD = re.compile(r"\s+(rather\s+than|before)\s+", re.IGNORECASE)


def _split_outside_parentheses(text: str) -> tuple[str, str, str] | None:
    """Split "A rather than B" / "A before B" at a keyword outside parentheses
    and strings (iteratively: any nesting)."""
    depth, quoted, escaped = 0, False, False
    for index, char in enumerate(text):
        if quoted:
            quoted = escaped or char != '"'
            escaped = not escaped and char == "\\"
        elif char == '"':
            quoted = True
        elif char in "([":
            depth += 1
        elif char in ")]":
            depth -= 1
        elif depth == 0 and char.isspace():
            match = _WORD.match(text, index)
            if match:
                keyword = " ".join(match.group(1).lower().split())
                return text[:index], keyword, text[match.end():]
    return None


@dataclass(frozen=True)
class Question:
    """A contrastive question: its kind and the actions it names (as text)."""

    kind: str
    action: str
    other: str | None = None

    def __post_init__(self):
        if self.kind not in KINDS:
            raise InputError(f"question: unknown kind {self.kind!r} (one of {', '.join(KINDS)})")
        if (self.kind in ("rather-than", "before")) != (self.other is not None):
            raise InputError(f"question: kind {self.kind} needs "
                             f"{'two actions' if self.other is None else 'one action'}")

    # -- text -----------------------------------------------------------------

    @classmethod
    def parse(cls, text: str) -> "Question":
        """Read a typed question such as ``why refrain rather than pull``."""
        body = text.strip().rstrip("?").strip()
        words = body.split(None, 1)
        if not words or words[0].lower() != "why" or len(words) < 2:
            raise InputError(f"question: expected 'why ...', got {text.strip()!r} "
                             "(forms: why A | why not A | why A rather than B | why A before B)")
        rest = words[1].strip()
        tokens = rest.lower().split()
        if tokens[-1] == "before" or tokens[-2:] == ["rather", "than"] or tokens[-1] == "not":
            raise InputError(f"question: missing action at the end of {text.strip()!r}")
        if tokens[0] == "before" or tokens[:2] == ["rather", "than"]:
            raise InputError(f"question: missing action before '{tokens[0]}' in {text.strip()!r}")
        split = _split_outside_parentheses(rest)
        if split is not None:
            first, keyword, second = (part.strip() for part in split)
            if not first or not second:
                raise InputError(f"question: missing action around '{keyword}' in {text.strip()!r}")
            return cls("rather-than" if keyword == "rather than" else "before", first, second)
        head = rest.split(None, 1)
        if head[0].lower() == "not":
            if len(head) < 2:
                raise InputError(f"question: missing action after 'why not' in {text.strip()!r}")
            return cls("why-not", head[1].strip())
        return cls("why", rest)

    def __str__(self) -> str:
        if self.kind == "why":
            return f"why {self.action}"
        if self.kind == "why-not":
            return f"why not {self.action}"
        keyword = "rather than" if self.kind == "rather-than" else "before"
        return f"why {self.action} {keyword} {self.other}"

    # -- JSON -----------------------------------------------------------------

    def to_json(self) -> dict:
        data = {"kind": self.kind, "action": self.action}
        if self.other is not None:
            data["other"] = self.other
        return data

    @classmethod
    def from_json(cls, data: dict) -> "Question":
        if not isinstance(data, dict) or "kind" not in data or "action" not in data:
            raise InputError("question: a JSON question needs 'kind' and 'action'")
        return cls(str(data["kind"]), str(data["action"]),
                   None if data.get("other") is None else str(data["other"]))

    # -- constraints ----------------------------------------------------------

    def contrasts(self, action: clingo.Symbol, other: clingo.Symbol | None) -> list[clingo.Symbol]:
        """The constraint terms C of ``contrast(Q,C)`` for resolved action terms."""
        use = lambda name, term: clingo.Function(name, [term])  # noqa: E731
        if self.kind == "why":
            return [use("unused", action)]
        if self.kind == "why-not":
            return [use("used", action)]
        if self.kind == "rather-than":
            return [use("unused", action), use("used", other)]
        return [clingo.Function("before", [other, action])]
