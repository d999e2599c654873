"""The references of the package's docstrings (Sphinx roles such as
``:class:`ethasp.planning.model.Model```, and dotted names in double back
quotes such as ``ethasp.reasons.DEFAULT_LIMIT``) name what exists: a module,
or an attribute of one.  The API reference shows them, so a stale name misleads."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ROLE = re.compile(r":(?:class|func|mod|meth|attr|data|exc):`~?(ethasp(?:\.\w+)+)(?:\(\))?`")
LITERAL = re.compile(r"``(ethasp(?:\.\w+)+)(?:\(\))?``")


def resolves(name: str) -> bool:
    """Is ``name`` a module, or an attribute (of an attribute ...) of one?"""
    parts = name.split(".")
    for split in range(len(parts), 0, -1):
        try:
            target = importlib.import_module(".".join(parts[:split]))
        except ImportError:
            continue
        for attribute in parts[split:]:
            if not hasattr(target, attribute):
                return False
            target = getattr(target, attribute)
        return True
    return False


def test_docstring_references_resolve():
    names = set()
    for path in sorted((ROOT / "ethasp").rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        names |= {(path.name, m.group(1)) for m in ROLE.finditer(text)}
        names |= {(path.name, m.group(1)) for m in LITERAL.finditer(text)}
    assert len(names) > 50
    stale = sorted(f"{file}: {name}" for file, name in names if not resolves(name))
    assert stale == []
