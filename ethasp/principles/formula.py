"""Formulas of the moral action query language L as text: parsing and printing.

The syntax (documented in docs/formulas.md)::

    formula     ::= disjunction [ "->" formula ]          (right associative)
    disjunction ::= conjunction { "or" conjunction }
    conjunction ::= negation { "and" negation }
    negation    ::= "not" negation | atom
    atom        ::= "(" formula ")" | "true" | "false"
                  | "Good(" element ")" | "Bad(" element ")" | "Neutral(" element ")"
                  | "Caused(" fact ")" | "GEq(" facts "," facts ")"
                  | "Goal(" fact ")" | "Finally(" fact ")" | "ButFor(" fact ")"
                  | "Instrumental(" fact ")" | "Avoidable(" fact ")"
                  | "Means(" patient ")" | "Means2(" patient ")" | "End(" patient ")"
                  | "AffectsPos(" fact "," patient ")" | "AffectsNeg(" fact "," patient ")"
                  | "I(" fact ")" | "Causes(" cause "," effect ")" | "Do(" facts "," effect ")"
                  | uterm ( ">" | ">=" | "=" | "<" | "<=" ) uterm
    uterm       ::= uprimary { ( "+" | "-" ) uprimary }
    uprimary    ::= "U(" facts ")" | integer | "-" uprimary
    facts       ::= fact { "&" fact } | "()"
    cause       ::= fact { "|" fact }
    effect      ::= fact { "&" fact } | fact { "|" fact }
    element     ::= action | fact
    fact        ::= variable | "-" variable

Actions, variables and moral patients are ASP terms of the model (``pull``,
``push(man)``, ``at(robot,r1)``, ``"4alive"``); ``v`` is the fact "v is true"
and ``-v`` the fact "v is false".  Actions and variables may also be written
as PDDL atoms (``(push man)``, ``(at robot r1)``), and a false fact as
``(not (at robot r1))``: reasons of PDDL models are printed so.  The
operator names are case-insensitive.
The operators after GEq are HERA's (see ``encodings/judgement/language.lp``);
a comparison of utility terms is ``ucompare(O,X,Y)`` with O ``gt``, ``geq``
or ``eq`` (``<`` and ``<=`` swap the sides), X and Y built of ``u(C)``,
``num(N)``, ``add/2``, ``sub/2``, ``minus/1``.  I, Causes and Do are defined
for causal agency models only (``encodings/cam/language.lp``), Avoidable for
plans only; in a causal agency model every action is also a variable, and
``Bad(pull)`` is about the fact that pull is done.

A parsed formula is the ASP term that ``encodings/judgement/language.lp`` evaluates
(``bad(action(pull))``, ``caused(five_will_die,false)``, ``neg/1``, ``and/2``,
``or/2``, ``imp/2``, ``geq(C,D)``), plus the members of the conjunctions of
facts that GEq compares, named ``c(1)``, ``c(2)``, ... (``conj/3`` facts).
``true`` and ``false`` are the empty conjunction ``all(empty)`` and the empty
disjunction ``any(empty)``.  :func:`format_formula` prints such terms back in
the same syntax.

Parsing and printing are iterative, so parentheses may nest as deep as a user
types them.  The term built may nest operators at most
:data:`ethasp.planning.terms.MAX_NESTING` (10,000) deep (a chain of ``and``
or ``or`` nests one level per operator): clingo grounds deeper terms slowly
and crashes on much deeper ones, so deeper formulas get an error naming the
column.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, NoReturn

import clingo
from clorm import Raw

from ethasp.errors import InputError
from ethasp.planning.naming import Naming, pddl_atom_to_term
from ethasp.planning.terms import MAX_NESTING, TermError, parse_symbol
from ethasp.vocabulary import Conj, FormulaOf

Function = clingo.Function
TRUE, FALSE = Function("true"), Function("false")
EMPTY = Function("empty")

# Operator names (lower case) and how they print.
ATOMS = {
    "good": "Good",
    "bad": "Bad",
    "neutral": "Neutral",
    "caused": "Caused",
    "geq": "GEq",
    "goal_fact": "Goal",
    "finally": "Finally",
    "but_for": "ButFor",
    "instrumental": "Instrumental",
    "avoidable": "Avoidable",
    "means": "Means",
    "means2": "Means2",
    "end": "End",
    "ucompare": "U",
    "affects_pos": "AffectsPos",
    "affects_neg": "AffectsNeg",
    "intended": "I",
    "causes": "Causes",
    "do": "Do",
}
# HERA's operators on facts and on patients, by the name users write (lower case).
FACT_OPERATORS = {
    "goal": "goal_fact",
    "finally": "finally",
    "butfor": "but_for",
    "instrumental": "instrumental",
    "avoidable": "avoidable",
}
PATIENT_OPERATORS = {"means": "means", "means2": "means2", "end": "end"}
AFFECTS_OPERATORS = {"affectspos": "affects_pos", "affectsneg": "affects_neg"}
# The operators defined for one kind of model only.
CAM_ONLY = {"i": "intended", "causes": "causes", "do": "do"}
PLAN_ONLY = {"avoidable"}
COMPARISONS = {
    ">=": ("geq", False),
    "<=": ("geq", True),
    ">": ("gt", False),
    "<": ("gt", True),
    "=": ("eq", False),
}
_SHOWN = {"gt": ">", "geq": ">=", "eq": "="}

_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_']*")
_PDDL_NOT = re.compile(r"\(\s*not\s+(\(.*\))\s*\)", re.IGNORECASE | re.DOTALL)
_STOP = {",", "&", "|", ")"}


# -- the model's elements -------------------------------------------------------


@dataclass(frozen=True)
class Elements:
    """The names a formula can use: the model's actions and variables (a
    causal agency model's actions are variables), and whether the model is a
    causal agency model (``cam``)."""

    actions: frozenset[clingo.Symbol]
    variables: frozenset[clingo.Symbol]
    patients: frozenset[clingo.Symbol] = frozenset()
    cam: bool = False

    @classmethod
    def of_model(cls, model) -> Elements:
        """The actions, variables and moral patients of a :class:`ethasp.planning.model.Model`."""
        planner = model.planner
        return cls(
            frozenset(a.arguments[0] for a in planner.get("action", 1)),
            frozenset(v.arguments[0] for v in planner.get("variable", 1)),
            frozenset(p.arguments[0] for p in planner.get("patient", 1)),
            model.is_cam,
        )


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
            facts += [
                Conj(name=Raw(conj), variable=Raw(variable), value=value)
                for variable, value in members
            ]
        return facts

    def __str__(self) -> str:
        return format_formula(self.term, self.conjunctions)


# Operators of the parser and their binding strength (stronger binds tighter).
_PRECEDENCE = {"imp": 1, "or": 2, "and": 3, "neg": 4}
_INFIX = (("->", "imp"), ("or", "or"), ("and", "and"))
_OPEN = "("


class _Parser:
    """An operator-precedence parser with explicit stacks (no recursion), so that
    parentheses may nest without limit; the term built may nest operators at most
    :data:`MAX_NESTING` deep.  Positions are 0-based internally."""

    def __init__(self, text: str, elements: Elements):
        self.text = text
        self.pos = 0
        self.elements = elements
        self.conjunctions: dict[clingo.Symbol, list[tuple[clingo.Symbol, str]]] = {}

    # -- scanning ---------------------------------------------------------------

    def fail(self, message: str, pos: int | None = None) -> NoReturn:
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
        """formula ::= disjunction ["->" formula]; disjunctions and conjunctions are
        left associative chains of "or" and "and"; "not" binds tightest."""
        operands: list[tuple[clingo.Symbol, int]] = []  # (term, operators nested in it)
        operators: list[tuple[str, int]] = []  # (operator or "(", position)

        def reduce_while_stronger(level: int) -> None:
            while operators and operators[-1][0] != _OPEN and _PRECEDENCE[operators[-1][0]] > level:
                self.apply(operators.pop(), operands)

        opened = 0  # "(" on the stack
        while True:
            # An operand: prefixes ("not", "("), then an atom.
            while True:
                start = self.pos
                if self.accept("not"):
                    operators.append(("neg", start))
                elif self.accept("("):
                    operators.append((_OPEN, start))
                    opened += 1
                else:
                    break
            operands.append((self.atom(), 0))
            # Closing parentheses (an unmatched one is reported at the end).
            while opened and self.accept(")"):
                reduce_while_stronger(0)
                operators.pop()
                opened -= 1
            # An infix operator, or the end.
            for token, name in _INFIX:
                self.skip()
                start = self.pos
                if self.accept(token):
                    # "->" is right associative; "and", "or" are left associative.
                    level = _PRECEDENCE[name]
                    reduce_while_stronger(level if name == "imp" else level - 1)
                    operators.append((name, start))
                    break
            else:
                break
        reduce_while_stronger(0)
        if opened:
            self.fail(f"expected ')', found {self.found()}")
        self.skip()
        if self.pos < len(self.text):
            self.fail(f"unexpected {self.found()}")
        term, _ = operands.pop()
        return Formula(term, self.conjunctions)

    def apply(self, operator: tuple[str, int], operands: list) -> None:
        """Replace the operands of an operator on the stack by its term."""
        name, position = operator
        arguments = [operands.pop()] if name == "neg" else [operands.pop(-2), operands.pop()]
        depth = 1 + max(depth for _, depth in arguments)
        if depth > MAX_NESTING:
            self.fail(
                f"the formula nests operators more than {MAX_NESTING} deep (the limit "
                "of ethasp; a chain of 'and' or 'or' nests one level per operator)",
                position,
            )
        operands.append((Function(name, [term for term, _ in arguments]), depth))

    def not_a_formula(self) -> NoReturn:
        self.fail(
            f"expected a formula (Good, Bad, Neutral, Caused, GEq, Goal, Finally, "
            f"ButFor, Instrumental, Avoidable, Means, Means2, End, AffectsPos, "
            f"AffectsNeg, I, Causes, Do, U, not, true, false or '('), found {self.found()}"
        )

    def atom(self) -> clingo.Symbol:
        word = self.word()
        key = word.lower() if word else None
        if word and key == "true" and self.accept(word):
            return Function("all", [EMPTY])
        if word and key == "false" and self.accept(word):
            return Function("any", [EMPTY])
        self.skip()
        if key == "u" or (
            word is None
            and self.pos < len(self.text)
            and (self.text[self.pos].isdigit() or self.text[self.pos] == "-")
        ):
            return self.comparison()
        if word is None or key is None:
            self.not_a_formula()
        if (
            key in CAM_ONLY
            and not self.elements.cam
            and self.text.startswith("(", self.pos + len(word))
        ):
            self.fail(f"{word} is defined for causal agency models only")
        if key in PLAN_ONLY and self.elements.cam:
            self.fail(f"{word} is defined for plans only, not for causal agency models")
        if key in CAM_ONLY and self.elements.cam:
            return self.cam_atom(word, key)
        if key in AFFECTS_OPERATORS:
            self.accept(word)
            self.expect("(")
            fact = self.element(allow_action=False, operator=word)
            self.expect(",")
            patient = self.patient(word)
            self.expect(")")
            return Function(AFFECTS_OPERATORS[key], [*fact.arguments, patient])
        if key in FACT_OPERATORS or key in PATIENT_OPERATORS:
            self.accept(word)
            self.expect("(")
            if key in PATIENT_OPERATORS:
                term = Function(PATIENT_OPERATORS[key], [self.patient(word)])
            else:
                fact = self.element(allow_action=False, operator=word)
                term = Function(FACT_OPERATORS[key], list(fact.arguments))
            self.expect(")")
            return term
        if key not in ATOMS or key in (
            "ucompare",
            "goal_fact",
            "but_for",
            "intended",
            "affects_pos",
            "affects_neg",
            "causes",
            "do",
        ):
            self.not_a_formula()
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

    def cam_atom(self, word: str, key: str) -> clingo.Symbol:
        """I(fact), Causes(cause, effect), Do(facts, effect)."""
        self.accept(word)
        self.expect("(")
        if key == "i":
            fact = self.element(allow_action=False, operator=word)
            self.expect(")")
            return Function("intended", list(fact.arguments))
        if key == "causes":
            first = self.facts_joined(word, ("|",))
        else:
            first = self.facts_joined(word, ("&",), always_named=True)
        self.expect(",")
        second = self.facts_joined(word, ("&", "|"))
        self.expect(")")
        if key == "do":
            return Function("do", [first.arguments[0], second])
        return Function("causes", [first, second])

    def facts_joined(
        self, operator: str, joints: tuple[str, ...], always_named: bool = False
    ) -> clingo.Symbol:
        """A fact, or facts joined by one of ``joints`` ("&": ``all_facts(c(N))``,
        "|": ``any_facts(c(N))``, their members in ``conjunctions``)."""
        members: list[tuple[clingo.Symbol, str]] = []
        joint = None
        while True:
            fact = self.element(allow_action=False, operator=operator)
            variable, value = fact.arguments
            members.append((variable, value.name))
            self.skip()
            found = next((j for j in ("&", "|") if self.text.startswith(j, self.pos)), None)
            if found is None:
                break
            if found not in joints or (joint is not None and found != joint):
                allowed = " or ".join(f"'{j}'" for j in joints)
                self.fail(f"{operator} joins these facts with {allowed} only, not '{found}'")
            joint = found
            self.pos += 1
        if len(members) == 1 and not always_named:
            member, truth = members[0]
            return Function("fact", [member, Function(truth)])
        name = Function("c", [clingo.Number(len(self.conjunctions) + 1)])
        self.conjunctions[name] = members
        return Function("any_facts" if joint == "|" else "all_facts", [name])

    # -- comparisons of utilities ------------------------------------------------------

    def comparison(self) -> clingo.Symbol:
        """uterm OP uterm, as ucompare(O,X,Y)."""
        left = self.utility_term()
        self.skip()
        for token in (">=", "<=", ">", "<", "="):
            if self.text.startswith(token, self.pos):
                self.pos += len(token)
                break
        else:
            self.fail(f"expected a comparison (>, >=, =, <, <=), found {self.found()}")
        right = self.utility_term()
        operator, swap = COMPARISONS[token]
        if swap:
            left, right = right, left
        return Function("ucompare", [Function(operator), left, right])

    def utility_term(self) -> clingo.Symbol:
        """uprimary { (+|-) uprimary }, left associative (no recursion)."""
        term = self.utility_primary()
        depth = 0
        while True:
            self.skip()
            if (
                self.pos < len(self.text)
                and self.text[self.pos] in "+-"
                and not self.text.startswith("->", self.pos)
            ):
                name = "add" if self.text[self.pos] == "+" else "sub"
                self.pos += 1
                depth += 1
                if depth > MAX_NESTING:
                    self.fail(f"the utility term nests more than {MAX_NESTING} operators")
                term = Function(name, [term, self.utility_primary()])
            else:
                return term

    def utility_primary(self) -> clingo.Symbol:
        signs = 0
        while True:
            self.skip()
            if self.pos < len(self.text) and self.text[self.pos] == "-":
                self.pos += 1
                signs += 1
                if signs > MAX_NESTING:
                    self.fail(f"more than {MAX_NESTING} signs")
                continue
            break
        start = self.pos
        match = re.compile(r"[0-9]+").match(self.text, self.pos)
        if match:
            self.pos = match.end()
            value = int(match.group())
            if value > 2**31 - 1:
                self.fail("the number is outside clingo's 32-bit integers", start)
            term = Function("num", [clingo.Number(value)])
        else:
            word = self.word()
            if word is None or word.lower() != "u":
                self.fail(f"expected U(...) or a number, found {self.found()}")
            self.accept(word)
            self.expect("(")
            term = Function("u", [self.conjunction_of_facts()])
            self.expect(")")
        for _ in range(signs):
            term = Function("minus", [term])
        return term

    def patient(self, operator: str) -> clingo.Symbol:
        text, start = self.term_text()
        if not text:
            self.fail(f"{operator} takes a moral patient, found {self.found()}", start)
        try:
            symbol = parse_symbol(text, "name")
        except TermError as error:
            detail = f" ({error.reason})" if error.reason else ""
            self.fail(f"not a patient name: '{text[:60]}'{detail}", start)
        if symbol not in self.elements.patients:
            self.fail(
                f"unknown moral patient '{symbol}' (declare it with patient/1, or "
                "affects in a situation)",
                start,
            )
        return symbol

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
        return self.text[start : self.pos].rstrip(), start

    def element(self, allow_action: bool, operator: str) -> clingo.Symbol:
        """``action(A)`` or ``fact(V,B)`` for the name at the current position."""
        text, start = self.term_text()
        if not text:
            self.fail(f"expected an action or a fact, found {self.found()}", start)
        negative = text.startswith("-")
        name = text[1:].lstrip() if negative else text
        pddl = _PDDL_NOT.fullmatch(name)  # (not (p a)): a PDDL model's false fact
        if pddl and not negative:
            negative, name = True, pddl.group(1)
        try:
            symbol = pddl_atom_to_term(name) if name.startswith("(") else parse_symbol(name, "name")
        except (TermError, InputError) as error:
            shown = text if len(text) <= 60 else text[:57] + "..."
            reason = getattr(error, "reason", "")
            detail = f" ({reason})" if reason else ""
            self.fail(f"not an action or variable name: '{shown}'{detail}", start)
        is_action = symbol in self.elements.actions
        is_variable = symbol in self.elements.variables
        written = " ".join(name.split()) if name.startswith("(") else symbol  # as typed
        if is_action and is_variable:
            self.fail(f"'{written}' is both an action and a variable of the model", start)
        if not is_action and not is_variable:
            self.fail(f"unknown action or variable '{written}'", start)
        if is_action:
            if negative:
                self.fail(f"'{written}' is an action; only facts can be negated", start)
            if not allow_action:
                self.fail(f"{operator} takes facts, but '{written}' is an action", start)
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

# Mappings read by name (a symbol or its text), so their keys are of any type.
ConjMembers = Mapping[Any, Iterable[tuple[Any, Any]]]
Members = Mapping[Any, Sequence[clingo.Symbol]]


def _truth(value) -> bool:
    """A truth value given as bool, "true"/"false" or the symbol true/false."""
    if isinstance(value, bool):
        return value
    if isinstance(value, clingo.Symbol):
        return value.type == clingo.SymbolType.Function and value.name == "true"
    return str(value) == "true"


def format_fact(variable, value, naming: Naming | None = None) -> str:
    """A fact as text: ``v`` (true) or ``-v`` (false); with a PDDL model's
    ``naming`` ``(v a)`` or ``(not (v a))``."""
    if naming is not None and naming.pddl and isinstance(variable, clingo.Symbol):
        return naming.fact_of(variable, _truth(value))
    return str(variable) if _truth(value) else f"-{variable}"


class _Lookup:
    """Members of conjunctions or of all/any names, found by symbol or by text."""

    def __init__(self, mapping: Mapping | None, naming: Naming | None = None):
        self.mapping = mapping or {}
        self.by_text: dict[str, list] | None = None
        self.naming = naming  # how the printed formula names actions and facts

    def __call__(self, name) -> list:
        if name in self.mapping:
            return list(self.mapping[name])
        if self.by_text is None:
            self.by_text = {str(key): list(value) for key, value in self.mapping.items()}
        return list(self.by_text.get(str(name), []))


def _element(term: clingo.Symbol, naming: Naming | None = None) -> str:
    if term.name == "action" and len(term.arguments) == 1:
        action = term.arguments[0]
        return naming.action(action) if naming is not None and naming.pddl else str(action)
    if term.name == "fact" and len(term.arguments) == 2:
        variable, value = term.arguments
        return format_fact(variable, value, naming)
    raise ValueError(f"not an element of L: {term}")


_CONNECTIVES = {"neg": 1, "and": 2, "or": 2, "imp": 2}
_STRENGTH = {"neg": _NOT, "and": _AND, "or": _OR, "imp": _IMP}


def _facts_text(side, conj: _Lookup) -> str:
    facts = [format_fact(variable, value, conj.naming) for variable, value in conj(side)]
    return " & ".join(facts) if facts else "()"


def _patient_text(patient: clingo.Symbol, conj: _Lookup) -> str:
    return conj.naming.name(patient) if conj.naming is not None else str(patient)


def _facts_term_text(term: clingo.Symbol, conj: _Lookup) -> str:
    """A fact (``fact(V,B)``) or facts joined (``all_facts(C)``: "&",
    ``any_facts(C)``: "|"), as text."""
    if term.name == "fact" and len(term.arguments) == 2:
        return format_fact(term.arguments[0], term.arguments[1], conj.naming)
    if term.name in ("all_facts", "any_facts") and len(term.arguments) == 1:
        joint = " & " if term.name == "all_facts" else " | "
        facts = [format_fact(v, b, conj.naming) for v, b in conj(term.arguments[0])]
        return joint.join(facts) if facts else "()"
    raise ValueError(f"not facts of L: {term}")


def _utility_text(term: clingo.Symbol, conj: _Lookup) -> str:
    """A utility term as text (no recursion: the left spine is walked)."""
    parts: list[str] = []
    while (
        term.type == clingo.SymbolType.Function
        and term.name in ("add", "sub")
        and len(term.arguments) == 2
    ):
        parts.append(
            ("+ " if term.name == "add" else "- ") + _utility_primary(term.arguments[1], conj)
        )
        term = term.arguments[0]
    return " ".join([_utility_primary(term, conj), *list(reversed(parts))])


def _utility_primary(term: clingo.Symbol, conj: _Lookup) -> str:
    signs = 0
    while (
        term.type == clingo.SymbolType.Function
        and term.name == "minus"
        and len(term.arguments) == 1
    ):
        signs += 1
        term = term.arguments[0]
    if term.type == clingo.SymbolType.Function and term.name == "num" and len(term.arguments) == 1:
        text = str(term.arguments[0])
    elif term.type == clingo.SymbolType.Function and term.name == "u" and len(term.arguments) == 1:
        text = f"U({_facts_text(term.arguments[0], conj)})"
    else:
        raise ValueError(f"not a utility term: {term}")
    return "-" * signs + text


def _atom_text(term: clingo.Symbol, conj: _Lookup) -> str:
    name, args = term.name, term.arguments
    if name in ("good", "bad", "neutral") and len(args) == 1:
        return f"{ATOMS[name]}({_element(args[0], conj.naming)})"
    if (
        name in ("caused", "goal_fact", "finally", "but_for", "instrumental", "avoidable")
        and len(args) == 2
    ):
        return f"{ATOMS[name]}({format_fact(args[0], args[1], conj.naming)})"
    if name in ("means", "means2", "end") and len(args) == 1:
        return f"{ATOMS[name]}({_patient_text(args[0], conj)})"
    if name == "intended" and len(args) == 2:
        return f"I({format_fact(args[0], args[1], conj.naming)})"
    if name in ("affects_pos", "affects_neg") and len(args) == 3:
        fact = format_fact(args[0], args[1], conj.naming)
        return f"{ATOMS[name]}({fact}, {_patient_text(args[2], conj)})"
    if name == "causes" and len(args) == 2:
        return f"Causes({_facts_term_text(args[0], conj)}, {_facts_term_text(args[1], conj)})"
    if name == "do" and len(args) == 2:
        return f"Do({_facts_text(args[0], conj)}, {_facts_term_text(args[1], conj)})"
    if name == "ucompare" and len(args) == 3 and args[0].name in _SHOWN:
        return (
            f"{_utility_text(args[1], conj)} {_SHOWN[args[0].name]} {_utility_text(args[2], conj)}"
        )
    if name == "geq" and len(args) == 2:
        sides = []
        for side in args:
            facts = [format_fact(variable, value, conj.naming) for variable, value in conj(side)]
            sides.append(" & ".join(facts) if facts else "()")
        return f"GEq({sides[0]}, {sides[1]})"
    raise ValueError(f"not a formula of L: {term}")


def _format(term: clingo.Symbol, conj: _Lookup, members: _Lookup) -> str:
    """The text of a formula term, built with an explicit stack (no recursion).

    The stack holds text to emit, formulas to print with the binding strength
    their place requires (in parentheses if they bind less tightly), and
    markers for the all/any names being printed (a name inside itself is a
    cycle, not a formula).
    """
    out: list[str] = []
    active: set[str] = set()
    stack: list = [(term, 0)]
    while stack:
        item = stack.pop()
        if isinstance(item, str):
            out.append(item)
            continue
        if item[0] is None:  # done with an all/any name
            active.discard(item[1])
            continue
        term, required = item
        if term.type != clingo.SymbolType.Function:
            raise ValueError(f"not a formula of L: {term}")
        name, args = term.name, term.arguments
        parts: list = []
        if name in ("all", "any") and len(args) == 1:
            key = str(args[0])
            if key in active:
                raise ValueError(f"not a formula of L: {name}({key}) contains itself")
            parts = members(args[0])
            if len(parts) == 1:  # prints as its one member
                active.add(key)
                stack += [(None, key), (parts[0], required)]
                continue
            strength = _ATOM if not parts else (_AND if name == "all" else _OR)
        elif name in _CONNECTIVES and len(args) == _CONNECTIVES[name]:
            strength = _STRENGTH[name]
        else:
            out.append(_atom_text(term, conj))
            continue
        if name == "neg":
            items: list = ["not ", (args[0], _NOT)]
        elif name == "and":
            items = [(args[0], _AND), " and ", (args[1], _NOT)]
        elif name == "or":
            items = [(args[0], _OR), " or ", (args[1], _AND)]
        elif name == "imp":
            items = [(args[0], _OR), " -> ", (args[1], _IMP)]
        elif not parts:
            items = ["true" if name == "all" else "false"]
        else:
            joint, level = (" and ", _NOT) if name == "all" else (" or ", _AND)
            items = []
            for index, part in enumerate(parts):
                items += ([joint] if index else []) + [(part, level)]
            active.add(str(args[0]))
            items.append((None, str(args[0])))
        if strength < required:
            items = ["(", *items, ")"]
        stack += reversed(items)
    return "".join(out)


def format_formula(
    term: clingo.Symbol,
    conj_members: ConjMembers | None = None,
    members: Members | None = None,
    naming: Naming | None = None,
) -> str:
    """Print a formula term of ``language.lp`` in the syntax of :func:`parse_formula`.

    ``conj_members`` maps conjunction names (symbols, or their text) to their
    facts as (variable, value) pairs, the value a bool, ``"true"``/``"false"``
    or the symbol; ``members`` maps the names of ``all/any`` to their member
    formulas.  A name missing from a mapping has no members (as in ASP): an
    empty ``all`` prints ``true``, an empty ``any`` prints ``false``.  With
    the ``naming`` of a PDDL model, actions and facts are printed in PDDL form
    (``Bad((move a b))``, ``Caused((not (at a)))``), which the parser reads too.
    """
    return _format(term, _Lookup(conj_members, naming), _Lookup(members))


def format_literal(
    term: clingo.Symbol, conj_members: ConjMembers | None = None, naming: Naming | None = None
) -> str:
    """Print a literal of L: an atom (Good, Bad, Neutral, Caused, GEq) or its negation."""
    atom = term.arguments[0] if term.name == "neg" and len(term.arguments) == 1 else term
    if atom.name not in ATOMS:
        raise ValueError(f"not a literal of L: {term}")
    return format_formula(term, conj_members, naming=naming)
