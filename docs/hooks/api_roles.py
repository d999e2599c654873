"""MkDocs hook: Sphinx roles in docstrings shown as plain code.

The docstrings of ``ethasp`` name other objects with Sphinx roles
(``:class:`Budget```, ``:func:`~ethasp.planning.search.any_plan```).  Rendered
as Markdown by mkdocstrings they would keep the role's prefix; this hook drops
it (and a leading ``~``, keeping the last part of the name, as Sphinx shows it).
"""

from __future__ import annotations

import re

ROLE = re.compile(r":(?:class|func|meth|mod|data|attr|exc|obj):<code>(~)?([^<]*)</code>")


def _plain(match: re.Match) -> str:
    name = match.group(2)
    if match.group(1):
        name = name.rsplit(".", 1)[-1]
    return f"<code>{name}</code>"


def on_page_content(html: str, page, config, files) -> str:
    return ROLE.sub(_plain, html)
