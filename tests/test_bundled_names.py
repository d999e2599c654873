"""The naming rule of the bundled models, as a user meets it outside the
checkout: every name of the README's table works in the commands, in
``ethasp batch`` (files and folders) and in ``Model.load``, and on the page;
a file or folder where the user is comes first."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import urllib.request
from pathlib import Path

import pytest
from conftest import MODELS, ROOT

from ethasp.resources import bundled_model, bundled_names

pytestmark = pytest.mark.slow  # real processes

WAIT = 120


def python(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        timeout=WAIT,
    )


def ethasp(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return python("-m", "ethasp.interfaces.cli", *args, cwd=cwd)


def readme_names() -> list[list[str]]:
    """The names of the README's table of bundled models (a row for each D)."""
    text = (ROOT / "README.md").read_text()
    section = text.split("[start:models]")[1].split("[end:models]")[0]
    found = []
    for row in re.findall(r"^\| `([^`]+)` \|(.*)\|$", section, re.M):
        name, what = row
        if " D" in what or "D-" in name:
            for domain in re.findall(r"`([\w-]+)`", what):
                found.append(name.replace("D-", f"{domain}-").replace("/D.", f"/{domain}.").split())
        else:
            found.append(name.split())  # a model of several files
    return found


def test_the_readme_names_every_bundled_model():
    names = {name for row in readme_names() for name in row}
    assert {"trolley", "hera/robot-and-frank.yaml", "pddl/gripper-domain.pddl"} <= names
    assert names == set(bundled_names())


@pytest.mark.parametrize("names", readme_names(), ids=lambda names: names[0])
def test_every_name_of_the_readme_works_outside_the_checkout(names, tmp_path):
    principle = "hera-deontology" if names[0].startswith("cam/") else "deontology"
    run = ethasp("plan", *names, "--principle", principle, "--json", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["status"] in ("found", "none")
    assert "warning" not in run.stderr  # the bundled files are as they should be


def test_folder_and_asp_prefix_and_short_names(tmp_path):
    run = ethasp("judge", "asp/hera/robot-and-frank.yaml", "--principle", "hera", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    run = ethasp("judge", "robot-and-frank.yaml", "--principle", "deontology", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    run = ethasp("plan", "asp/trolley", cwd=tmp_path)
    assert run.returncode == 0 and run.stdout.startswith("plan of 1 step"), run.stderr
    run = ethasp("plan", "hera/robot", cwd=tmp_path)
    assert run.returncode == 2 and "hera/robot: no such file" in run.stderr


@pytest.mark.parametrize("folder", ["hera", "asp/hera"])
def test_batch_takes_a_bundled_folder_by_its_name(folder, tmp_path):
    run = ethasp("batch", folder, "-o", "out.jsonl", "--quiet", "--workers", "1", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    lines = [json.loads(line) for line in (tmp_path / "out.jsonl").read_text().splitlines()]
    assert {line["case"] for line in lines} == {"hera/robot-and-frank.yaml", "hera/trolley.yaml"}


def test_batch_takes_bundled_files_and_pddl_by_their_names(tmp_path):
    pddl = ["pddl/care-domain.pddl", "pddl/care-problem.pddl", "pddl/care-utility.lp"]
    run = ethasp(
        "batch", "trolley", *pddl, "-o", "out.jsonl", "--quiet", "--workers", "1", cwd=tmp_path
    )
    assert run.returncode == 0, run.stderr
    lines = [json.loads(line) for line in (tmp_path / "out.jsonl").read_text().splitlines()]
    assert {line["case"] for line in lines} == {"trolley.lp", " + ".join(pddl)}
    (tmp_path / "cases.csv").write_text("files\ntrolley\nhera/trolley.yaml\n")
    run = ethasp("batch", "cases.csv", "-o", "more.jsonl", "--quiet", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    lines = [json.loads(line) for line in (tmp_path / "more.jsonl").read_text().splitlines()]
    assert {line["case"] for line in lines} == {"trolley.lp", "hera/trolley.yaml"}


def test_a_folder_where_the_user_is_comes_first(tmp_path):
    (tmp_path / "hera").mkdir()
    (tmp_path / "hera" / "mine.lp").write_text((MODELS / "trolley.lp").read_text())
    run = ethasp("batch", "hera", "-o", "out.jsonl", "--quiet", "--workers", "1", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    lines = [json.loads(line) for line in (tmp_path / "out.jsonl").read_text().splitlines()]
    assert {line["case"] for line in lines} == {str(Path("hera") / "mine.lp")}


def test_model_load_takes_the_names(tmp_path):
    program = (
        "from ethasp import Model\n"
        "for names in (['trolley'], ['hera/robot-and-frank.yaml'], ['asp/footbridge.lp'],"
        " ['pddl/gripper-domain.pddl', 'pddl/gripper-problem.pddl']):\n"
        "    print(len(Model.load(names).sources))\n"
    )
    run = python("-c", program, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert run.stdout.split() == ["1", "1", "1", "1"]


def test_the_page_serves_a_bundled_model_by_its_name(tmp_path):
    process = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "ethasp.interfaces.cli",
            "serve",
            "hera/trolley.yaml",
            "--port",
            "0",
        ],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=tmp_path,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    try:
        line = process.stdout.readline()
        match = re.search(r" at (http://\S+/)$", line.strip())
        assert match, line + process.stderr.read()
        with urllib.request.urlopen(match.group(1) + "api/model", timeout=WAIT) as reply:
            assert json.loads(reply.read())["files"] == ["trolley.yaml"]
    finally:
        process.send_signal(signal.SIGINT)
        process.wait(timeout=WAIT)


def test_names_stay_inside_the_bundled_folder():
    assert bundled_model("trolley") == MODELS / "trolley.lp"
    assert bundled_model("asp") == MODELS and bundled_model("hera") == MODELS / "hera"
    assert bundled_model("robot-and-frank.yaml") == MODELS / "hera" / "robot-and-frank.yaml"
    for name in ("../asp/trolley.lp", "hera/../../README.md", str(MODELS / "trolley.lp"), "*.lp"):
        assert bundled_model(name) is None, name
    assert bundled_model("") is None and bundled_model("nothing") is None
