"""The command line of the question language and of step-by-step explanations:
ethasp ask with the new forms, ethasp explain (words, JSON, SVG), and the
dialogue's why step, drop and principle switches."""

import json
import subprocess
import sys

from conftest import MODELS, ROOT

RESCUE = str(MODELS / "rescue.lp")
TROLLEY = str(MODELS / "trolley.lp")
FRANK = str(MODELS / "hera" / "robot-and-frank.yaml")
KEY_PLAN = "take_key move(r1,r2) move(r2,r3) unlock_door move(r3,r4)"


def ethasp(*args, stdin=None, cwd=ROOT):
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        input=stdin,
        capture_output=True,
        text=True,
        cwd=cwd,
    )


def test_ask_help_lists_the_grammar():
    run = ethasp("ask", "--help")
    text = " ".join(run.stdout.split())
    for form in (
        "'why A after B'",
        "'why A at T'",
        "'why not A within T1..T2'",
        "'why F'",
        "'why not F at T'",
        "'why not in N steps'",
        "'why fact X'",
    ):
        assert form in text, form
    assert "dropped only when no plan meeting the question is proven permissible" in text


def test_ask_new_forms_json():
    run = ethasp("ask", RESCUE, "--plan", KEY_PLAN, "--question", "why take_key at 1", "--json")
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data["constraints"] == ["not_at(take_key,1)"] and data["status"] == "found"
    assert data["contrast"]["plan"][0] != "take_key" and "take_key" in data["contrast"]["plan"]
    assert data["note"] == "" and data["principle_dropped"] is False
    run = ethasp("ask", RESCUE, "--plan", KEY_PLAN, "--question", "why at(r4)", "--json")
    data = json.loads(run.stdout)
    assert data["status"] == "none" and data["conflict"] == ["ends(at(r4),false)"]
    assert "contradicts the goal" in data["proof"]
    run = ethasp("ask", RESCUE, "--plan", KEY_PLAN, "--question", "why not in 3 steps")
    assert run.returncode == 0 and "no plan can take at most 3 steps" in run.stdout


def test_a_satisficing_contrast_has_at_most_the_steps_asked_for():
    """A plan found fast for "why not in N steps" has at most N steps: the
    greedy search's plan of more steps ends no search (the search went on
    at horizon 0 until the time limit, and answered bounded)."""
    for steps, status in ((4, "found"), (3, "none")):
        question = f"why not in {steps} steps"
        answers = [
            json.loads(
                ethasp(
                    *("ask", RESCUE, "--plan", KEY_PLAN, "--question", question),
                    *("--json", "--time-limit", "60", *satisficing),
                ).stdout
            )
            for satisficing in (["--satisficing"], [])
        ]
        for answer in answers:
            assert answer["status"] == status, (question, answer["proof"])
        if status == "found":
            assert len(answers[0]["contrast"]["plan"]) <= steps
            assert answers[0]["principle_dropped"] == answers[1]["principle_dropped"] is True


def test_ask_errors_are_one_line():
    for question, message in (
        ("why take_key at 2", "step 2 of the plan is move(r1,r2)"),
        ("why take_key at x", "expected a step number"),
        ("why door_broken", "door_broken is false at the end"),
        ("why jump", "unknown action jump (nor a state variable)"),
    ):
        run = ethasp("ask", RESCUE, "--plan", KEY_PLAN, "--question", question)
        assert run.returncode == 2 and message in run.stderr, run.stderr
        assert run.stderr.count("\n") == 1 and "Traceback" not in run.stderr
    run = ethasp("ask", TROLLEY, "--plan", "pull", "--question", "why pull", "--under", "all")
    assert run.returncode == 2 and "names a group" in run.stderr


def test_explain_words():
    run = ethasp("explain", RESCUE, "--plan", KEY_PLAN)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert lines[0] == f"plan of 5 steps: {KEY_PLAN}"
    assert lines[1] == ("Step 1, take the key, lets step 4 unlock the door (the fact holding_key).")
    assert lines[4] == (
        "Step 4, unlock the door, lets step 5 move to the exit (the fact door_open)."
    )
    assert lines[5] == "Step 5, move to the exit, brings about the goal (the fact at(r4))."
    assert lines[6] == "removable steps: none"
    # Then the E-links and D-links, a sentence per step.
    assert lines[7] == "E-links and D-links (what enables and what requires each step):"
    assert lines[-1] == (
        "  Step 5, move to the exit: the fact not at(r4) holds initially and requires it; it "
        "results in the fact at(r4), which fulfils the goal."
    )
    run = ethasp("explain", TROLLEY, "--plan", "refrain pull")
    assert (
        "Step 1, refrain from action, is not needed: the plan without it is still a plan."
        in run.stdout
    )
    assert "it causes the death of the one person (utility -1)" in run.stdout
    assert "removable steps: 1, 2" in run.stdout.splitlines()


def test_explain_json_and_svg(tmp_path):
    picture = tmp_path / "steps.svg"
    run = ethasp("explain", RESCUE, "--plan", KEY_PLAN, "--json", "--svg", str(picture))
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    first = data["steps"][0]
    assert first["step"] == 1 and first["action"] == "take_key" and first["removable"] is False
    assert first["links"] == [
        {
            "variable": "holding_key",
            "value": True,
            "to": 4,
            "kind": "precondition",
            "shown": "holding_key",
        }
    ]
    assert data["steps"][4]["links"][0]["to"] == "goal"
    assert first["chain"] == [1, 4, 5, "goal"] and first["bad"] is False
    svg = picture.read_text()
    # An arrow per E-link, and per D-link in their own colour.
    assert svg.count('marker-end="url(#arrowhead)"') == len(data["e_links"]) > 0
    assert svg.count('marker-end="url(#demandhead)"') == len(data["d_links"]) > 0
    assert "at(r4) (goal)" in svg and "requires (D-link)" in svg
    # The model's own plan (a HERA situation's), with events.
    data = json.loads(ethasp("explain", FRANK, "--json").stdout)
    assert data["plan"] == ["lie_to_frank"] and data["steps"][0]["bad"] is True
    assert data["steps"][0]["harms"] == [
        {"variable": "frank_deceived", "value": True, "utility": -2}
    ]
    assert any(link["to"] == "goal" for event in data["events"] for link in event["links"])
    # Without a plan: the plan made under a principle.
    data = json.loads(ethasp("explain", RESCUE, "--principle", "deontology", "--json").stdout)
    assert data["plan"][0] == "take_key"


def test_explain_errors():
    run = ethasp("explain", TROLLEY, "--plan", "jump")
    assert run.returncode == 2 and "unknown action jump" in run.stderr
    run = ethasp("explain", RESCUE, "--plan", "unlock_door")
    assert run.returncode == 2 and run.stderr.startswith("ethasp: error: not a plan")


def test_dialogue_why_step_drop_and_principles(tmp_path):
    script = (
        "\n".join(
            [
                "why step 1",
                "why step 9",
                "principle kantian-humanity",
                "principle all",
                "why lie_to_frank",
                "why not lie_to_frank",
                "drop",
                "drop",
                "history",
            ]
        )
        + "\n"
    )
    run = ethasp("dialogue", FRANK, "--save", "-", stdin=script, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    out = run.stdout
    assert out.startswith("current plan: lie_to_frank (deontology: impermissible)")
    assert "Step 1, lie to Frank, lets the event frank believes of step 1 happen" in out
    assert "error: why step 9: the current plan has steps 1 to 1" in out
    assert "error: principle kantian-humanity cannot restrict plan search" in out
    assert "error: principle 'all' names a group" in out
    assert "No plan can meet the questions asked so far together" in out
    assert "Type drop to take back the last question." in out
    assert "dropped: why not lie_to_frank" in out
    assert "error: drop: the last question does not conflict" in out
    assert "1. why lie_to_frank (under deontology): unused(lie_to_frank)" in out


def test_answers_name_only_the_reasons_that_tell_the_plans_apart():
    """The reasons "only for" one plan hold of that plan alone: the contrast
    plan also moves from room 2 to room 3, so that step's reason is shared."""
    run = ethasp("ask", RESCUE, "--plan", KEY_PLAN, "--question", "why take_key")
    assert run.returncode == 0, run.stderr
    last = run.stdout.strip().splitlines()[-1]
    assert last == (
        "  reasons only for the plan asked about: not Bad(take_key), not Bad(unlock_door); "
        "only for the contrast: Bad(break_door)"
    ), last
    data = json.loads(
        ethasp("ask", RESCUE, "--plan", KEY_PLAN, "--question", "why take_key", "--json").stdout
    )
    assert data["reason_difference"]["original_only"] == [
        "not Bad(take_key)",
        "not Bad(unlock_door)",
    ]


def test_an_answer_without_a_contrast_plan_says_so_once():
    run = ethasp("ask", TROLLEY, "--plan", "pull", "--question", "why not in 0 steps")
    assert run.returncode == 0, run.stderr
    assert "  no contrast plan: no plan meets the question: " in run.stdout
    assert "contrast plan: none" not in run.stdout and "(none:" not in run.stdout
    assert "only for the contrast" not in run.stdout and "reasons only" not in run.stdout


def test_the_dialogue_saves_only_when_asked_and_minus_is_standard_output(tmp_path):
    script = "why refrain rather than pull\nquit\n"
    harm = ("--principle", "do-no-harm")  # its first plan: refrain
    run = ethasp("dialogue", TROLLEY, *harm, stdin=script, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert list(tmp_path.iterdir()) == []  # nothing written without --save
    assert "saved" not in run.stdout
    run = ethasp("dialogue", TROLLEY, *harm, "--save", "-", stdin=script, cwd=tmp_path)
    assert run.returncode == 0 and list(tmp_path.iterdir()) == [], run.stderr
    head, json_text = run.stdout.split("\n{\n", 1)
    assert head.startswith("current plan: refrain")
    data = json.loads("{\n" + json_text)
    assert data["format"] == "ethasp-dialogue" and len(data["steps"]) == 1
    run = ethasp("dialogue", TROLLEY, *harm, "--save", "d.json", stdin=script, cwd=tmp_path)
    assert run.returncode == 0 and run.stdout.endswith("dialogue saved to d.json\n")
    assert json.loads((tmp_path / "d.json").read_text())["steps"]
    run = ethasp("dialogue", TROLLEY, stdin="save -\nquit\n", cwd=tmp_path)
    assert (
        '"format": "ethasp-dialogue"' in run.stdout and "written to standard output" in run.stdout
    )


def test_an_empty_plan_given_is_the_plan_asked_about_not_the_models_own():
    """``--plan ""`` is the empty plan: ask answers about it, and explain
    explains it (or refuses it where it is no plan of an ASP model), never the
    plan the model comes with or a plan it searches."""
    run = ethasp("ask", "hera/trolley.yaml", "--plan", "", "--question", "why not pull", "--json")
    assert run.returncode == 0, run.stderr
    answer = json.loads(run.stdout)
    assert answer["original"]["plan"] == [] and answer["contrast"]["plan"] == ["pull"]
    run = ethasp("explain", "trolley", "--plan", "")  # an ASP model's plan reaches its goal
    assert run.returncode == 2 and "goal is not reached" in run.stderr, run.stdout
    run = ethasp("explain", "hera/trolley.yaml", "--plan", "", "--json")
    assert run.returncode == 0, run.stderr
    explained = json.loads(run.stdout)
    assert explained["plan"] == [] and explained["goal_reached"] is False
    assert explained["unmet_goal"] == ["-five_dead"]
    run = ethasp("explain", "hera/trolley.yaml", "--plan", "")
    assert run.returncode == 0, run.stderr
    assert "The plan does not reach its goal: five saved lives does not hold" in run.stdout
    run = ethasp("explain", "hera/trolley.yaml", "--plan", "refrain")  # needs nothing
    assert "is not needed: without it, the plan still reaches every goal fact" in run.stdout
    run = ethasp("judge", "hera/trolley.yaml", "--plan", "", "--principle", "deontology")
    assert "goal: not reached (-five_dead does not hold at the end)" in run.stdout, run.stdout
    run = ethasp("dialogue", "hera/trolley.yaml", "--plan", "", stdin="quit\n")
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith("current plan: (empty)"), run.stdout
