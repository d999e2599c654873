"""The report of a batch: one self-contained HTML page drawn from its JSON lines.

The page (drawn from the Jinja2 templates of ``templates/``, with its style
sheet and its script inside: nothing from elsewhere, so that it opens offline
and can be mailed) shows

* the verdicts of each principle: permissible, impermissible, undecided (a
  search cut short: no verdict), errors, and how many verdicts are bounded;
* the pairwise agreement of the principles over the cases both judged: a
  table of the share of agreeing verdicts, and for each pair the cases on
  which they disagree (folded), linked to the case's row in the table of cases;
* the distribution of the cases' times (a histogram on a logarithmic scale,
  and quantiles);
* the slowest cases and the failed ones;
* every case, its verdict under each principle, and a link to its files.

Its tables of lists sort by a column when its heading is clicked.  On the
task plan, a principle that can only judge judged a plan found without it
(``"judged": true``); the table of verdicts counts those lines and names
the principles.

A line is identified by its hash: when a file holds a line twice, the last
one counts.  Lines of the task ask are compared per case and question.
"""

from __future__ import annotations

import bisect
import functools
import math
import os
import statistics
import time
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path

import jinja2

from ethasp.batch.output import read_lines
from ethasp.errors import InputError

TEMPLATES = Path(__file__).resolve().parent / "templates"  # report.html, .css, .js
# Cases listed at most per pair of disagreeing principles, and slowest cases.
LISTED = 200
SLOWEST = 15
# Histogram bin edges, seconds.
EDGES = (
    0.001,
    0.002,
    0.005,
    0.01,
    0.02,
    0.05,
    0.1,
    0.2,
    0.5,
    1,
    2,
    5,
    10,
    20,
    50,
    100,
    200,
    500,
    1000,
)


@dataclass
class Item:
    """A case (with its question, for the task ask) and its lines."""

    case: str
    question: str | None
    files: list[str] = field(default_factory=list)
    verdicts: dict[str, dict] = field(default_factory=dict)  # principle -> line
    errors: list[dict] = field(default_factory=list)
    seconds: float | None = None

    @property
    def title(self) -> str:
        return self.case if self.question is None else f"{self.case}: {self.question}"


def load(path: str | os.PathLike) -> list[dict]:
    """The lines of a results file, each hash once (the last line of a hash counts)."""
    path = Path(path)
    if not path.is_file():
        raise InputError(
            f"{path}: no such results file"
            if not path.exists()
            else f"{path}: is a directory, not a results file"
        )
    lines: dict = {}
    for number, line in enumerate(read_lines(path)):
        if "case" not in line:
            raise InputError(f"{path}: line {number + 1} has no case: not batch results")
        lines[line.get("hash") or ("line", number)] = line
    return list(lines.values())


def _items(lines: list[dict]) -> tuple[list[Item], list[str]]:
    items: dict[tuple, Item] = {}
    principles: list[str] = []
    for line in lines:
        key = (str(line["case"]), line.get("question"))
        item = items.get(key)
        if item is None:
            item = items[key] = Item(*key, files=list(line.get("files") or []))
        principle = line.get("principle")
        if principle is not None and principle not in principles:
            principles.append(principle)
        if "error" in line:
            item.errors.append(line)
        if principle is not None:
            item.verdicts[principle] = line
        seconds = line.get("seconds")
        if isinstance(seconds, (int, float)) and not isinstance(seconds, bool):
            item.seconds = max(item.seconds or 0.0, float(seconds))
    return list(items.values()), principles


def _verdict(line: dict | None) -> str:
    """permissible, impermissible, undecided or error."""
    if line is None:
        return "missing"
    if "error" in line:
        return "error"
    if line.get("permissible") is True:
        return "permissible"
    if line.get("permissible") is False:
        return "impermissible"
    return "undecided"


SHORT = {"permissible": "P", "impermissible": "I", "undecided": "?", "error": "E", "missing": ""}
CSS = {"P": "P", "I": "I", "?": "Q", "E": "E"}
DECIDED = ("permissible", "impermissible")


def _seconds(value: float) -> str:
    if value < 1:
        return f"{value * 1000:.0f} ms" if value >= 0.001 else f"{value * 1000:.2f} ms"
    if value < 120:
        return f"{value:.1f} s"
    return f"{value / 60:.1f} min"


def _href(file: str, base: Path) -> str:
    """A link to a case's file, relative to the report's folder where it can be."""
    path = Path(file)
    try:
        absolute = path if path.is_absolute() else Path.cwd() / path
        return Path(os.path.relpath(absolute, base)).as_posix()
    except ValueError:  # another drive
        return path.resolve().as_uri()


def _verdicts(items: list[Item], principles: list[str]) -> list[dict]:
    """A row per principle: its verdicts counted."""
    rows = []
    for principle in principles:
        counts: dict[str, int] = defaultdict(int)
        bounded = judged = 0
        for item in items:
            line = item.verdicts.get(principle)
            if line is None:
                continue
            counts[_verdict(line)] += 1
            bounded += line.get("status") == "bounded"
            judged += line.get("judged") is True
        rows.append(
            {
                "principle": principle,
                **{verdict: counts[verdict] for verdict in (*DECIDED, "undecided", "error")},
                "bounded": bounded,
                "judged": judged,
                "total": sum(counts.values()),
            }
        )
    return rows


def _agreement(items: list[Item], principles: list[str], anchors: dict[int, str]) -> dict:
    """The principles with verdicts, the matrix of their agreement, and for
    each pair that disagrees the cases it disagrees on."""
    decided = [
        p for p in principles if any(_verdict(item.verdicts.get(p)) in DECIDED for item in items)
    ]
    pairs: dict[tuple[str, str], tuple[int, list[Item]]] = {}
    for i, first in enumerate(decided):
        for second in decided[i + 1 :]:
            both, differ = 0, []
            for item in items:
                a, b = _verdict(item.verdicts.get(first)), _verdict(item.verdicts.get(second))
                if a in DECIDED and b in DECIDED:
                    both += 1
                    if a != b:
                        differ.append(item)
            pairs[(first, second)] = (both, differ)

    def anchor(first: str, second: str) -> str:
        return f"pair-{decided.index(first)}-{decided.index(second)}"

    rows = []
    for row, first in enumerate(decided):
        cells: list[dict | None] = []
        for column, second in enumerate(decided):
            if row == column:
                cells.append(None)
                continue
            key = (first, second) if row < column else (second, first)
            both, differ = pairs[key]
            share = 100.0 * (both - len(differ)) / both if both else 0.0
            cells.append(
                {
                    "both": both,
                    "differ": len(differ),
                    "share": f"{share:.0f}",
                    "anchor": anchor(*key),
                }
            )
        rows.append({"principle": first, "cells": cells})
    listed = [
        {
            "anchor": anchor(first, second),
            "first": first,
            "second": second,
            "both": both,
            "differ": differ,
            "listed": [
                {
                    "anchor": anchors[id(item)],
                    "title": item.title,
                    "first": _verdict(item.verdicts[first]),
                    "second": _verdict(item.verdicts[second]),
                }
                for item in differ[:LISTED]
            ],
            "more": max(0, len(differ) - LISTED),
        }
        for (first, second), (both, differ) in pairs.items()
        if differ
    ]
    return {"principles": decided, "rows": rows, "pairs": listed}


def _histogram(times: list[float]) -> dict | None:
    """Quantiles of the cases' times, and the bars of a histogram on a logarithmic scale."""
    if not times:
        return None
    ordered = sorted(times)

    def quantile(q: float) -> float:
        return ordered[min(len(ordered) - 1, math.ceil(q * len(ordered)) - 1)]

    bounds = [edge for edge in EDGES if ordered[0] < edge <= ordered[-1]] or [EDGES[0]]
    counts = [0] * (len(bounds) + 1)
    for value in times:
        counts[bisect.bisect_right(bounds, value)] += 1
    labels = [f"<{_seconds(bound)}" for bound in bounds] + [f"\u2265{_seconds(bounds[-1])}"]
    if not counts[0]:
        counts, labels = counts[1:], labels[1:]
    width, height, gap = 64, 160, 6
    peak = max(counts) or 1
    bars = []
    for index, count in enumerate(counts):
        bar = int(height * count / peak)
        x = 20 + index * (width + gap)
        bars.append(
            {
                "x": x,
                "y": height - bar + 15,
                "width": width,
                "height": bar,
                "middle": x + width / 2,
                "count": count,
                "label": labels[index],
            }
        )
    return {
        "count": len(times),
        "total": _seconds(sum(times)),
        "mean": _seconds(statistics.fmean(times)),
        "median": _seconds(quantile(0.5)),
        "q90": _seconds(quantile(0.9)),
        "q99": _seconds(quantile(0.99)),
        "slowest": _seconds(ordered[-1]),
        "width": len(counts) * (width + gap) + 40,
        "height": height + 50,
        "label_y": height + 32,
        "bars": bars,
    }


def _cells(item: Item, principles: list[str]) -> list[dict]:
    """A case's verdict under each principle, as the table of cases shows it."""
    cells = []
    for principle in principles:
        line = item.verdicts.get(principle)
        verdict = _verdict(line)
        short = SHORT[verdict]
        hint = f"{principle}: {verdict}"
        if line is not None and verdict == "error":
            hint += f" ({line.get('error')})"
        elif line is not None and line.get("judged") is True:
            hint += " (a plan found without it, judged under it)"
        cells.append(
            {
                "short": short,
                "css": CSS.get(short, ""),
                "hint": hint,
                "bounded": line is not None and line.get("status") == "bounded",
            }
        )
    return cells


@functools.cache
def _template() -> jinja2.Template:
    environment = jinja2.Environment(
        loader=jinja2.FileSystemLoader(TEMPLATES), autoescape=True, keep_trailing_newline=True
    )
    return environment.get_template("report.html")


def build(lines: list[dict], title: str, base: Path) -> str:
    """The page (see the module docstring); links to files relative to ``base``."""
    items, principles = _items(lines)
    anchors = {id(item): f"case-{index + 1}" for index, item in enumerate(items)}
    failed = [item for item in items if item.errors]
    timed = [item for item in items if item.seconds is not None]
    per_case: dict[str, float] = {}
    for item in timed:
        per_case[item.case] = max(per_case.get(item.case, 0.0), item.seconds or 0.0)
    judged = sorted({str(line["principle"]) for line in lines if line.get("judged") is True})
    return _template().render(
        title=title,
        cases=len({item.case for item in items}),
        lines=len(lines),
        principles=principles,
        tasks=sorted({str(line.get("task")) for line in lines if line.get("task")}),
        failed_cases=len({item.case for item in failed}),
        versions=sorted(
            {str(line.get("ethasp_version")) for line in lines if line.get("ethasp_version")}
        ),
        drawn=time.strftime("%Y-%m-%d %H:%M"),
        verdicts=_verdicts(items, principles),
        judged=judged,
        agreement=_agreement(items, principles, anchors),
        histogram=_histogram(list(per_case.values())),
        slowest=[
            {
                "anchor": anchors[id(item)],
                "title": item.title,
                "seconds": item.seconds,
                "time": _seconds(item.seconds or 0.0),
            }
            for item in sorted(timed, key=lambda item: -(item.seconds or 0.0))[:SLOWEST]
        ],
        failed=[
            {
                "anchor": anchors[id(item)],
                "title": item.title,
                "principle": line.get("principle") or "all",
                "message": line.get("error"),
            }
            for item in failed
            for line in item.errors
        ],
        items=[
            {
                "anchor": anchors[id(item)],
                "number": index + 1,
                "title": item.title,
                "files": [{"href": _href(f, base), "name": Path(f).name} for f in item.files],
                "cells": _cells(item, principles),
                "seconds": item.seconds,
                "time": _seconds(item.seconds) if item.seconds is not None else "",
            }
            for index, item in enumerate(items)
        ],
    )


def write_report(results: str | os.PathLike, destination: str | os.PathLike) -> Path:
    """Draw the report of a results file into ``destination`` (HTML); returns its path."""
    lines = load(results)
    destination = Path(destination)
    base = destination.resolve().parent
    page = build(lines, f"ethasp batch report: {Path(results).name}", base)
    destination.write_text(page, encoding="utf-8")
    return destination
