"""ethasp plan --principle: HPlans on the command line, and the HPlanResult API."""

import json
import subprocess
import sys

from conftest import MODELS, ROOT
from ethasp import Model
from ethasp.principles.restriction import plan_with_principles

TROLLEY = str(MODELS / "trolley.lp")


def ethasp(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "ethasp.interfaces.cli", *args], capture_output=True,
                          text=True, cwd=ROOT)


def test_trolley_hplans_as_json_with_judgements():
    expected = {"deontology": None, "utilitarianism": ["pull"], "do-no-harm": ["refrain"]}
    for principle, plan in expected.items():
        run = ethasp("plan", TROLLEY, "--principle", principle, "--json")
        assert run.returncode == 0, run.stderr
        data = json.loads(run.stdout)
        assert data["status"] == "found" and data["principles"] == [principle]
        assert plan is None or data["plan"] == plan
        assert [j["principle"] for j in data["judgements"]] == [principle]
        assert all(j["permissible"] and j["status"] == "proven" for j in data["judgements"])
        assert ("best_utility" in data) == (principle == "utilitarianism")
    data = json.loads(ethasp("plan", "trolley", "--principle", "utilitarianism", "--json").stdout)
    assert data["best_utility"] == 4 and data["best_utility_status"] == "proven"


def test_several_principles_and_no_permissible_plan():
    run = ethasp("plan", "footbridge", "--principle", "deontology",
                 "--principle", "utilitarianism", "--json")
    data = json.loads(run.stdout)
    assert run.returncode == 0
    assert data["status"] == "none" and data["plan"] is None
    assert data["principles"] == ["deontology", "utilitarianism"] and data["best_utility"] == 4
    text = ethasp("plan", "footbridge", "--principle", "deontology",
                  "--principle", "utilitarianism").stdout
    assert text.startswith("no permissible plan exists")


def test_text_output_names_the_principle_and_the_verdict():
    run = ethasp("plan", TROLLEY, "--principle", "do-no-harm")
    assert run.stdout.startswith("plan of 1 step permissible under do-no-harm: refrain")
    assert "do-no-harm: permissible (proven)" in run.stdout
    # The HPlan's explanation is shown, as ethasp judge shows it.
    assert ("The man can refrain from action. Doing so is permissible because this way the "
            "death of the five persons is not caused by the man's action.") in run.stdout


def test_bounded_is_not_none():
    run = ethasp("plan", "rescue", "--principle", "utilitarianism", "--max-horizon", "3",
                 "--json")
    data = json.loads(run.stdout)
    assert data["status"] == "bounded" and data["plan"] is None
    assert data["best_utility_status"] == "bounded"


def test_unknown_principle_is_one_line_exit_2():
    run = ethasp("plan", TROLLEY, "--principle", "kantianism")
    assert run.returncode == 2
    assert run.stderr.strip().count("\n") == 0 and "unknown principle" in run.stderr


def test_api_rescue_under_every_principle():
    model = Model.load([MODELS / "rescue.lp"])
    plain = plan_with_principles(model, [])
    assert plain.status == "found" and len(plain.plan) == 4  # breaks the door
    deontic = plan_with_principles(model, ["deontology"])
    assert deontic.status == "found" and "break_door" not in map(str, deontic.plan)
    assert len(deontic.plan) == 5
    both = plan_with_principles(model, ["utilitarianism", "do_no_harm"])
    assert both.status == "found" and both.best.utility == 10
    assert {"put_down(p2,r4)", "put_down(p3,r4)"} <= set(map(str, both.plan))
