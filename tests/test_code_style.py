"""The code passes its linter, its formatter's check and the type check of
the public API, as configured in pyproject.toml."""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

pytestmark = pytest.mark.slow


def _run(*arguments: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", *arguments], cwd=ROOT, capture_output=True, text=True
    )


def test_ruff_check_finds_nothing():
    result = _run("ruff", "check", "--no-cache", ".")
    assert result.returncode == 0, result.stdout + result.stderr


def test_ruff_format_would_change_nothing():
    result = _run("ruff", "format", "--no-cache", "--check", ".")
    assert result.returncode == 0, result.stdout + result.stderr


def test_mypy_accepts_the_public_api():
    # The files and options are [tool.mypy] in pyproject.toml.
    result = _run("mypy", "--no-incremental", "--cache-dir", "/dev/null")
    assert result.returncode == 0, result.stdout + result.stderr


def test_the_type_check_covers_every_export():
    """Each lazy export is imported for type checkers from its home, and its
    home is among the files that mypy checks."""
    tomllib = pytest.importorskip("tomllib")
    import ethasp

    files = set(tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["mypy"]["files"])
    homes = {module.replace(".", "/") + ".py" for module in ethasp._HOMES.values()}
    assert homes <= files, homes - files
    tree = ast.parse((ROOT / "ethasp" / "__init__.py").read_text())
    typed = {
        alias.name: node.module
        for block in tree.body
        if isinstance(block, ast.If) and ast.unparse(block.test) == "TYPE_CHECKING"
        for node in block.body
        if isinstance(node, ast.ImportFrom)
        for alias in node.names
    }
    assert typed == ethasp._HOMES


def _given(function: ast.FunctionDef) -> bool:
    """Is a test decorated with Hypothesis's ``@given(...)``?"""
    for decorator in function.decorator_list:
        called = decorator.func if isinstance(decorator, ast.Call) else decorator
        name = called.attr if isinstance(called, ast.Attribute) else getattr(called, "id", "")
        if name == "given":
            return True
    return False


def _returns(function: ast.FunctionDef) -> list[ast.Return]:
    """The return statements of a function's own body (not of nested ones)."""
    found, stack = [], list(function.body)
    while stack:
        node = stack.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)):
            continue
        if isinstance(node, ast.Return):
            found.append(node)
        stack.extend(ast.iter_child_nodes(node))
    return found


def test_no_property_test_returns_early():
    """A property test that returns early passes without checking anything:
    an uninteresting draw is rejected with ``assume``, an expected outcome is
    asserted."""
    early = [
        f"{path.name}:{node.lineno} ({function.name})"
        for path in sorted((ROOT / "tests").glob("*.py"))
        for function in ast.walk(ast.parse(path.read_text()))
        if isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef)) and _given(function)
        for node in _returns(function)
    ]
    assert not early, early


def test_the_hypothesis_profile_is_loaded():
    """The property tests run under the profile that tests/conftest.py loads;
    under ``ci`` (set by .ci/run) every run draws the same examples."""
    from conftest import PROFILE
    from hypothesis import settings

    assert settings.get_current_profile_name() == PROFILE
    ci = settings.get_profile("ci")
    assert ci.derandomize and ci.database is None and ci.deadline is None
    assert "export HYPOTHESIS_PROFILE=ci" in (ROOT / ".ci" / "run").read_text()
    probe = subprocess.run(
        [
            sys.executable,
            "-c",
            "import conftest; from hypothesis import settings; "
            "print(settings.get_current_profile_name(), settings().derandomize)",
        ],
        cwd=ROOT / "tests",
        env={**os.environ, "HYPOTHESIS_PROFILE": "ci"},
        capture_output=True,
        text=True,
    )
    assert probe.stdout.split() == ["ci", "True"], probe.stderr


def test_every_package_is_installed():
    """Every package of ethasp is listed in pyproject.toml, so that a wheel (not
    only a checkout or an editable install) has it."""
    import tomllib

    listed = set(
        tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"]
    )
    found = {
        ".".join(path.parent.relative_to(ROOT).parts)
        for path in (ROOT / "ethasp").rglob("__init__.py")
    }
    assert found <= listed, sorted(found - listed)
