"""The ethical principles: one encoding each in ``encodings/principles/``.

A file ``encodings/principles/NAME.lp`` is the principle NAME (on the command
line and in the API with ``-`` for ``_``: ``do_no_harm.lp`` is ``do-no-harm``).
It defines ``formula(NAME, F)``, a formula of L (``encodings/judgement/language.lp``)
that holds exactly when the plan is permissible.  A principle whose encoding
reads ``alternative/1`` is given a best reachable state as ``alternative(best)``
with its facts ``conj(best,V,B)``; its formula must be falsified by one
reachable state, as utilitarianism's ``/\\_i GEq(s_n, s_i)`` is (see
:mod:`ethasp.principles.judgement`).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from pathlib import Path
from typing import Iterable

from clingo import ast

from ethasp.errors import InputError
from ethasp.resources import ENCODINGS

FOLDER = "principles"


@dataclass(frozen=True)
class Principle:
    """An ethical principle and its encoding."""

    name: str                 # as users write it: do-no-harm
    asp_name: str             # as the encoding writes it: do_no_harm
    encoding: str             # relative to the encodings folder
    reads_alternatives: bool  # it needs a best reachable state


def _reads_alternatives(path: Path) -> bool:
    """Does the encoding use the atom alternative/1 (outside #defined)?"""
    found: list[bool] = []

    class Finder(ast.Transformer):
        def visit_SymbolicAtom(self, node):  # noqa: N802 (clingo's visitor naming)
            symbol = node.symbol
            if (symbol.ast_type == ast.ASTType.Function and symbol.name == "alternative"
                    and len(symbol.arguments) == 1):
                found.append(True)
            return node

    finder = Finder()
    ast.parse_files([str(path)], finder, logger=lambda code, message: None)
    return bool(found)


@functools.lru_cache(maxsize=1)
def _discover() -> tuple[Principle, ...]:
    """Every principle of ``encodings/principles/`` (read once)."""
    result = []
    for path in sorted((ENCODINGS / FOLDER).glob("*.lp")):
        result.append(Principle(path.stem.replace("_", "-"), path.stem,
                                f"{FOLDER}/{path.name}", _reads_alternatives(path)))
    return tuple(result)


def available_principles() -> list[Principle]:
    """Every principle of ``encodings/principles/``, by name."""
    return list(_discover())


def select_principles(names: Iterable[str] | None = None) -> list[Principle]:
    """The principles of the given names (all when None), without repeats.

    ``do-no-harm`` and ``do_no_harm`` both work; an unknown name is an InputError.
    """
    known = available_principles()
    if names is None:
        return known
    by_name = {p.name: p for p in known} | {p.asp_name: p for p in known}
    chosen: list[Principle] = []
    for name in names:
        principle = by_name.get(name.strip().lower())
        if principle is None:
            raise InputError(f"unknown principle {name!r} "
                             f"(known: {', '.join(p.name for p in known)})")
        if principle not in chosen:
            chosen.append(principle)
    return chosen
