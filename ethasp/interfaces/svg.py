"""Pictures of plans as SVG text: a plan as a timeline, and a contrast plan
drawn aligned with the plan asked about.

A timeline has one column per step: the action on top, below it the facts
its effects change (effects that set a value the variable already had are
drawn dashed).  A first column shows the initial values of the variables the
plan changes, a last one the final state with its utility.  Every action and
fact is coloured by its moral value (good green, bad red, neutral grey; the
utility is written beside it) and the facts the plan causes (``Caused`` of L)
carry a dark border and the tag "caused".  In a contrast picture the two
plans share their columns, the steps before the first difference are faded,
a line marks where the plans part, and final facts that differ are marked.

Everything drawn comes from :class:`ethasp.planning.timeline.Timeline` (answer
sets); this module only lays it out.  The SVG is standalone (no scripts, no
external fonts or links), so it can go into papers and reports.
"""

from __future__ import annotations

import itertools
import re
import textwrap
from dataclasses import dataclass
from xml.sax.saxutils import escape, quoteattr

from ethasp.planning.naming import ASP_NAMING, Naming
from ethasp.planning.timeline import Fact, Timeline, moral

FONT = "DejaVu Sans, Verdana, Arial, sans-serif"
MARGIN = 20
COLUMN = 216  # width of a column's boxes
GAP = 22  # between columns
HEADER = 22  # the step numbers above the columns
ACTION = 46  # height of an action box
FACT = 40  # height of a fact box
SPACE = 8  # between boxes
LINE = 18  # height of a line of text
CHAR = 0.6  # average glyph width as a share of the font size
READABLE = 960  # headings and notes wrap at this width, however wide the steps run

COLOURS = {  # moral value: (fill, stroke, text)
    "good": ("#dcf3e4", "#1e7b3c", "#14532d"),
    "bad": ("#fbe1df", "#b3261e", "#7f1d1d"),
    "neutral": ("#f2f2f2", "#8a8a8a", "#333333"),
}
INK = "#1f2328"
MUTED = "#5b6470"
PART = "#7c3aed"


def _fit(text: str, size: float, width: float) -> str:
    """Text cut to fit ``width`` pixels at font ``size`` (with an ellipsis)."""
    room = max(3, int(width / (size * CHAR)))
    return text if len(text) <= room else text[: room - 1] + "\u2026"


def _lines(text: str, size: float, width: float, most: int) -> list[str]:
    """Text in at most ``most`` lines of ``width`` pixels at font ``size``,
    broken after spaces, commas and opening parentheses (names such as
    ``(not (robot-at kitchen))`` or ``move(kitchen,hall)``); the last line is
    cut with an ellipsis if the text is longer still (the box's tooltip has
    it whole)."""
    room = max(3, int(width / (size * CHAR)))
    if len(text) <= room:
        return [text]
    breaks = [match.end() for match in re.finditer(r"[ ,(]", text)] + [len(text)]
    starts, start = [], 0
    while start < len(text):
        starts.append(start)
        fitting = [end for end in breaks if start < end and len(text[start:end].rstrip()) <= room]
        start = fitting[-1] if fitting else start + room  # a word longer than a line
    starts.append(len(text))
    lines = [text[one:two].rstrip() for one, two in itertools.pairwise(starts)]
    if len(lines) > most:
        lines = [*lines[: most - 1], _fit(text[starts[most - 1] :], size, width)]
    return lines


def _text(
    x: float,
    y: float,
    text: str,
    size: float = 12,
    colour: str = INK,
    weight: str = "normal",
    anchor: str = "start",
    style: str = "normal",
) -> str:
    return (
        f'<text x="{x:.0f}" y="{y:.0f}" font-size="{size}" fill="{colour}" '
        f'font-weight="{weight}" font-style="{style}" text-anchor="{anchor}">'
        f"{escape(text)}</text>"
    )


def _utility(utility: int) -> str:
    return f"{utility:+d}".replace("-", "\u2212") if utility else ""


@dataclass
class _Canvas:
    parts: list[str]
    width: float = 0.0
    height: float = 0.0

    def add(self, part: str) -> None:
        self.parts.append(part)

    def grow(self, x: float, y: float) -> None:
        self.width, self.height = max(self.width, x), max(self.height, y)

    def svg(self, title: str) -> str:
        width, height = self.width + MARGIN, self.height + MARGIN
        return (
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" '
            f'height="{height:.0f}" viewBox="0 0 {width:.0f} {height:.0f}" '
            f'font-family="{FONT}" role="img" aria-label={quoteattr(title)}>\n'
            f"<title>{escape(title)}</title>\n"
            f'<rect x="0" y="0" width="{width:.0f}" height="{height:.0f}" fill="#ffffff"/>\n'
            + "\n".join(self.parts)
            + "\n</svg>\n"
        )


NAME_LINES = 4  # lines of an action's or a fact's name in its box
LABEL_LINES = 2  # lines of its label


def _box(
    canvas: _Canvas,
    x: float,
    y: float,
    height: float,
    utility: int,
    first: str,
    second: str,
    tip: str,
    caused: bool = False,
    dashed: bool = False,
    marked: str = "",
    attributes: str = "",
    bold: bool = False,
) -> float:
    """A box with a name (``first``, wrapped) and a label (``second``); it is
    ``height`` tall, more for names or labels of several lines.  Returns the
    height drawn."""
    fill, stroke, ink = COLOURS[moral(utility)]
    border = INK if caused else stroke
    extra = ' stroke-dasharray="5 3"' if dashed else ""
    value = _utility(utility)
    right = x + COLUMN - 8
    size = 13 if bold else 12
    value_width = len(value) * 12 * CHAR + 6 if value else 0
    room = COLUMN - 16 - value_width - (50 if caused else 0)
    names = _lines(first, size, room, NAME_LINES)
    labels = _lines(second, 11, COLUMN - 16, LABEL_LINES) if second else []
    height += (len(names) - 1 + max(0, len(labels) - 1)) * (LINE - 3)
    canvas.add(f"<g{attributes}>")
    canvas.add(f"<title>{escape(tip)}</title>")
    canvas.add(
        f'<rect x="{x:.0f}" y="{y:.0f}" width="{COLUMN}" height="{height}" rx="6" '
        f'fill="{fill}" stroke="{border}" stroke-width="{2.5 if caused else 1.2}"{extra}/>'
    )
    for index, name in enumerate(names):
        canvas.add(
            _text(x + 8, y + 17 + index * (LINE - 3), name, size, ink, "bold" if bold else "normal")
        )
    if value:
        canvas.add(_text(right, y + 17, value, 12, ink, "bold", "end"))
    if caused:
        left = right - value_width - 44
        canvas.add(
            f'<rect x="{left:.0f}" y="{y + 6:.0f}" width="44" height="15" rx="7" fill="{INK}"/>'
        )
        canvas.add(_text(left + 22, y + 17, "caused", 10, "#ffffff", "bold", "middle"))
    for index, label in enumerate(labels):
        canvas.add(
            _text(
                x + 8,
                y + height - 9 - (len(labels) - 1 - index) * (LINE - 3),
                label,
                11,
                MUTED,
                style="italic",
            )
        )
    if marked:
        canvas.add(_text(x + COLUMN + 4, y + 17, marked, 13, PART, "bold"))
    canvas.add("</g>")
    return height


def _fact_box(
    canvas: _Canvas,
    timeline: Timeline,
    naming: Naming,
    x: float,
    y: float,
    fact: Fact,
    caused: bool,
    dashed: bool = False,
    marked: str = "",
) -> float:
    valuation = timeline.valuation
    utility = valuation.fact_utility(fact)
    label = valuation.fact_label(fact)
    tip = f"{fact.shown(naming)}: {label or 'no label'}; utility {utility} ({moral(utility)})"
    if caused:
        tip += "; caused by the plan"
    if dashed:
        tip += "; set again (no change)"
    height = _box(
        canvas, x, y, FACT, utility, fact.shown(naming), label, tip, caused, dashed, marked
    )
    return y + height + SPACE


@dataclass
class _Lane:
    """Where one plan is drawn: its first column's x and its top y."""

    timeline: Timeline
    name: str
    top: float


def _column_x(index: int) -> float:
    """x of column ``index`` (0: the initial state, 1..n: the steps)."""
    return MARGIN + index * (COLUMN + GAP)


def _step_bands(canvas: _Canvas, steps: int, top: float, bottom: float) -> None:
    """A band over each step's column, from ``top`` to ``bottom``: invisible
    and letting the pointer through (``class="column"``, ``data-step``), for
    a page to show the step under the pointer."""
    for step in range(1, steps + 1):
        canvas.add(
            f'<rect class="column" data-step="{step}" x="{_column_x(step) - GAP / 2:.0f}" '
            f'y="{top:.0f}" width="{COLUMN + GAP:.0f}" height="{bottom - top:.0f}" '
            'fill="none" pointer-events="none"/>'
        )


def _draw_lane(
    canvas: _Canvas,
    lane: _Lane,
    naming: Naming,
    end_index: int,
    faded_until: int = 0,
    other_final: set[Fact] | None = None,
) -> float:
    """Draw a timeline; return the lowest y used.  Steps before ``faded_until``
    are faded; final facts not in ``other_final`` (when given) are marked."""
    timeline, top = lane.timeline, lane.top
    valuation = timeline.valuation
    boxes_top = top + HEADER
    # The time axis behind the step numbers.
    axis_end = _column_x(end_index) + COLUMN
    canvas.add(
        f'<line x1="{MARGIN}" y1="{top + 6:.0f}" x2="{axis_end:.0f}" y2="{top + 6:.0f}" '
        f'stroke="#c8ccd2" stroke-width="2"/>'
    )
    lowest = boxes_top
    # Initial state: the variables the plan changes.
    x = _column_x(0)
    canvas.add(_text(x, top + 2, "start", 11, MUTED, "bold"))
    y = boxes_top
    if not timeline.initial:
        canvas.add(_text(x, y + 14, "(no change)", 11, MUTED, style="italic"))
        y += LINE
    for fact in timeline.initial:
        y = _fact_box(canvas, timeline, naming, x, y, fact, caused=False)
    lowest = max(lowest, y)
    # One column per step.
    for column in timeline.columns:
        x = _column_x(column.step)
        faded = column.step < faded_until
        if faded:
            canvas.add('<g opacity="0.45">')
        cost = valuation.action_cost(column.action)
        costs = f" \u00b7 cost {cost}" if cost is not None else ""
        canvas.add(_text(x, top + 2, f"step {column.step}{costs}", 11, MUTED, "bold"))
        utility = valuation.action_utility(column.action)
        shown = naming.action(column.action)
        label = valuation.action_label(column.action)
        tip = (
            f"step {column.step}: {shown}: {label or 'no label'}; utility {utility} "
            f"({moral(utility)})" + (f"; cost {cost}" if cost is not None else "")
        )
        attributes = (
            f' class="action" data-lane={quoteattr(lane.name)} '
            f'data-step="{column.step}" data-action={quoteattr(str(column.action))} '
            f"data-shown={quoteattr(shown)}"
        )
        height = _box(
            canvas,
            x,
            boxes_top,
            ACTION,
            utility,
            shown,
            label,
            tip,
            attributes=attributes,
            bold=True,
        )
        y = boxes_top + height + SPACE
        for fact in column.changes:
            y = _fact_box(canvas, timeline, naming, x, y, fact, fact in column.causing)
        for fact in column.kept:
            y = _fact_box(canvas, timeline, naming, x, y, fact, fact in column.causing, dashed=True)
        if faded:
            canvas.add("</g>")
        lowest = max(lowest, y)
    # Final state: what changed, what is morally valued, what the goal asks.
    x = _column_x(end_index)
    costs = f" \u00b7 cost {timeline.cost}" if timeline.cost is not None else ""
    canvas.add(
        _text(x, top + 2, f"end \u00b7 utility {timeline.utility}{costs}", 11, MUTED, "bold")
    )
    moved = set(timeline.changed_variables())
    wanted = {fact.variable for fact in valuation.goal}
    y = boxes_top
    for fact in timeline.final:
        if fact.variable in moved or fact.variable in wanted or valuation.fact_utility(fact) != 0:
            marked = "\u2260" if other_final is not None and fact not in other_final else ""
            y = _fact_box(
                canvas, timeline, naming, x, y, fact, fact in timeline.caused, marked=marked
            )
    lowest = max(lowest, y)
    canvas.grow(axis_end + (16 if other_final is not None else 0), lowest)
    return lowest


def _heading(
    canvas: _Canvas,
    y: float,
    lines: list,
    width: float,
    size: float = 12,
    colour: str = INK,
    weight: str = "normal",
) -> float:
    """Wrapped lines of text from ``y``; return the y below them.  A line given
    as ``(text, True)`` is emphasised (dark and bold).  Lines wrap at ``width``
    or at READABLE pixels, whichever is less, so that the text of a picture of
    a long plan stays at its left, where it is read."""
    room = max(40, int(min(width, READABLE) / (size * CHAR)))
    for line in lines:
        strong = isinstance(line, tuple) and line[1]
        text = line[0] if isinstance(line, tuple) else line
        for piece in textwrap.wrap(text, room) or [""]:
            y += size + 6
            canvas.add(
                _text(
                    MARGIN, y, piece, size, INK if strong else colour, "bold" if strong else weight
                )
            )
    return y


def _legend(canvas: _Canvas, y: float) -> float:
    x = MARGIN
    y += 14
    for name in ("good", "bad", "neutral"):
        fill, stroke, _ = COLOURS[name]
        canvas.add(
            f'<rect x="{x}" y="{y:.0f}" width="16" height="12" rx="3" fill="{fill}" '
            f'stroke="{stroke}"/>'
        )
        canvas.add(_text(x + 22, y + 11, name, 11, MUTED))
        x += 82
    canvas.add(f'<rect x="{x}" y="{y:.0f}" width="44" height="14" rx="7" fill="{INK}"/>')
    canvas.add(_text(x + 22, y + 11, "caused", 10, "#ffffff", "bold", "middle"))
    canvas.add(_text(x + 52, y + 11, "a fact the plan causes", 11, MUTED))
    x += 220
    canvas.add(
        f'<rect x="{x}" y="{y:.0f}" width="16" height="12" rx="3" fill="#ffffff" '
        f'stroke="#8a8a8a" stroke-dasharray="4 2"/>'
    )
    canvas.add(_text(x + 22, y + 11, "set again, unchanged", 11, MUTED))
    canvas.grow(x + 160, y + 16)
    return y + 16


def _width(columns: int) -> float:
    return _column_x(columns) - GAP


@dataclass(frozen=True)
class Arrow:
    """A link drawn as an arrow above a timeline: from the column of step
    ``source`` (0: the start column, the initial state) to that of step
    ``target`` (None: the final state), labelled with the fact it carries;
    ``event`` when an event of the source step set the fact; ``demand`` for
    a D-link (the fact requires the target step), drawn in another colour."""

    source: int
    target: int | None
    label: str
    event: bool = False
    demand: bool = False


ARROW = "#2563eb"
DEMAND = "#c2410c"
ARROW_LEVEL = 18  # height between stacked arrows


def _arrow_levels(arrows: list[Arrow], end_index: int) -> list[tuple[Arrow, int, int, int]]:
    """Each arrow with its columns and a level, so that arrows over the same
    columns are stacked (a greedy interval colouring)."""
    placed: list[tuple[Arrow, int, int, int]] = []
    spans = sorted(
        (
            (arrow, arrow.source, end_index if arrow.target is None else arrow.target)
            for arrow in arrows
        ),
        key=lambda item: (item[2] - item[1], item[1]),
    )
    for arrow, start, end in spans:
        level = 0
        while any(level == other and not (end <= a or start >= b) for _, a, b, other in placed):
            level += 1
        placed.append((arrow, start, end, level))
    return placed


def _draw_arrows(canvas: _Canvas, arrows: list[Arrow], end_index: int, bottom: float) -> None:
    """Arrows as arcs whose feet stand on ``bottom`` (above the step numbers)."""
    markers = [("arrowhead", ARROW)] + (
        [("demandhead", DEMAND)] if any(arrow.demand for arrow in arrows) else []
    )
    canvas.add(
        "<defs>"
        + "".join(
            f'<marker id="{name}" markerWidth="8" markerHeight="8" refX="7" '
            f'refY="4" orient="auto"><path d="M0,0 L8,4 L0,8 z" fill="{colour}"/></marker>'
            for name, colour in markers
        )
        + "</defs>"
    )
    for arrow, start, end, level in _arrow_levels(arrows, end_index):
        x1 = _column_x(start) + COLUMN / 2 + 12
        x2 = _column_x(end) + COLUMN / 2 - 12
        apex = bottom - 16 - level * ARROW_LEVEL
        colour, head = (DEMAND, "demandhead") if arrow.demand else (ARROW, "arrowhead")
        dash = (
            ' stroke-dasharray="2 3"'
            if arrow.demand
            else (' stroke-dasharray="5 3"' if arrow.event else "")
        )
        canvas.add(
            f"<g><title>{escape(arrow.label)}</title>"
            f'<path d="M{x1:.0f},{bottom:.0f} C{x1:.0f},{apex:.0f} {x2:.0f},{apex:.0f} '
            f'{x2:.0f},{bottom:.0f}" fill="none" stroke="{colour}" stroke-width="1.6"'
            f'{dash} marker-end="url(#{head})"/>'
        )
        middle = (x1 + x2) / 2
        room = max(x2 - x1 - 8, 60)
        top = bottom - 0.75 * (bottom - apex)  # the highest point of the curve
        canvas.add(
            _text(middle, top - 3, _fit(arrow.label, 10, room), 10, colour, "bold", "middle")
        )
        canvas.add("</g>")


def plan_svg(
    timeline: Timeline,
    naming: Naming = ASP_NAMING,
    title: str = "",
    notes: list | None = None,
    arrows: list[Arrow] | None = None,
) -> str:
    """A plan as a timeline; ``title`` and ``notes`` (e.g. verdicts) above it
    (a note ``(text, True)`` is emphasised); ``arrows`` (causal links) drawn
    as arcs above the steps."""
    canvas = _Canvas([])
    end_index = len(timeline.columns) + 1
    width = max(_width(end_index + 1), 560)
    title = title or f"plan: {naming.actions(timeline.plan) or '(empty)'}"
    y = _heading(canvas, MARGIN - 6, [title], width, 15, weight="bold")
    y = _heading(canvas, y, notes or [], width, 12, MUTED)
    if arrows:
        levels = max(level for *_, level in _arrow_levels(arrows, end_index)) + 1
        bottom = y + 24 + levels * ARROW_LEVEL
        _draw_arrows(canvas, arrows, end_index, bottom)
        y = bottom - 12
    lowest = _draw_lane(canvas, _Lane(timeline, "plan", y + 22), naming, end_index)
    _step_bands(canvas, len(timeline.columns), y + 16, lowest)
    lowest = _legend(canvas, lowest + 4)
    if arrows and any(arrow.demand for arrow in arrows):
        _arrow_legend(canvas, lowest + 4)
    canvas.grow(width, 0)
    return canvas.svg(title)


def _arrow_legend(canvas: _Canvas, y: float) -> float:
    """What the two kinds of arrows mean (E-links and D-links)."""
    x = MARGIN
    y += 10
    for colour, dash, text in (
        (ARROW, "", "enables (E-link)"),
        (DEMAND, ' stroke-dasharray="2 3"', "requires (D-link)"),
    ):
        canvas.add(
            f'<line x1="{x}" y1="{y + 6:.0f}" x2="{x + 28}" y2="{y + 6:.0f}" stroke="{colour}" '
            f'stroke-width="1.6"{dash}/>'
        )
        canvas.add(_text(x + 34, y + 11, text, 11, MUTED))
        x += 170
    canvas.grow(x, y + 16)
    return y + 16


def parting_step(first: Timeline, second: Timeline) -> int:
    """The first step at which two plans differ (1-based; one past the shorter
    plan when it is a prefix of the other; 0 when the plans are equal)."""
    for index, (one, other) in enumerate(zip(first.plan, second.plan, strict=False), start=1):
        if one != other:
            return index
    if len(first.plan) == len(second.plan):
        return 0
    return min(len(first.plan), len(second.plan)) + 1


def contrast_svg(
    original: Timeline,
    contrast: Timeline | None,
    naming: Naming = ASP_NAMING,
    title: str = "",
    notes: list | None = None,
    original_title: str = "",
    contrast_title: str = "",
    missing: str = "no contrast plan",
) -> str:
    """The plan asked about above its contrast plan, their steps aligned.

    Steps before the plans part are faded, a line marks where they part, and
    final facts of one plan that the other's final state lacks are marked
    with a sign.  Without a contrast plan, ``missing`` says why.
    """
    canvas = _Canvas([])
    length = max(len(original.columns), len(contrast.columns) if contrast else 0)
    end_index = length + 1
    width = max(_width(end_index + 1), 720)
    title = title or "contrast"
    y = _heading(canvas, MARGIN - 6, [title], width, 15, weight="bold")
    y = _heading(canvas, y, notes or [], width, 12, MUTED)
    part = parting_step(original, contrast) if contrast else 0
    first_final = set(original.final)
    second_final = set(contrast.final) if contrast else set()
    lanes_top = y + 8
    y = _heading(
        canvas,
        lanes_top + (LINE if part else 0),
        [original_title or "plan asked about"],
        width,
        13,
        weight="bold",
    )
    spans = [(lanes_top, lanes_top + LINE - 2)]
    lowest = _draw_lane(
        canvas,
        _Lane(original, "original", y + 16),
        naming,
        end_index,
        faded_until=part,
        other_final=second_final if contrast else None,
    )
    spans.append((y + 10, lowest))
    y = _heading(canvas, lowest + 12, [contrast_title or "contrast plan"], width, 13, weight="bold")
    if contrast is None:
        y = _heading(canvas, y, [missing], width, 12, MUTED)
        lowest = y
    else:
        lowest = _draw_lane(
            canvas,
            _Lane(contrast, "contrast", y + 16),
            naming,
            end_index,
            faded_until=part,
            other_final=first_final,
        )
        spans.append((y + 10, lowest))
    if part:
        x = _column_x(part) - GAP / 2
        for top, bottom in spans:
            canvas.add(
                f'<line x1="{x:.0f}" y1="{top:.0f}" x2="{x:.0f}" y2="{bottom:.0f}" '
                f'stroke="{PART}" stroke-width="2" stroke-dasharray="6 4"/>'
            )
        canvas.add(_text(x + 6, lanes_top + 12, f"the plans part at step {part}", 11, PART, "bold"))
    elif contrast is not None:
        canvas.add(_text(MARGIN, lowest + 14, "the two plans are the same", 11, PART, "bold"))
        lowest += 18
    _step_bands(canvas, length, lanes_top, lowest)
    _legend(canvas, lowest + 4)
    canvas.grow(width, 0)
    return canvas.svg(title)
