"""Plans: sequences of action terms, read from and written as text."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

import clingo

from ethasp.errors import InputError
from ethasp.planning.naming import pddl_atom_to_term
from ethasp.planning.terms import TermError, parse_symbol

if TYPE_CHECKING:  # the typed vocabulary is imported where it is used (start-up time)
    from ethasp.vocabulary import Occurs


def steps(count: int) -> str:
    """``1 step``, ``2 steps``."""
    return f"{count} step" if count == 1 else f"{count} steps"


def split_terms(text: str) -> list[str]:
    """Split "a1 push(man, bridge) a3" at spaces outside parentheses and strings.

    A semicolon outside parentheses separates too, as plan-explainer writes
    plans (``(serve coke);(refill coke)``), and a line that starts with one is
    a comment (Fast Downward's plan files end with ``; cost = 2 (unit cost)``).
    """
    text = "\n".join(line for line in text.splitlines() if not line.lstrip().startswith(";"))
    terms: list[str] = []
    current: list[str] = []
    depth, quoted, escaped = 0, False, False
    for char in text:
        if quoted:
            quoted = escaped or char != '"'
            escaped = not escaped and char == "\\"
        elif char == '"':
            quoted = True
        elif char in "([":
            depth += 1
        elif char in ")]":
            depth -= 1
        elif (char.isspace() or char == ";") and depth == 0:
            if current:
                terms.append("".join(current))
                current = []
            continue
        current.append(char)
    if current:
        terms.append("".join(current))
    return terms


def parse_action(text: str) -> clingo.Symbol:
    """An action term, e.g. ``push(man)``, or a PDDL action, e.g. ``(push man)``.

    The text is read as one term (:func:`ethasp.planning.terms.parse_symbol`),
    never as rule text.
    """
    if text.startswith("("):
        try:
            return pddl_atom_to_term(text)
        except InputError as error:
            if "," not in text:  # not a tuple term such as (p,q) either
                raise error from None
    try:
        return parse_symbol(text, "action")
    except TermError as error:
        shown = text if len(text) <= 60 else text[:57] + "..."
        detail = f" ({error.reason})" if error.reason else ""
        raise InputError(f"not an action term: {shown!r}{detail}") from None


@dataclass(frozen=True)
class Plan:
    """A sequence of actions (clingo terms); the first action is step 1."""

    actions: tuple[clingo.Symbol, ...]

    @classmethod
    def parse(cls, text: str) -> Plan:
        """Read actions separated by spaces: ``"a1 push(man) a3"`` or ``"(a1) (push man)"``.

        Each distinct action text is read once (long plans repeat actions)."""
        read: dict[str, clingo.Symbol] = {}
        actions = []
        for term in split_terms(text):
            if term not in read:
                read[term] = parse_action(term)
            actions.append(read[term])
        return cls(tuple(actions))

    @classmethod
    def from_symbols(cls, symbols: Iterable[clingo.Symbol]) -> Plan:
        """The plan of the ``occurs(A,T)`` atoms among clingo symbols (other
        atoms are left aside): read without the typed vocabulary, whose
        classes take longer to build than a short plan search takes."""
        occurs = [
            symbol.arguments
            for symbol in symbols
            if symbol.name == "occurs" and len(symbol.arguments) == 2
        ]
        return cls(tuple(action for action, _ in sorted(occurs, key=lambda a: a[1].number)))

    def facts(self) -> list[Occurs]:
        """The plan as ``occurs(A,T)`` facts."""
        from clorm import Raw

        from ethasp.vocabulary import Occurs

        return [
            Occurs(action=Raw(action), step=index)
            for index, action in enumerate(self.actions, start=1)
        ]

    def __len__(self) -> int:
        return len(self.actions)

    def __iter__(self) -> Iterator[clingo.Symbol]:
        return iter(self.actions)

    def to_list(self) -> list[str]:
        return [str(action) for action in self.actions]

    def __str__(self) -> str:
        return " ".join(self.to_list())
