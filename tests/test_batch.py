"""ethasp batch on the local pool: cases, lines, resume, bad cases, dead workers, report, CLI."""

from __future__ import annotations

import json
import os
import signal
from pathlib import Path

import pytest
import yaml
from conftest import MODELS
from test_bad_inputs import FIXTURES, run_in_process

import ethasp
from ethasp.batch.cases import Case, discover
from ethasp.batch.output import read_lines
from ethasp.batch.report import write_report
from ethasp.batch.task import Settings
from ethasp.planning.model import Model
from ethasp.principles.principle import HERA

FIELDS = {
    "case",
    "principle",
    "permissible",
    "status",
    "plan",
    "utility",
    "seconds",
    "ethasp_version",
    "hash",
}


def variants(folder: Path, count: int) -> list[Path]:
    """Trolley situations with other utilities and plans (generated cases)."""
    base = yaml.safe_load((MODELS / "hera" / "trolley.yaml").read_text())
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for index in range(count):
        situation = json.loads(json.dumps(base))
        situation["utilities"][0]["utility"] = -1 - index % 7
        situation["utilities"][2]["utility"] = -1 - index % 3
        situation["plan"] = ["pull"] if index % 2 else ["refrain"]
        path = folder / f"trolley-{index:02d}.json"
        path.write_text(json.dumps(situation))
        paths.append(path)
    return paths


def run(*args, **kwargs) -> list[dict]:
    return list(ethasp.batch(*args, **kwargs))


def by_hash(lines: list[dict]) -> dict[str, dict]:
    hashes = [line["hash"] for line in lines]
    assert len(hashes) == len(set(hashes)), "a line twice"
    return {line["hash"]: line for line in lines}


def without_times(line: dict) -> dict:
    return {key: value for key, value in line.items() if key != "seconds"}


# -- cases ----------------------------------------------------------------------------------


def test_folders_pair_pddl_files_and_their_annotations():
    cases = discover([MODELS / "pddl"])
    assert len(cases) == 4
    for case in cases:
        stem = Path(case.files[0]).name.split("-")[0]
        assert [Path(name).name for name in case.files] == [
            f"{stem}-domain.pddl",
            f"{stem}-problem.pddl",
            f"{stem}-utility.lp",
        ]


def test_a_glob_chooses_file_names_in_folders(tmp_path):
    variants(tmp_path / "a" / "b", 3)
    (tmp_path / "a" / "other.lp").write_text("variable(x).\n")
    found = discover([tmp_path], "trolley-0[01].json")
    assert [Path(case.name).name for case in found] == ["trolley-00.json", "trolley-01.json"]
    assert len(discover([tmp_path])) == 4


def test_manifests_give_cases_their_plans_principles_and_questions(tmp_path):
    (tmp_path / "cases.csv").write_text(
        "name,files,plan,principles,questions\n"
        f'pulled,{MODELS / "trolley.lp"},pull,"deontology, utilitarianism",\n'
        f"asked,{MODELS / 'trolley.lp'},,deontology,why pull\n"
    )
    (tmp_path / "cases.yaml").write_text(
        yaml.safe_dump(
            {"cases": [{"files": [str(MODELS / "hera" / "trolley.yaml")], "principles": ["hera"]}]}
        )
    )
    csv_cases = discover([tmp_path / "cases.csv"])
    assert csv_cases[0] == Case(
        (str(MODELS / "trolley.lp"),), "pulled", "pull", ("deontology", "utilitarianism")
    )
    assert csv_cases[1].questions == ("why pull",)
    lines = run([tmp_path / "cases.csv", tmp_path / "cases.yaml"], workers=2)
    pulled = [line for line in lines if line["case"] == "pulled"]
    assert {line["principle"] for line in pulled} == {"deontology", "utilitarianism"}
    assert all(line["task"] == "judge" and line["plan"] == ["pull"] for line in pulled)
    asked = [line for line in lines if line["case"] == "asked"]
    assert len(asked) == 1 and asked[0]["task"] == "ask"
    assert asked[0]["question"] == "why pull" and asked[0]["contrast_plan"] is not None
    situation = [line for line in lines if line["case"].endswith("trolley.yaml")]
    assert sorted(line["principle"] for line in situation) == sorted(HERA)


def test_an_empty_list_in_a_yaml_manifest_is_the_empty_plan(tmp_path):
    """``plan: []`` gives the empty plan (judged: HERA's trolley situation
    misses its goal with it), an empty cell none (the model's own plan)."""
    situation = str(MODELS / "hera" / "trolley.yaml")
    (tmp_path / "cases.yaml").write_text(
        yaml.safe_dump(
            {
                "cases": [
                    {
                        "name": "empty",
                        "files": [situation],
                        "plan": [],
                        "principles": ["deontology"],
                    },
                    {"name": "own", "files": [situation], "plan": "", "principles": ["deontology"]},
                ]
            }
        )
    )
    cases = {case.name: case for case in discover([tmp_path / "cases.yaml"])}
    assert cases["empty"].plan == "" and cases["own"].plan is None
    lines = {line["case"]: line for line in run([tmp_path / "cases.yaml"], workers=1)}
    assert lines["empty"]["task"] == "judge" and lines["empty"]["plan"] == []
    assert lines["empty"]["goal_reached"] is False
    assert lines["own"]["plan"] == ["pull"]


def test_a_bad_manifest_is_refused_before_anything_runs(tmp_path):
    manifest = tmp_path / "bad.csv"
    manifest.write_text("files,colour\ntrolley.lp,red\n")
    with pytest.raises(ethasp.InputError, match=r"bad\.csv:2: unknown column 'colour'"):
        ethasp.batch([manifest])


# -- results --------------------------------------------------------------------------------


def test_lines_are_those_of_the_api(tmp_path):
    paths = variants(tmp_path / "cases", 4)
    lines = run(
        [tmp_path / "cases", MODELS / "trolley.lp"],
        ["hera"],
        workers=2,
        output=tmp_path / "results.jsonl",
    )
    assert by_hash(lines) == by_hash(list(read_lines(tmp_path / "results.jsonl")))
    assert len(lines) == 5 * len(HERA)
    for line in lines:
        assert set(line) >= FIELDS, line
        assert line["ethasp_version"] == ethasp.interfaces.version.package_version()
    for path in paths:
        model = Model.load([path])
        report = ethasp.judge(model, model.own_plan(), ["hera"], reasons_limit=0)
        mine = {line["principle"]: line for line in lines if line["case"] == str(path)}
        for judgement in report.judgements:
            line = mine[judgement.principle]
            assert (line["task"], line["permissible"], line["status"], line["utility"]) == (
                "judge",
                judgement.permissible,
                judgement.status,
                report.utility,
            )
            assert line["plan"] == report.plan.to_list()
    # A model without a plan is planned for; a principle without a restriction
    # judges a shortest plan found without it, as ethasp.judge does.
    planned = {line["principle"]: line for line in lines if line["case"].endswith("trolley.lp")}
    assert planned["hera-deontology"]["task"] == "plan"
    assert planned["hera-deontology"]["status"] == "found"
    assert "judged" not in planned["hera-deontology"]
    double = planned["double-effect"]
    assert double["judged"] is True and "error" not in double
    model = Model.load([MODELS / "trolley.lp"])
    judgement = ethasp.judge(model, ethasp.Plan.parse(" ".join(double["plan"])), ["double-effect"])
    judgement = judgement.judgements[0]
    assert (double["permissible"], double["status"]) == (judgement.permissible, judgement.status)
    assert double["plan"] == ethasp.find_plan(model).plan.to_list()


def test_resume_computes_only_the_missing_lines(tmp_path):
    variants(tmp_path / "cases", 6)
    complete = tmp_path / "complete.jsonl"
    lines = run([tmp_path / "cases"], ["paper"], workers=2, output=complete)
    assert len(lines) == 18
    # A run that ended after 7 lines, in the middle of writing the 8th.
    partial = tmp_path / "partial.jsonl"
    raw = complete.read_bytes().splitlines(keepends=True)
    partial.write_bytes(b"".join(raw[:7]) + raw[7][:25])
    again = ethasp.batch([tmp_path / "cases"], ["paper"], workers=2, output=partial)
    assert again.lines_before == 7 and again.skipped == 2
    new = list(again)
    assert len(new) == 11
    resumed = list(read_lines(partial))
    assert len(resumed) == 18
    assert {h: without_times(line) for h, line in by_hash(resumed).items()} == {
        h: without_times(line) for h, line in by_hash(lines).items()
    }
    # Nothing is left to do now.
    assert run([tmp_path / "cases"], ["paper"], workers=2, output=partial) == []
    # Other options are other lines.
    assert len(run([tmp_path / "cases"], ["paper"], workers=1, output=partial, max_horizon=3)) == 18


def test_bad_cases_get_their_line_and_the_batch_goes_on(tmp_path):
    pulled = Case((str(MODELS / "trolley.lp"),), "pulled", plan="pull")
    cases = [FIXTURES / "syntax.lp", FIXTURES / "script.lp", MODELS / "trolley.lp", pulled]
    # (A limit over before any search starts; the grace lets the cases load.)
    lines = run(
        cases,
        ["paper"],
        workers=2,
        time_limit=1e-6,
        grace=30.0,
        task="judge",
        output=tmp_path / "out.jsonl",
    )
    by_case = {}
    for line in lines:
        by_case.setdefault(line["case"], []).append(line)
    for bad in ("syntax.lp", "script.lp"):
        [line] = by_case[str(FIXTURES / bad)]
        code, _, err = run_in_process(["judge", str(FIXTURES / bad), "--plan", "pull"])
        assert code == 2 and err.strip() == f"ethasp: error: {line['error']}"
        assert line["status"] == "error" and line["hash"]
    assert "#script block" in by_case[str(FIXTURES / "script.lp")][0]["error"]
    # trolley.lp has no plan of its own: judging needs one.
    assert "no plan to judge" in by_case[str(MODELS / "trolley.lp")][0]["error"]
    # Pulling's utilitarian verdict needs a search (its utility is below the upper
    # bound) that the time limit, over before the search starts, cut.
    judged = {line["principle"]: line for line in by_case["pulled"]}
    assert judged["utilitarianism"]["status"] == "bounded"
    assert judged["utilitarianism"]["permissible"] is True
    assert judged["deontology"]["status"] == "proven"


def test_a_case_stuck_in_grounding_loses_its_worker_not_the_batch(tmp_path):
    stuck = tmp_path / "stuck.lp"
    stuck.write_text(
        "variable(a). action(go). eff(go,a,true). goal(a,true).\nn(1). n(X+1) :- n(X).\n"
    )
    lines = run(
        [stuck, MODELS / "hera" / "trolley.yaml"],
        ["deontology"],
        workers=1,
        time_limit=0.2,
        grace=1.0,
    )
    [line] = [line for line in lines if line["case"] == str(stuck)]
    assert "no answer within the limits: the time limit of 0.2 s was reached" in line["error"]
    assert [line["status"] for line in lines if line["case"] != str(stuck)] == ["proven"]


def test_a_case_that_kills_its_worker_is_retried_once(tmp_path):
    paths = variants(tmp_path / "cases", 4)
    settings = Settings(principles=("deontology",), crash_case="trolley-01.json", crash_attempts=1)
    lines = run([tmp_path / "cases"], workers=2, settings=settings)
    assert sorted(line["case"] for line in lines) == sorted(map(str, paths))
    assert all("error" not in line for line in lines)
    settings = Settings(principles=("deontology",), crash_case="trolley-02.json", crash_attempts=2)
    lines = run([tmp_path / "cases"], workers=2, settings=settings)
    [line] = [line for line in lines if line["case"].endswith("trolley-02.json")]
    assert (
        "its worker process ended while computing it, twice (killed by signal SIGKILL)"
        in line["error"]
    )
    assert sum("error" not in line for line in lines) == 3


def test_a_worker_killed_mid_run_loses_no_case(tmp_path):
    variants(tmp_path / "cases", 12)
    output = tmp_path / "out.jsonl"
    running = ethasp.batch([tmp_path / "cases"], ["hera"], workers=2, output=output)
    lines, killed = [], False
    for line in running:
        lines.append(line)
        busy = running.busy_pids()
        if not killed and busy:
            os.kill(busy[0], signal.SIGKILL)
            killed = True
    assert killed
    assert len(by_hash(lines)) == 12 * len(HERA)
    assert all("error" not in line for line in lines)
    assert len(list(read_lines(output))) == 12 * len(HERA)


# -- command line and report ----------------------------------------------------------------


def test_the_command_writes_results_and_the_report(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    variants(tmp_path / "cases", 5)
    code, out, err = run_in_process(
        [
            "batch",
            "cases",
            "trolley",
            "--principle",
            "hera",
            "--principle",
            "paper",
            "--output",
            "results.jsonl",
            "--report",
            "report.html",
            "--workers",
            "2",
        ]
    )
    # trolley.lp has no plan of its own, so it is planned for: the principles
    # that can only judge judge a shortest plan found without them.
    assert code == 0, err
    assert "6 cases (6 computed now), 0 failed" in err
    lines = list(read_lines(tmp_path / "results.jsonl"))
    assert len(lines) == 6 * 13
    judged = [line for line in lines if line.get("judged")]
    assert {line["principle"] for line in judged} == {
        "hera-do-no-harm",
        "do-no-instrumental-harm",
        "kantian-humanity",
        "kantian-humanity-2",
        "double-effect",
    }
    assert all(line["case"] == "trolley.lp" and line["task"] == "plan" for line in judged)
    assert all(line["plan"] and line["status"] == "proven" for line in judged)
    assert "cannot restrict plan search, so a shortest plan found without it" in judged[0]["proof"]
    page = (tmp_path / "report.html").read_text()
    assert "Agreement of the principles" in page and "href='#pair-" in page
    assert "Verdicts per principle" in page and "Slowest cases" in page
    assert "judged: lines of the task plan for a principle that cannot restrict" in page
    assert "src=" not in page  # self-contained: its script and style are inside
    assert "http://" not in page.replace("http://www.w3.org/2000/svg", "")
    assert "https://" not in page
    # Drawn again from the lines, the same tables.
    code, out, err = run_in_process(["report", "results.jsonl", "--output", "again.html"])
    assert code == 0 and "again.html" in out
    assert (tmp_path / "again.html").read_text().split("drawn")[1].split("</p>", 1)[
        1
    ] == page.split("drawn")[1].split("</p>", 1)[1]
    # Resumed: nothing to compute.
    code, out, err = run_in_process(
        [
            "batch",
            "cases",
            "trolley",
            "--principle",
            "hera",
            "--principle",
            "paper",
            "-o",
            "results.jsonl",
        ]
    )
    assert code == 0 and "0 computed now, 6 done before" in err
    code, out, err = run_in_process(
        ["batch", "cases", "--principle", "hera", "-o", "results.jsonl", "--quiet"]
    )
    assert (code, err) == (0, "")


@pytest.mark.parametrize(
    "arguments, fragment",
    [
        (["nowhere.lp"], "nowhere.lp: no such file or folder"),
        (["trolley", "--principle", "kindness"], "unknown principle 'kindness'"),
        (["trolley", "--workers", "0"], "the number of workers must be at least 1"),
        (["trolley", "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "--workers is for"),
        (["trolley", "--task", "judge", "--question", "why pull"], "questions are asked by"),
        (["trolley", "--question", "because"], "because"),
        (["trolley", "--time-limit", "-1"], "--time-limit"),
        (["trolley", "--output", "."], "is a directory"),
    ],
)
def test_bad_options_get_one_line_and_exit_code_2(arguments, fragment, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    if "--output" not in arguments:
        arguments = [*arguments, "--output", "out.jsonl"]
    code, _out, err = run_in_process(["batch", *arguments])
    assert code == 2 and len(err.splitlines()) == 1 and fragment in err, err
    assert "Traceback" not in err


def test_a_scheduler_that_is_not_there_is_one_line(tmp_path, monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr("ethasp.batch.cluster.CONNECT_TIMEOUT", 2)
    code, _out, err = run_in_process(
        ["batch", "trolley", "-o", "out.jsonl", "--scheduler", "tcp://127.0.0.1:9"]
    )
    assert code == 2 and len(err.splitlines()) == 1, err
    assert "cannot connect to a Dask scheduler" in err


def test_the_report_of_a_file_that_is_not_results_is_one_line(tmp_path):
    (tmp_path / "notes.jsonl").write_text("hello\n")
    code, _out, err = run_in_process(["report", str(tmp_path / "notes.jsonl")])
    assert code == 2 and "notes.jsonl:1: not a line of batch results" in err
    # Advice about --output belongs to a batch resuming into the file, not to a report.
    assert "--output" not in err


def test_a_batch_into_a_file_that_is_not_results_says_to_give_another(tmp_path):
    (tmp_path / "notes.jsonl").write_text("hello\n")
    code, _out, err = run_in_process(
        ["batch", "trolley", "--principle", "deontology", "-o", str(tmp_path / "notes.jsonl")]
    )
    assert code == 2 and len(err.splitlines()) == 1, err
    assert "notes.jsonl:1: not a line of batch results" in err and "--output" in err


def test_report_agreement_lists_the_disagreeing_cases(tmp_path):
    lines = [
        {
            "case": f"c{i}",
            "principle": p,
            "permissible": v,
            "status": "proven",
            "seconds": 0.01 * (i + 1),
            "hash": f"{i}{p}",
        }
        for i in range(4)
        for p, v in (("a", True), ("b", i % 2 == 0))
    ]
    results = tmp_path / "r.jsonl"
    results.write_text("".join(json.dumps(line) + "\n" for line in lines))
    page = write_report(results, tmp_path / "r.html").read_text()
    assert "a vs b: disagree on 2 of 4 cases" in page
    assert "<a href='#case-2'>c1</a>" in page and "<a href='#case-4'>c3</a>" in page
    assert "50% <a href='#pair-0-1'>(2)</a>" in page


def test_progress_is_a_bar_on_a_terminal_and_plain_lines_elsewhere():
    import io

    from ethasp.batch.progress import BatchProgress

    stream = io.StringIO()
    bar = BatchProgress(10, before=2, stream=stream, terminal=True)
    bar.update(5, 1)
    bar.finish("done")
    text = stream.getvalue()
    assert text.startswith("\r[#") and "5/10 cases, 1 failed," in text and "left" in text
    assert text.endswith("done\n")
    stream = io.StringIO()
    plain = BatchProgress(10, stream=stream, terminal=False)
    plain.last -= 60  # the first plain line is due
    plain.update(4, 0)
    assert stream.getvalue().startswith("ethasp batch: 4/10 cases, none failed, ")
    assert "\r" not in stream.getvalue()
