"""Reasons shortened for a terminal: bounded lines instead of whole formulas.

A reason can be long: a sufficient reason of do-no-harm on a PDDL task names
every fact of the final state, and a GEq literal of utilitarianism compares
two whole states.  The command line's text prints such reasons shortened
(``--json`` keeps them whole):

* a GEq literal shows the facts in which its two sides differ (as many as
  fit) and counts the facts they share: ``not GEq(deprived(bob) & … [4 more;
  117 shared], -deprived(bob) & … [4 more; 117 shared])``;
* any literal longer than the width is cut with an ellipsis;
* a reason shows as many literals as fit in the width, then ``… and N more``;
* the reasons of one kind go on one line when they fit (``ONE_LINE``
  characters), else one per line.

The text is that of :func:`ethasp.principles.formula.format_literal` (facts
are ``v``/``-v`` or PDDL atoms); it is split at the top level of parentheses
and quotes only.
"""

from __future__ import annotations

from collections.abc import Sequence

WIDTH = 100  # characters of a line of reasons, when they are shortened
ONE_LINE = 160  # the reasons of one kind stay on one line up to this length
ELLIPSIS = "\u2026"


def _split(text: str, separator: str) -> list[str]:
    """``text`` split at ``separator`` outside parentheses and strings."""
    parts, depth, quoted, start, index = [], 0, False, 0, 0
    while index < len(text):
        char = text[index]
        if quoted:
            if char == "\\":
                index += 1
            elif char == '"':
                quoted = False
        elif char == '"':
            quoted = True
        elif char == "(":
            depth += 1
        elif char == ")":
            depth -= 1
        elif depth == 0 and text.startswith(separator, index):
            parts.append(text[start:index])
            index += len(separator)
            start = index
            continue
        index += 1
    parts.append(text[start:])
    return parts


def _cut(text: str, width: int) -> str:
    return text if len(text) <= width else text[: max(1, width - 1)] + ELLIPSIS


def _side(facts: list[str], shared: int, room: int) -> str:
    """One side of a GEq: its own facts as far as they fit in ``room``, then
    how many more, and how many facts both sides share."""
    shown: list[str] = []
    for index, fact in enumerate(facts):
        rest = len(facts) - index - 1
        tail = len(f" & {ELLIPSIS} [{rest} more; {shared} shared]") if rest else 0
        if shown and len(" & ".join([*shown, fact])) + tail > room:
            break
        shown.append(fact)
    rest = len(facts) - len(shown)
    more = f"{rest} more; " if rest else ""
    return " & ".join([*shown, f"{ELLIPSIS} [{more}{shared} shared]"])


def _geq(literal: str, width: int) -> str | None:
    """A GEq literal in about ``width`` characters: the facts in which its
    sides differ, the facts both share counted, not listed (None if the
    literal is no GEq or its sides share nothing)."""
    negation = "not " if literal.startswith("not ") else ""
    body = literal[len(negation) :]
    if not (body.startswith("GEq(") and body.endswith(")")):
        return None
    sides = _split(body[4:-1], ", ")
    if len(sides) != 2:
        return None
    left, right = (_split(side.strip(), " & ") for side in sides)
    shared = set(left) & set(right)
    if not shared:
        return None
    room = max(30, (width - len(negation) - 7) // 2)
    first = _side([fact for fact in left if fact not in shared], len(shared), room)
    second = _side([fact for fact in right if fact not in shared], len(shared), room)
    return f"{negation}GEq({first}, {second})"


def shorten_literal(literal: str, width: int = WIDTH) -> str:
    """A literal of L in at most ``width`` characters (GEq: shared facts counted)."""
    if len(literal) <= width:
        return literal
    shorter = _geq(literal, width)
    if shorter is not None:  # a little over is better than cutting its counts off
        return _cut(shorter, width + width // 5)
    return _cut(literal, width)


def shorten_reason(reason: Sequence[str], width: int = WIDTH) -> str:
    """``{a, b, … and N more}``: as many literals as fit in ``width`` characters."""
    shown: list[str] = []
    used = 2
    for index, literal in enumerate(reason):
        text = shorten_literal(literal, max(20, width - 2))
        rest = len(reason) - index - 1
        tail = len(f", {ELLIPSIS} and {rest} more") if rest else 0
        if shown and used + len(text) + 2 + tail > width:
            break
        shown.append(text)
        used += len(text) + 2
    if len(shown) < len(reason):
        shown.append(f"{ELLIPSIS} and {len(reason) - len(shown)} more")
    return "{" + ", ".join(shown) + "}"


def reasons_lines(
    kind: str, reasons: Sequence[Sequence[str]], truncated: bool, width: int = WIDTH
) -> tuple[list[str], bool]:
    """The lines of one kind of reasons (``necessary``, ``sufficient``) and
    whether anything was shortened."""
    more = " (limit reached; more may exist)" if truncated else ""
    whole = "; ".join("{" + ", ".join(reason) + "}" for reason in reasons) or "none"
    line = f"  {kind} reasons: {whole}{more}"
    if len(line) <= max(width, ONE_LINE):
        return [line], False
    count = f"{len(reasons)}{'; limit reached, more may exist' if truncated else ''}"
    lines = [f"  {kind} reasons ({count}):"]
    lines += [f"    {shorten_reason(reason, width - 4)}" for reason in reasons]
    shortened = any(
        shorten_reason(reason, width - 4) != "{" + ", ".join(reason) + "}" for reason in reasons
    )
    return lines, shortened
