"""PDDL input: a STRIPS domain and problem as lifted ASP rules.

The fragment read is STRIPS with ``:typing``, ``:negative-preconditions`` and
``:equality``: preconditions and goals are conjunctions of atoms and negated
atoms (preconditions also of ``(= t1 t2)`` and ``(not (= t1 t2))``), effects
are conjunctions of atoms and negated atoms.  Any other feature (conditional
or quantified effects, disjunctions, numeric fluents, durative actions,
derived predicates, ...) is refused with an InputError naming it.

Files are parsed with the ``pddl`` package after lowering their case (PDDL
is case-insensitive, the package's keywords are not).  The translation does
not ground anything: it writes rules over the model vocabulary of
``encodings/planning/model.lp`` and the typing vocabulary of ``encodings/planning/pddl.lp``,
and clingo grounds them.  For a domain with ``(:types room robot)`` and

    (:action move :parameters (?r - robot ?from ?to - room)
      :precondition (and (at ?r ?from) (not (= ?from ?to)))
      :effect (and (not (at ?r ?from)) (at ?r ?to)))

it writes

    action(move(R,From,To)) :- has_type(R,robot), has_type(From,room),
                               has_type(To,room), From != To.
    pre(move(R,From,To),at(R,From),true) :- action(move(R,From,To)).
    pddl_del(move(R,From,To),at(R,From)) :- action(move(R,From,To)).
    pddl_add(move(R,From,To),at(R,To)) :- action(move(R,From,To)).

plus ``variable/1`` rules for every predicate, ``pddl_object/2`` and
``pddl_subtype/2`` facts for objects and types, and ``init/1`` and ``goal/2``
facts.  Names follow the rule of :mod:`ethasp.planning.naming` (``five-will-die`` is
``five_will_die``).
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable, Sequence

from ethasp.errors import InputError
from ethasp.planning.naming import pddl_name_to_asp

FRAGMENT = "ethasp reads STRIPS with :typing, :negative-preconditions and :equality"

# Keywords (the word after an opening parenthesis) outside the fragment.
UNSUPPORTED = {
    "when": "conditional effects (when)",
    "forall": "universal quantifiers (forall)",
    "exists": "existential quantifiers (exists)",
    "or": "disjunctive conditions (or)",
    "imply": "implications (imply)",
    "oneof": "non-deterministic effects (oneof)",
    "either": "either-types (either)",
    "increase": "numeric effects (increase)",
    "decrease": "numeric effects (decrease)",
    "assign": "numeric effects (assign)",
    "scale-up": "numeric effects (scale-up)",
    "scale-down": "numeric effects (scale-down)",
    "<": "numeric comparisons (<)",
    ">": "numeric comparisons (>)",
    "<=": "numeric comparisons (<=)",
    ">=": "numeric comparisons (>=)",
    ":functions": "numeric fluents (:functions)",
    ":derived": "derived predicates (:derived)",
    ":durative-action": "durative actions (:durative-action)",
    ":process": "processes (:process)",
    ":event": "events (:event)",
    ":constraints": "constraints (:constraints)",
    "preference": "preferences (preference)",
    ":metric": "plan metrics (:metric)",
}

# Requirements that the pddl package knows; others are refused by name.
KNOWN_REQUIREMENTS = {
    ":strips", ":typing", ":negative-preconditions", ":equality", ":adl",
    ":disjunctive-preconditions", ":existential-preconditions",
    ":universal-preconditions", ":quantified-preconditions", ":conditional-effects",
    ":derived-predicates", ":non-deterministic", ":fluents", ":numeric-fluents",
    ":action-costs",
}

_COMMENT = re.compile(r";[^\n]*")
_OPENING = re.compile(r"\(\s*([^\s()]+)")
_REQUIREMENTS = re.compile(r"\(\s*:requirements\b([^()]*)\)")
_DEFINE = re.compile(r"\(\s*define\s*\(\s*(domain|problem)\b")


@dataclass(frozen=True)
class PddlFile:
    """A PDDL file's text, lower case, with its name for messages."""

    name: str
    text: str

    @classmethod
    def read(cls, path: Path) -> "PddlFile":
        if not path.is_file():
            raise InputError(f"{path}: no such file")
        try:
            return cls(str(path), path.read_text().lower())
        except (OSError, UnicodeDecodeError) as exc:
            raise InputError(f"{path}: cannot be read ({exc})") from None

    def kind(self) -> str | None:
        """``domain``, ``problem`` or None, from the ``(define (...`` header."""
        match = _DEFINE.search(_COMMENT.sub("", self.text))
        return match.group(1) if match else None


def _line(text: str, offset: int) -> int:
    return text.count("\n", 0, offset) + 1


def check_fragment(file: PddlFile) -> None:
    """Refuse, naming it, the first feature outside the fragment (by keyword)."""
    text = _COMMENT.sub(lambda match: " " * len(match.group(0)), file.text)
    for match in _OPENING.finditer(text):
        word = match.group(1)
        if word in UNSUPPORTED:
            raise InputError(f"{file.name}:{_line(text, match.start())}: unsupported PDDL "
                             f"feature: {UNSUPPORTED[word]}; {FRAGMENT}")
        if word == "=" and re.match(r"\(\s*=\s*\(", text[match.start():]):
            raise InputError(f"{file.name}:{_line(text, match.start())}: unsupported PDDL "
                             f"feature: numeric fluents (= on a function); {FRAGMENT}")
    for match in _REQUIREMENTS.finditer(text):
        for requirement in match.group(1).split():
            if requirement not in KNOWN_REQUIREMENTS:
                raise InputError(f"{file.name}:{_line(text, match.start())}: unsupported PDDL "
                                 f"requirement {requirement}; {FRAGMENT}")


# -- parsing --------------------------------------------------------------------

def _parsers():
    """The pddl package's parsers, with two changes.

    pddl 0.5 fails on an action without ``:precondition`` (or ``:effect``);
    an empty conjunction stands in for the missing part.  And the grammar
    tables are cached (lark's ``cache``, in the temporary folder), which
    saves about 0.1 seconds for each file read.
    """
    from lark import Lark
    from lark import Transformer as LarkTransformer
    from pddl.logic.base import And
    from pddl.parser import GRAMMAR_FILE, PARSERS_DIRECTORY
    from pddl.parser.domain import DomainParser, DomainTransformer
    from pddl.parser.problem import ProblemParser

    class Cached:
        def __init__(self) -> None:
            LarkTransformer.__init__(self)
            self._transformer = self.transformer_cls()
            self._parser = Lark(GRAMMAR_FILE.read_text(), parser="lalr", cache=True,
                                import_paths=[PARSERS_DIRECTORY], start=self.start_symbol,
                                transformer=self._transformer)

    class Transformer(DomainTransformer):
        def action_def(self, args):
            children = args[5].children
            body = {children[i]: children[i + 1]
                    for i in range(0, len(children) - 1, 2) if children[i] is not None}
            body.setdefault(":precondition", And())
            body.setdefault(":effect", And())
            args[5].children = [item for pair in body.items() for item in pair]
            return super().action_def(args)

    class Domain(Cached, DomainParser):
        transformer_cls = Transformer

    class Problem(Cached, ProblemParser):
        pass

    return Domain, Problem


def _parse(file: PddlFile, parser_class):
    """Parse with the pddl package; every failure becomes one InputError line."""
    from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedToken
    from pddl.exceptions import PDDLMissingRequirementError

    saved = getattr(sys, "tracebacklimit", None)
    try:
        return parser_class()(file.text)
    except UnexpectedToken as error:
        if error.token.type == "$END":
            raise InputError(f"{file.name}: syntax error: unexpected end of file") from None
        raise InputError(f"{file.name}:{error.line}:{error.column}: syntax error: "
                         f"unexpected {str(error.token)!r}") from None
    except UnexpectedCharacters as error:
        raise InputError(f"{file.name}:{error.line}:{error.column}: syntax error: "
                         f"unexpected {error.char!r}") from None
    except UnexpectedEOF:
        raise InputError(f"{file.name}: syntax error: unexpected end of file") from None
    except PDDLMissingRequirementError as error:
        raise InputError(f"{file.name}: requirement {error.requirement} is used "
                         "but not declared in :requirements") from None
    except Exception as error:  # the package raises many kinds; all are bad input
        first = " ".join(str(error).split("\n", 1)[0].split()) or type(error).__name__
        raise InputError(f"{file.name}: invalid PDDL: {first}") from None
    finally:
        # The package lowers sys.tracebacklimit while parsing and may leave it so.
        if saved is None:
            if hasattr(sys, "tracebacklimit"):
                del sys.tracebacklimit
        else:
            sys.tracebacklimit = saved


# -- translation ----------------------------------------------------------------

class _Translator:
    """Writes the rules of one domain and problem (see the module docstring)."""

    def __init__(self, domain_file: PddlFile, problem_file: PddlFile):
        self.domain_file = domain_file
        self.problem_file = problem_file
        self.lines: list[str] = []

    # terms and atoms

    @staticmethod
    def variable(name: str) -> str:
        asp = pddl_name_to_asp(name)
        return asp[0].upper() + asp[1:]

    def term(self, term, parameters: set[str] | None, where: str) -> str:
        from pddl.logic.terms import Variable

        if isinstance(term, Variable):
            if parameters is None or str(term.name) not in parameters:
                raise InputError(f"{where}: unknown variable ?{term.name}")
            return self.variable(term.name)
        return pddl_name_to_asp(term.name)

    def atom(self, predicate, parameters: set[str] | None, where: str) -> str:
        name = pddl_name_to_asp(predicate.name)
        if not predicate.terms:
            return name
        return f"{name}({','.join(self.term(t, parameters, where) for t in predicate.terms)})"

    @staticmethod
    def type_of(tags, where: str) -> str:
        tags = sorted(str(tag) for tag in tags)
        if len(tags) > 1:
            raise InputError(f"{where}: unsupported PDDL feature: either-types; {FRAGMENT}")
        return pddl_name_to_asp(tags[0]) if tags else "object"

    # formulas

    def literals(self, formula, where: str, kind: str) -> list[tuple[bool, object]]:
        """A conjunction as (positive, atom) pairs; atoms are Predicate or EqualTo."""
        from pddl.logic.base import And, Not
        from pddl.logic.predicates import EqualTo, Predicate

        if formula is None:
            return []
        if isinstance(formula, And):
            return [pair for operand in formula.operands
                    for pair in self.literals(operand, where, kind)]
        if isinstance(formula, Not) and isinstance(formula.argument, (Predicate, EqualTo)):
            return [(False, formula.argument)]
        if isinstance(formula, (Predicate, EqualTo)):
            return [(True, formula)]
        raise InputError(f"{where}: unsupported PDDL feature in {kind}: {formula}; {FRAGMENT}")

    # the program

    def emit(self, line: str) -> None:
        self.lines.append(line)

    def declarations(self, domain, problem) -> None:
        for name, parent in sorted(domain.types.items(), key=lambda item: str(item[0])):
            if str(name) != "object":
                parent_name = pddl_name_to_asp(parent) if parent else "object"
                self.emit(f"pddl_subtype({pddl_name_to_asp(name)},{parent_name}).")
        objects = list(domain.constants) + list(problem.objects)
        for constant in sorted(objects, key=lambda c: str(c.name)):
            where = f"{self.domain_file.name}, {self.problem_file.name}: object {constant.name}"
            self.emit(f"pddl_object({pddl_name_to_asp(constant.name)},"
                      f"{self.type_of(constant.type_tags, where)}).")

    def predicates(self, domain) -> None:
        for predicate in sorted(domain.predicates, key=lambda p: str(p.name)):
            where = f"{self.domain_file.name}: predicate {predicate.name}"
            names = {str(term.name) for term in predicate.terms}
            head = self.atom(predicate, names, where)
            body = [f"has_type({self.variable(term.name)},{self.type_of(term.type_tags, where)})"
                    for term in predicate.terms]
            self.emit(f"variable({head})" + (f" :- {', '.join(body)}." if body else "."))

    def action(self, action) -> None:
        from pddl.logic.predicates import EqualTo, Predicate

        where = f"{self.domain_file.name}: action {action.name}"
        parameters = {str(p.name) for p in action.parameters}
        name = pddl_name_to_asp(action.name)
        args = [self.variable(p.name) for p in action.parameters]
        head = f"{name}({','.join(args)})" if args else name
        body = [f"has_type({self.variable(p.name)},{self.type_of(p.type_tags, where)})"
                for p in action.parameters]
        pre = []
        for positive, atom in self.literals(action.precondition, where, "a precondition"):
            if isinstance(atom, EqualTo):
                left = self.term(atom.left, parameters, where)
                right = self.term(atom.right, parameters, where)
                body.append(f"{left} {'=' if positive else '!='} {right}")
            else:
                pre.append(f"pre({head},{self.atom(atom, parameters, where)},"
                           f"{'true' if positive else 'false'})")
        self.emit(f"action({head})" + (f" :- {', '.join(body)}." if body else "."))
        condition = f" :- action({head})." if body else "."
        for line in pre:
            self.emit(line + condition)
        for positive, atom in self.literals(action.effect, where, "an effect"):
            if not isinstance(atom, Predicate):
                raise InputError(f"{where}: unsupported PDDL feature in an effect: {atom}; "
                                 f"{FRAGMENT}")
            effect = "pddl_add" if positive else "pddl_del"
            self.emit(f"{effect}({head},{self.atom(atom, parameters, where)}){condition}")

    def problem(self, problem) -> None:
        from pddl.logic.base import Not
        from pddl.logic.predicates import Predicate

        where = f"{self.problem_file.name}: init"
        for fact in sorted(problem.init, key=str):
            if isinstance(fact, Predicate):
                self.emit(f"init({self.atom(fact, None, where)}).")
            elif not (isinstance(fact, Not) and isinstance(fact.argument, Predicate)):
                raise InputError(f"{where}: unsupported PDDL feature: {fact}; {FRAGMENT}")
        where = f"{self.problem_file.name}: goal"
        for positive, atom in self.literals(problem.goal, where, "the goal"):
            if not isinstance(atom, Predicate):
                raise InputError(f"{where}: unsupported PDDL feature: equality in the goal; "
                                 f"{FRAGMENT}")
            self.emit(f"goal({self.atom(atom, None, where)},{'true' if positive else 'false'}).")

    def translate(self) -> str:
        for file in (self.domain_file, self.problem_file):
            check_fragment(file)
        domain_parser, problem_parser = _parsers()
        domain = _parse(self.domain_file, domain_parser)
        problem = _parse(self.problem_file, problem_parser)
        if problem.domain_name != domain.name:
            raise InputError(f"{self.problem_file.name}: the problem is for domain "
                             f"{problem.domain_name}, not {domain.name} "
                             f"({self.domain_file.name})")
        self.emit(f"% {self.domain_file.name} and {self.problem_file.name}, "
                  "translated by ethasp (see encodings/planning/pddl.lp)")
        self.declarations(domain, problem)
        self.predicates(domain)
        for action in sorted(domain.actions, key=lambda a: str(a.name)):
            self.action(action)
        self.problem(problem)
        return "\n".join(self.lines) + "\n"


def translate(domain: PddlFile, problem: PddlFile) -> str:
    """The ASP rules of a PDDL domain and problem (to be read with encodings/planning/pddl.lp)."""
    return _Translator(domain, problem).translate()


def is_pddl(path: str | Path) -> bool:
    """Whether a model file is PDDL (by its suffix ``.pddl``)."""
    return Path(path).suffix.lower() == ".pddl"


def translate_files(paths: Sequence[str | Path]) -> tuple[str, str]:
    """Translate one domain file and one problem file, given in either order.

    Returns the rules and a name for them (the two file names) for messages.
    """
    files = [PddlFile.read(Path(path)) for path in paths]
    kinds: dict[str, list[PddlFile]] = {"domain": [], "problem": []}
    for file in files:
        kind = file.kind()
        if kind is None:
            raise InputError(f"{file.name}: not a PDDL domain or problem "
                             "(it should start with (define (domain ...) or (define (problem ...))")
        kinds[kind].append(file)
    if len(kinds["domain"]) != 1 or len(kinds["problem"]) != 1:
        names = ", ".join(file.name for file in files)
        raise InputError(f"PDDL input needs one domain file and one problem file, got: {names}")
    domain, problem = kinds["domain"][0], kinds["problem"][0]
    return translate(domain, problem), f"{domain.name}, {problem.name}"


def split_paths(paths: Iterable[str | Path]) -> tuple[list[Path], list[Path]]:
    """The PDDL files and the other (ASP) files among model files."""
    pddl, other = [], []
    for path in map(Path, paths):
        (pddl if is_pddl(path) else other).append(path)
    return pddl, other
