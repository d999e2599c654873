"""How actions and facts are named: as ASP terms, or in PDDL form.

A model read from PDDL uses ASP terms internally (``push(man,bridge)``) but is
shown to users in PDDL form (``(push man bridge)``).  Commands print actions
and facts through the model's :class:`Naming`, so that choice is made in one
place.

The name rule between PDDL and ASP
----------------------------------
PDDL names match ``[A-Za-z][-_A-Za-z0-9]*`` and are case-insensitive; ASP
constants must start with a lower-case letter and may contain letters, digits,
``_`` and ``'``.  A PDDL name becomes an ASP constant by

1. lower case (PDDL does not distinguish ``Robot`` from ``robot``),
2. each ``-`` becomes ``_``,
3. each ``_`` becomes ``'``.

So ``five-will-die`` is ``five_will_die`` and ``pick_up`` is ``pick'up``.  The
rule maps characters one to one, so it is reversed character by character
(:func:`asp_name_to_pddl`); a name comes back in lower case.  A PDDL name never
starts with a digit, so no other case arises.  An atom ``(at robot room-1)``
becomes the term ``at(robot,room_1)``, a nullary atom ``(done)`` the constant
``done``.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

import clingo

from ethasp.errors import InputError

PDDL_NAME = re.compile(r"[a-z][-_a-z0-9]*")
ASP_NAME = re.compile(r"[a-z]['_a-z0-9]*")

_TO_ASP = str.maketrans({"_": "'", "-": "_"})
_TO_PDDL = str.maketrans({"_": "-", "'": "_"})


def pddl_name_to_asp(name: str) -> str:
    """The ASP constant of a PDDL name (``Five-Will-Die`` -> ``five_will_die``)."""
    lowered = name.lower()
    if not PDDL_NAME.fullmatch(lowered):
        raise InputError(f"not a PDDL name: {name!r}")
    return lowered.translate(_TO_ASP)


def asp_name_to_pddl(name: str) -> str:
    """The PDDL name of an ASP constant made by :func:`pddl_name_to_asp`."""
    if not ASP_NAME.fullmatch(name):
        raise InputError(f"not the ASP form of a PDDL name: {name!r}")
    return name.translate(_TO_PDDL)


def term_to_pddl(symbol: clingo.Symbol) -> str:
    """A ground term as a PDDL atom: ``push(man,bridge)`` -> ``(push man bridge)``."""
    if symbol.type != clingo.SymbolType.Function or not symbol.name:
        return str(symbol)
    parts = [asp_name_to_pddl(symbol.name)]
    for argument in symbol.arguments:
        if argument.type == clingo.SymbolType.Function and argument.name and not argument.arguments:
            parts.append(asp_name_to_pddl(argument.name))
        else:
            parts.append(str(argument))
    return "(" + " ".join(parts) + ")"


def pddl_atom_to_term(text: str) -> clingo.Symbol:
    """A PDDL atom as a term: ``(push man bridge)`` -> ``push(man,bridge)``."""
    inner = text.strip()
    if not (inner.startswith("(") and inner.endswith(")")):
        raise InputError(f"not a PDDL atom: {text!r}")
    words = inner[1:-1].split()
    if not words or any("(" in word or ")" in word for word in words):
        raise InputError(f"not a PDDL atom: {text!r}")
    try:
        names = [pddl_name_to_asp(word) for word in words]
    except InputError:
        raise InputError(f"not a PDDL atom: {text!r}") from None
    return clingo.Function(names[0], [clingo.Function(name) for name in names[1:]])


class Naming:
    """Actions and facts shown as ASP terms (models written in ASP)."""

    pddl = False

    def action(self, action: clingo.Symbol | str) -> str:
        """An action (a term, or its text), e.g. ``push(man)``."""
        return str(action)

    def fact(self, literal: str) -> str:
        """A fact given as ``v`` (true) or ``-v`` (false)."""
        return literal

    def fact_of(self, variable: clingo.Symbol, value: bool) -> str:
        """The fact that ``variable`` has ``value``: ``v`` or ``-v``."""
        return self.fact(str(variable) if value else f"-{variable}")

    def name(self, term: clingo.Symbol) -> str:
        """Another term of the model (an object, a moral patient), e.g. ``frank``."""
        return str(term)

    def constraint(self, term: clingo.Symbol) -> str:
        """A question's constraint term, e.g. ``unused(pull)``."""
        return str(term)

    def actions(self, actions: Iterable[clingo.Symbol | str]) -> str:
        """A sequence of actions (a plan) separated by spaces."""
        return " ".join(self.action(action) for action in actions)

    def facts(self, literals: Iterable[str]) -> str:
        """Facts separated by spaces."""
        return " ".join(self.fact(literal) for literal in literals)


# The naming of models written in ASP (it holds nothing: one serves everyone).
ASP_NAMING = Naming()


class PddlNaming(Naming):
    """Actions and facts shown in PDDL form (models read from PDDL):
    ``(move kitchen hall)``, ``(robot-at hall)``, ``(not (robot-at hall))``."""

    pddl = True

    def action(self, action: clingo.Symbol | str) -> str:
        if isinstance(action, str):
            try:
                action = clingo.parse_term(action)
            except RuntimeError:
                return action
        return term_to_pddl(action)

    def fact(self, literal: str) -> str:
        negative = literal.startswith("-")
        try:
            atom = term_to_pddl(clingo.parse_term(literal[1:] if negative else literal))
        except (RuntimeError, InputError):
            return literal
        return f"(not {atom})" if negative else atom

    def name(self, term: clingo.Symbol) -> str:
        if term.type == clingo.SymbolType.Function and term.name and not term.arguments:
            try:
                return asp_name_to_pddl(term.name)
            except InputError:
                return str(term)
        try:
            return term_to_pddl(term)
        except InputError:
            return str(term)

    def constraint(self, term: clingo.Symbol) -> str:
        """``unused((move kitchen hall))``: the constraint's kind, its actions and
        facts in PDDL form."""
        if term.type != clingo.SymbolType.Function or not term.arguments:
            return str(term)
        parts = []
        for argument in term.arguments:
            if (
                argument.type == clingo.SymbolType.Function
                and argument.name in ("true", "false")
                and not argument.arguments
            ):
                parts.append(argument.name)
                continue
            if argument.type == clingo.SymbolType.Function and argument.name:
                try:
                    parts.append(term_to_pddl(argument))
                    continue
                except InputError:
                    pass
            parts.append(str(argument))
        return f"{term.name}({','.join(parts)})"
