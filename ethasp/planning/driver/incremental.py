"""Compile time-indexed encodings into program parts for multi-shot solving.

The encodings are written once, over time variables, so that the clingo
command line can run them with a fixed horizon (``time(0..h). step(1..h).
horizon(h).``).  Domain atoms in a rule's body, the *markers*, say in which
program part the rule belongs:

* ``step(T)``: the rule belongs to step ``T``; it goes into a part with the
  parameter ``t`` for ``T`` (named ``step``, or another name given for the
  file), and the atom ``step(t)`` is dropped;
* ``horizon(T)``: the rule is about the last time ``T``; it goes into the
  part ``check(t)``, where ``horizon(t)`` is an external atom that the driver
  sets true while ``t`` is the horizon;
* an *input* ``I(X)``, for the names in :data:`INPUTS`: the rule is about
  one value ``x`` of an input that a driver gives later (a question, a
  utility threshold, ...); it goes into part ``I(x)``, or ``I_step(x,t)`` /
  ``I_check(x,t)`` together with a time marker.  ``I(x)`` is an external atom
  declared in part ``I(x)``: the driver switches the input on and off.
* anything else goes into ``base``.

A file may also get a *switch*, an atom added to the body of each of its
rules (and optimisation statements): its rules then hold only while the
switch, an external declared in ``base``, is true.  So one grounding serves
searches with and without a restriction.

Each part is grounded once per parameter value, never again.
"""

from __future__ import annotations

import functools
import re
from collections import defaultdict
from collections.abc import Callable
from pathlib import Path

import clingo
from clingo import ast

from ethasp.errors import InputError

STEP = "step"
CHECK = "check"
TIME_MARKER = "horizon"
TIME = "t"
VALUE = "x"

# Inputs that parameterise parts (see the module docstring).
INPUTS = ("question", "at_least", "other_state", "simple_path")


def part_name(kind: str, input_name: str | None = None) -> str:
    """The name of a part: ``step``, ``check``, ``question``, ``question_step``, ..."""
    if input_name is None:
        return kind
    return input_name if kind == "base" else f"{input_name}_{kind}"


def _binding(location, variable: str, parameter: str):
    """The body literal ``Variable = parameter``: it binds a time or input
    variable to the part's parameter (cheaper than rewriting the statement)."""
    guard = ast.Guard(
        ast.ComparisonOperator.Equal, ast.SymbolicTerm(location, clingo.Function(parameter))
    )
    return ast.Literal(
        location, ast.Sign.NoSign, ast.Comparison(ast.Variable(location, variable), [guard])
    )


# A positive body literal name(X) with a variable X, as clingo prints it.
_MARKER = re.compile(r"([a-z_'][A-Za-z0-9_']*)\(([A-Z_'][A-Za-z0-9_']*)\)")


def _marker(literal) -> tuple[str, str] | None:
    """(name, variable) of a positive body literal ``name(X)``, else None.

    Read from the literal's text: one call into clingo instead of one per
    attribute of the syntax tree."""
    found = _MARKER.fullmatch(str(literal))
    return (found.group(1), found.group(2)) if found else None


def _switch_literal(location, switch: clingo.Symbol):
    atom = ast.SymbolicAtom(ast.SymbolicTerm(location, switch))
    return ast.Literal(location, ast.Sign.NoSign, atom)


_PLACED = (ast.ASTType.Rule, ast.ASTType.Minimize, ast.ASTType.Heuristic)


def _place(
    statement,
    step_part: str,
    switch: clingo.Symbol | None,
    where: str,
    base_part: str = "base",
    kind=None,
    check_part: str = CHECK,
):
    """The part of a statement (of type ``kind``, if known), the part's
    parameters, and the statement to add there."""
    if (statement.ast_type if kind is None else kind) not in _PLACED:
        return base_part, (), statement
    body = list(statement.body)
    time_kind, input_name, mapping, drop = None, None, {}, None
    for index, literal in enumerate(body):
        found = _marker(literal)
        if found is None:
            continue
        name, variable = found
        if name == STEP and time_kind is None:
            time_kind, drop = STEP, index
            mapping[variable] = TIME
        elif name == TIME_MARKER and time_kind is None:
            time_kind = CHECK
            mapping[variable] = TIME
        elif name in INPUTS and input_name is None:
            input_name = name
            mapping[variable] = VALUE
    if not mapping and switch is None:
        return base_part, (), statement  # nothing to rewrite
    if drop is not None:
        del body[drop]
    for variable, parameter in mapping.items():
        body.append(_binding(statement.location, variable, parameter))
    if switch is not None:
        body.append(_switch_literal(statement.location, switch))
    rewritten = statement.update(body=body)
    if input_name is None:
        if time_kind is None:
            return base_part, (), rewritten
        return (step_part if time_kind == STEP else check_part), (TIME,), rewritten
    if time_kind is None:
        return input_name, (VALUE,), rewritten
    return part_name(time_kind, input_name), (VALUE, TIME), rewritten


def add_encoding(
    builder: ast.ProgramBuilder,
    path: Path | None,
    step_part: str = STEP,
    switch: clingo.Symbol | None = None,
    text: str | None = None,
    on_message: Callable[[clingo.MessageCode, str], None] | None = None,
    base_part: str = "base",
    check_part: str = CHECK,
) -> dict[str, tuple[str, ...]]:
    """Add an encoding (a file, or ``text``) to a program, split into parts.

    Rules without markers go into ``base_part``, rules about the horizon into
    ``check_part``.  Returns the parts used, with their parameters.
    """
    where = str(path) if path is not None else "<encoding>"
    if text is None:
        # An encoding file is split once per process (and per way of splitting
        # it): every planner of the process (a model's, its HModels') adds the
        # same statements.
        parts, params = _split_file(str(path), step_part, switch, base_part, check_part)
    else:
        parts, params = _split(text, None, step_part, switch, base_part, on_message, check_part)
    location = ast.Location(ast.Position(where, 1, 1), ast.Position(where, 1, 1))
    for part, statements in parts.items():
        builder.add(ast.Program(location, part, [ast.Id(location, p) for p in params[part]]))
        for statement in statements:
            builder.add(statement)
    return dict(params)


# A name that may be a marker, as an atom (with "#program": the text is split).
_MAYBE_MARKED = re.compile(r"\b(?:" + "|".join([STEP, TIME_MARKER, *INPUTS]) + r")\s*\(|#program")


@functools.cache
def plain_text(path: Path) -> str | None:
    """The text of an encoding file that no marker can be in (no name of one
    followed by a parenthesis, no ``#program``): every statement of it goes
    into one part as it is, so the text is added to that part whole, without
    reading its syntax tree here (a part of every command's start).  None
    for a file to split (:func:`add_encoding`)."""
    text = Path(path).read_text()
    return None if _MAYBE_MARKED.search(text) else text


@functools.cache
def _split_file(
    path: str, step_part: str, switch: clingo.Symbol | None, base_part: str, check_part: str
) -> tuple[dict[str, list], dict[str, tuple[str, ...]]]:
    """An encoding file's statements by part, and the parts' parameters."""
    return _split(None, path, step_part, switch, base_part, None, check_part)


def _split(
    text: str | None,
    path: str | None,
    step_part: str,
    switch: clingo.Symbol | None,
    base_part: str,
    on_message,
    check_part: str = CHECK,
) -> tuple[dict[str, list], dict[str, tuple[str, ...]]]:
    where = path if path is not None else "<encoding>"
    parts: dict[str, list] = defaultdict(list)
    params: dict[str, tuple[str, ...]] = {}

    def collect(statement):
        kind = statement.ast_type
        if kind == ast.ASTType.Program:
            if statement.name != "base" or statement.parameters:
                raise InputError(f"{where}: encodings for multi-shot solving must not use #program")
            return
        part, parameters, placed = _place(
            statement, step_part, switch, where, base_part, kind, check_part
        )
        parts[part].append(placed)
        params[part] = parameters

    if text is not None:
        ast.parse_string(text, collect, logger=on_message)
    else:
        ast.parse_files([path], collect, logger=on_message)
    return dict(parts), params


def time_parts() -> dict[str, tuple[list[str], str]]:
    """The time domain and the externals of the parts: ``time/1`` and the
    external ``past(t)`` (step t comes after the end) in ``step(t)``, the
    horizon external in ``check(t)``, each input's external in its part."""
    parts = {
        STEP: ([TIME], f"time({TIME}). #external past({TIME})."),
        CHECK: ([TIME], f"#external {TIME_MARKER}({TIME})."),
    }
    for name in INPUTS:
        parts[name] = ([VALUE], f"#external {name}({VALUE}).")
    return parts
