"""Formulas of the moral action query language L as text: parsing and printing.

The syntax (documented in the README, section "Formulas")::

    formula     ::= disjunction [ "->" formula ]          (right associative)
    disjunction ::= conjunction { "or" conjunction }
    conjunction ::= negation { "and" negation }
    negation    ::= "not" negation | atom
    atom        ::= "(" formula ")" | "true" | "false"
                  | "Good(" element ")" | "Bad(" element ")" | "Neutral(" element ")"
                  | "Caused(" fact ")" | "GEq(" facts "," facts ")"
    facts       ::= fact { "&" fact } | "()"
    element     ::= action | fact
    fact        ::= variable | "-" variable

Actions and variables are ASP terms of the model (``pull``, ``push(man)``,
``at(robot,r1)``); ``v`` is the fact "v is true" and ``-v`` the fact "v is
false".  The operator names are case-insensitive.

A parsed formula is the ASP term that ``encodings/judgement/language.lp`` evaluates
(``bad(action(pull))``, ``caused(five_will_die,false)``, ``neg/1``, ``and/2``,
``or/2``, ``imp/2``, ``geq(C,D)``), plus the members of the conjunctions of
facts that GEq compares, named ``c(1)``, ``c(2)``, ... (``conj/3`` facts).
``true`` and ``false`` are the empty conjunction ``all(empty)`` and the empty
disjunction ``any(empty)``.  :func:`format_formula` prints such terms back in
the same syntax.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Iterable, Mapping, Sequence

import clingo
from clorm import Raw

from ethasp.errors import InputError
from ethasp.vocabulary import Conj, FormulaOf

Function = clingo.Function
TRUE, FALSE = Function("true"), Function("false")
EMPTY = Function("empty")

# Operator names (lower case) and how they print.
ATOMS = {"good": "Good", "bad": "Bad", "neutral": "Neutral", "caused": "Caused", "geq": "GEq"}
KEYWORDS = {"not", "and", "or", "true", "false"}

_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_']*")
_STOP = {",", "&", ")"}


# -- the model's elements -------------------------------------------------------

@dataclass(frozen=True)
class Elements:
    """The names a formula can use: the model's actions and variables."""

    actions: frozenset[clingo.Symbol]
    variables: frozenset[clingo.Symbol]

    @classmethod
    def of_model(cls, model) -> "Elements":
        """The actions and variables of a :class:`ethasp.model.Model`."""
        planner = model.planner
        return cls(frozenset(a.arguments[0] for a in planner.get("action", 1)),
                   frozenset(v.arguments[0] for v in planner.get("variable", 1)))


# -- parsed formulas ------------------------------------------------------------

@dataclass
class Formula:
    """A formula of L as ASP: its term and the members of its GEq conjunctions.

    ``conjunctions`` maps each conjunction name (``c(1)``, ...) to its facts,
    in the order written, as (variable, ``"true"`` or ``"false"``).
    """

    term: clingo.Symbol
    conjunctions: dict[clingo.Symbol, list[tuple[clingo.Symbol, str]]] = field(default_factory=dict)

    def facts(self, name: clingo.Symbol | str = "query") -> list:
        """``formula(name, F)`` and the ``conj/3`` facts, as clorm facts."""
        symbol = Function(name) if isinstance(name, str) else name
        facts: list = [FormulaOf(name=Raw(symbol), formula=Raw(self.term))]
        for conj, members in self.conjunctions.items():
            facts += [Conj(name=Raw(conj), variable=Raw(variable), value=value)
                      for variable, value in members]
        return facts

    def __str__(self) -> str:
        return format_formula(self.term, self.conjunctions)


class _Parser:
    """Recursive descent over the text; positions are 0-based internally."""

    def __init__(self, text: str, elements: Elements):
        self.text = text
        self.pos = 0
        self.elements = elements
        self.conjunctions: dict[clingo.Symbol, list[tuple[clingo.Symbol, str]]] = {}

    # -- scanning ---------------------------------------------------------------

    def fail(self, message: str, pos: int | None = None):
        column = (self.pos if pos is None else pos) + 1
        raise InputError(f"formula: column {column}: {message}")

    def skip(self) -> None:
        while self.pos < len(self.text) and self.text[self.pos].isspace():
            self.pos += 1

    def found(self) -> str:
        """What stands at the current position, for messages."""
        self.skip()
        if self.pos >= len(self.text):
            return "the end of the formula"
        match = _WORD.match(self.text, self.pos)
        return f"'{match.group() if match else self.text[self.pos]}'"

    def accept(self, token: str) -> bool:
        self.skip()
        if not self.text.startswith(token, self.pos):
            return False
        end = self.pos + len(token)
        if token[-1].isalnum() and end < len(self.text) and _WORD.match(self.text[end]):
            return False  # a longer word, e.g. "order" for "or"
        self.pos = end
        return True

    def expect(self, token: str) -> None:
        if not self.accept(token):
            self.fail(f"expected '{token}', found {self.found()}")

    def word(self) -> str | None:
        self.skip()
        match = _WORD.match(self.text, self.pos)
        return match.group() if match else None

    # -- formulas -----------------------------------------------------------------

    def parse(self) -> Formula:
        term = self.implication()
        self.skip()
        if self.pos < len(self.text):
            self.fail(f"unexpected {self.found()}")
        return Formula(term, self.conjunctions)

    def implication(self) -> clingo.Symbol:
        left = self.disjunction()
        if self.accept("->"):
            return Function("imp", [left, self.implication()])
        return left

    def disjunction(self) -> clingo.Symbol:
        left = self.conjunction()
        while self.accept("or"):
            left = Function("or", [left, self.conjunction()])
        return left

    def conjunction(self) -> clingo.Symbol:
        left = self.negation()
        while self.accept("and"):
            left = Function("and", [left, self.negation()])
        return left

    def negation(self) -> clingo.Symbol:
        if self.accept("not"):
            return Function("neg", [self.negation()])
        return self.atom()

    def atom(self) -> clingo.Symbol:
        if self.accept("("):
            term = self.implication()
            self.expect(")")
            return term
        word = self.word()
        key = word.lower() if word else None
        if key == "true" and self.accept(word):
            return Function("all", [EMPTY])
        if key == "false" and self.accept(word):
            return Function("any", [EMPTY])
        if key not in ATOMS:
            self.fail(f"expected a formula (Good, Bad, Neutral, Caused, GEq, not, true, false "
                      f"or '('), found {self.found()}")
        self.accept(word)
        self.expect("(")
        if key == "geq":
            first = self.conjunction_of_facts()
            self.expect(",")
            second = self.conjunction_of_facts()
            self.expect(")")
            return Function("geq", [first, second])
        element = self.element(allow_action=key != "caused", operator=ATOMS[key])
        self.expect(")")
        if key == "caused":
            variable, value = element.arguments
            return Function("caused", [variable, value])
        return Function(key, [element])

    # -- elements -------------------------------------------------------------------

    def term_text(self) -> tuple[str, int]:
        """The text of a term up to a top-level ',', '&' or ')'; and its start."""
        self.skip()
        start, depth, quoted = self.pos, 0, False
        while self.pos < len(self.text):
            char = self.text[self.pos]
            if quoted:
                if char == "\\":
                    self.pos += 1
                elif char == '"':
                    quoted = False
            elif char == '"':
                quoted = True
            elif char in "([":
                depth += 1
            elif char in ")]" and depth > 0:
                depth -= 1
            elif depth == 0 and char in _STOP:
                break
            self.pos += 1
        return self.text[start:self.pos].rstrip(), start

    def element(self, allow_action: bool, operator: str) -> clingo.Symbol:
        """``action(A)`` or ``fact(V,B)`` for the name at the current position."""
        text, start = self.term_text()
        if not text:
            self.fail(f"expected an action or a fact, found {self.found()}", start)
        negative = text.startswith("-")
        name = text[1:].lstrip() if negative else text
        try:
            symbol = clingo.parse_term(name, logger=lambda code, message: None)
        except RuntimeError:
            self.fail(f"not an action or variable name: '{text}'", start)
        is_action = symbol in self.elements.actions
        is_variable = symbol in self.elements.variables
        if is_action and is_variable:
            self.fail(f"'{symbol}' is both an action and a variable of the model", start)
        if not is_action and not is_variable:
            self.fail(f"unknown action or variable '{symbol}'", start)
        if is_action:
            if negative:
                self.fail(f"'{symbol}' is an action; only facts can be negated", start)
            if not allow_action:
                self.fail(f"{operator} takes facts, but '{symbol}' is an action", start)
            return Function("action", [symbol])
        return Function("fact", [symbol, FALSE if negative else TRUE])

    def conjunction_of_facts(self) -> clingo.Symbol:
        """A conjunction of facts for GEq; its members go to ``conjunctions``."""
        name = Function("c", [clingo.Number(len(self.conjunctions) + 1)])
        members: list[tuple[clingo.Symbol, str]] = []
        self.conjunctions[name] = members
        if self.accept("()"):
            return name
        while True:
            fact = self.element(allow_action=False, operator="GEq")
            variable, value = fact.arguments
            members.append((variable, value.name))
            if not self.accept("&"):
                return name


def parse_formula(text: str, elements: Elements) -> Formula:
    """Parse a formula of L; raise InputError with the column of the first problem."""
    if not text.strip():
        raise InputError("formula: empty formula")
    return _Parser(text, elements).parse()


# -- printing --------------------------------------------------------------------

# Binding strength: a subformula printed where a stronger one is expected gets
# parentheses.
_IMP, _OR, _AND, _NOT, _ATOM = range(1, 6)

ConjMembers = Mapping[object, Iterable[tuple[object, object]]]
Members = Mapping[object, Sequence[clingo.Symbol]]


def _truth(value) -> bool:
    """A truth value given as bool, "true"/"false" or the symbol true/false."""
    if isinstance(value, bool):
        return value
    if isinstance(value, clingo.Symbol):
        return value.type == clingo.SymbolType.Function and value.name == "true"
    return str(value) == "true"


def format_fact(variable, value) -> str:
    """A fact as text: ``v`` (true) or ``-v`` (false)."""
    return str(variable) if _truth(value) else f"-{variable}"


def _lookup(mapping: Mapping | None, name) -> list:
    if not mapping:
        return []
    if name in mapping:
        return list(mapping[name])
    by_text = {str(key): value for key, value in mapping.items()}
    return list(by_text.get(str(name), []))


def _element(term: clingo.Symbol) -> str:
    if term.name == "action" and len(term.arguments) == 1:
        return str(term.arguments[0])
    if term.name == "fact" and len(term.arguments) == 2:
        return format_fact(*term.arguments)
    raise ValueError(f"not an element of L: {term}")


def _format(term: clingo.Symbol, conj: ConjMembers | None, members: Members | None
            ) -> tuple[str, int]:
    """The text of a term and its binding strength."""
    name, args = term.name, term.arguments

    def sub(child: clingo.Symbol, strength: int) -> str:
        text, own = _format(child, conj, members)
        return f"({text})" if own < strength else text

    if name == "neg" and len(args) == 1:
        return f"not {sub(args[0], _NOT)}", _NOT
    if name == "and" and len(args) == 2:
        return f"{sub(args[0], _AND)} and {sub(args[1], _NOT)}", _AND
    if name == "or" and len(args) == 2:
        return f"{sub(args[0], _OR)} or {sub(args[1], _AND)}", _OR
    if name == "imp" and len(args) == 2:
        return f"{sub(args[0], _OR)} -> {sub(args[1], _IMP)}", _IMP
    if name in ("all", "any") and len(args) == 1:
        parts = _lookup(members, args[0])
        if not parts:
            return ("true" if name == "all" else "false"), _ATOM
        if len(parts) == 1:
            return _format(parts[0], conj, members)
        if name == "all":
            return " and ".join(sub(part, _NOT) for part in parts), _AND
        return " or ".join(sub(part, _AND) for part in parts), _OR
    if name in ("good", "bad", "neutral") and len(args) == 1:
        return f"{ATOMS[name]}({_element(args[0])})", _ATOM
    if name == "caused" and len(args) == 2:
        return f"Caused({format_fact(*args)})", _ATOM
    if name == "geq" and len(args) == 2:
        sides = []
        for side in args:
            facts = [format_fact(variable, value) for variable, value in _lookup(conj, side)]
            sides.append(" & ".join(facts) if facts else "()")
        return f"GEq({sides[0]}, {sides[1]})", _ATOM
    raise ValueError(f"not a formula of L: {term}")


def format_formula(term: clingo.Symbol, conj_members: ConjMembers | None = None,
                   members: Members | None = None) -> str:
    """Print a formula term of ``language.lp`` in the syntax of :func:`parse_formula`.

    ``conj_members`` maps conjunction names (symbols, or their text) to their
    facts as (variable, value) pairs, the value a bool, ``"true"``/``"false"``
    or the symbol; ``members`` maps the names of ``all/any`` to their member
    formulas.  A name missing from a mapping has no members (as in ASP): an
    empty ``all`` prints ``true``, an empty ``any`` prints ``false``.
    """
    return _format(term, conj_members, members)[0]


def format_literal(term: clingo.Symbol, conj_members: ConjMembers | None = None) -> str:
    """Print a literal of L: an atom (Good, Bad, Neutral, Caused, GEq) or its negation."""
    atom = term.arguments[0] if term.name == "neg" and len(term.arguments) == 1 else term
    if atom.name not in ATOMS:
        raise ValueError(f"not a literal of L: {term}")
    return format_formula(term, conj_members)
