"""The documentation: the site builds with ``mkdocs build --strict`` (broken
links, missing pages and unresolved references fail it), and the README is a
front page whose links lead somewhere.

The build needs the ``docs`` extra; without it the test is skipped, unless
``ETHASP_REQUIRE_DOCS=1`` (set by ``.ci/run``), when it must run.
"""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
LINK = re.compile(r"\]\(([^)\s]+)\)")


@pytest.mark.slow  # a build of the whole site, the API reference included
def test_the_site_builds_strictly(tmp_path):
    if importlib.util.find_spec("mkdocs") is None:
        if os.environ.get("ETHASP_REQUIRE_DOCS") == "1":
            raise AssertionError("mkdocs is not installed: pip install '.[docs]'")
        pytest.skip("mkdocs is not installed (pip install '.[docs]')")
    site = tmp_path / "site"
    run = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert run.returncode == 0, run.stderr[-5000:]
    # The generated tables are there.
    principles = (site / "principles" / "index.html").read_text()
    assert "kantian-humanity-2" in principles and "Definition 3 of the paper" in principles
    cam = (site / "models" / "cam" / "index.html").read_text()
    assert "KantianHumanityPrincipleReading2" in cam and "HERA 0.22.3" in cam
    assert "ethasp.planning.driver.planner" in (site / "architecture" / "index.html").read_text()
    assert "find_plan" in (site / "api" / "index.html").read_text()


def test_the_readme_is_a_front_page():
    text = README.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 200
    for target in LINK.findall(text):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        assert (ROOT / target.split("#")[0]).exists(), target
    # It links to every page of the site's navigation.
    nav = re.findall(r"^\s*-[^#\n]*:\s*([\w/-]+\.md)\s*$", (ROOT / "mkdocs.yml").read_text(), re.M)
    linked = {target.split("#")[0] for target in LINK.findall(text)}
    missing = [
        page
        for page in nav
        if f"docs/{page}" not in linked and page not in ("index.md", "changelog.md")
    ]
    assert not missing, missing
