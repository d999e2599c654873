"""The command line of the planning core: ethasp plan and ethasp validate."""

import json
import subprocess
import sys

from conftest import MODELS, ROOT

TROLLEY = str(MODELS / "trolley.lp")


def ethasp(*args: str, cwd=ROOT) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
    )


def test_plan_json_on_trolley():
    run = ethasp("plan", TROLLEY, "--json")
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data["status"] == "found" and len(data["plan"]) == 1
    assert data["plan"][0] in ("pull", "refrain")


def test_plan_text_and_all():
    run = ethasp("plan", TROLLEY, "--all")
    assert run.returncode == 0 and "pull" in run.stdout and "refrain" in run.stdout


def test_bundled_model_by_name_from_another_directory(tmp_path):
    run = ethasp("plan", "rescue", "--json", cwd=tmp_path)
    assert run.returncode == 0 and len(json.loads(run.stdout)["plan"]) == 4


def test_plan_bounded_and_none():
    run = ethasp("plan", str(MODELS / "rescue.lp"), "--max-horizon", "2", "--json")
    assert json.loads(run.stdout)["status"] == "bounded"
    run = ethasp("plan", str(MODELS / "rescue.lp"), "--max-horizon", "2")
    assert "bounded" in run.stdout and "may still exist" in run.stdout


def test_validate_reports_failure(tmp_path):
    run = ethasp("validate", str(MODELS / "heist.lp"), "--plan", "steal give_jewels")
    assert run.returncode == 2
    assert (
        "step 1: action steal is not applicable: precondition scouted does not hold" in run.stdout
    )
    run = ethasp(
        "validate", str(MODELS / "heist.lp"), "--plan", "scout steal give_jewels", "--json"
    )
    assert run.returncode == 0 and json.loads(run.stdout)["valid"] is True


def test_errors_are_one_line_with_exit_code_2(tmp_path):
    bad = tmp_path / "bad.lp"
    bad.write_text("variable(a).\ngoal(a,true)\naction(x).\n")
    for args, needle in [
        (("plan", str(bad)), "bad.lp:3"),
        (("plan", str(tmp_path / "missing.lp")), "no such file"),
        (("validate", TROLLEY, "--plan", "pull jump"), "unknown action jump"),
        (("validate", TROLLEY, "--plan", "pull("), "not an action term"),
    ]:
        run = ethasp(*args)
        assert run.returncode == 2, (args, run.stderr)
        assert needle in run.stderr, (args, run.stderr)
        assert len(run.stderr.strip().splitlines()) == 1 and "Traceback" not in run.stderr


def test_scripts_refused_unless_allowed(tmp_path):
    path = tmp_path / "script.lp"
    path.write_text("#script (python)\ndef f(): pass\n#end.\nvariable(a). init(a). goal(a,true).\n")
    run = ethasp("plan", str(path))
    assert run.returncode == 2 and "--allow-scripts" in run.stderr
    run = ethasp("plan", str(path), "--allow-scripts", "--json")
    assert run.returncode == 0 and json.loads(run.stdout)["plan"] == []


def test_installed_package_holds_every_encoding_and_model(tmp_path):
    """A non-editable install carries the encodings and bundled models (run from elsewhere)."""
    code = (
        "import ethasp.resources as r, json; "
        "print(json.dumps([sorted(str(p.relative_to(r.ENCODINGS))"
        " for p in r.ENCODINGS.rglob('*.lp')),"
        " sorted(str(p.relative_to(r.MODELS)) for p in r.MODELS.rglob('*') if p.is_file()"
        " and p.suffix in ('.lp', '.pddl', '.yaml', '.json'))]))"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    encodings, models = json.loads(run.stdout)
    assert encodings == sorted(
        str(p.relative_to(ROOT / "encodings")) for p in (ROOT / "encodings").rglob("*.lp")
    )
    assert models == sorted(
        str(p.relative_to(MODELS))
        for p in MODELS.rglob("*")
        if p.is_file() and p.suffix in (".lp", ".pddl", ".yaml", ".json")
    )


def test_time_limit_zero_means_none_and_negative_is_refused():
    run = ethasp("plan", TROLLEY, "--time-limit", "-1")
    assert run.returncode == 2 and "must be a number of seconds from 0" in run.stderr
    run = ethasp("plan", TROLLEY, "--time-limit", "0")
    assert run.returncode == 0 and run.stdout.startswith("plan of 1 step")
    assert "Traceback" not in run.stderr
