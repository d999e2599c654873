"""The ethical principles: one encoding each in ``encodings/principles/``.

A file ``encodings/principles/NAME.lp`` is the principle NAME (on the command
line and in the API with ``-`` for ``_``: ``do_no_harm.lp`` is ``do-no-harm``)
for plans; a file ``encodings/principles/cam/NAME.lp`` is the principle NAME
for causal agency models (HERA's CAMs: :mod:`ethasp.principles.causal`).  A
name may stand for both, where the concept is the same (``hera-deontology``),
and a principle is refused with one line for a kind of model it is not
defined for.
It defines ``formula(NAME, F)``, a formula of L (``encodings/judgement/language.lp``)
that holds exactly when the plan is permissible.  A principle whose encoding
reads ``alternative/1`` is given a best reachable state as ``alternative(best)``
with its facts ``conj(best,V,B)``; its formula must be falsified by one
reachable state, as utilitarianism's ``/\\_i GEq(s_n, s_i)`` is (see
:mod:`ethasp.principles.judgement`).  A principle whose formula uses HERA's
counterfactual operators (``but_for``, ``instrumental``, ``means``,
``means2``) or ``avoidable`` needs facts that searches establish first
(:attr:`Principle.needs`).

Without names, commands judge plans under the paper's three principles
(:data:`DEFAULT`) and choices in CAMs under HERA's (:data:`HERA_CAM`); the
names ``paper``, ``hera`` and ``all`` select groups (``hera``: every HERA
principle defined for the kind of model).
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

import clingo
from clingo import ast

from ethasp.errors import InputError
from ethasp.resources import ENCODINGS

FOLDER = "principles"
CAM_FOLDER = "principles/cam"

# The kinds of model a principle may be defined for.
PLAN = "plan"
CAM = "cam"
KIND_WORDS = {PLAN: "plans", CAM: "causal agency models"}


@dataclass(frozen=True)
class Principle:
    """An ethical principle and its encoding."""

    name: str  # as users write it: do-no-harm
    asp_name: str  # as the encoding writes it: do_no_harm
    encoding: str  # relative to the encodings folder
    reads_alternatives: bool  # it needs a best reachable state
    needs: frozenset[str] = frozenset()  # inputs searched first: COUNTERFACTUALS, GOAL_REACHABLE
    kind: str = PLAN  # the kind of model: PLAN or CAM


# Inputs that a principle's formula may need (see language.lp): the
# counterfactual facts of judgement/counterfactual.lp, and whether a plan
# reaches the goal.
COUNTERFACTUALS = "counterfactuals"
GOAL_REACHABLE = "goal_reachable"
_NEEDS = {
    ("but_for", 2): COUNTERFACTUALS,
    ("instrumental", 2): COUNTERFACTUALS,
    ("means", 1): COUNTERFACTUALS,
    ("means2", 1): COUNTERFACTUALS,
    ("avoidable", 2): GOAL_REACHABLE,
}

# The groups of principles that --principle names (besides "all").
PAPER = ("deontology", "do-no-harm", "utilitarianism")
HERA = (
    "hera-deontology",
    "goal-deontology",
    "avoid-any-harm",
    "avoid-avoidable-harm",
    "hera-do-no-harm",
    "do-no-instrumental-harm",
    "kantian-humanity",
    "kantian-humanity-2",
    "double-effect",
    "hera-utilitarianism",
)
# HERA's principles for causal agency models, in the order of its classes.
HERA_CAM = (
    "hera-deontology",
    "intention-deontology",
    "goal-deontology",
    "hera-utilitarianism",
    "hera-do-no-harm",
    "do-no-instrumental-harm",
    "do-no-instrumental-harm-without-intentions",
    "minimize-harm",
    "minimax-harm",
    "double-effect",
    "kantian-humanity",
    "kantian-humanity-2",
    "pareto",
    "discourse",
    "universality",
)
GROUPS = {"paper": PAPER, "hera": HERA}
CAM_GROUPS = {"hera": HERA_CAM}
DEFAULT = PAPER


_COMMENTS = re.compile(r"%\*.*?\*%|%[^\n]*|\"(?:\\.|[^\"\\])*\"", re.S)


def _scan(path: Path) -> tuple[bool, frozenset[str]]:
    """Does the encoding use the atom alternative/1 (outside #defined), and
    which inputs do the operators of its terms need (its text, comments and
    strings left out)?"""
    found: list[bool] = []

    class Finder(ast.Transformer):
        def visit_SymbolicAtom(self, node):
            symbol = node.symbol
            if (
                symbol.ast_type == ast.ASTType.Function
                and symbol.name == "alternative"
                and len(symbol.arguments) == 1
            ):
                found.append(True)
            return node

    text = _COMMENTS.sub(" ", path.read_text())
    if re.search(r"\balternative\(", text):  # parsed only where it may occur
        ast.parse_files([str(path)], Finder(), logger=lambda code, message: None)
    needs = {need for (name, _), need in _NEEDS.items() if re.search(rf"\b{name}\(", text)}
    return bool(found), frozenset(needs)


def formula_needs(term) -> frozenset[str]:
    """The inputs a formula term (a clingo symbol) needs."""
    needs, stack = set(), [term]
    while stack:
        term = stack.pop()
        if term.type == clingo.SymbolType.Function:
            need = _NEEDS.get((term.name, len(term.arguments)))
            if need:
                needs.add(need)
            stack.extend(term.arguments)
    return frozenset(needs)


@functools.lru_cache(maxsize=2)
def _discover(kind: str = PLAN) -> tuple[Principle, ...]:
    """Every principle of a kind of model (``encodings/principles/`` for plans,
    ``encodings/principles/cam/`` for CAMs; read once)."""
    folder = CAM_FOLDER if kind == CAM else FOLDER
    result = []
    for path in sorted((ENCODINGS / folder).glob("*.lp")):
        if kind == CAM:  # the CAM's program computes everything its formulas read
            alternatives, needs = False, frozenset()
        else:
            alternatives, needs = _scan(path)
        result.append(
            Principle(
                path.stem.replace("_", "-"),
                path.stem,
                f"{folder}/{path.name}",
                alternatives,
                needs,
                kind,
            )
        )
    return tuple(result)


def available_principles(kind: str = PLAN) -> list[Principle]:
    """Every principle defined for a kind of model (plans by default), by name."""
    return list(_discover(kind))


def select_principles(names: Iterable[str] | None = None, kind: str = PLAN) -> list[Principle]:
    """The principles of the given names for a kind of model (``plan`` or
    ``cam``), without repeats; when None, the paper's three for plans and
    HERA's for causal agency models.

    ``do-no-harm`` and ``do_no_harm`` both work; ``paper``, ``hera`` and
    ``all`` name groups, of the principles defined for the kind; an unknown
    name, or one not defined for the kind, is an InputError.
    """
    known = available_principles(kind)
    by_name = {p.name: p for p in known} | {p.asp_name: p for p in known}
    groups = CAM_GROUPS if kind == CAM else GROUPS
    if names is None:
        names = HERA_CAM if kind == CAM else DEFAULT
    chosen: list[Principle] = []
    for name in names:
        key = name.strip().lower()
        if key in GROUPS and key not in groups:
            raise InputError(
                f"principle group {key} is not defined for {KIND_WORDS[kind]} (groups: "
                f"{', '.join([*groups, 'all'])})"
            )
        group = [p.name for p in known] if key == "all" else list(groups.get(key, [key]))
        for member in group:
            principle = by_name.get(member)
            if principle is None:
                raise InputError(_unknown(name, member, kind, known, groups))
            if principle not in chosen:
                chosen.append(principle)
    return chosen


def _unknown(name: str, member: str, kind: str, known: list[Principle], groups) -> str:
    """The one line for a principle name unknown for a kind of model."""
    other = CAM if kind == PLAN else PLAN
    others = {p.name for p in available_principles(other)} | {
        p.asp_name for p in available_principles(other)
    }
    if member in others:
        return (
            f"principle {member.replace('_', '-')} is not defined for {KIND_WORDS[kind]} "
            f"(only for {KIND_WORDS[other]}; for {KIND_WORDS[kind]}: "
            f"{', '.join(p.name for p in known)})"
        )
    return (
        f"unknown principle {name!r} (known for {KIND_WORDS[kind]}: "
        f"{', '.join(p.name for p in known)}; groups: {', '.join([*groups, 'all'])})"
    )
