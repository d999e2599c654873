"""Plans step by step (encodings/planning/steps.lp, ethasp.planning.timeline)
and their pictures (ethasp.interfaces.svg, --svg on the command line)."""

import json
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

import clingo
import pytest
from conftest import MODELS, ROOT, only_answer

from ethasp import InputError, Model, Plan
from ethasp.interfaces.pictures import Pictures
from ethasp.interfaces.svg import contrast_svg, parting_step, plan_svg
from ethasp.planning.timeline import MAX_STEPS, Fact, Valuation, timeline
from ethasp.questions.contrast import ask

STEPS = ["planning/model.lp", "planning/trace.lp", "planning/steps.lp"]
SVG = "{http://www.w3.org/2000/svg}"

# x is set twice (the second time without change), y is set and unset.
TOGGLE = """
variable(x;y;z). action(a;b;c).
eff(a,x,true). eff(a,y,true).
eff(b,x,true). eff(b,y,false).
eff(c,z,true).
init(z). goal(x,true).
utility(y,true,-2). utility(x,true,3). utility(c,-1).
"""


def test_steps_encoding_changes_kept_effects_and_causing():
    atoms = only_answer(STEPS, TOGGLE + "occurs(a,1). occurs(b,2). occurs(c,3).")
    assert {
        "set(1,x,true)",
        "set(1,y,true)",
        "set(2,x,true)",
        "set(2,y,false)",
        "set(3,z,true)",
    } <= atoms
    assert {a for a in atoms if a.startswith("changed(")} == {
        "changed(1,x,true)",
        "changed(1,y,true)",
        "changed(2,y,false)",
    }
    # Caused(v) needs v in the final state and some action with it as effect.
    assert {a for a in atoms if a.startswith("caused(")} == {
        "caused(x,true)",
        "caused(y,false)",
        "caused(z,true)",
    }
    assert {a for a in atoms if a.startswith("causing(")} == {
        "causing(1,x,true)",
        "causing(2,x,true)",
        "causing(2,y,false)",
        "causing(3,z,true)",
    }
    assert {a for a in atoms if a.startswith("initially(")} == {
        "initially(x,false)",
        "initially(y,false)",
        "initially(z,true)",
    }


def test_steps_encoding_of_the_empty_plan():
    atoms = only_answer(STEPS, TOGGLE)
    assert not any(a.startswith(("set(", "changed(", "causing(", "caused(")) for a in atoms)


@pytest.fixture(scope="module")
def toggle():
    return Model.from_string(TOGGLE)


@pytest.fixture(scope="module")
def trolley():
    return Model.load([MODELS / "trolley.lp"])


def test_timeline_reads_the_answer_set(toggle):
    line = timeline(toggle, Plan.parse("a b c"))
    x, y, z = (Fact(clingo.Function(n), True) for n in "xyz")
    first, second, third = line.columns
    assert first.changes == [x, y] and first.kept == []
    assert second.changes == [Fact(y.variable, False)] and second.kept == [x]
    assert third.changes == [] and third.kept == [z]  # z is true from the start
    assert second.causing == {x, Fact(y.variable, False)}
    assert line.initial == [Fact(x.variable, False), Fact(y.variable, False)]
    assert line.utility == 3 and line.caused == {x, Fact(y.variable, False), z}
    valuation = line.valuation
    assert valuation.action_utility(third.action) == -1
    assert valuation.fact_utility(y) == -2 and valuation.fact_utility(x) == 3
    assert valuation.fact_utility(Fact(y.variable, False)) == 0


def test_timeline_refuses_non_plans_and_long_plans(toggle):
    with pytest.raises(InputError, match="not a plan: the goal is not reached"):
        timeline(toggle, Plan.parse("c"))
    with pytest.raises(InputError, match="unknown action d at step 1"):
        timeline(toggle, Plan.parse("d"))
    with pytest.raises(InputError, match=f"at most {MAX_STEPS} steps"):
        timeline(toggle, Plan.parse(" ".join(["a"] * (MAX_STEPS + 1))))


def test_valuation_has_the_labels_and_the_goal(trolley):
    glance = Valuation.of_model(trolley).to_json(trolley.naming)
    assert glance["agent"] == {"name": "the man", "possessive": "his"}
    pull = next(a for a in glance["actions"] if a["term"] == "pull")
    assert pull == {
        "term": "pull",
        "shown": "pull",
        "utility": 0,
        "moral": "neutral",
        "label": "pull the lever",
    }
    five = next(v for v in glance["variables"] if v["term"] == "five_will_die")
    assert five["initial"] is True
    assert (
        five["true"]["moral"] == "bad" and five["true"]["label"] == "the death of the five persons"
    )
    assert five["false"]["utility"] == 5 and five["false"]["moral"] == "good"
    assert glance["goal"][0]["literal"] == "done"


def _svg(text: str) -> ET.Element:
    root = ET.fromstring(text)  # well-formed, standalone
    assert root.tag == f"{SVG}svg"
    assert "http" not in text.replace("http://www.w3.org/2000/svg", "")  # nothing fetched
    return root


def _texts(root: ET.Element) -> list[str]:
    return [node.text or "" for node in root.iter(f"{SVG}text")]


def test_plan_picture(trolley):
    line = timeline(trolley, Plan.parse("pull"))
    root = _svg(plan_svg(line, trolley.naming, notes=["do-no-harm: impermissible"]))
    texts = _texts(root)
    assert "plan: pull" in texts and "step 1" in texts and "do-no-harm: impermissible" in texts
    assert "end \u00b7 utility 4" in texts and texts.count("caused") >= 3
    assert "the death of the one person" in texts and "\u22121" in texts and "+5" in texts
    actions = [g for g in root.iter(f"{SVG}g") if g.get("class") == "action"]
    assert [(g.get("data-step"), g.get("data-action")) for g in actions] == [("1", "pull")]
    fills = {rect.get("fill") for rect in root.iter(f"{SVG}rect")}
    assert {"#dcf3e4", "#fbe1df", "#f2f2f2"} <= fills  # good, bad, neutral


def test_contrast_picture_marks_where_the_plans_part(trolley):
    refrain, pull = (timeline(trolley, Plan.parse(p)) for p in ("refrain", "pull"))
    assert parting_step(refrain, pull) == 1 and parting_step(pull, pull) == 0
    root = _svg(contrast_svg(refrain, pull, trolley.naming, title="why refrain rather than pull"))
    texts = _texts(root)
    assert "the plans part at step 1" in texts
    assert texts.count("\u2260") == 4  # final facts that differ, in both lanes
    none = _svg(contrast_svg(refrain, None, trolley.naming, missing="none (none: proven)"))
    assert "none (none: proven)" in _texts(none)


def test_parting_after_a_common_prefix():
    model = Model.from_string(TOGGLE)
    first, second = timeline(model, Plan.parse("a c")), timeline(model, Plan.parse("a b"))
    assert parting_step(first, second) == 2
    assert parting_step(timeline(model, Plan.parse("a")), first) == 2


def test_labels_are_escaped():
    model = Model.from_string(TOGGLE + 'action_label(a, "<b>&amp; go</b>", "going").')
    root = _svg(plan_svg(timeline(model, Plan.parse("a"))))
    assert "<b>&amp; go</b>" in _texts(root)


def test_answer_picture(trolley):
    answer = ask(trolley, "why refrain rather than pull", principle="do-no-harm")
    root = _svg(Pictures(trolley).answer(answer))
    texts = " ".join(_texts(root))
    assert "why refrain rather than pull" in texts and "The man could refrain" in texts
    assert "plan asked about: refrain \u2014 do-no-harm: permissible (proven)" in texts
    assert "contrast plan: pull \u2014 do-no-harm: impermissible (proven)" in texts
    assert "was dropped for the contrast" in texts
    bare = " ".join(_texts(_svg(Pictures(trolley).answer(answer, words=False))))
    assert "The man could refrain" not in bare and "plan asked about" in bare


def test_pddl_pictures_show_pddl_names():
    model = Model.load(
        [
            MODELS / "pddl" / "trolley-domain.pddl",
            MODELS / "pddl" / "trolley-problem.pddl",
            MODELS / "pddl" / "trolley-utility.lp",
        ]
    )
    plan = Pictures(model).plan(Plan.parse(str(next(iter(Valuation.of_model(model).actions)))))
    assert "(" in " ".join(_texts(_svg(plan)))


def ethasp(*args, cwd=ROOT):
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
    )


def test_cli_svg_on_judge_plan_and_ask(tmp_path):
    trolley = str(MODELS / "trolley.lp")
    judged = tmp_path / "judge.svg"
    run = ethasp("judge", trolley, "--plan", "pull", "--svg", str(judged), "--json")
    assert run.returncode == 0, run.stderr
    json.loads(run.stdout)  # the picture does not disturb the JSON
    assert "do-no-harm: impermissible (proven)" in _texts(_svg(judged.read_text()))
    planned = tmp_path / "plan.svg"
    run = ethasp("plan", trolley, "--principle", "do-no-harm", "--svg", str(planned))
    assert run.returncode == 0, run.stderr
    assert "plan of 1 step permissible under do-no-harm: refrain" in _texts(
        _svg(planned.read_text())
    )
    run = ethasp("plan", "rescue", "--svg", str(planned))
    assert run.returncode == 0 and "step 4" in _texts(_svg(planned.read_text()))
    asked = tmp_path / "ask.svg"
    run = ethasp(
        "ask",
        trolley,
        "--principle",
        "do-no-harm",
        "--question",
        "why refrain rather than pull",
        "--svg",
        str(asked),
    )
    assert run.returncode == 0, run.stderr
    assert "the plans part at step 1" in _texts(_svg(asked.read_text()))


def test_cli_svg_errors_and_no_plan(tmp_path):
    run = ethasp("judge", "trolley", "--plan", "pull", "--svg", str(tmp_path / "no" / "x.svg"))
    assert run.returncode == 2 and run.stderr.startswith("ethasp: error: ")
    assert "cannot be written" in run.stderr and "Traceback" not in run.stderr
    run = ethasp("plan", "rescue", "--max-horizon", "2", "--svg", str(tmp_path / "x.svg"))
    assert run.returncode == 0 and "no picture was written" in run.stderr
    assert not (tmp_path / "x.svg").exists()


def test_cli_version():
    run = ethasp("--version")
    assert run.returncode == 0 and run.stdout.startswith("ethasp ")
    from importlib.metadata import version

    assert run.stdout.split()[1] == version("ethasp")


def test_long_names_are_wrapped_in_their_boxes_not_cut():
    """A PDDL task's names are longer than a box: each box shows its name
    whole over up to four lines, its tooltip too; the picture keeps its
    viewBox, so that the page can scale it to its box."""
    pddl = MODELS / "pddl"
    care = Model.load(
        [pddl / "care-domain.pddl", pddl / "care-problem.pddl", pddl / "care-utility.lp"]
    )
    plan = Plan.parse(
        "(pick-up pills-bob kitchen) (move kitchen hall) (move hall living-room) "
        "(give-other-medicine pills-bob ann bob living-room pills-ann)"
    )
    text = plan_svg(timeline(care, plan), care.naming)
    root = _svg(text)
    assert root.get("viewBox") == f"0 0 {root.get('width')} {root.get('height')}"
    boxes = 0
    for group in root.iter(f"{SVG}g"):
        title = group.find(f"{SVG}title")
        if title is None:
            continue
        name = re.sub(r"^step \d+: ", "", title.text).split(": ")[0]  # its tooltip
        lines = [
            node.text
            for node in group.iter(f"{SVG}text")
            if node.get("font-style") == "normal"
            and node.text != "caused"
            and not node.text.lstrip("+\u2212").isdigit()
        ]
        assert " ".join(lines) == name, (name, lines)  # broken at spaces here
        assert "\u2026" not in "".join(lines)
        boxes += 1
    assert boxes > 10
    assert any(
        title.text.startswith("(not (robot-at kitchen))") for title in root.iter(f"{SVG}title")
    )
