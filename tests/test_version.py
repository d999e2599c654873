"""The version comes from one place, ``pyproject.toml``: ``ethasp --version``
and the footer of the web page show it, as the installed package (editable or
not) or the checkout reads it."""

from __future__ import annotations

import re
import subprocess
import sys

import pytest
from conftest import MODELS, ROOT

from ethasp import Model
from ethasp.interfaces.version import checkout_version, package_version
from ethasp.interfaces.web.app import create_app
from ethasp.interfaces.web.workspace import Workspace

tomllib = pytest.importorskip("tomllib", reason="tomllib needs Python 3.11")

VERSION = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]


def test_the_version_is_pyprojects():
    assert package_version() == VERSION
    assert checkout_version(ROOT / "pyproject.toml") == VERSION


def test_version_on_the_command_line():
    run = subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", "--version"],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert run.returncode == 0 and run.stdout == f"ethasp {VERSION}\n", run.stderr


def test_version_in_the_footer_of_the_page():
    trolley = str(MODELS / "trolley.lp")
    client = create_app(Workspace(Model.load([trolley]), [trolley], "do-no-harm")).test_client()
    page = client.get("/").get_data(as_text=True)
    assert re.search(r'<footer>.*id="version".*</footer>', page, re.S)
    assert client.get("/api/model").json["version"] == VERSION
    # The page writes it into the footer (the browser test sees it there).
    script = client.get("/static/app.js").get_data(as_text=True)
    assert '$("version").textContent = `ethasp ${model.version}`' in script


def test_only_ethasps_own_pyproject_counts(tmp_path):
    path = tmp_path / "pyproject.toml"
    assert checkout_version(path) is None  # none there
    path.write_text('[project]\nname = "ethasp"\nversion = "9.8.7"\n\n[tool.x]\nversion = "1"\n')
    assert checkout_version(path) == "9.8.7"
    path.write_text('[project]\nname = "other"\nversion = "9.8.7"\n')
    assert checkout_version(path) is None
    path.write_bytes(b"\xff\xfe")
    assert checkout_version(path) is None
