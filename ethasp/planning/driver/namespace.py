"""The model's namespace: which predicates a model may define, and which it may read.

A model is the bottom layer of every program ethasp solves: the encodings
read it, and it must not read or change them.  So a model file, an
annotation file or a file they include

* defines (in a rule head, a choice, a disjunction, ``#external`` or a
  ``#show`` term) only the model vocabulary below and predicates of its own;
* reads (in rule bodies and conditions) only the vocabulary, its own
  predicates, and what ``encodings/planning/model.lp`` (and, for PDDL tasks,
  ``encodings/planning/pddl.lp``) derive from the model alone: ``fact/2``,
  ``weight/2``, ``has_type/2``, ...;
* defines no constant (``#const``) whose name the encodings use (a constant
  is replaced in every file of a program: ``#const true = false.``);
* has no optimisation statements, weak constraints, ``#heuristic``,
  ``#project``, ``#edge``, theory atoms or program parts other than ``base``:
  each would change the searches of the encodings;
* has exactly one answer set (checked by :meth:`ethasp.planning.model.Model.check`).

Then, by the splitting theorem, the answer sets of a model with encodings
are those of the encodings over the model's one answer set: no model can
change what an encoding means.

The encodings' predicates are not listed by hand: every ``.lp`` file under
``encodings/`` is grounded alone (no facts, a few milliseconds) and the
signatures of its program are collected (:func:`mentioned`); for messages,
:func:`encoding_predicates` reads the files with clingo's parser and tells
which encoding defines a predicate and which only reads it.  So a new
encoding is covered as soon as it exists.  Reserved are the predicates the
encodings mention minus the model vocabulary.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import clingo
from clingo import ast

from ethasp.errors import InputError
from ethasp.resources import ENCODINGS

# -- the vocabulary a model defines ---------------------------------------------------

#: The model vocabulary: what models are meant to define (see docs/models/asp.md).
MODEL_VOCABULARY: dict[tuple[str, int], str] = {
    ("variable", 1): "variable(V): a Boolean state variable",
    ("action", 1): "action(A): an action",
    ("pre", 3): "pre(A,V,B): precondition of A: V has value B",
    ("eff", 3): "eff(A,V,B): effect of A: V gets value B",
    ("cpre", 4): "cpre(A,K,V,B): conditional effect K of A fires when V has value B before A",
    ("ceff", 4): "ceff(A,K,V,B): conditional effect K of A sets V to B",
    ("derived", 1): "derived(D): a derived variable (computed from the state by axioms)",
    ("axiom", 2): "axiom(D,K): axiom K of derived variable D",
    ("axiom_pre", 4): "axiom_pre(D,K,V,B): axiom K of D holds when V has value B",
    ("init", 1): "init(V): V is true initially",
    ("goal", 2): "goal(V,B): the goal requires V to have value B",
    ("utility", 2): "utility(A,U): moral value of action A",
    ("utility", 3): "utility(V,B,U): moral value of the fact V=B",
    ("cost", 2): "cost(A,N): the cost of action A (a model with costs plans cheapest plans)",
    ("event", 1): "event(E): an exogenous event",
    ("event_at", 2): "event_at(E,T): event E is due at step T (after the action of step T)",
    ("event_pre", 3): "event_pre(E,V,B): event E happens only if V has value B",
    ("event_effect", 4): "event_effect(E,K,V,B): effect K of event E sets V to B",
    (
        "event_condition",
        4,
    ): "event_condition(E,K,V,B): effect K of event E fires when V has value B",
    ("patient", 1): "patient(P): a moral patient",
    (
        "affects",
        4,
    ): "affects(P,V,B,S): the fact V=B affects patient P positively (pos) or negatively (neg)",
    ("plan_length", 1): "plan_length(N): the model comes with a plan of N steps",
    ("plan_step", 2): "plan_step(T,A): the model's plan has action A at step T",
    ("alternative_plan", 2): "alternative_plan(K,N): alternative plan K has N steps",
    ("alternative_step", 3): "alternative_step(K,T,A): alternative plan K has action A at step T",
    ("override", 4): "override(A,K,V,B): cpre(A,K,V,B) only lets a later effect of A win",
    ("changeable", 1): "changeable(V): a repair may change the initial value of V",
    ("changeable", 2): "changeable(V,C): ... at cost C",
    ("creative", 1): "creative(A): A is a creative alternative, an action a repair may add",
    ("creative", 2): "creative(A,C): ... at cost C",
    ("preventable", 1): "preventable(E): a repair may prevent event E",
    ("preventable", 2): "preventable(E,C): ... at cost C",
    ("goal_cost", 3): "goal_cost(V,B,C): dropping the goal fact V=B costs C",
    ("goal_fixed", 2): "goal_fixed(V,B): a repair may not drop the goal fact V=B",
    ("agent_label", 2): "agent_label(Name,Possessive): words for the agent",
    ("action_label", 3): "action_label(A,Phrase,Gerund): words for action A",
    ("fact_label", 3): "fact_label(V,B,Phrase): words for the fact V=B",
    ("patient_label", 2): "patient_label(P,Phrase): words for the moral patient P",
}

#: What the translation of a PDDL task writes besides the model vocabulary
#: (read by encodings/planning/pddl.lp, and by encodings/planning/static.lp
#: when a plan names an action that does not exist).
PDDL_VOCABULARY: dict[tuple[str, int], str] = {
    ("pddl_subtype", 2): "pddl_subtype(S,T): type S is a subtype of T",
    ("pddl_object", 2): "pddl_object(X,T): object X is declared of type T",
    ("pddl_add", 2): "pddl_add(A,V): an add effect",
    ("pddl_del", 2): "pddl_del(A,V): a delete effect",
    ("pddl_action", 1): "pddl_action(A): A is an instance of an action schema",
    ("pddl_static", 1): "pddl_static(V): V is an atom of a static predicate (no action of "
    "the domain changes it)",
    ("pddl_candidate", 1): "pddl_candidate(A): a term of a plan that is no action (validation)",
    ("pddl_value", 2): "pddl_value(F,N): function F has value N in the initial state",
    ("pddl_schema_instance", 1): "pddl_schema_instance(A): candidate A is an instance of an "
    "action schema",
    ("pddl_static_failure", 3): "pddl_static_failure(A,V,B): static precondition V=B of the "
    "instance A fails",
}

VOCABULARY = {**MODEL_VOCABULARY, **PDDL_VOCABULARY}

#: What only the translation writes: the static atoms its pruning trusts, and
#: the rules that tell validation why a term is no action.  An annotation
#: file defining them would make check.lp refuse what the domain changes, or
#: change validation's words, so they are reserved for the
#: files given with a PDDL task (the translation itself is not checked; a
#: translation saved as an ASP model, which has no PDDL task behind it, may
#: write them).
TRANSLATION_ONLY = (
    ("pddl_action", 1),
    ("pddl_static", 1),
    ("pddl_candidate", 1),
    ("pddl_schema_instance", 1),
    ("pddl_static_failure", 3),
)

# Encodings whose predicates depend on the model alone, so models may read them.
MODEL_LAYER = ("planning/model.lp",)
PDDL_LAYER = ("planning/pddl.lp",)


def signature_text(signature: tuple[str, int]) -> str:
    return f"{signature[0]}/{signature[1]}"


def misused_vocabulary(signatures) -> str:
    """A sentence on the first predicate that has a name of the vocabulary but
    another arity (``init(v,true)`` for ``init(v)``), else ''."""
    arities: dict[str, list[tuple[str, int]]] = {}
    for signature in VOCABULARY:
        arities.setdefault(signature[0], []).append(signature)
    for signature in sorted(set(signatures)):
        known = arities.get(signature[0])
        if known and signature not in VOCABULARY:
            meant = " or ".join(VOCABULARY[s] for s in known)
            return (
                f"{signature_text(signature)} is not in the model vocabulary, which has "
                f"{' and '.join(signature_text(s) for s in known)} ({meant})"
            )
    return ""


def vocabulary_text() -> str:
    """The model vocabulary as a short list, for messages."""
    return ", ".join(signature_text(s) for s in MODEL_VOCABULARY)


# -- walking clingo's AST (iteratively: user programs may nest deeply) ---------------


def _children(node) -> Iterator:
    for key in node.child_keys:
        value = getattr(node, key)
        if value is None:
            continue
        if isinstance(value, ast.AST):
            yield value
        else:
            yield from value


# Nodes that hold terms but no atoms: not walked.
_TERMS = {
    ast.ASTType.Variable,
    ast.ASTType.SymbolicTerm,
    ast.ASTType.Function,
    ast.ASTType.UnaryOperation,
    ast.ASTType.BinaryOperation,
    ast.ASTType.Interval,
    ast.ASTType.Pool,
    ast.ASTType.Comparison,
    ast.ASTType.Guard,
    ast.ASTType.BooleanConstant,
}


def _atoms(root) -> Iterator:
    """Every SymbolicAtom under ``root``."""
    stack = [root]
    while stack:
        node = stack.pop()
        kind = node.ast_type
        if kind == ast.ASTType.SymbolicAtom:
            yield node
        elif kind not in _TERMS:
            stack.extend(_children(node))


def _term_signatures(term) -> list[tuple[str, int]]:
    """The predicate signatures of an atom's term (``-p(X)`` counts as ``p/1``)."""
    found, stack = [], [term]
    while stack:
        term = stack.pop()
        kind = term.ast_type
        if kind == ast.ASTType.UnaryOperation and term.operator_type == ast.UnaryOperator.Minus:
            stack.append(term.argument)
        elif kind == ast.ASTType.Function and not term.external:
            found.append((term.name, len(term.arguments)))
        elif kind == ast.ASTType.SymbolicTerm and term.symbol.type.name == "Function":
            found.append((term.symbol.name, len(term.symbol.arguments)))
        elif kind == ast.ASTType.Pool:
            stack.extend(term.arguments)
    return found


def _atom_signatures(root) -> list[tuple[str, int]]:
    return [signature for atom in _atoms(root) for signature in _term_signatures(atom.symbol)]


DEFINES, SHOWS, READS = "defines", "shows", "reads"


@dataclass(frozen=True)
class Use:
    """One use of a predicate in a program statement: the statement defines it (a
    head, a choice, #external), shows it (#show) or reads it (a body, a condition)."""

    signature: tuple[str, int]
    role: str


def _head_uses(head) -> tuple[list, list]:
    """(defined atoms' signatures, nodes read) of a rule head."""
    kind = head.ast_type
    if kind == ast.ASTType.Literal:
        if head.atom.ast_type == ast.ASTType.SymbolicAtom:
            return _term_signatures(head.atom.symbol), []
        return [], [head]
    if kind == ast.ASTType.Disjunction:
        defined, read = [], []
        for element in head.elements:
            defined += _atom_signatures(element.literal)
            read += list(element.condition)
        return defined, read
    if kind == ast.ASTType.Aggregate:
        defined, read = [], []
        for element in head.elements:
            defined += _atom_signatures(element.literal)
            read += list(element.condition)
        return defined, read
    if kind == ast.ASTType.HeadAggregate:
        defined, read = [], []
        for element in head.elements:
            defined += _atom_signatures(element.condition.literal)
            read += list(element.condition.condition)
        return defined, read
    return [], [head]


class Refused(Exception):
    """A statement kind that models may not contain (with the reason)."""


_REFUSED = {
    ast.ASTType.Minimize: "an optimisation statement (#minimize, #maximize or a weak "
    "constraint), which would change the optimisations of the encodings",
    ast.ASTType.Heuristic: "a #heuristic statement, which would change the searches of the "
    "encodings",
    ast.ASTType.ProjectAtom: "a #project statement, which would change the enumerations of the "
    "encodings",
    ast.ASTType.ProjectSignature: "a #project statement, which would change the enumerations "
    "of the encodings",
    ast.ASTType.Edge: "an #edge statement, which would add acyclicity constraints to the encodings",
    ast.ASTType.TheoryDefinition: "a #theory definition (theory atoms are not part of models)",
}


def statement_uses(statement) -> list[Use]:
    """The predicates a statement defines and reads (Refused for statements models
    may not contain)."""
    kind = statement.ast_type
    defined: list[tuple[str, int]] = []
    shown: list[tuple[str, int]] = []
    read_nodes: list = []
    if kind in _REFUSED:
        raise Refused(_REFUSED[kind])
    if kind == ast.ASTType.Program:
        if statement.name != "base" or len(statement.parameters) > 0:
            raise Refused(
                f"a program part #program {statement.name} (models belong to the "
                "base program; the other parts are the encodings')"
            )
    elif kind == ast.ASTType.Rule:
        if _has_theory_atom(statement):
            raise Refused("a theory atom (theory atoms are not part of models)")
        defined, read_nodes = _head_uses(statement.head)
        read_nodes = read_nodes + list(statement.body)
    elif kind == ast.ASTType.External:
        defined = _term_signatures(statement.atom.symbol)
        read_nodes = list(statement.body)
    elif kind == ast.ASTType.ShowTerm:
        term = statement.term
        signatures = _term_signatures(term)
        if not signatures and not (
            term.ast_type == ast.ASTType.SymbolicTerm
            and term.symbol.type.name in ("Number", "String")
        ):
            raise Refused(
                f"a #show term {term} that is not a function term of the model's "
                "own (it could show any atom)"
            )
        shown = signatures
        read_nodes = list(statement.body)
    elif kind == ast.ASTType.ShowSignature:
        shown = [(statement.name, statement.arity)]
    uses = [Use(s, DEFINES) for s in defined] + [Use(s, SHOWS) for s in shown]
    for node in read_nodes:
        uses += [Use(s, READS) for s in _atom_signatures(node)]
    return uses


def _has_theory_atom(rule) -> bool:
    """Does a rule have a theory atom (they stand in its head or as body literals)?"""
    if rule.head.ast_type == ast.ASTType.TheoryAtom:
        return True
    return any(
        literal.ast_type == ast.ASTType.Literal and literal.atom.ast_type == ast.ASTType.TheoryAtom
        for literal in rule.body
    )


# -- the encodings' predicates --------------------------------------------------------


@dataclass(frozen=True)
class Owner:
    """Where an encoding mentions a predicate first: its file (relative to the
    encodings folder) and whether it defines it there or only reads it."""

    encoding: str
    defines: bool

    def describe(self) -> str:
        path = f"encodings/{self.encoding}"
        return f"defined by {path}" if self.defines else f"an input of {path}"


def _encoding_files() -> list[Path]:
    """The encodings, those of planning/ first: a predicate that another
    encoding also defines (holds/2 of cam/questions.lp, a choice's world as a
    plan's state) is named after the planning encoding that defines it."""
    return sorted(ENCODINGS.rglob("*.lp"), key=lambda path: (path.parent.name != "planning", path))


@cache
def encoding_predicates() -> dict[str, dict[tuple[str, int], bool]]:
    """For each encoding (path relative to the encodings folder), the predicates it
    mentions, each with True if it defines it (head, choice, #external) and False if
    it only reads, shows or declares it."""
    root = ENCODINGS.resolve()
    result: dict[str, dict[tuple[str, int], bool]] = {
        path.resolve().relative_to(root).as_posix(): {} for path in _encoding_files()
    }

    files: dict[str, str | None] = {}

    def visit(statement):
        # Statements of included files count for the file that holds them.
        filename = statement.location.begin.filename
        if filename not in files:
            try:
                files[filename] = Path(filename).resolve().relative_to(root).as_posix()
            except ValueError:
                files[filename] = None
        mentions = result.get(files[filename])
        if mentions is None:
            return
        kind = statement.ast_type
        if kind == ast.ASTType.Defined:
            mentions.setdefault((statement.name, statement.arity), False)
            return
        if kind in _REFUSED:  # the encodings' own optimisations and heuristics
            for signature in _atom_signatures(statement):
                mentions.setdefault(signature, False)
            if kind == ast.ASTType.ProjectSignature:
                mentions.setdefault((statement.name, statement.arity), False)
            return
        for use in statement_uses(statement):
            if use.role == DEFINES:
                mentions[use.signature] = True
            else:
                mentions.setdefault(use.signature, False)

    for path in _encoding_files():
        ast.parse_files([str(path)], visit, logger=lambda code, message: None)
    return result


def _ground_alone(name: str) -> frozenset[tuple[str, int]]:
    """The predicates in clingo's symbol table after grounding an encoding alone."""
    ctl = clingo.Control(["--warn=none"], logger=lambda code, message: None)
    ctl.load(str(ENCODINGS / name))
    ctl.ground([("base", [])])
    return frozenset((name_, arity) for name_, arity, _ in ctl.symbolic_atoms.signatures)


def _cache_folder() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "ethasp"


@cache
def _all_mentioned() -> dict[str, frozenset[tuple[str, int]]]:
    """:func:`mentioned` of every encoding, computed once per content of the
    encodings: kept in the user's cache folder under a digest of every
    encoding's name and text, so that a changed or new encoding is covered at
    once, and an unchanged set costs no grounding at start-up.  (Without a
    writable cache folder they are computed at every start.)"""
    root = ENCODINGS.resolve()
    names = sorted(path.resolve().relative_to(root).as_posix() for path in _encoding_files())
    digest = hashlib.sha256()
    for name in names:
        digest.update(name.encode() + b"\0" + (ENCODINGS / name).read_bytes() + b"\0")
    digest.update(clingo.__version__.encode())
    cache = _cache_folder() / f"namespace-{digest.hexdigest()[:32]}.json"
    try:
        stored = json.loads(cache.read_text())
        return {name: frozenset((p, a) for p, a in stored[name]) for name in names}
    except (OSError, ValueError, KeyError, TypeError):
        pass
    result = {name: _ground_alone(name) for name in names}
    try:
        cache.parent.mkdir(parents=True, exist_ok=True)
        temporary = cache.with_suffix(f".{os.getpid()}.tmp")
        temporary.write_text(json.dumps({name: sorted(result[name]) for name in names}))
        temporary.replace(cache)
    except OSError:
        pass
    return result


def mentioned(name: str) -> frozenset[tuple[str, int]]:
    """The predicates an encoding's program mentions (in any statement but #show),
    from clingo's symbol table after grounding the encoding alone."""
    known = _all_mentioned()
    return known[name] if name in known else _ground_alone(name)


def _encoding_names(pddl: bool) -> list[str]:
    root = ENCODINGS.resolve()
    names = [path.resolve().relative_to(root).as_posix() for path in _encoding_files()]
    return [name for name in names if pddl or name not in PDDL_LAYER]


@cache
def reserved(pddl: bool = False) -> frozenset[tuple[str, int]]:
    """The predicates a model may not define: every predicate an encoding mentions,
    except the vocabulary.  ``planning/pddl.lp`` counts only for PDDL tasks,
    and so does :data:`TRANSLATION_ONLY` (reserved there)."""
    found: set[tuple[str, int]] = set()
    for name in _encoding_names(pddl):
        found |= mentioned(name)
    allowed = set(VOCABULARY) - (set(TRANSLATION_ONLY) if pddl else set())
    return frozenset(found - allowed)


def owner(signature: tuple[str, int], pddl: bool = True) -> Owner | None:
    """The encoding that defines a predicate (else the first that reads it)."""
    result = None
    for name, mentions in encoding_predicates().items():
        if (name in PDDL_LAYER and not pddl) or signature not in mentions:
            continue
        if mentions[signature]:
            return Owner(name, True)
        result = result or Owner(name, False)
    return result


_COMMENTS = re.compile(r"%\*.*?\*%|%[^\n]*|\"(?:\\.|[^\"\\])*\"", re.S)


@cache
def encoding_names() -> frozenset[str]:
    """Every lower-case name (predicate or constant) written in an encoding."""
    names: set[str] = set()
    for path in _encoding_files():
        names |= set(_NAME.findall(_COMMENTS.sub(" ", path.read_text())))
    return frozenset(names)


@cache
def readable(pddl: bool = False) -> frozenset[tuple[str, int]]:
    """The encodings' predicates a model may read: those of the model layer."""
    layers = MODEL_LAYER + (PDDL_LAYER if pddl else ())
    return frozenset(signature for name in layers for signature in mentioned(name))


# -- the check ----------------------------------------------------------------------------

_NAME = re.compile(r"[a-z_'][A-Za-z0-9_']*")


class NamespaceCheck:
    """Checks the statements of a model's files (a visitor for clingo's parser).

    A rule in whose text no name of a reserved predicate occurs needs no
    closer look (the fast path for the facts of large models).
    """

    def __init__(self, pddl: bool = False):
        self.pddl = pddl
        self.reserved = reserved(pddl)
        self.readable = readable(pddl)
        self.names = frozenset(name for name, _ in self.reserved)

    def __call__(self, statement) -> None:
        if statement.ast_type == ast.ASTType.Definition and statement.name in encoding_names():
            begin = statement.location.begin
            raise InputError(
                f"{begin.filename}:{begin.line}: the model defines the constant "
                f"{statement.name} (#const), a name the encodings use: it would change them; "
                "rename it"
            )
        if statement.ast_type == ast.ASTType.Rule:
            text = str(statement)
            if "&" not in text and self.names.isdisjoint(_NAME.findall(text)):
                return
        begin = statement.location.begin
        where = f"{begin.filename}:{begin.line}"
        try:
            uses = statement_uses(statement)
        except Refused as refusal:
            raise InputError(f"{where}: the model contains {refusal}; it is refused") from None
        for use in uses:
            if use.signature not in self.reserved:
                continue
            if use.role == READS and use.signature in self.readable:
                continue
            predicate = signature_text(use.signature)
            found = owner(use.signature, self.pddl)
            whose = found.describe() if found else "a predicate of the encodings"
            if use.role != READS:
                raise InputError(
                    f"{where}: the model {use.role} {predicate}, {whose}; a model may define "
                    f"and show only the model vocabulary ({vocabulary_text()}) and predicates "
                    "of its own: rename it"
                )
            raise InputError(
                f"{where}: the model reads {predicate}, {whose}; a model may read only its "
                "vocabulary, its own predicates and what encodings/planning/model.lp derives "
                "from it"
            )
