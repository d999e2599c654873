"""The report of a batch: one self-contained HTML page drawn from its JSON lines.

The page (no script, no style sheet or picture from elsewhere: it opens
offline and can be mailed) shows

* the verdicts of each principle: permissible, impermissible, undecided (a
  search cut short: no verdict), errors, and how many verdicts are bounded;
* the pairwise agreement of the principles over the cases both judged: a
  table of the share of agreeing verdicts, and for each pair the cases on
  which they disagree, linked to the case's row in the table of cases;
* the distribution of the cases' times (a histogram on a logarithmic scale,
  and quantiles);
* the slowest cases and the failed ones;
* every case, its verdict under each principle, and a link to its files.

A line is identified by its hash: when a file holds a line twice, the last
one counts.  Lines of the task ask are compared per case and question.
"""

from __future__ import annotations

import bisect
import html
import math
import os
import statistics
import time
from collections import defaultdict
from dataclasses import dataclass, field
from pathlib import Path

from ethasp.batch.output import read_lines
from ethasp.errors import InputError

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


def _e(text) -> str:
    return html.escape(str(text), quote=True)


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
        return _e(Path(os.path.relpath(absolute, base)).as_posix())
    except ValueError:  # another drive
        return _e(path.resolve().as_uri())


STYLE = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;margin:2em;
color:#222;max-width:80em}
h1{font-size:1.5em}h2{font-size:1.2em;margin-top:2em;border-bottom:1px solid #ccc}
table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ddd;padding:.2em .5em;
text-align:right}th{background:#f4f4f4}td.l,th.l{text-align:left}
.P{background:#d9f2d9}.I{background:#f7d4d4}.Q{background:#fff1c2}.E{background:#e0e0e0}
.agree td.cell{min-width:4em}a{color:#1a5fb4}small{color:#666}
.bar{fill:#5b8dd6}.axis{font-size:11px;fill:#444}
code{background:#f4f4f4;padding:0 .2em}
"""


def _verdict_table(items: list[Item], principles: list[str]) -> list[str]:
    out = [
        "<h2 id='verdicts'>Verdicts per principle</h2>",
        "<table><tr><th class=l>principle</th><th>permissible</th><th>impermissible</th>"
        "<th>undecided</th><th>error</th><th>bounded</th><th>cases</th></tr>",
    ]
    for principle in principles:
        counts: dict[str, int] = defaultdict(int)
        bounded = 0
        for item in items:
            line = item.verdicts.get(principle)
            if line is None:
                continue
            counts[_verdict(line)] += 1
            bounded += line.get("status") == "bounded"
        total = sum(counts.values())
        out.append(
            f"<tr><td class=l>{_e(principle)}</td><td class=P>{counts['permissible']}"
            f"</td><td class=I>{counts['impermissible']}</td><td class=Q>"
            f"{counts['undecided']}</td><td class=E>{counts['error']}</td>"
            f"<td>{bounded}</td><td>{total}</td></tr>"
        )
    out.append(
        "</table><p><small>undecided: the search was cut short (by the time limit or "
        "the horizon) before a verdict; bounded: verdicts reached against the states "
        "searched only.</small></p>"
    )
    return out


def _agreement(items: list[Item], principles: list[str], anchors: dict[int, str]) -> list[str]:
    out = ["<h2 id='agreement'>Agreement of the principles</h2>"]
    decided = [
        p
        for p in principles
        if any(_verdict(item.verdicts.get(p)) in ("permissible", "impermissible") for item in items)
    ]
    if len(decided) < 2:
        return [*out, "<p>Fewer than two principles with verdicts: nothing to compare.</p>"]
    pairs: dict[tuple[str, str], tuple[int, list[Item]]] = {}
    for i, first in enumerate(decided):
        for second in decided[i + 1 :]:
            both, differ = 0, []
            for item in items:
                a, b = _verdict(item.verdicts.get(first)), _verdict(item.verdicts.get(second))
                if a in ("permissible", "impermissible") and b in ("permissible", "impermissible"):
                    both += 1
                    if a != b:
                        differ.append(item)
            pairs[(first, second)] = (both, differ)
    out.append(
        "<p>The share of cases on which two principles give the same verdict (of the "
        "cases both decided), and the number of cases on which they disagree (a link "
        "to the list).</p><table class=agree><tr><th></th>"
    )
    out += [f"<th title='{_e(p)}'>{index + 1}</th>" for index, p in enumerate(decided)]
    out.append("</tr>")
    for row, first in enumerate(decided):
        out.append(f"<tr><th class=l>{row + 1}. {_e(first)}</th>")
        for column, second in enumerate(decided):
            if row == column:
                out.append("<td class=cell>&ndash;</td>")
                continue
            key = (first, second) if row < column else (second, first)
            both, differ = pairs[key]
            if not both:
                out.append("<td class=cell><small>none both</small></td>")
                continue
            share = 100.0 * (both - len(differ)) / both
            link = (
                f" <a href='#pair-{decided.index(key[0])}-{decided.index(key[1])}'>"
                f"({len(differ)})</a>"
                if differ
                else " (0)"
            )
            out.append(f"<td class=cell>{share:.0f}%{link}</td>")
        out.append("</tr>")
    out.append("</table>")
    for (first, second), (both, differ) in pairs.items():
        if not differ:
            continue
        anchor = f"pair-{decided.index(first)}-{decided.index(second)}"
        out.append(
            f"<h3 id='{anchor}'>{_e(first)} vs {_e(second)}: disagree on "
            f"{len(differ)} of {both} cases</h3><ul>"
        )
        for item in differ[:LISTED]:
            a = _verdict(item.verdicts[first])
            b = _verdict(item.verdicts[second])
            out.append(
                f"<li><a href='#{anchors[id(item)]}'>{_e(item.title)}</a>: "
                f"{_e(first)} {a}, {_e(second)} {b}</li>"
            )
        if len(differ) > LISTED:
            out.append(f"<li>and {len(differ) - LISTED} more (see the table of cases)</li>")
        out.append("</ul>")
    return out


def _histogram(times: list[float]) -> list[str]:
    out = ["<h2 id='times'>Time per case</h2>"]
    if not times:
        return [*out, "<p>No times recorded.</p>"]
    ordered = sorted(times)

    def quantile(q: float) -> float:
        return ordered[min(len(ordered) - 1, math.ceil(q * len(ordered)) - 1)]

    out.append(
        f"<p>{len(times)} cases; total {_seconds(sum(times))} of work; mean "
        f"{_seconds(statistics.fmean(times))}, median {_seconds(quantile(0.5))}, "
        f"90% within {_seconds(quantile(0.9))}, 99% within {_seconds(quantile(0.99))},"
        f" slowest {_seconds(ordered[-1])}.  (A case's time is its whole time in its "
        "worker: loading and every principle and question.)</p>"
    )
    bounds = [edge for edge in EDGES if ordered[0] < edge <= ordered[-1]] or [EDGES[0]]
    counts = [0] * (len(bounds) + 1)
    for value in times:
        counts[bisect.bisect_right(bounds, value)] += 1
    labels = [f"&lt;{_seconds(bound)}" for bound in bounds] + [f"&#8805;{_seconds(bounds[-1])}"]
    if not counts[0]:
        counts, labels = counts[1:], labels[1:]
    width, height, gap = 64, 160, 6
    peak = max(counts) or 1
    svg = [
        f"<svg xmlns='http://www.w3.org/2000/svg' width='{len(counts) * (width + gap) + 40}'"
        f" height='{height + 50}' role='img' aria-label='histogram of case times'>"
    ]
    for index, count in enumerate(counts):
        bar = int(height * count / peak)
        x = 20 + index * (width + gap)
        label = labels[index]
        svg.append(
            f"<rect class='bar' x='{x}' y='{height - bar + 15}' width='{width}' "
            f"height='{bar}'><title>{count} cases</title></rect>"
        )
        svg.append(
            f"<text class='axis' x='{x + width / 2}' y='{height - bar + 11}' "
            f"text-anchor='middle'>{count}</text>"
        )
        svg.append(
            f"<text class='axis' x='{x + width / 2}' y='{height + 32}' "
            f"text-anchor='middle'>{label}</text>"
        )
    svg.append("</svg>")
    return [*out, "".join(svg)]


def build(lines: list[dict], title: str, base: Path) -> str:
    """The page (see the module docstring); links to files relative to ``base``."""
    items, principles = _items(lines)
    anchors = {id(item): f"case-{index + 1}" for index, item in enumerate(items)}
    failed = [item for item in items if item.errors]
    versions = sorted(
        {str(line.get("ethasp_version")) for line in lines if line.get("ethasp_version")}
    )
    tasks = sorted({str(line.get("task")) for line in lines if line.get("task")})
    cases = len({item.case for item in items})
    out = [
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
        f"<title>{_e(title)}</title><style>{STYLE}</style></head><body>",
        f"<h1>{_e(title)}</h1>",
        f"<p>{cases} cases, {len(lines)} lines, {len(principles)} principles"
        f"{' (task ' + _e(', '.join(tasks)) + ')' if tasks else ''}; "
        f"<a href='#failed'>{len({item.case for item in failed})} cases failed</a>; "
        f"ethasp {_e(', '.join(versions) or 'unknown')}; drawn "
        f"{_e(time.strftime('%Y-%m-%d %H:%M'))}.</p>",
        "<p><a href='#verdicts'>verdicts</a> &middot; <a href='#agreement'>agreement</a> "
        "&middot; <a href='#times'>times</a> &middot; <a href='#slowest'>slowest</a> "
        "&middot; <a href='#failed'>failed</a> &middot; <a href='#cases'>cases</a></p>",
    ]
    out += _verdict_table(items, principles)
    out += _agreement(items, principles, anchors)
    timed = [item for item in items if item.seconds is not None]
    per_case: dict[str, float] = {}
    for item in timed:
        per_case[item.case] = max(per_case.get(item.case, 0.0), item.seconds)
    out += _histogram(list(per_case.values()))
    out.append(
        "<h2 id='slowest'>Slowest cases</h2><table><tr><th class=l>case</th><th>time</th></tr>"
    )
    for item in sorted(timed, key=lambda item: -item.seconds)[:SLOWEST]:
        out.append(
            f"<tr><td class=l><a href='#{anchors[id(item)]}'>{_e(item.title)}</a></td>"
            f"<td>{_seconds(item.seconds)}</td></tr>"
        )
    out.append("</table>")
    out.append(f"<h2 id='failed'>Failed cases ({len(failed)})</h2>")
    if failed:
        out.append(
            "<table><tr><th class=l>case</th><th class=l>principle</th><th class=l>error</th></tr>"
        )
        for item in failed:
            for line in item.errors:
                out.append(
                    f"<tr><td class=l><a href='#{anchors[id(item)]}'>{_e(item.title)}"
                    f"</a></td><td class=l>{_e(line.get('principle') or 'all')}</td>"
                    f"<td class=l>{_e(line.get('error'))}</td></tr>"
                )
        out.append("</table>")
    else:
        out.append("<p>None.</p>")
    out.append(
        "<h2 id='cases'>Cases</h2><p><small>P permissible, I impermissible, ? "
        "undecided, E error; a verdict in italics is bounded.</small></p><table><tr>"
        "<th class=l>#</th><th class=l>case</th>"
    )
    out += [f"<th title='{_e(p)}'>{index + 1}</th>" for index, p in enumerate(principles)]
    out.append("<th>time</th></tr>")
    for item in items:
        files = " ".join(
            f"<a href='{_href(file, base)}'>{_e(Path(file).name)}</a>" for file in item.files
        )
        out.append(
            f"<tr id='{anchors[id(item)]}'><td class=l>{anchors[id(item)][5:]}</td>"
            f"<td class=l>{_e(item.title)}<br><small>{files}</small></td>"
        )
        for principle in principles:
            line = item.verdicts.get(principle)
            verdict = _verdict(line)
            short = SHORT[verdict]
            css = {"P": "P", "I": "I", "?": "Q", "E": "E"}.get(short, "")
            shown = (
                f"<i>{short}</i>" if line is not None and line.get("status") == "bounded" else short
            )
            hint = _e(
                f"{principle}: {verdict}"
                + (f" ({line.get('error')})" if verdict == "error" else "")
            )
            out.append(f"<td class='{css}' title='{hint}'>{shown}</td>")
        out.append(f"<td>{_seconds(item.seconds) if item.seconds is not None else ''}</td></tr>")
    out.append(
        "</table><p><small>Principles: "
        + "; ".join(f"{index + 1}. {_e(p)}" for index, p in enumerate(principles))
        + "</small></p>"
    )
    out.append("</body></html>\n")
    return "\n".join(out)


def write_report(results: str | os.PathLike, destination: str | os.PathLike) -> Path:
    """Draw the report of a results file into ``destination`` (HTML); returns its path."""
    lines = load(results)
    destination = Path(destination)
    base = destination.resolve().parent
    page = build(lines, f"ethasp batch report: {Path(results).name}", base)
    destination.write_text(page, encoding="utf-8")
    return destination
