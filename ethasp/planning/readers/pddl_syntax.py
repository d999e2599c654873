"""PDDL syntax: a domain or problem file read into plain data.

PDDL is case-insensitive, so a file is read in lower case.  Reading has two
stages: the text becomes nested lists of words (s-expressions, each with its
offset in the text for messages), then :func:`read_domain` and
:func:`read_problem` read the sections of PDDL from them.  Nothing here knows
ASP: :mod:`ethasp.planning.readers.pddl` translates the data into rules.

What is read: requirements, types (with ``either`` parents), constants and
objects (typed, ``either`` allowed), predicates, functions (only for action
costs), actions (precondition: any goal description; effect: ``and``,
``not``, ``forall``, ``when``, and ``increase`` of ``total-cost``), derived
predicates, and problems with init, goal and metric.  Formulas are goal
descriptions: atoms, ``=``, ``not``, ``and``, ``or``, ``imply``, ``exists``,
``forall``.  Features outside this (durative actions, processes, events,
numeric conditions and effects, non-deterministic effects, constraints,
preferences) raise an :class:`~ethasp.errors.InputError` naming the feature and
its line; so do syntax errors (with line and column).

While reading, the requirements that the file uses are collected
(``used``), so that those not declared can be reported.
"""

from __future__ import annotations

import bisect
import re
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

from ethasp.errors import InputError

FRAGMENT = (
    "ethasp reads STRIPS and ADL (typing, equality, negation, disjunction, quantifiers, "
    "conditional effects), derived predicates and action costs"
)

_TOKEN = re.compile(r";[^\n]*|[()]|[^\s();]+")
_NAME = re.compile(r"[a-z][-_a-z0-9]*")
_DEFINE = re.compile(r"\(\s*define\s*\(\s*(domain|problem)\b")
_COMMENT = re.compile(r";[^\n]*")
# Names that are keywords of ASP (a PDDL name becomes an ASP constant).
RESERVED = {"not"}


# -- files and s-expressions ----------------------------------------------------


class Word(str):
    """A word of a PDDL file, with its offset in the text."""

    pos: int

    def __new__(cls, text: str, pos: int) -> Word:
        word = super().__new__(cls, text)
        word.pos = pos
        return word


class Group(list):
    """A parenthesised list of words and groups, with the offset of its '('."""

    def __init__(self, pos: int):
        super().__init__()
        self.pos = pos


Expr = Word | Group


@dataclass(frozen=True)
class PddlFile:
    """A PDDL file's text, lower case, with its name for messages."""

    name: str
    text: str

    @classmethod
    def read(cls, path: Path) -> PddlFile:
        """Read a file: UTF-8 (a byte order mark is skipped), or else Latin-1 (as
        planners read it: comments may carry accented letters), unless it holds
        a NUL byte, which no text does."""
        try:
            if path.is_dir():
                raise InputError(f"{path}: is a directory, not a file")
            if not path.exists():
                raise InputError(f"{path}: no such file")
            data = path.read_bytes()
        except OSError as exc:
            raise InputError(f"{path}: cannot be read ({exc.strerror or exc})") from None
        try:
            text = data.decode("utf-8-sig")
        except UnicodeDecodeError as exc:
            if b"\0" in data:
                raise InputError(
                    f"{path}: cannot be read (not UTF-8 text: byte "
                    f"{exc.object[exc.start]:#04x} at offset {exc.start})"
                ) from None
            text = data.decode("latin-1")
        return cls(str(path), text.lower())

    def kind(self) -> str | None:
        """``domain``, ``problem`` or None, from the ``(define (...`` header."""
        match = _DEFINE.search(_COMMENT.sub("", self.text))
        return match.group(1) if match else None

    @cached_property
    def _line_starts(self) -> list[int]:
        return [0] + [match.end() for match in re.finditer("\n", self.text)]

    def position(self, pos: int) -> tuple[int, int]:
        """Line and column (both from 1) of an offset."""
        line = bisect.bisect_right(self._line_starts, pos)
        return line, pos - self._line_starts[line - 1] + 1

    def at(self, expr: Expr | int) -> str:
        """``file:line`` of an expression, for messages."""
        pos = expr if isinstance(expr, int) else expr.pos
        return f"{self.name}:{self.position(pos)[0]}"

    def error(self, expr: Expr | int, message: str) -> InputError:
        return InputError(f"{self.at(expr)}: {message}")

    def syntax_error(self, expr: Expr | int, message: str) -> InputError:
        pos = expr if isinstance(expr, int) else expr.pos
        line, column = self.position(pos)
        return InputError(f"{self.name}:{line}:{column}: syntax error: {message}")

    def unsupported(self, expr: Expr | int, feature: str) -> InputError:
        return self.error(expr, f"unsupported PDDL feature: {feature}; {FRAGMENT}")


def parse_expressions(file: PddlFile) -> tuple[Group, int | None]:
    """The first top-level group of a file, and the offset of a '(' left open.

    Groups left open at the end of the file are closed there, so that the
    structure can be read and a misplaced parenthesis reported where the
    structure goes wrong; if it reads well, the open '(' is the error.
    """
    stack: list[Group] = []
    top: Group | None = None
    for match in _TOKEN.finditer(file.text):
        token = match.group()
        if token[0] == ";":
            continue
        pos = match.start()
        if top is not None and not stack:
            raise file.syntax_error(pos, f"unexpected {token!r} after the end of the definition")
        if token == "(":
            group = Group(pos)
            if stack:
                stack[-1].append(group)
            stack.append(group)
        elif token == ")":
            if not stack:
                raise file.syntax_error(pos, "unexpected ')'")
            group = stack.pop()
            if not stack:
                top = group
        elif not stack:
            raise file.syntax_error(pos, f"unexpected {token!r} outside parentheses")
        else:
            stack[-1].append(Word(token, pos))
    if top is None and not stack:
        raise InputError(f"{file.name}: syntax error: empty file")
    if stack:
        return stack[0], stack[0].pos if top is None else None
    return top, None


# -- formulas, effects and declarations ------------------------------------------


@dataclass(frozen=True)
class Param:
    """A typed name: a variable (without '?') or an object; no types means object."""

    name: str
    types: tuple[str, ...]


@dataclass(frozen=True)
class Atom:
    """An atom ``(p t1 ... tn)``; a term is a variable '?x' or a name."""

    predicate: str
    terms: tuple[str, ...]
    pos: int


@dataclass(frozen=True)
class Equal:
    """``(= t1 t2)``: two terms name the same object."""

    left: str
    right: str
    pos: int


@dataclass(frozen=True)
class Not:
    """``(not f)``."""

    argument: Formula


@dataclass(frozen=True)
class And:
    """``(and f ...)``."""

    parts: tuple[Formula, ...]


@dataclass(frozen=True)
class Or:
    """``(or f ...)``."""

    parts: tuple[Formula, ...]


@dataclass(frozen=True)
class Imply:
    """``(imply f g)``."""

    left: Formula
    right: Formula


@dataclass(frozen=True)
class Exists:
    """``(exists (?x ...) f)``."""

    params: tuple[Param, ...]
    body: Formula


@dataclass(frozen=True)
class Forall:
    """``(forall (?x ...) f)``."""

    params: tuple[Param, ...]
    body: Formula


Formula = Atom | Equal | Not | And | Or | Imply | Exists | Forall


@dataclass(frozen=True)
class Literal:
    """An effect: the atom becomes true (positive) or false."""

    atom: Atom
    positive: bool


@dataclass(frozen=True)
class AllEffects:
    """An ``and`` of effects."""

    parts: tuple[Effect, ...]


@dataclass(frozen=True)
class ForallEffect:
    """``(forall (?x ...) e)``: the effect for every object."""

    params: tuple[Param, ...]
    effect: Effect


@dataclass(frozen=True)
class When:
    """``(when f e)``: a conditional effect."""

    condition: Formula
    effect: Effect


@dataclass(frozen=True)
class CostEffect:
    """``(increase (total-cost) N)`` or ``(increase (total-cost) (f t ...))``:
    an action cost, a number (``amount``) or the value of a function the
    problem's initial state gives (``function``, an atom of the function)."""

    pos: int
    amount: str | None = None
    function: Atom | None = None


Effect = Literal | AllEffects | ForallEffect | When | CostEffect


@dataclass(frozen=True)
class Action:
    """``(:action name :parameters ... :precondition ... :effect ...)``."""

    name: str
    params: tuple[Param, ...]
    precondition: Formula
    effect: Effect
    pos: int


@dataclass(frozen=True)
class Derived:
    """``(:derived (p ?x ...) body)``."""

    predicate: str
    params: tuple[Param, ...]
    body: Formula
    pos: int


@dataclass
class Domain:
    """A domain file read: its name, requirements, types, constants,
    predicates, functions, actions and derived predicates."""

    file: PddlFile
    name: str
    requirements: set[str] = field(default_factory=set)
    types: list[Param] = field(default_factory=list)  # a type and its parents
    constants: list[Param] = field(default_factory=list)
    predicates: dict[str, tuple[Param, ...]] = field(default_factory=dict)
    predicate_pos: dict[str, int] = field(default_factory=dict)
    declares_predicates: bool = False  # has a :predicates section
    functions: set[str] = field(default_factory=set)
    actions: list[Action] = field(default_factory=list)
    derived: list[Derived] = field(default_factory=list)
    used: dict[str, int] = field(default_factory=dict)  # requirement -> first offset


@dataclass(frozen=True)
class NumericFact:
    """``(= (f c ...) N)`` in the initial state: a function's value."""

    function: str
    terms: tuple[str, ...]
    value: str
    pos: int


@dataclass
class Problem:
    """A problem file read: its name, domain, objects, initial state, goal and metric."""

    file: PddlFile
    name: str
    domain_name: str
    requirements: set[str] = field(default_factory=set)
    objects: list[Param] = field(default_factory=list)
    init: list[Atom] = field(default_factory=list)
    numeric_init: list[NumericFact] = field(default_factory=list)
    goal: Formula = And(())
    metric: int | None = None  # offset of (:metric ...)
    minimizes_cost: bool = False  # the metric is (:metric minimize (total-cost))
    used: dict[str, int] = field(default_factory=dict)


# Requirements that ethasp accepts (Fast Downward's list, which also names
# the ones it implies, and PDDL 1.2's :domain-axioms and :safety-constraints,
# which the ADL domains of the first competitions declare without using:
# their sections, (:axiom ...) and (:safety ...), are refused where they
# occur); others are refused by name.
REQUIREMENTS = {
    ":strips",
    ":typing",
    ":negative-preconditions",
    ":negation",
    ":equality",
    ":disjunctive-preconditions",
    ":existential-preconditions",
    ":universal-preconditions",
    ":quantified-preconditions",
    ":conditional-effects",
    ":derived-predicates",
    ":action-costs",
    ":adl",
    ":fluents",
    ":numeric-fluents",
    ":domain-axioms",
    ":safety-constraints",
    ":ucpop",
}
IMPLIED = {
    ":ucpop": {":adl", ":domain-axioms", ":safety-constraints"},
    ":adl": {
        ":strips",
        ":typing",
        ":negative-preconditions",
        ":disjunctive-preconditions",
        ":equality",
        ":existential-preconditions",
        ":universal-preconditions",
        ":quantified-preconditions",
        ":conditional-effects",
    },
    ":quantified-preconditions": {":existential-preconditions", ":universal-preconditions"},
    ":disjunctive-preconditions": {":negative-preconditions"},
    ":negation": {":negative-preconditions"},
    ":fluents": {":numeric-fluents", ":action-costs"},
    ":numeric-fluents": {":action-costs"},
}

NUMERIC_EFFECTS = {"increase", "decrease", "assign", "scale-up", "scale-down"}
COMPARISONS = {"<", ">", "<=", ">="}
SECTIONS_UNSUPPORTED = {
    ":durative-action": "durative actions (:durative-action)",
    ":process": "processes (:process)",
    ":event": "events (:event)",
    ":constraints": "constraints (:constraints)",
    ":axiom": "PDDL 1.2 axioms (:axiom; derived predicates, :derived, are read)",
    ":safety": "safety constraints (:safety)",
}


class _Reader:
    """Reads the sections of one file; collects the requirements it uses."""

    def __init__(self, file: PddlFile):
        self.file = file
        self.used: dict[str, int] = {}

    # -- helpers ------------------------------------------------------------

    def use(self, requirement: str, expr: Expr) -> None:
        self.used.setdefault(requirement, expr.pos)

    def group(self, expr: Expr, what: str) -> Group:
        if not isinstance(expr, Group):
            raise self.file.syntax_error(expr, f"expected {what}, found {expr!r}")
        return expr

    def word(self, expr: Expr, what: str) -> Word:
        if not isinstance(expr, Word):
            raise self.file.syntax_error(expr, f"expected {what}, found '('")
        return expr

    def name(self, expr: Expr, what: str = "a name") -> str:
        word = self.word(expr, what)
        if not _NAME.fullmatch(word):
            hint = (
                ""
                if word[0] in "?:-"
                else " (ethasp reads names that start with a letter and have only letters, "
                "digits, '-' and '_')"
            )
            raise self.file.syntax_error(word, f"expected {what}, found {word!r}{hint}")
        if word in RESERVED:
            raise self.file.error(
                word,
                f"the name {word} cannot be used: "
                "it is a keyword of ASP, into which PDDL is translated",
            )
        return str(word)

    def arity(self, group: Group, count: int, what: str) -> None:
        if len(group) != count + 1:
            raise self.file.syntax_error(
                group,
                f"{what} takes {count} argument{'s' if count != 1 else ''}, found {len(group) - 1}",
            )

    def head(self, group: Group) -> str | None:
        return str(group[0]) if group and isinstance(group[0], Word) else None

    # -- typed lists ----------------------------------------------------------

    def type_spec(self, expr: Expr) -> tuple[str, ...]:
        if isinstance(expr, Word):
            return (self.name(expr, "a type"),)
        if self.head(expr) != "either" or len(expr) < 2:
            raise self.file.syntax_error(expr, "expected a type or (either type ...)")
        return tuple(self.name(item, "a type") for item in expr[1:])

    def typed_list(self, items, variables: bool) -> list[Param]:
        """``a b - t c - (either u v) d``: each name with its types."""
        result: list[Param] = []
        pending: list[str] = []
        index = 0
        items = list(items)
        while index < len(items):
            item = items[index]
            if isinstance(item, Word) and item == "-":
                if index + 1 >= len(items) or not pending:
                    raise self.file.syntax_error(item, "a '-' must follow names and precede a type")
                self.use(":typing", item)
                types = self.type_spec(items[index + 1])
                result += [Param(name, types) for name in pending]
                pending = []
                index += 2
                continue
            if variables:
                word = self.word(item, "a variable ?x")
                if not word.startswith("?") or not _NAME.fullmatch(word[1:]):
                    raise self.file.syntax_error(word, f"expected a variable ?x, found {word!r}")
                pending.append(str(word[1:]))
            else:
                pending.append(self.name(item))
            index += 1
        result += [Param(name, ()) for name in pending]
        return result

    # -- formulas -------------------------------------------------------------

    def term(self, expr: Expr) -> str:
        if isinstance(expr, Group):
            raise self.file.unsupported(expr, "numeric fluents (a function as a term)")
        if expr.startswith("?"):
            if not _NAME.fullmatch(expr[1:]):
                raise self.file.syntax_error(expr, f"expected a variable ?x, found {expr!r}")
            return str(expr)
        return self.name(expr, "a term")

    def atom(self, group: Group) -> Atom:
        predicate = self.name(group[0], "a predicate")
        return Atom(predicate, tuple(self.term(item) for item in group[1:]), group.pos)

    def condition(self, expr: Expr) -> Formula:
        group = self.group(expr, "a formula")
        if not group:
            return And(())
        head = self.head(group)
        if head is None:
            raise self.file.syntax_error(group[0], "expected a formula, found '('")
        if head == "and":
            return And(tuple(self.condition(part) for part in group[1:]))
        if head == "or":
            self.use(":disjunctive-preconditions", group)
            return Or(tuple(self.condition(part) for part in group[1:]))
        if head == "not":
            self.arity(group, 1, "not")
            self.use(":negative-preconditions", group)
            return Not(self.condition(group[1]))
        if head == "imply":
            self.arity(group, 2, "imply")
            self.use(":disjunctive-preconditions", group)
            return Imply(self.condition(group[1]), self.condition(group[2]))
        if head in ("exists", "forall"):
            self.arity(group, 2, head)
            self.use(
                ":existential-preconditions" if head == "exists" else ":universal-preconditions",
                group,
            )
            params = tuple(self.typed_list(self.group(group[1], "(?x - type ...)"), True))
            body = self.condition(group[2])
            return Exists(params, body) if head == "exists" else Forall(params, body)
        if head == "=":
            self.arity(group, 2, "=")
            if any(isinstance(item, Group) for item in group[1:]):
                raise self.file.unsupported(group, "numeric fluents (= on a function)")
            self.use(":equality", group)
            return Equal(self.term(group[1]), self.term(group[2]), group.pos)
        if head in COMPARISONS:
            raise self.file.unsupported(group, f"numeric comparisons ({head})")
        if head == "preference":
            raise self.file.unsupported(group, "preferences (preference)")
        if head in ("at", "over") and len(group) > 1 and group[1] in ("start", "end", "all"):
            raise self.file.unsupported(group, "durative actions (temporal conditions)")
        return self.atom(group)

    def effect(self, expr: Expr) -> Effect:
        group = self.group(expr, "an effect")
        if not group:
            return AllEffects(())
        head = self.head(group)
        if head is None:
            raise self.file.syntax_error(group[0], "expected an effect, found '('")
        if head == "and":
            return AllEffects(tuple(self.effect(part) for part in group[1:]))
        if head == "not":
            self.arity(group, 1, "not")
            inner = self.group(group[1], "an atom")
            if self.head(inner) in ("=", "and", "not", "or", "when", "forall"):
                raise self.file.syntax_error(inner, "a negative effect must be (not (p ...))")
            return Literal(self.atom(inner), False)
        if head == "forall":
            self.arity(group, 2, "forall")
            self.use(":conditional-effects", group)
            params = tuple(self.typed_list(self.group(group[1], "(?x - type ...)"), True))
            return ForallEffect(params, self.effect(group[2]))
        if head == "when":
            self.arity(group, 2, "when")
            self.use(":conditional-effects", group)
            return When(self.condition(group[1]), self.effect(group[2]))
        if head in NUMERIC_EFFECTS:
            target = group[1] if len(group) > 1 else None
            if (
                head == "increase"
                and isinstance(target, Group)
                and self.head(target) == "total-cost"
            ):
                self.use(":action-costs", group)
                self.arity(group, 2, "increase")
                amount = group[2]
                if isinstance(amount, Group):
                    if not amount:
                        raise self.file.syntax_error(amount, "expected (f ...)")
                    function = self.name(amount[0], "a function")
                    terms = tuple(self.term(item) for item in amount[1:])
                    return CostEffect(group.pos, function=Atom(function, terms, amount.pos))
                return CostEffect(group.pos, amount=str(amount))
            raise self.file.unsupported(group, f"numeric effects ({head})")
        if head == "oneof":
            raise self.file.unsupported(group, "non-deterministic effects (oneof)")
        if head in ("at", "over") and len(group) > 1 and group[1] in ("start", "end", "all"):
            raise self.file.unsupported(group, "durative actions (temporal effects)")
        if head in ("=", "or", "exists", "imply"):
            raise self.file.syntax_error(group, f"'{head}' is not an effect")
        return Literal(self.atom(group), True)

    # -- sections -------------------------------------------------------------

    def sections(self, top: Group, kind: str) -> tuple[str, list[Group]]:
        """The name after ``(define (kind NAME)`` and the sections that follow."""
        if self.head(top) != "define" or len(top) < 2:
            raise self.file.syntax_error(top, f"expected (define ({kind} ...) ...)")
        header = self.group(top[1], f"({kind} NAME)")
        if self.head(header) != kind or len(header) != 2:
            raise self.file.syntax_error(header, f"expected ({kind} NAME)")
        sections = []
        for section in top[2:]:
            group = self.group(section, "a section (:keyword ...)")
            head = self.head(group)
            if head is None or not head.startswith(":"):
                raise self.file.syntax_error(group, "expected a section (:keyword ...)")
            sections.append(group)
        return self.name(header[1]), sections

    def requirements(self, group: Group) -> set[str]:
        declared = set()
        for item in group[1:]:
            word = self.word(item, "a requirement")
            if word not in REQUIREMENTS:
                raise self.file.error(word, f"unsupported PDDL requirement {word}; {FRAGMENT}")
            declared.add(str(word))
        return declared

    def action(self, group: Group) -> Action:
        if len(group) < 2:
            raise self.file.syntax_error(group, "an action needs a name")
        name = self.name(group[1], "an action name")
        parts: dict[str, Expr] = {}
        index = 2
        while index < len(group):
            key = group[index]
            if not isinstance(key, Word) or key not in (":parameters", ":precondition", ":effect"):
                raise self.file.syntax_error(
                    key,
                    "expected :parameters, :precondition or :effect, found "
                    + (f"{key!r}" if isinstance(key, Word) else "'('"),
                )
            if index + 1 >= len(group):
                raise self.file.syntax_error(key, f"{key} needs a value")
            parts[str(key)] = group[index + 1]
            index += 2
        params = ()
        if ":parameters" in parts:
            params = tuple(
                self.typed_list(self.group(parts[":parameters"], "(?x - type ...)"), True)
            )
        precondition = (
            self.condition(parts[":precondition"]) if ":precondition" in parts else And(())
        )
        effect = self.effect(parts[":effect"]) if ":effect" in parts else AllEffects(())
        return Action(name, params, precondition, effect, group.pos)

    def derived(self, group: Group) -> Derived:
        self.use(":derived-predicates", group)
        if len(group) != 3:
            raise self.file.syntax_error(group, "expected (:derived (p ?x ...) formula)")
        head = self.group(group[1], "(p ?x ...)")
        predicate = self.name(head[0] if head else head, "a predicate")
        params = tuple(self.typed_list(head[1:], True))
        return Derived(predicate, params, self.condition(group[2]), group.pos)

    def predicate_declarations(self, group: Group, domain: Domain) -> None:
        for item in group[1:]:
            declaration = self.group(item, "(p ?x ...)")
            if not declaration:
                raise self.file.syntax_error(declaration, "expected (p ?x ...)")
            if declaration[0] == "=":  # equality, built in; some writers of PDDL declare it
                continue
            predicate = self.name(declaration[0], "a predicate")
            domain.predicates[predicate] = tuple(self.typed_list(declaration[1:], True))
            domain.predicate_pos[predicate] = declaration.pos

    def function_declarations(self, group: Group, domain: Domain) -> None:
        for item in group[1:]:
            if isinstance(item, Word):  # "- number" after a function
                continue
            if not item:
                raise self.file.syntax_error(item, "expected (f ?x ...)")
            domain.functions.add(self.name(item[0], "a function"))


def read_domain(file: PddlFile) -> Domain:
    """Read a domain file (see the module docstring)."""
    top, unclosed = parse_expressions(file)
    reader = _Reader(file)
    name, sections = reader.sections(top, "domain")
    domain = Domain(file, name)
    for group in sections:
        head = reader.head(group)
        if head == ":requirements":
            domain.requirements |= reader.requirements(group)
        elif head == ":types":
            domain.types += reader.typed_list(group[1:], False)
        elif head == ":constants":
            domain.constants += reader.typed_list(group[1:], False)
        elif head == ":predicates":
            domain.declares_predicates = True
            reader.predicate_declarations(group, domain)
        elif head == ":functions":
            reader.use(":action-costs", group)
            reader.function_declarations(group, domain)
        elif head == ":action":
            domain.actions.append(reader.action(group))
        elif head == ":derived":
            domain.derived.append(reader.derived(group))
        elif head in SECTIONS_UNSUPPORTED:
            raise file.unsupported(group, SECTIONS_UNSUPPORTED[head])
        else:
            raise file.syntax_error(group, f"unknown section {head} in a domain")
    if unclosed is not None:
        raise file.syntax_error(unclosed, "this '(' is not closed (unexpected end of file)")
    domain.used = reader.used
    return domain


def read_problem(file: PddlFile) -> Problem:
    """Read a problem file (see the module docstring)."""
    top, unclosed = parse_expressions(file)
    reader = _Reader(file)
    name, sections = reader.sections(top, "problem")
    problem = Problem(file, name, "")
    has_goal = False
    for group in sections:
        head = reader.head(group)
        if head == ":domain":
            reader.arity(group, 1, ":domain")
            problem.domain_name = reader.name(group[1], "a domain name")
        elif head == ":requirements":
            problem.requirements |= reader.requirements(group)
        elif head == ":objects":
            problem.objects += reader.typed_list(group[1:], False)
        elif head == ":init":
            _read_init(reader, group, problem)
        elif head == ":goal":
            reader.arity(group, 1, ":goal")
            problem.goal = reader.condition(group[1])
            has_goal = True
        elif head == ":metric":
            problem.metric = group.pos
            target = group[2] if len(group) == 3 else None
            problem.minimizes_cost = (
                len(group) == 3
                and group[1] == "minimize"
                and isinstance(target, Group)
                and len(target) == 1
                and target[0] == "total-cost"
            )
        elif head in SECTIONS_UNSUPPORTED:
            raise file.unsupported(group, SECTIONS_UNSUPPORTED[head])
        else:
            raise file.syntax_error(group, f"unknown section {head} in a problem")
    if unclosed is not None:
        raise file.syntax_error(unclosed, "this '(' is not closed (unexpected end of file)")
    if not problem.domain_name:
        raise file.error(top, "the problem names no domain (:domain NAME)")
    if not has_goal:
        raise file.error(top, "the problem has no goal (:goal ...)")
    problem.used = reader.used
    return problem


def _read_init(reader: _Reader, group: Group, problem: Problem) -> None:
    for item in group[1:]:
        element = reader.group(item, "an atom")
        head = reader.head(element)
        if head == "=":
            reader.arity(element, 2, "=")
            if not isinstance(element[1], Group):
                raise reader.file.error(
                    element,
                    "an equality of objects in the initial state "
                    "(only numeric facts (= (f ...) N) use =; "
                    "objects are equal only to themselves)",
                )
            function = element[1]
            if not function:
                raise reader.file.syntax_error(function, "expected (f ...)")
            name = reader.name(function[0], "a function")
            terms = tuple(reader.name(item, "an object") for item in function[1:])
            value = reader.word(element[2], "a number")
            problem.numeric_init.append(NumericFact(name, terms, str(value), element.pos))
            continue
        if head == "not":  # closed world: negative facts are the default
            reader.arity(element, 1, "not")
            reader.atom(reader.group(element[1], "an atom"))
            continue
        if head == "at" and len(element) == 3 and isinstance(element[2], Group):
            raise reader.file.unsupported(element, "timed initial literals (at)")
        atom = reader.atom(element)
        for term in atom.terms:
            if term.startswith("?"):
                raise reader.file.syntax_error(element, f"a variable {term} in the initial state")
        problem.init.append(atom)
