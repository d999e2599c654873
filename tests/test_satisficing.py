"""Any-plan search (--satisficing): valid plans, not claimed shortest, permissible
under principles; against the oracle and on IPC instances."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import MODELS, ROOT, answer_sets
from hypothesis import given, settings
from hypothesis import strategies as st
from oracle import features, random_model

from ethasp import InputError, Model, find_plan, plan_with_principles, validate
from ethasp.principles.judgement import judge
from ethasp.questions.contrast import ask
from ethasp.questions.dialogue import Dialogue

RESCUE = str(MODELS / "rescue.lp")
DATA = Path(__file__).resolve().parent / "data" / "ipc"
# More IPC instances, from a folder of domain folders (domain.pddl, pN.pddl) named by
# ETHASP_IPC; the tests that read them are skipped without it.
IPC_FOLDER = Path(os.environ["ETHASP_IPC"]) if os.environ.get("ETHASP_IPC") else None


def ethasp(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )


# -- the encoding ----------------------------------------------------------------


def plans(horizon: int, model: str, heuristic: bool) -> set[tuple[str, ...]]:
    files = ["planning/plan.lp"] + (["planning/satisficing.lp"] if heuristic else [])
    arguments = ("0", "-c", f"horizon={horizon}") + (("--heuristic=Domain",) if heuristic else ())
    result = set()
    for answer in answer_sets(files, model, arguments=arguments):
        steps = sorted(
            (int(a.split(",")[-1].rstrip(")")), a[len("occurs(") : a.rindex(",")])
            for a in answer
            if a.startswith("occurs(")
        )
        result.add(tuple(name for _, name in steps))
    return result


def test_the_heuristic_removes_no_plan():
    model = (MODELS / "rescue.lp").read_text()
    for horizon in (3, 5):
        assert plans(horizon, model, True) == plans(horizon, model, False)


# -- the API ---------------------------------------------------------------------


@pytest.mark.slow
@settings(max_examples=80, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.booleans())
def test_any_plan_is_a_plan_and_none_is_proven(seed, conditional):
    spec = random_model(
        seed, far_goal=seed % 2 == 0, **dict(features(seed), conditional=conditional)
    )
    model = Model.from_string(spec.to_asp())
    result = find_plan(model, max_horizon=20, satisficing=True)
    expected = spec.shortest_plan_length()
    if expected is None:
        assert result.status == "none", result
    else:
        assert result.status == "found", result
        assert not result.optimal and result.to_json()["optimal"] is False
        plan = [str(a) for a in result.plan]
        assert spec.is_plan(plan) and len(plan) >= expected


def test_find_plan_json_says_optimal():
    model = Model.load([RESCUE])
    shortest = find_plan(model)
    assert shortest.optimal and shortest.to_json()["optimal"] is True
    anyone = find_plan(model, satisficing=True)
    assert anyone.status == "found" and anyone.to_json()["optimal"] is False
    assert validate(model, anyone.plan).valid
    assert anyone.proof == "a plan found by greedy forward search (not proven shortest)"


def test_all_plans_cannot_be_satisficing():
    with pytest.raises(InputError):
        find_plan(Model.load([RESCUE]), all_plans=True, satisficing=True)


@pytest.mark.parametrize("principle", ["deontology", "do-no-harm", "utilitarianism"])
def test_satisficing_plans_under_principles_are_permissible(principle):
    model = Model.load([RESCUE])
    result = plan_with_principles(model, [principle], satisficing=True)
    assert result.status == "found" and not result.optimal
    assert result.to_json()["optimal"] is False
    report = judge(model, result.plan, [principle])
    assert report.judgements[0].permissible


@pytest.mark.slow
@settings(max_examples=40, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.sampled_from(["deontology", "do-no-harm"]))
def test_satisficing_hplans_against_the_oracle(seed, principle):
    spec = random_model(seed, **features(seed))
    model = Model.from_string(spec.to_asp())
    result = plan_with_principles(model, [principle], max_horizon=12, satisficing=True)
    expected = spec.shortest_permissible_length([principle])
    if expected is None:
        assert result.status in ("none", "bounded"), result
    else:
        assert result.status == "found", result
        plan = [str(a) for a in result.plan]
        assert spec.is_plan(plan) and spec.permissible(plan, principle)


def test_ask_and_dialogue_with_satisficing():
    model = Model.load([MODELS / "trolley.lp"])
    answer = ask(model, "why refrain rather than pull", principle="do-no-harm", satisficing=True)
    assert answer.contrast is not None and answer.to_json()["optimal"] is False
    dialogue = Dialogue.start(model, "do-no-harm", satisficing=True)
    answer = dialogue.ask("why refrain rather than pull")
    assert answer.contrast is not None and answer.to_json()["optimal"] is False


# -- the command line ------------------------------------------------------------


def test_cli_plan_satisficing_json_and_text():
    run = ethasp("plan", RESCUE, "--satisficing", "--json")
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data["status"] == "found" and data["optimal"] is False
    check = ethasp("validate", RESCUE, "--plan", " ".join(data["plan"]))
    assert check.returncode == 0, check.stdout
    run = ethasp("plan", RESCUE, "--satisficing")
    assert "(not proven shortest)" in run.stdout
    run = ethasp("plan", RESCUE, "--json")
    assert json.loads(run.stdout)["optimal"] is True


def test_cli_satisficing_with_principle_ask_and_refusal():
    run = ethasp("plan", RESCUE, "--satisficing", "--principle", "do-no-harm", "--json")
    data = json.loads(run.stdout)
    assert data["status"] == "found" and data["optimal"] is False
    assert all(j["permissible"] for j in data["judgements"])
    run = ethasp(
        "ask",
        str(MODELS / "trolley.lp"),
        "--principle",
        "do-no-harm",
        "--question",
        "why refrain rather than pull",
        "--satisficing",
        "--json",
    )
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["optimal"] is False
    run = ethasp("plan", RESCUE, "--satisficing", "--all")
    assert run.returncode == 2 and run.stderr.count("\n") == 1 and "--satisficing" in run.stderr


def test_cli_dialogue_takes_satisficing(tmp_path):
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "ethasp.interfaces.cli",
            "dialogue",
            str(MODELS / "trolley.lp"),
            "--principle",
            "do-no-harm",
            "--satisficing",
            "--save",
            str(tmp_path / "d.json"),
        ],
        input="why refrain rather than pull\nquit\n",
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert run.returncode == 0, run.stderr
    assert "pull" in run.stdout


# -- IPC instances ---------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize("domain", sorted(path.name for path in DATA.iterdir() if path.is_dir()))
def test_ipc_first_instances_satisficing(domain):
    folder = DATA / domain
    model = Model.load([folder / "domain.pddl", folder / "p1.pddl"])
    result = find_plan(model, satisficing=True)
    assert result.status == "found" and validate(model, result.plan).valid


@pytest.mark.skipif(
    IPC_FOLDER is None or not IPC_FOLDER.is_dir(),
    reason="ETHASP_IPC names no folder of IPC domains",
)
@pytest.mark.parametrize(
    "instance, length",
    [
        ("gripper-round-1-strips/p5", 35),
        ("logistics-strips-typed/p4", 27),
        ("blocks-strips-typed/p6", 16),
        ("elevator-strips-simple-typed/p8", 7),
    ],
)
def test_ipc_instances_with_long_plans_are_solved_optimally(instance, length):
    folder, problem = instance.split("/")
    model = Model.load(
        [IPC_FOLDER / folder / "domain.pddl", IPC_FOLDER / folder / f"{problem}.pddl"]
    )
    result = find_plan(model)
    assert result.status == "found" and result.optimal and len(result.plan) == length
    assert validate(model, result.plan).valid
