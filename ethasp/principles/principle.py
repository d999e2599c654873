"""The ethical principles: one encoding each in ``encodings/principles/``.

A file ``encodings/principles/NAME.lp`` is the principle NAME (on the command
line and in the API with ``-`` for ``_``: ``do_no_harm.lp`` is ``do-no-harm``).
It defines ``formula(NAME, F)``, a formula of L (``encodings/judgement/language.lp``)
that holds exactly when the plan is permissible.  A principle whose encoding
reads ``alternative/1`` is given a best reachable state as ``alternative(best)``
with its facts ``conj(best,V,B)``; its formula must be falsified by one
reachable state, as utilitarianism's ``/\\_i GEq(s_n, s_i)`` is (see
:mod:`ethasp.principles.judgement`).  A principle whose formula uses HERA's
counterfactual operators (``but_for``, ``instrumental``, ``means``,
``means2``) or ``avoidable`` needs facts that searches establish first
(:attr:`Principle.needs`).

Without names, commands judge under the paper's three principles
(:data:`DEFAULT`); the names ``paper``, ``hera`` and ``all`` select groups.
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


@dataclass(frozen=True)
class Principle:
    """An ethical principle and its encoding."""

    name: str  # as users write it: do-no-harm
    asp_name: str  # as the encoding writes it: do_no_harm
    encoding: str  # relative to the encodings folder
    reads_alternatives: bool  # it needs a best reachable state
    needs: frozenset[str] = frozenset()  # inputs searched first: COUNTERFACTUALS, GOAL_REACHABLE


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
GROUPS = {"paper": PAPER, "hera": HERA}
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


@functools.lru_cache(maxsize=1)
def _discover() -> tuple[Principle, ...]:
    """Every principle of ``encodings/principles/`` (read once)."""
    result = []
    for path in sorted((ENCODINGS / FOLDER).glob("*.lp")):
        alternatives, needs = _scan(path)
        result.append(
            Principle(
                path.stem.replace("_", "-"), path.stem, f"{FOLDER}/{path.name}", alternatives, needs
            )
        )
    return tuple(result)


def available_principles() -> list[Principle]:
    """Every principle of ``encodings/principles/``, by name."""
    return list(_discover())


def select_principles(names: Iterable[str] | None = None) -> list[Principle]:
    """The principles of the given names (the paper's three when None),
    without repeats.

    ``do-no-harm`` and ``do_no_harm`` both work; ``paper``, ``hera`` and
    ``all`` name groups; an unknown name is an InputError.
    """
    known = available_principles()
    by_name = {p.name: p for p in known} | {p.asp_name: p for p in known}
    if names is None:
        names = DEFAULT
    chosen: list[Principle] = []
    for name in names:
        key = name.strip().lower()
        group = [p.name for p in known] if key == "all" else list(GROUPS.get(key, [key]))
        for member in group:
            principle = by_name.get(member)
            if principle is None:
                raise InputError(
                    f"unknown principle {name!r} (known: "
                    f"{', '.join(p.name for p in known)}; groups: paper, hera, all)"
                )
            if principle not in chosen:
                chosen.append(principle)
    return chosen
