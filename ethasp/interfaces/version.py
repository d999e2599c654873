"""The version of ethasp, written in one place: ``version`` in ``pyproject.toml``.

An installed package reads it from its metadata, which the installation wrote
from ``pyproject.toml``.  Run from a checkout (an editable install, or the
source folder on the path), ethasp reads the checkout's ``pyproject.toml``
itself: an editable install's metadata is written when it is installed and
would miss a later change of the version.
"""

from __future__ import annotations

import re
from pathlib import Path

# The checkout's pyproject.toml, when this package is the one in its source folder.
PYPROJECT = Path(__file__).resolve().parents[2] / "pyproject.toml"
_PROJECT = re.compile(r"^\[project\]\s*$(.*?)(?=^\[|\Z)", re.M | re.S)
_FIELD = re.compile(r'^(name|version)\s*=\s*"([^"]*)"\s*$', re.M)


def checkout_version(path: Path = PYPROJECT) -> str | None:
    """The version that ``path`` (a pyproject.toml) gives ethasp, or None when
    it is not ethasp's or cannot be read."""
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return None
    table = _PROJECT.search(text)
    fields = dict(_FIELD.findall(table.group(1))) if table else {}
    return fields.get("version") if fields.get("name") == "ethasp" else None


def package_version() -> str:
    """ethasp's version: the checkout's when it runs from one, else the installed
    package's (``unknown`` for neither)."""
    found = checkout_version()
    if found:
        return found
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("ethasp")
    except PackageNotFoundError:
        return "unknown"
