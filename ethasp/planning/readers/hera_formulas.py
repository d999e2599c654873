"""HERA's formula strings, as causal agency models write them: parsed, never
evaluated.

HERA (``ethics.tools.my_eval``) evaluates a formula string as Python in the
namespace of ``ethics.language`` and reads a string that fails to evaluate as
one atom: ``'pull'`` and ``pull`` are the variable pull, ``Not('d1')`` its
negation, ``And('healthy_0', 'asking_0')`` a conjunction, and ``people in
building die`` (which is no Python) the variable of that name.  This module
reads the same strings with a grammar of its own::

    formula ::= call | quoted | "True" | "False" | name
    call    ::= ("Not" | "Atom") "(" formula ")"
              | ("And" | "Or") "(" formula "," formula { "," formula } ")"
              | ("Impl" | "BiImpl") "(" formula "," formula ")"
    quoted  ::= "'" characters "'" | '"' characters '"'   (backslash escapes)
    name    ::= a Python identifier, as an argument of a call

and, as HERA does, reads a whole string that is not such a formula as the
name of one variable (``airplane crashes building``).  Where HERA's
evaluation would yield something else than a formula (a bare ``help`` is
Python's help function, ``And('a', 'b', 'c')`` a TypeError), ethasp reads the
name, or the conjunction of the three.

A parsed formula is a tuple: ``("var", name)``, ``("not", f)``, ``("and",
[f, ...])``, ``("or", [f, ...])``, ``("imp", f, g)``, ``("iff", f, g)`` or
``("const", bool)``.
"""

from __future__ import annotations

import re
from typing import Any

Parsed = tuple

_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_ARITY = {"Not": (1, 1), "Atom": (1, 1), "And": (2, None), "Or": (2, None)}
_ARITY |= {"Impl": (2, 2), "BiImpl": (2, 2)}
_KIND = {"Not": "not", "And": "and", "Or": "or", "Impl": "imp", "BiImpl": "iff"}


class FormulaError(ValueError):
    """A string that looks like a formula (it has a call) but is not one."""


class _Parser:
    def __init__(self, text: str):
        self.text = text
        self.pos = 0

    def fail(self, message: str):
        raise FormulaError(f"column {self.pos + 1}: {message}")

    def skip(self) -> None:
        while self.pos < len(self.text) and self.text[self.pos].isspace():
            self.pos += 1

    def peek(self) -> str:
        self.skip()
        return self.text[self.pos] if self.pos < len(self.text) else ""

    def formula(self) -> Parsed:
        char = self.peek()
        if char in ("'", '"'):
            return ("var", self.quoted())
        match = _IDENTIFIER.match(self.text, self.pos)
        if not match:
            found = f"'{char}'" if char else "the end"
            self.fail(f"expected a formula, found {found}")
        word = match.group()
        self.pos = match.end()
        if self.peek() != "(":
            if word in ("True", "False"):
                return ("const", word == "True")
            return ("var", word)
        if word not in _ARITY:
            self.fail(f"unknown connective {word} (HERA's are Not, And, Or, Impl, BiImpl)")
        self.pos += 1
        arguments = [self.formula()]
        while self.peek() == ",":
            self.pos += 1
            arguments.append(self.formula())
        if self.peek() != ")":
            self.fail(f"expected ',' or ')' in {word}(...)")
        self.pos += 1
        least, most = _ARITY[word]
        if len(arguments) < least or (most is not None and len(arguments) > most):
            count = f"{least}" if least == most else f"at least {least}"
            self.fail(f"{word} takes {count} argument{'s' if least > 1 else ''}")
        if word == "Atom":
            if arguments[0][0] != "var":
                self.fail("Atom takes a name")
            return arguments[0]
        kind = _KIND[word]
        if kind == "not":
            return ("not", arguments[0])
        if kind in ("and", "or"):
            return (kind, arguments)
        return (kind, arguments[0], arguments[1])

    def quoted(self) -> str:
        quote = self.text[self.pos]
        self.pos += 1
        out = []
        while self.pos < len(self.text):
            char = self.text[self.pos]
            if char == "\\" and self.pos + 1 < len(self.text):
                out.append(self.text[self.pos + 1])
                self.pos += 2
                continue
            if char == quote:
                self.pos += 1
                return "".join(out)
            out.append(char)
            self.pos += 1
        self.fail("a quoted name is not closed")
        raise AssertionError  # unreachable


def parse_hera_formula(value: Any) -> Parsed:
    """The formula of a HERA formula string (or of a Boolean).

    A string that is a formula of the grammar is read as one; a string
    without parentheses or quotes that is not one is the name of one variable
    (as HERA reads it); anything else raises :class:`FormulaError`.
    """
    if isinstance(value, bool):
        return ("const", value)
    if not isinstance(value, str):
        raise FormulaError(f"a formula must be a string, not {value!r}")
    parser = _Parser(value)
    try:
        parsed = parser.formula()
        if parser.peek():
            parser.fail(f"unexpected '{parser.peek()}'")
        return parsed
    except FormulaError:
        if value.strip() and not any(char in value for char in "()'\","):
            return ("var", value)
        raise


def variables_of(parsed: Parsed) -> list[str]:
    """The variables a parsed formula names, in order, each once."""
    found: dict[str, None] = {}
    stack = [parsed]
    while stack:
        node = stack.pop()
        kind = node[0]
        if kind == "var":
            found[node[1]] = None
        elif kind == "not":
            stack.append(node[1])
        elif kind in ("and", "or"):
            stack.extend(reversed(node[1]))
        elif kind in ("imp", "iff"):
            stack.extend([node[2], node[1]])
    return list(found)


def literal_of(parsed: Parsed) -> tuple[str, bool] | None:
    """(variable, value) if the formula is a variable or its negation, else None."""
    if parsed[0] == "var":
        return parsed[1], True
    if parsed[0] == "not" and parsed[1][0] == "var":
        return parsed[1][1], False
    return None


def hera_literal_text(variable: str, value: bool) -> str:
    """How HERA writes a literal as a key (``d1``, ``Not('d1')``): its ``str``."""
    return variable if value else f"Not('{variable}')"
