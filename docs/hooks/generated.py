"""MkDocs hook: tables generated from the sources when the site is built.

A page line that is one of these placeholders is replaced:

``<!-- principles: table -->``
    one row per file of ``encodings/principles/``: the name ``--principle``
    takes, the first paragraph of the encoding's header (what the principle
    permits), and the first paragraph of the header of
    ``encodings/restrictions/NAME.lp`` (plan generation), or that there is none;
``<!-- principles: headers -->``
    the complete header comments of those files, folded;
``<!-- cam principles: table -->``
    one row per file of ``encodings/principles/cam/`` (the principles of
    causal agency models, in the order of ``--principle hera``): the name
    ``--principle`` takes, HERA's class (the first name ending in
    ``Principle...`` that the header gives), and the first paragraph of the
    header;
``<!-- encodings: table -->``
    one row per encoding outside ``principles/`` and ``restrictions/``, with the
    first sentence of its header;
``<!-- modules: table -->``
    one row per module of the ``ethasp`` package, with the first line of its
    docstring.

So these tables are as true as the headers and docstrings they come from: a new
file appears on the next build, and nothing is kept by hand in two places.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
ENCODINGS = ROOT / "encodings"
PRINCIPLES = ENCODINGS / "principles"
CAM_PRINCIPLES = PRINCIPLES / "cam"
RESTRICTIONS = ENCODINGS / "restrictions"
PACKAGE = ROOT / "ethasp"
# The paper's three first, in its order, then the others by name.
PAPER = ["deontology", "utilitarianism", "do_no_harm"]
# Encoding folders in the order a reader meets them.
FOLDERS = ["planning", "judgement", "reasons", "questions"]
PACKAGES = [
    "",
    "vocabulary",
    "planning",
    "planning/readers",
    "planning/driver",
    "planning/engines",
    "principles",
    "reasons",
    "questions",
    "interfaces",
    "interfaces/cli",
    "interfaces/web",
]


def header(path: Path) -> list[str]:
    """The leading comment lines of an encoding, without their ``%``."""
    lines = []
    for line in path.read_text(encoding="utf-8").splitlines():
        if not line.startswith("%"):
            break
        lines.append(line[1:].removeprefix(" ").rstrip())
    return lines


def paragraphs(lines: list[str]) -> list[str]:
    """The header's paragraphs, each joined into one line of text."""
    found, current = [], []
    for line in [*lines, ""]:
        if line.strip():
            current.append(line.strip())
        elif current:
            found.append(" ".join(current))
            current = []
    return found


def summary(path: Path) -> str:
    """The first paragraph of a header: what the encoding is about."""
    found = paragraphs(header(path))
    if not found or found[0].startswith(("Reads:", "Defines:")):
        raise ValueError(f"{path.relative_to(ROOT)}: the header does not start with a description")
    return found[0]


def first_sentence(path: Path) -> str:
    """The header's first sentence (sentences end with a full stop and two
    spaces, or at the end of a line)."""
    lines = header(path)
    text = "\n".join(lines[: lines.index("")] if "" in lines else lines)
    match = re.search(r"[.:](?: {2,}|\n|$)", text)
    sentence = text[: match.start() + 1] if match else text
    sentence = " ".join(sentence.split()).rstrip(":")
    return sentence if sentence.endswith((".", "?", "!")) else sentence + "."


def escape(text: str) -> str:
    """Text shown as it is written, in a Markdown table cell."""
    text = text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    for char in "\\`*_[]|":
        text = text.replace(char, "\\" + char)
    return text


CODE = re.compile(r"(?::[a-z]+:)?``?~?([^`]+?)``?")


def inline(text: str) -> str:
    """A docstring's reST inline text in Markdown: ``code`` and Sphinx roles
    (:mod:`name`) become code spans, everything else is shown as written."""
    parts, end = [], 0
    for match in CODE.finditer(text):
        parts.append(escape(text[end : match.start()]))
        parts.append(f"`{match.group(1)}`")
        end = match.end()
    parts.append(escape(text[end:]))
    return "".join(parts)


def principle_names() -> list[str]:
    stems = sorted(path.stem for path in PRINCIPLES.glob("*.lp"))
    return [s for s in PAPER if s in stems] + [s for s in stems if s not in PAPER]


def principles_table() -> str:
    rows = [
        "| `--principle` | permissible iff (`encodings/principles/`) "
        "| plan generation, the HModel (`encodings/restrictions/`) |",
        "| --- | --- | --- |",
    ]
    for stem in principle_names():
        restriction = RESTRICTIONS / f"{stem}.lp"
        plans = (
            escape(summary(restriction))
            if restriction.exists()
            else "none: judged, explained and asked about, but `ethasp plan --principle` "
            "refuses it ([why](#why-five-principles-generate-no-plans))"
        )
        rows.append(
            f"| `{stem.replace('_', '-')}` | {escape(summary(PRINCIPLES / f'{stem}.lp'))} "
            f"| {plans} |"
        )
    return "\n".join(rows)


def principles_headers() -> str:
    blocks = []
    for stem in principle_names():
        for path in (PRINCIPLES / f"{stem}.lp", RESTRICTIONS / f"{stem}.lp"):
            if path.exists():
                text = "\n".join("    " + line if line else "" for line in header(path))
                blocks.append(
                    f'??? note "{path.relative_to(ROOT).as_posix()}"\n\n'
                    f"    ```text\n{text}\n    ```\n"
                )
    return "\n".join(blocks)


HERA_CLASS = re.compile(r"\b[A-Z][A-Za-z]*Principle[A-Za-z0-9]*\b")


def cam_principles_table() -> str:
    rows = [
        "| `--principle` | HERA's class (`ethics.cam.principles`) "
        "| permissible iff (`encodings/principles/cam/`) |",
        "| --- | --- | --- |",
    ]
    from ethasp.principles.principle import HERA_CAM  # the order of `--principle hera`

    stems = sorted(path.stem for path in CAM_PRINCIPLES.glob("*.lp"))
    order = [n.replace("-", "_") for n in HERA_CAM if n.replace("-", "_") in stems]
    for stem in order + [s for s in stems if s not in order]:
        path = CAM_PRINCIPLES / f"{stem}.lp"
        text = summary(path)
        found = HERA_CLASS.search(" ".join(header(path)))
        if found is None:
            raise ValueError(f"{path.relative_to(ROOT)}: the header names no class of HERA's")
        rows.append(f"| `{path.stem.replace('_', '-')}` | `{found.group(0)}` | {escape(text)} |")
    return "\n".join(rows)


def encodings_table() -> str:
    rows = ["| encoding | what its header says it is |", "| --- | --- |"]
    folders = FOLDERS + sorted(
        p.name
        for p in ENCODINGS.iterdir()
        if p.is_dir() and p.name not in [*FOLDERS, "principles", "restrictions"]
    )
    for folder in folders:
        for path in sorted((ENCODINGS / folder).glob("*.lp")):
            rows.append(f"| `{folder}/{path.name}` | {escape(first_sentence(path))} |")
    rows.append(
        "| `principles/*.lp` | the formula of each ethical principle "
        "([Principles](principles.md)) |"
    )
    rows.append(
        "| `restrictions/*.lp` | plan search restricted to the plans a principle "
        "permits, the HModels ([Principles](principles.md)) |"
    )
    return "\n".join(rows)


def modules_table() -> str:
    rows = ["| module | what its docstring says it is |", "| --- | --- |"]
    found = {
        p.relative_to(PACKAGE).parent.as_posix().replace(".", "")
        for p in PACKAGE.rglob("__init__.py")
    }
    packages = [p for p in PACKAGES if p in found] + sorted(found - set(PACKAGES))
    for package in packages:
        for path in sorted((PACKAGE / package).glob("*.py")):
            if path.name == "__init__.py":
                continue
            name = ".".join(["ethasp", *[p for p in package.split("/") if p], path.stem])
            doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
            line = " ".join(doc.split("\n\n")[0].split()) or "(no docstring)"
            rows.append(f"| `{name}` | {inline(line)} |")
    return "\n".join(rows)


def engines_contract() -> str:
    """The docstring of ethasp.planning.engines (the contract), in Markdown,
    without its first line (the page has its own heading)."""
    path = PACKAGE / "planning" / "engines" / "__init__.py"
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
    body = doc.split("\n\n", 1)[1]
    return CODE.sub(lambda match: f"`{match.group(1)}`", body)


PLACEHOLDERS = {
    "<!-- engines: contract -->": engines_contract,
    "<!-- principles: table -->": principles_table,
    "<!-- principles: headers -->": principles_headers,
    "<!-- cam principles: table -->": cam_principles_table,
    "<!-- encodings: table -->": encodings_table,
    "<!-- modules: table -->": modules_table,
}


def on_page_markdown(markdown: str, page, config, files) -> str:
    for placeholder, make in PLACEHOLDERS.items():
        if placeholder in markdown:
            table = make()
            if table.startswith("|"):  # names in the first column, on one line
                table = f'<div class="names-table" markdown>\n\n{table}\n\n</div>'
            markdown = markdown.replace(placeholder, table)
    return markdown
