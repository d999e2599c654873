"""PDDL input: a domain and problem as lifted ASP rules that clingo grounds.

The files are read by :mod:`ethasp.planning.readers.pddl_syntax`; this module writes
rules over the model vocabulary of ``encodings/planning/model.lp`` and the
typing vocabulary of ``encodings/planning/pddl.lp``.  Nothing is grounded in
Python.  For a domain with ``(:types room robot)`` and

    (:action move :parameters (?r - robot ?from ?to - room)
      :precondition (and (at ?r ?from) (not (= ?from ?to)))
      :effect (and (not (at ?r ?from)) (at ?r ?to)))

it writes

    pddl_action(move(R,From,To)) :- has_type(R,robot), has_type(From,room),
                                    has_type(To,room), From != To.
    pre(move(R,From,To),at(R,From),true) :- pddl_action(move(R,From,To)).
    pddl_del(move(R,From,To),at(R,From)) :- pddl_action(move(R,From,To)).
    pddl_add(move(R,From,To),at(R,To)) :- pddl_action(move(R,From,To)).

(``encodings/planning/pddl.lp`` makes each instance an action, unless an
annotation file declares it a creative alternative, which a repair adds.)
A precondition on a static predicate (one that no effect changes) that is a
plain conjunct also goes into the body of the ``pddl_action/1`` rule, as
``init(p)`` or ``not init(p)``: an instance whose static precondition fails
does not exist.  Per action schema, ``pddl_schema_instance/1`` and
``pddl_static_failure/3`` rules over ``pddl_candidate/1`` tell a validation
why a term is no action (``encodings/planning/static.lp``); in the model they
derive nothing.  The same goes for axioms (of derived predicates, and of
the auxiliary derived variables below): an axiom instance whose static
literal fails is not written.  ``pddl_static/1`` names the atoms of static
predicates:
an annotation file that gives an effect on one is refused
(``encodings/planning/check.lp``), as the pruning would be wrong for it.

The translation also writes ``variable/1`` (``derived/1`` for derived
predicates) rules for every predicate that some effect changes (the atoms
of a static predicate are variables where the task uses them, by
``encodings/planning/pddl.lp``: in the initial state, a precondition, a
condition or the goal; and where an annotation file values or changes
them), ``pddl_object/2`` and
``pddl_subtype/2`` facts for objects and types, and ``init/1`` and
``goal/2`` facts.  Names follow the rule of
:mod:`ethasp.planning.naming` (``five-will-die`` is ``five_will_die``).

The ADL fragment
----------------
Formulas (preconditions, goals, conditions of effects, bodies of derived
predicates) are first put in negation normal form (``imply`` and ``not``
pushed down to atoms, ``forall`` and ``exists`` swapped under ``not``).

* A conjunction of literals becomes ``pre/3`` (``goal/2``, ``cpre/4``,
  ``axiom_pre/4``) literals; ``=`` and ``not =`` become comparisons in the
  rule body (in a precondition, they decide which actions exist).
* Any other subformula (``or``, ``exists``, ``forall``) becomes an auxiliary
  derived variable ``formula_N(X,...)`` over its free variables, defined by
  axioms (``derived/1``, ``axiom/2``, ``axiom_pre/4``), as Fast Downward's
  translator does with axioms: a disjunction has one axiom per disjunct, an
  existential's variables become part of the axiom's name, and ``forall x
  F`` is the negation of ``exists x (not F)``.  The model then only needs
  conjunctions of literals over state variables and derived variables.
* Where a disjunction or an existential makes up a whole axiom body or a
  whole effect condition, it is split into several axioms (effects) instead.
* ``(when C E)`` and ``(forall (?x) E)`` effects become conditional effects
  ``ceff(A,K,V,B)`` with conditions ``cpre(A,K,W,C)``, where ``K`` is
  ``N`` or ``(N,X,...)``: the effect's number within the action and the
  values of the variables it is quantified over.  An effect without a
  condition is an unconditional one (``pddl_add/2``, ``pddl_del/2``).
* ``(:derived (p ?x) F)`` gives ``axiom(p(X),K)`` with ``K = (J,I,...)``:
  the definition's number, the disjunct's number and its existential
  variables.

Leniency, as planners have it: requirements used but not declared are
accepted with one warning line per file on standard error; domain constants
that only the problem declares (as objects) are accepted; names that the
domain uses as constants and that nobody declares are objects (with a
warning); a domain without ``:predicates`` has the predicates it and the
problem use, with the arity of their first use and arguments of any type
(with a warning; a predicate used with two arities is an error at the
second use), its atoms the ones the task uses; an atom that the domain or
problem uses is a state variable even if its arguments do not match the
predicate's declared types; a type that the domain uses but that is
declared nowhere and that no object has has no objects (with a warning).
Action costs (``:action-costs``): with ``(:metric minimize (total-cost))``
in the problem, each action instance's ``increase`` of ``total-cost`` (a
number, or a function whose value the initial state gives, such as
``(road-length ?from ?to)``) becomes its ``cost/2``, an action without one
costing 0, and plans are cheapest ones; without that metric, action costs
and another metric are ignored with a warning (plans are shortest in number
of actions); numeric facts of undeclared functions are ignored with a
warning.  Other numeric features, durative actions, processes and events
are refused with one line naming them.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ethasp.errors import InputError
from ethasp.planning.naming import pddl_name_to_asp
from ethasp.planning.readers.pddl_syntax import (
    FRAGMENT,
    IMPLIED,
    Action,
    AllEffects,
    And,
    Atom,
    CostEffect,
    Domain,
    Effect,
    Equal,
    Exists,
    Forall,
    ForallEffect,
    Formula,
    Imply,
    Literal,
    Not,
    Or,
    Param,
    PddlFile,
    Problem,
    When,
    read_domain,
    read_problem,
)

__all__ = ["FRAGMENT", "PddlFile", "is_pddl", "split_paths", "translate", "translate_files"]

AUXILIARY = "formula"


# -- negation normal form ---------------------------------------------------------


@dataclass(frozen=True)
class Lit:
    """A literal of a formula in negation normal form: an atom or an equality."""

    atom: Atom | Equal
    positive: bool


TRUE, FALSE = And(()), Or(())


def nnf(formula: Formula, positive: bool = True):
    """The negation normal form of a formula (or of its negation)."""
    if isinstance(formula, (Atom, Equal)):
        return Lit(formula, positive)
    if isinstance(formula, Not):
        return nnf(formula.argument, not positive)
    if isinstance(formula, And):
        parts = tuple(nnf(part, positive) for part in formula.parts)
        return And(parts) if positive else Or(parts)
    if isinstance(formula, Or):
        parts = tuple(nnf(part, positive) for part in formula.parts)
        return Or(parts) if positive else And(parts)
    if isinstance(formula, Imply):
        return nnf(Or((Not(formula.left), formula.right)), positive)
    if isinstance(formula, Exists):
        body = nnf(formula.body, positive)
        return Exists(formula.params, body) if positive else Forall(formula.params, body)
    if isinstance(formula, Forall):
        body = nnf(formula.body, positive)
        return Forall(formula.params, body) if positive else Exists(formula.params, body)
    raise TypeError(formula)


def free_variables(formula) -> set[str]:
    """The free variables (names without '?') of a formula in negation normal form."""
    if isinstance(formula, Lit):
        atom = formula.atom
        terms = atom.terms if isinstance(atom, Atom) else (atom.left, atom.right)
        return {term[1:] for term in terms if term.startswith("?")}
    if isinstance(formula, (And, Or)):
        return set().union(*(free_variables(part) for part in formula.parts))
    if isinstance(formula, (Exists, Forall)):
        return free_variables(formula.body) - {param.name for param in formula.params}
    raise TypeError(formula)


# -- rules --------------------------------------------------------------------------


@dataclass(frozen=True)
class Scope:
    """Variables in scope (PDDL name -> ASP variable) and body atoms that bind them."""

    variables: tuple[tuple[str, str], ...] = ()
    body: tuple[str, ...] = ()

    def asp(self, name: str) -> str | None:
        for pddl, asp in reversed(self.variables):
            if pddl == name:
                return asp
        return None


@dataclass
class Conjunction:
    """A conjunction of literals: ``(atom, value)`` pairs, comparisons, and the
    typing atoms and variables of existentials lifted into it."""

    literals: list[tuple[str, str]] = field(default_factory=list)
    comparisons: list[str] = field(default_factory=list)
    body: list[str] = field(default_factory=list)
    variables: list[str] = field(default_factory=list)

    def extend(self, other: Conjunction) -> None:
        self.literals += other.literals
        self.comparisons += other.comparisons
        self.body += other.body
        self.variables += other.variables


def rule(head: str, body: Iterable[str]) -> str:
    body = list(dict.fromkeys(body))
    return f"{head} :- {', '.join(body)}." if body else f"{head}."


def term_of(head: str, arguments: Sequence[str]) -> str:
    return f"{head}({','.join(arguments)})" if arguments else head


def name_term(number: int, variables: Sequence[str]) -> str:
    """The name of an effect or axiom: ``N`` or ``(N,X,...)``."""
    return f"({','.join([str(number), *variables])})" if variables else str(number)


class _Translator:
    """Writes the rules of one domain and problem (see the module docstring)."""

    def __init__(self, domain: Domain, problem: Problem):
        self.domain = domain
        self.problem = problem
        self.lines: list[str] = []
        self.auxiliaries = 0
        self.fresh = 0
        self.eithers: set[tuple[str, ...]] = set()
        self.costs: int | None = None  # offset of the first action cost
        self.cost_functions: set[str] = set()  # functions that action costs read
        self.action_scope: tuple = ()  # the parameters of the action translated
        self.undeclared_types: dict[str, None] = {}  # used, declared nowhere, no objects
        self.undeclared_functions: dict[str, None] = {}  # in numeric facts, not declared
        self.derived = {d.predicate for d in domain.derived}
        self.objects = {pddl_name_to_asp(p.name) for p in domain.constants + problem.objects}
        # Predicates read from their uses (a domain without :predicates), and
        # names the domain uses as constants that nobody declares: objects.
        self.inferred = {} if domain.declares_predicates else self.infer_predicates()
        self.implicit = self.implicit_constants()
        self.objects |= set(self.implicit)
        self.names = {*domain.predicates, *self.derived}
        # Static predicates: base predicates that no effect (conditional or
        # not) adds or deletes.  Their atoms hold in every state exactly when
        # they hold initially, so a precondition on one decides which actions
        # exist, as a type does (untyped domains write types so: (ball ?b)).
        changed = {
            predicate for action in domain.actions for predicate in effect_predicates(action.effect)
        }
        self.static = {
            pddl_name_to_asp(predicate)
            for predicate in domain.predicates
            if predicate not in changed and predicate not in self.derived
        }

    def emit(self, line: str) -> None:
        self.lines.append(line)

    def uses(self):
        """Every atom of the domain's actions and derived predicates and of the
        problem's initial state and goal, with its file, in the order written."""
        for action in self.domain.actions:
            for atom in formula_atoms(action.precondition):
                yield self.domain.file, atom
            for atom in effect_atoms(action.effect):
                yield self.domain.file, atom
        for definition in self.domain.derived:
            for atom in formula_atoms(definition.body):
                yield self.domain.file, atom
        for atom in self.problem.init:
            yield self.problem.file, atom
        for atom in formula_atoms(self.problem.goal):
            yield self.problem.file, atom

    def infer_predicates(self) -> dict[str, None]:
        """The predicates of a domain without ``:predicates``: those its uses
        name (derived ones aside), with the arity of the first use and
        arguments of any type; a use with another arity is an error."""
        inferred: dict[str, tuple[PddlFile, int]] = {}
        for file, atom in self.uses():
            if not isinstance(atom, Atom) or atom.predicate in self.derived:
                continue
            first = inferred.get(atom.predicate)
            if first is None:
                inferred[atom.predicate] = (file, atom.pos)
                self.domain.predicates[atom.predicate] = tuple(
                    Param(f"x{index}", ()) for index in range(len(atom.terms))
                )
                self.domain.predicate_pos[atom.predicate] = atom.pos
                continue
            arity = len(self.domain.predicates[atom.predicate])
            if arity != len(atom.terms):
                raise file.error(
                    atom.pos,
                    f"predicate {atom.predicate} is used with {len(atom.terms)} "
                    f"argument{'s' if len(atom.terms) != 1 else ''} here and with {arity} at "
                    f"{first[0].at(first[1])} (the domain has no :predicates)",
                )
        return dict.fromkeys(inferred)

    def implicit_constants(self) -> dict[str, None]:
        """Names the domain's actions and derived predicates use as constants
        that neither the domain nor the problem declares (objects, as
        plan-explainer's reader has them)."""
        found: dict[str, None] = {}
        for file, atom in self.uses():
            if file is not self.domain.file:
                continue
            terms = atom.terms if isinstance(atom, Atom) else (atom.left, atom.right)
            for term in terms:
                if not term.startswith("?") and pddl_name_to_asp(term) not in self.objects:
                    found.setdefault(pddl_name_to_asp(term))
        return found

    # -- names and types --------------------------------------------------------

    def type_term(self, types: tuple[str, ...]) -> str:
        if not types:
            return "object"
        names = tuple(sorted({pddl_name_to_asp(name) for name in types}))
        if len(names) == 1:
            return names[0]
        self.eithers.add(names)
        return f"either({','.join(names)})"

    def bind(self, scope: Scope, params: Sequence[Param]) -> tuple[Scope, list[str], list[str]]:
        """A scope extended by typed parameters; their ASP variables and typing atoms."""
        variables, typing, names = list(scope.variables), [], []
        taken = {asp for _, asp in scope.variables}
        for param in params:
            asp = pddl_name_to_asp(param.name)
            asp = asp[0].upper() + asp[1:]
            while asp in taken:
                self.fresh += 1
                asp = f"{asp}'{self.fresh}"
            taken.add(asp)
            variables.append((param.name, asp))
            names.append(asp)
            typing.append(f"has_type({asp},{self.type_term(param.types)})")
        return Scope(tuple(variables), scope.body + tuple(typing)), names, typing

    def term(self, term: str, scope: Scope, file: PddlFile, pos: int) -> str:
        if term.startswith("?"):
            asp = scope.asp(term[1:])
            if asp is None:
                raise file.error(pos, f"unknown variable {term}")
            return asp
        asp = pddl_name_to_asp(term)
        if asp not in self.objects:
            raise file.error(
                pos,
                f"unknown constant {term} (declare it in :constants "
                "of the domain or :objects of the problem)",
            )
        return asp

    def atom(self, atom: Atom, scope: Scope, file: PddlFile) -> str:
        if atom.predicate not in self.names:
            raise file.error(
                atom.pos, f"unknown predicate {atom.predicate} (declare it in :predicates)"
            )
        declared = self.domain.predicates.get(atom.predicate)
        if declared is not None and len(declared) != len(atom.terms):
            raise file.error(
                atom.pos,
                f"predicate {atom.predicate} takes {len(declared)} "
                f"argument{'s' if len(declared) != 1 else ''}, "
                f"found {len(atom.terms)}",
            )
        arguments = [self.term(term, scope, file, atom.pos) for term in atom.terms]
        return term_of(pddl_name_to_asp(atom.predicate), arguments)

    # -- formulas ---------------------------------------------------------------

    def literal(self, lit: Lit, scope: Scope, file: PddlFile, into: Conjunction) -> None:
        atom = lit.atom
        if isinstance(atom, Equal):
            left = self.term(atom.left, scope, file, atom.pos)
            right = self.term(atom.right, scope, file, atom.pos)
            into.comparisons.append(f"{left} {'=' if lit.positive else '!='} {right}")
        else:
            into.literals.append(
                (self.atom(atom, scope, file), "true" if lit.positive else "false")
            )

    def conjunction(self, formula, scope: Scope, file: PddlFile, lift: bool) -> Conjunction:
        """A formula in negation normal form as one conjunction of literals.

        Subformulas that are not literals become auxiliary derived variables,
        except that with ``lift`` an existential's variables join the
        conjunction (its axiom or effect takes one instance per value).
        """
        result = Conjunction()
        parts = formula.parts if isinstance(formula, And) else (formula,)
        for part in parts:
            if isinstance(part, Lit):
                self.literal(part, scope, file, result)
            elif isinstance(part, And):
                result.extend(self.conjunction(part, scope, file, lift))
            elif lift and isinstance(part, Exists):
                inner, names, typing = self.bind(scope, part.params)
                result.body += typing
                result.variables += names
                result.extend(self.conjunction(part.body, inner, file, lift))
            elif isinstance(part, Forall):
                counterexample = Exists(part.params, nnf_negate(part.body))
                result.literals.append((self.auxiliary(counterexample, scope, file), "false"))
            else:
                result.literals.append((self.auxiliary(part, scope, file), "true"))
        return result

    def alternatives(self, formula, scope: Scope, file: PddlFile) -> list[Conjunction]:
        """A formula in negation normal form as a disjunction of conjunctions.

        Only a disjunction or an existential at the top is split (an
        existential's variables join each conjunction); deeper ones become
        auxiliary derived variables.
        """
        if isinstance(formula, Or):
            return [alt for part in formula.parts for alt in self.alternatives(part, scope, file)]
        if isinstance(formula, Exists):
            inner, names, typing = self.bind(scope, formula.params)
            result = []
            for alt in self.alternatives(formula.body, inner, file):
                alt.body[:0] = typing
                alt.variables[:0] = names
                result.append(alt)
            return result
        return [self.conjunction(formula, scope, file, lift=True)]

    def auxiliary(self, formula, scope: Scope, file: PddlFile) -> str:
        """An auxiliary derived variable that holds exactly where the formula holds."""
        self.auxiliaries += 1
        name = f"{AUXILIARY}_{self.auxiliaries}"
        while name.replace("_", "-") in self.names:
            self.auxiliaries += 1
            name = f"{AUXILIARY}_{self.auxiliaries}"
        free = free_variables(formula)
        arguments = [asp for pddl, asp in dict(scope.variables).items() if pddl in free]
        head = term_of(name, arguments)
        self.emit(rule(f"derived({head})", scope.body))
        for number, alt in enumerate(self.alternatives(formula, scope, file), start=1):
            self.axiom(head, name_term(number, alt.variables), alt, scope.body)
        return head

    def axiom(self, head: str, name: str, alt: Conjunction, body: Iterable[str]) -> None:
        # A literal on a static predicate holds in every state exactly when it
        # holds initially: an instance of the axiom whose static literal fails
        # never holds, so it is not written (as for actions); axiom_pre/4 keeps
        # the literal.
        static = [
            f"init({atom})" if value == "true" else f"not init({atom})"
            for atom, value in alt.literals
            if atom.split("(")[0] in self.static
        ]
        body = [*body, *alt.body, *alt.comparisons, *static]
        self.emit(rule(f"axiom({head},{name})", body))
        for atom, value in alt.literals:
            self.emit(rule(f"axiom_pre({head},{name},{atom},{value})", body))

    # -- the domain -------------------------------------------------------------

    def declarations(self) -> None:
        for param in self.domain.types:
            name = pddl_name_to_asp(param.name)
            if name == "object":
                continue
            for parent in param.types or ("object",):
                self.emit(f"pddl_subtype({name},{pddl_name_to_asp(parent)}).")
        for param in sorted(self.domain.constants + self.problem.objects, key=lambda p: p.name):
            for type_name in param.types or ("object",):
                self.emit(
                    f"pddl_object({pddl_name_to_asp(param.name)},{pddl_name_to_asp(type_name)})."
                )
        for name in sorted(self.implicit):
            self.emit(f"pddl_object({name},object).")

    def predicates(self) -> None:
        for predicate, params in sorted(self.domain.predicates.items()):
            _, names, typing = self.bind(Scope(), params)
            kind = "derived" if predicate in self.derived else "variable"
            atom = term_of(pddl_name_to_asp(predicate), names)
            if pddl_name_to_asp(predicate) not in self.static:
                # (A predicate read from its uses has the atoms the task uses:
                # planning/pddl.lp makes them variables.)
                if predicate not in self.inferred:
                    self.emit(rule(f"{kind}({atom})", typing))
            else:
                # A static atom is a variable where the task uses it (pddl.lp):
                # in the initial state, a precondition, a condition or the
                # goal.  The others are false in every state, and declaring
                # every typed combination (IPC nomystery's sum/3: 50,653, of
                # which 703 hold) cost every engine time and memory.  An atom
                # that an annotation file values or changes stays a variable.
                for use in (f"utility({atom},_,_)", f"eff(_,{atom},_)"):
                    self.emit(rule(f"{kind}({atom})", [*typing, use]))
                # Pruning trusts that nothing changes it: check.lp refuses an
                # annotation file's effect on it.
                self.emit(rule(f"pddl_static({atom})", [f"variable({atom})"]))
        for definition in self.domain.derived:
            if definition.predicate not in self.domain.predicates:
                _scope, names, typing = self.bind(Scope(), definition.params)
                self.emit(
                    rule(
                        f"derived({term_of(pddl_name_to_asp(definition.predicate), names)})", typing
                    )
                )

    def derived_predicates(self) -> None:
        file = self.domain.file
        for number, definition in enumerate(self.domain.derived, start=1):
            declared = self.domain.predicates.get(definition.predicate)
            if declared is not None and len(declared) != len(definition.params):
                raise file.error(
                    definition.pos,
                    f"derived predicate {definition.predicate} "
                    f"takes {len(declared)} arguments, "
                    f"found {len(definition.params)}",
                )
            scope, names, typing = self.bind(Scope(), definition.params)
            head = term_of(pddl_name_to_asp(definition.predicate), names)
            alternatives = self.alternatives(nnf(definition.body), scope, file)
            for index, alt in enumerate(alternatives, start=1):
                self.axiom(
                    head, f"({','.join([str(number), str(index), *alt.variables])})", alt, typing
                )

    def action(self, action: Action) -> None:
        file = self.domain.file
        scope, names, typing = self.bind(Scope(), action.params)
        head = term_of(pddl_name_to_asp(action.name), names)
        anchor = f"pddl_action({head})"
        scope = Scope(scope.variables, (anchor,))
        precondition = self.conjunction(nnf(action.precondition), scope, file, lift=False)
        # An action whose static precondition fails initially never occurs,
        # so it does not exist (as an action of a wrong type); pre/3 keeps the
        # precondition, for reasons and words.
        static = [
            (atom, value)
            for atom, value in precondition.literals
            if atom.split("(")[0] in self.static
        ]
        pruning = [
            f"init({atom})" if value == "true" else f"not init({atom})" for atom, value in static
        ]
        valued = self.action_cost(action, head, Scope(scope.variables, tuple(typing)))
        self.emit(rule(anchor, typing + precondition.comparisons + pruning + valued))
        for atom, value in precondition.literals:
            self.emit(rule(f"pre({head},{atom},{value})", [anchor]))
        self.schema(head, typing + precondition.comparisons, static)
        number = 0
        for effect_scope, conditions, literals in self.effect_groups(action.effect, scope):
            atoms = []
            for literal in literals:
                if literal.atom.predicate in self.derived:
                    raise file.error(
                        literal.atom.pos,
                        f"an effect on the derived predicate {literal.atom.predicate}",
                    )
                atoms.append((self.atom(literal.atom, effect_scope, file), literal.positive))
            alternatives = (
                [Conjunction()]
                if not conditions
                else self.alternatives(nnf(And(conditions)), effect_scope, file)
            )
            quantified = [asp for _, asp in effect_scope.variables[len(names) :]]
            for alt in alternatives:
                body = [*effect_scope.body, *alt.body, *alt.comparisons]
                if not alt.literals:
                    for atom, positive in atoms:
                        kind = "pddl_add" if positive else "pddl_del"
                        self.emit(rule(f"{kind}({head},{atom})", body))
                    continue
                number += 1
                name = name_term(number, quantified + alt.variables)
                for atom, positive in atoms:
                    value = "true" if positive else "false"
                    self.emit(rule(f"ceff({head},{name},{atom},{value})", body))
                for condition_atom, condition_value in alt.literals:
                    self.emit(rule(f"cpre({head},{name},{condition_atom},{condition_value})", body))

    def schema(self, head: str, body: list[str], static: list[tuple[str, str]]) -> None:
        """Rules telling why a term of a plan is no action (for validation):
        whether a ``pddl_candidate/1`` is a well-typed instance of the action
        schema (its equalities hold), and which static preconditions fail.
        Without candidates (in every program but validation's) they derive
        nothing."""
        instance = f"pddl_schema_instance({head})"
        self.emit(rule(instance, [f"pddl_candidate({head})", *body]))
        for atom, value in static:
            holds = f"init({atom})" if value == "false" else f"not init({atom})"
            self.emit(rule(f"pddl_static_failure({head},{atom},{value})", [instance, holds]))

    def effect_groups(self, effect: Effect, scope: Scope):
        """The literal effects, grouped by scope and conditions (one group per
        ``when`` and ``forall``, in the order written)."""
        groups: list[tuple[Scope, tuple, list[Literal]]] = []
        for effect_scope, conditions, literal in self.effects(effect, scope, ()):
            if groups and groups[-1][0] is effect_scope and groups[-1][1] is conditions:
                groups[-1][2].append(literal)
            else:
                groups.append((effect_scope, conditions, [literal]))
        return groups

    def effects(self, effect: Effect, scope: Scope, conditions: tuple):
        """The literal effects under their scope and conditions."""
        if isinstance(effect, Literal):
            yield scope, conditions, effect
        elif isinstance(effect, AllEffects):
            for part in effect.parts:
                yield from self.effects(part, scope, conditions)
        elif isinstance(effect, ForallEffect):
            inner, _, _ = self.bind(scope, effect.params)
            yield from self.effects(effect.effect, inner, conditions)
        elif isinstance(effect, When):
            yield from self.effects(effect.effect, scope, (*conditions, effect.condition))
        elif isinstance(effect, CostEffect):
            if self.costs is None:
                self.costs = effect.pos
            if conditions or scope.variables != self.action_scope:
                raise self.domain.file.unsupported(
                    effect.pos,
                    "conditional action costs (an increase of total-cost in when or forall)",
                )
        else:
            raise TypeError(effect)

    def action_cost(self, action: Action, head: str, scope: Scope) -> list[str]:
        """The cost of an action (with ``(:metric minimize (total-cost))``): the
        sum of its increases of ``total-cost``, numbers or values of functions
        in the initial state (``pddl_value/2``); 0 without any.  Returns the
        conditions under which the action exists: an instance whose cost
        reads a function without a value has no cost, and cannot be applied
        (as in PDDL 2.1, where an effect on an undefined value makes an
        action inapplicable; Fast Downward's translator asserts that no
        reachable action has one)."""
        self.action_scope = scope.variables
        if not self.problem.minimizes_cost:
            return []
        file = self.domain.file
        parts, body, exists = [], [f"action({head})"], []
        for number, effect in enumerate(cost_effects(action.effect)):
            if effect.function is None:
                parts.append(str(self.integer(file, effect.pos, effect.amount or "")))
                continue
            arguments = [self.term(t, scope, file, effect.pos) for t in effect.function.terms]
            term = term_of(pddl_name_to_asp(effect.function.predicate), arguments)
            self.cost_functions.add(effect.function.predicate)
            body.append(f"pddl_value({term},Cost{number})")
            exists.append(f"pddl_value({term},_)")
            parts.append(f"Cost{number}")
        self.emit(rule(f"cost({head},{'+'.join(parts) or '0'})", body))
        return exists

    @staticmethod
    def integer(file: PddlFile, pos: int, text: str) -> int:
        """A cost or a function's value, which must be an integer (1.0 is 1)."""
        try:
            value = float(text)
        except ValueError:
            raise file.error(pos, f"an action cost must be a number, found {text}") from None
        if value != int(value):
            raise file.error(pos, f"action costs must be integers, found {text}")
        return int(value)

    def numeric_values(self) -> None:
        """The values of the functions that action costs read (``pddl_value/2``)."""
        if not self.problem.minimizes_cost:
            return
        file = self.problem.file
        for fact in self.problem.numeric_init:
            if fact.function not in self.cost_functions:
                continue
            arguments = [pddl_name_to_asp(term) for term in fact.terms]
            term = term_of(pddl_name_to_asp(fact.function), arguments)
            self.emit(f"pddl_value({term},{self.integer(file, fact.pos, fact.value)}).")

    # -- the problem -------------------------------------------------------------

    def initial_state(self) -> None:
        file = self.problem.file
        for atom in self.problem.init:
            if atom.predicate in self.derived:
                raise file.error(
                    atom.pos, f"the derived predicate {atom.predicate} in the initial state"
                )
            self.emit(f"init({self.atom(atom, Scope(), file)}).")

    def goal(self) -> None:
        file = self.problem.file
        formula = nnf(self.problem.goal)
        goal = self.conjunction(formula, Scope(), file, lift=False)
        if goal.comparisons or not (goal.literals or goal.comparisons):
            # comparisons (or nothing at all): the whole goal as one derived variable
            goal = Conjunction([(self.auxiliary(formula, Scope(), file), "true")])
        for atom, value in goal.literals:
            self.emit(f"goal({atom},{value}).")

    # -- requirements and warnings ------------------------------------------------

    def warnings(self) -> list[str]:
        """One line per file: undeclared requirements, ignored costs and metric."""
        declared = closure(self.domain.requirements)
        lines = []
        for file, used, requirements in (
            (self.domain.file, self.domain.used, declared),
            (self.problem.file, self.problem.used, declared | closure(self.problem.requirements)),
        ):
            notes = []
            missing = sorted(set(used) - requirements - {":strips"})
            if missing:
                notes.append(
                    f"requirement{'s' if len(missing) > 1 else ''} "
                    f"{', '.join(missing)} used but not declared (read anyway)"
                )
            if file is self.domain.file and self.inferred:
                names = ", ".join(
                    f"{name}/{len(self.domain.predicates[name])}" for name in self.inferred
                )
                notes.append(f"no :predicates section (predicates read from their uses: {names})")
            if file is self.domain.file and self.implicit:
                names = ", ".join(self.implicit)
                notes.append(
                    f"constant{'s' if len(self.implicit) > 1 else ''} {names} used but not "
                    "declared (read as objects)"
                )
            if file is self.domain.file and self.undeclared_types:
                names = ", ".join(self.undeclared_types)
                notes.append(
                    f"type{'s' if len(self.undeclared_types) > 1 else ''} {names} "
                    "used but not declared (read as having no objects)"
                )
            if (
                file is self.domain.file
                and self.costs is not None
                and not self.problem.minimizes_cost
            ):
                notes.append(
                    "action costs are ignored: the problem has no (:metric minimize (total-cost)) "
                    "(plans are shortest in number of actions)"
                )
            if file is self.problem.file and self.undeclared_functions:
                names = ", ".join(self.undeclared_functions)
                notes.append(
                    f"numeric facts of the undeclared function"
                    f"{'s' if len(self.undeclared_functions) > 1 else ''} {names} "
                    "are ignored"
                )
            if (
                file is self.problem.file
                and self.problem.metric is not None
                and not self.problem.minimizes_cost
            ):
                notes.append(
                    "the metric is ignored: only (:metric minimize (total-cost)) is read (plans "
                    "are shortest in number of actions)"
                )
            if notes:
                lines.append(f"{file.name}: warning: {'; '.join(notes)}")
        return lines

    def check_numeric_init(self) -> None:
        """Numeric facts are ignored; those of undeclared functions are noted."""
        for fact in self.problem.numeric_init:
            if fact.function not in self.domain.functions:
                self.undeclared_functions.setdefault(fact.function)

    def check_types(self) -> None:
        """Types that the domain uses but that are neither declared nor given to
        an object are noted: they have no objects (planners read them so)."""
        known = {"object"}
        for param in self.domain.types + self.domain.constants + self.problem.objects:
            known |= set(param.types)
        known |= {param.name for param in self.domain.types}
        for params in [
            *self.domain.predicates.values(),
            *(action.params for action in self.domain.actions),
            *(definition.params for definition in self.domain.derived),
        ]:
            for param in params:
                for type_name in param.types:
                    if type_name not in known:
                        self.undeclared_types.setdefault(type_name)

    def translate(self) -> str:
        if self.problem.domain_name != self.domain.name:
            raise InputError(
                f"{self.problem.file.name}: the problem is for domain "
                f"{self.problem.domain_name}, not {self.domain.name} "
                f"({self.domain.file.name})"
            )
        self.check_types()
        self.check_numeric_init()
        self.emit(
            f"% {self.domain.file.name} and {self.problem.file.name}, "
            "translated by ethasp (see encodings/planning/pddl.lp)"
        )
        self.declarations()
        self.predicates()
        self.derived_predicates()
        for action in self.domain.actions:
            self.action(action)
        self.initial_state()
        self.numeric_values()
        self.goal()
        for names in sorted(self.eithers):
            for name in names:
                self.emit(f"pddl_subtype({name},either({','.join(names)})).")
        for line in self.warnings():
            print(line, file=sys.stderr)
        return "\n".join(self.lines) + "\n"


def formula_atoms(formula: Formula):
    """The atoms and equalities of a formula, in the order written."""
    if isinstance(formula, (Atom, Equal)):
        yield formula
    elif isinstance(formula, Not):
        yield from formula_atoms(formula.argument)
    elif isinstance(formula, (And, Or)):
        for part in formula.parts:
            yield from formula_atoms(part)
    elif isinstance(formula, Imply):
        yield from formula_atoms(formula.left)
        yield from formula_atoms(formula.right)
    elif isinstance(formula, (Exists, Forall)):
        yield from formula_atoms(formula.body)


def effect_atoms(effect: Effect):
    """The atoms of an effect and of its conditions, in the order written."""
    if isinstance(effect, Literal):
        yield effect.atom
    elif isinstance(effect, AllEffects):
        for part in effect.parts:
            yield from effect_atoms(part)
    elif isinstance(effect, ForallEffect):
        yield from effect_atoms(effect.effect)
    elif isinstance(effect, When):
        yield from formula_atoms(effect.condition)
        yield from effect_atoms(effect.effect)


def cost_effects(effect: Effect) -> list[CostEffect]:
    """The increases of ``total-cost`` of an effect, outside ``when`` and
    ``forall`` (which :meth:`_Translator.effects` refuses to contain them)."""
    if isinstance(effect, CostEffect):
        return [effect]
    if isinstance(effect, AllEffects):
        return [cost for part in effect.parts for cost in cost_effects(part)]
    return []


def effect_predicates(effect: Effect) -> set[str]:
    """The predicates that an effect may change."""
    if isinstance(effect, Literal):
        return {effect.atom.predicate}
    if isinstance(effect, AllEffects):
        return set().union(*(effect_predicates(part) for part in effect.parts))
    if isinstance(effect, (ForallEffect, When)):
        return effect_predicates(effect.effect)
    return set()


def closure(requirements: Iterable[str]) -> set[str]:
    """Requirements with those they imply."""
    result, todo = set(), list(requirements)
    while todo:
        requirement = todo.pop()
        if requirement not in result:
            result.add(requirement)
            todo += IMPLIED.get(requirement, ())
    return result


def nnf_negate(formula):
    """The negation of a formula in negation normal form, in negation normal form."""
    if isinstance(formula, Lit):
        return Lit(formula.atom, not formula.positive)
    if isinstance(formula, And):
        return Or(tuple(nnf_negate(part) for part in formula.parts))
    if isinstance(formula, Or):
        return And(tuple(nnf_negate(part) for part in formula.parts))
    if isinstance(formula, Exists):
        return Forall(formula.params, nnf_negate(formula.body))
    if isinstance(formula, Forall):
        return Exists(formula.params, nnf_negate(formula.body))
    raise TypeError(formula)


def translate(domain: PddlFile, problem: PddlFile) -> str:
    """The ASP rules of a PDDL domain and problem (to be read with encodings/planning/pddl.lp).

    Warnings (undeclared requirements, ignored action costs) go to standard
    error, one line per file.
    """
    return _Translator(read_domain(domain), read_problem(problem)).translate()


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
            raise InputError(
                f"{file.name}: not a PDDL domain or problem "
                "(it should start with (define (domain ...) or (define (problem ...))"
            )
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
