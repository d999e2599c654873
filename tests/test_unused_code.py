"""No dead code: every function, class and module-level name that the package
defines is named somewhere else (in the package, the tests, the
documentation or the benchmarks).  Names called by others' conventions are
left out: dunder names, ``visit_*`` methods of clingo's AST visitors, and
functions registered by decorators (the web server's routes)."""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FOLDERS = ("ethasp", "tests", "docs", "benchmarks")
SUFFIXES = (".py", ".md", ".js", ".html", ".lp", ".toml", ".yml")
PLAIN_DECORATORS = {"staticmethod", "classmethod", "property", "cache", "cached_property"}


def _plain(node: ast.AST) -> bool:
    """Is a definition called by name only (not registered by a decorator)?"""
    decorators = getattr(node, "decorator_list", [])
    return all(
        (isinstance(d, ast.Name) and d.id in PLAIN_DECORATORS)
        or (isinstance(d, ast.Attribute) and d.attr in PLAIN_DECORATORS)
        for d in decorators
    )


def definitions() -> list[tuple[str, str]]:
    """(file, name) of every function, class and module-level assignment."""
    found = []
    for path in sorted((ROOT / "ethasp").rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            kinds = (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)
            if isinstance(node, kinds) and _plain(node):
                found.append((path.relative_to(ROOT).as_posix(), node.name))
        for node in tree.body:
            if isinstance(node, ast.Assign):
                found += [
                    (path.relative_to(ROOT).as_posix(), target.id)
                    for target in node.targets
                    if isinstance(target, ast.Name)
                ]
    return [
        (file, name)
        for file, name in found
        if not name.startswith("__") and not name.startswith("visit_")
    ]


def test_every_definition_is_used():
    text = "\n".join(
        path.read_text(encoding="utf-8", errors="replace")
        for folder in FOLDERS
        for path in (ROOT / folder).rglob("*")
        if path.suffix in SUFFIXES and path.is_file()
    )
    text += (ROOT / "pyproject.toml").read_text()
    counts: dict[str, int] = {}
    for word in re.findall(r"\w+", text):
        counts[word] = counts.get(word, 0) + 1
    found = definitions()
    assert len(found) > 500
    unused = sorted(f"{file}: {name}" for file, name in found if counts.get(name, 0) < 2)
    assert unused == []
