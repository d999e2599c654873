"""Turn time-indexed encodings into program parts for multi-shot solving.

The encodings are written once, over time variables, so that the clingo command
line can run them with a fixed horizon (``time(0..h). step(1..h). horizon(h).``).
Three domain atoms mark how a statement depends on time:

* ``step(T)``: the statement belongs to step ``T``; it goes into the part
  ``step(t)`` (or a part of another name, see :func:`add_encoding`) with ``T``
  replaced by the parameter ``t``, and the atom ``step(t)`` is dropped.
* ``horizon(T)``: the statement is about the last time ``T``; it goes into the
  part ``check(t)`` with ``T`` replaced by ``t``, where ``horizon(t)`` is an
  external atom that the driver sets true while ``t`` is the horizon.
* anything else goes into ``base``.

Each part is then grounded once per time step, never again.
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path
from typing import Callable, Iterable

import clingo
from clingo import ast

from ethasp.errors import InputError

STEP = "step"
CHECK = "check"
PARAMETER = "t"


class _Substitute(ast.Transformer):
    """Replace one variable by the part parameter ``t``."""

    def __init__(self, name: str):
        self.name = name

    def visit_Variable(self, node):  # noqa: N802 (clingo's visitor naming)
        if node.name == self.name:
            return ast.SymbolicTerm(node.location, clingo.Function(PARAMETER))
        return node


def _marker(literal, name: str) -> str | None:
    """The variable of a positive body literal ``name(X)``, else None."""
    if literal.ast_type != ast.ASTType.Literal or literal.sign != ast.Sign.NoSign:
        return None
    atom = literal.atom
    if atom.ast_type != ast.ASTType.SymbolicAtom:
        return None
    symbol = atom.symbol
    if symbol.ast_type != ast.ASTType.Function or symbol.name != name:
        return None
    if len(symbol.arguments) != 1 or symbol.arguments[0].ast_type != ast.ASTType.Variable:
        return None
    return symbol.arguments[0].name


def _place(statement, step_part: str):
    """The part a statement belongs to, and the statement to add there."""
    if statement.ast_type not in (ast.ASTType.Rule, ast.ASTType.Minimize):
        return "base", statement
    body = list(statement.body)
    for index, literal in enumerate(body):
        for marker, part in ((STEP, step_part), (CHECK_MARKER, CHECK)):
            variable = _marker(literal, marker)
            if variable is None:
                continue
            if marker == STEP:
                del body[index]
            rewritten = statement.update(body=body)
            return part, _Substitute(variable)(rewritten)
    return "base", statement


CHECK_MARKER = "horizon"


def add_encoding(
    builder: ast.ProgramBuilder,
    path: Path,
    step_part: str = STEP,
    on_message: Callable[[clingo.MessageCode, str], None] | None = None,
) -> set[str]:
    """Add an encoding file to a program, split into parts; return the parts used."""
    parts: dict[str, list] = defaultdict(list)

    def collect(statement):
        if statement.ast_type == ast.ASTType.Program:
            if statement.name != "base" or statement.parameters:
                raise InputError(f"{path}: encodings for incremental solving must not use #program")
            return
        part, placed = _place(statement, step_part)
        parts[part].append(placed)

    ast.parse_files([str(path)], collect, logger=on_message)
    location = ast.Location(ast.Position(str(path), 1, 1), ast.Position(str(path), 1, 1))
    for part, statements in parts.items():
        params = [] if part == "base" else [ast.Id(location, PARAMETER)]
        builder.add(ast.Program(location, part, params))
        for statement in statements:
            builder.add(statement)
    return set(parts)


def add_encodings(
    control: clingo.Control,
    paths: Iterable[Path],
    step_part: str = STEP,
    on_message: Callable[[clingo.MessageCode, str], None] | None = None,
) -> set[str]:
    """Add several encodings (see :func:`add_encoding`) to a control object."""
    used: set[str] = set()
    with ast.ProgramBuilder(control) as builder:
        for path in paths:
            used |= add_encoding(builder, path, step_part, on_message)
    return used


def time_parts() -> str:
    """The time domain of the incremental parts: ``time/1`` and the horizon external."""
    return (
        "#program base. time(0).\n"
        f"#program {STEP}({PARAMETER}). time({PARAMETER}).\n"
        f"#program {CHECK}({PARAMETER}). #external {CHECK_MARKER}({PARAMETER}).\n"
    )
