"""Contrastive explanations: the paper's conductor example, the user study's
contrastive texts, every question form, conflicts, ethasp ask and dialogue."""

import json
import subprocess
import sys

import pytest

from conftest import MODELS, ROOT
from ethasp import InputError, Model, Plan
from ethasp.questions.contrast import ask
from ethasp.questions.dialogue import Dialogue

CONDUCTOR = (
    "The man could refrain from action. This would be permissible under the do-no-harm "
    "principle because this way the death of the five persons is not caused by his action. "
    "Alternatively, the man could pull the lever. Doing so is impermissible under the "
    "do-no-harm principle because this way the death of the one person is caused by his "
    "action.")
UTILITARIAN = (
    "The man could refrain from action. This would be permissible under the do-no-harm "
    "principle because this way the death of the five persons is not caused by his action. "
    "Alternatively, the man could pull the lever. Doing so is permissible under the "
    "utilitarianism principle because five saved lives is better than one saved life.")


@pytest.fixture(scope="module")
def trolley():
    return Model.load([MODELS / "trolley.lp"])


def test_conductor_example(trolley):
    answer = ask(trolley, "why refrain rather than pull", principle="do-no-harm")
    assert str(answer.original.plan) == "refrain" and answer.original.judgement.permissible
    assert str(answer.contrast.plan) == "pull" and not answer.contrast.judgement.permissible
    assert answer.principle_dropped and answer.status == "found"
    assert "every reachable state was searched" in answer.dropped_because
    assert [str(c) for c in answer.constraints] == ["unused(refrain)", "used(pull)"]
    assert answer.difference == {"original_only": ["not Caused(five_will_die)"],
                                 "contrast_only": ["Caused(one_will_die)"]}
    assert answer.explanation == CONDUCTOR


def test_conductor_asks_again_under_utilitarianism(trolley):
    answer = ask(trolley, "why refrain rather than pull", principle="do-no-harm",
                 under="utilitarianism")
    assert not answer.principle_dropped and answer.contrast.judgement.permissible
    assert answer.explanation == UTILITARIAN
    assert answer.contrast.judgement.explanation.chosen_reason[0].startswith("GEq(")


def test_study_contrastive_deontology(trolley):
    answer = ask(trolley, "why pull rather than refrain", plan=Plan.parse("pull"),
                 principle="deontology")
    text = answer.explanation
    assert "pull the lever" in text and "pulling a lever is not inherently bad" in text
    assert "Alternatively, the man could refrain from action" in text
    assert "doing nothing is not inherently bad" in text
    assert answer.contrast.judgement.permissible and answer.original.judgement.permissible


def test_study_contrastive_utilitarianism(trolley):
    answer = ask(trolley, "why pull rather than refrain", principle="utilitarianism")
    assert str(answer.original.plan) == "pull"
    assert answer.principle_dropped and not answer.contrast.judgement.permissible
    assert "because five saved lives is better than one saved life" in answer.explanation
    assert answer.explanation.endswith(
        "Doing so is impermissible under the utilitarianism principle because one saved life "
        "is worse than five saved lives.")


HEIST = MODELS / "heist.lp"


@pytest.mark.parametrize("question,check", [
    ("why steal", lambda p: "steal" not in p),
    ("why not buy_flowers", lambda p: "buy_flowers" in p),
    ("why steal rather than buy_flowers", lambda p: "steal" not in p and "buy_flowers" in p),
    ("why scout before steal", lambda p: "steal" in p and "scout" in p
     and p.index("steal") < len(p) - 1 - p[::-1].index("scout")),
])
def test_every_question_form_on_a_multi_step_model(question, check):
    model = Model.load([HEIST])
    answer = ask(model, question, plan=Plan.parse("scout steal give_jewels"),
                 principle="utilitarianism", under="deontology")
    if answer.contrast is not None:
        plan = [str(a) for a in answer.contrast.plan]
        assert check(plan), plan
    else:
        # "steal before scout" is impossible: stealing needs scouting first.
        assert answer.status == "none" and question == "why scout before steal"


def test_no_plan_even_without_the_principle_names_a_minimal_conflict(trolley):
    dialogue = Dialogue.start(trolley, "do-no-harm")
    dialogue.ask("why refrain rather than pull")
    assert str(dialogue.current_plan) == "pull"
    answer = dialogue.ask("why pull rather than refrain")
    assert answer.contrast is None and answer.status == "none"
    conflict = {str(c) for c in answer.conflict}
    assert conflict in ({"used(pull)", "unused(pull)"}, {"unused(refrain)", "used(refrain)"})
    assert "There is no alternative plan" in answer.explanation


def test_questions_are_checked_against_the_plan(trolley):
    with pytest.raises(InputError, match="unknown action jump"):
        ask(trolley, "why not jump", plan=Plan.parse("pull"))
    with pytest.raises(InputError, match="already meets"):
        ask(trolley, "why not pull", plan=Plan.parse("pull"))
    with pytest.raises(InputError, match="unknown action jump at step 1"):
        ask(trolley, "why pull", plan=Plan.parse("jump"))
    with pytest.raises(InputError, match="not a plan"):
        ask(trolley, "why pull", plan=Plan.parse(""))
    with pytest.raises(InputError, match="unknown principle"):
        ask(trolley, "why pull", plan=Plan.parse("pull"), principle="kindness")


def test_dialogue_accumulates_undoes_switches_and_saves(trolley, tmp_path):
    dialogue = Dialogue.start(trolley, "do-no-harm", model_files=[str(MODELS / "trolley.lp")])
    first = dialogue.ask("why refrain rather than pull")
    assert first.explanation == CONDUCTOR and len(dialogue.constraints) == 2
    dialogue.undo()
    assert str(dialogue.current_plan) == "refrain" and dialogue.constraints == []
    dialogue.switch_principle("utilitarianism")
    assert dialogue.ask("why refrain rather than pull").explanation == UTILITARIAN
    path = tmp_path / "saved.json"
    dialogue.save(path)
    again = Dialogue.load(path)
    assert [str(s.question) for s in again.steps] == ["why refrain rather than pull"]
    assert again.steps[0].answer.explanation == UTILITARIAN and again.under == "utilitarianism"
    with pytest.raises(InputError, match="nothing to undo"):
        Dialogue.start(trolley, "deontology").undo()


def ethasp(*args, stdin=None, cwd=ROOT):
    return subprocess.run([sys.executable, "-m", "ethasp.interfaces.cli", *args], input=stdin,
                          capture_output=True, text=True, cwd=cwd)


def test_cli_ask_json():
    run = ethasp("ask", str(MODELS / "trolley.lp"), "--principle", "do-no-harm",
                 "--question", "why refrain rather than pull", "--json")
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data["explanation"] == CONDUCTOR
    assert data["original"]["plan"] == ["refrain"] and data["contrast"]["plan"] == ["pull"]
    assert data["contrast"]["permissible"] is False and data["principle_dropped"] is True
    assert data["constraints"] == ["unused(refrain)", "used(pull)"]
    for side in ("original", "contrast"):
        assert {"plan", "principle", "permissible", "sufficient_reasons",
                "necessary_reasons"} <= set(data[side])


def test_cli_ask_errors():
    run = ethasp("ask", str(MODELS / "trolley.lp"), "--question", "how pull")
    assert run.returncode == 2 and "question" in run.stderr and "Traceback" not in run.stderr


def test_cli_dialogue_through_standard_input(tmp_path):
    script = "\n".join(["help", "why refrain rather than pull", "history", "undo",
                        "principle utilitarianism", "why refrain rather than pull",
                        "principle kindness", "why not jump"]) + "\n"
    saved = tmp_path / "dialogue.json"
    run = ethasp("dialogue", str(MODELS / "trolley.lp"), "--principle", "do-no-harm",
                 "--save", str(saved), stdin=script, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    out = run.stdout
    assert CONDUCTOR in out and UTILITARIAN in out
    assert "took back: why refrain rather than pull" in out
    assert "error: unknown principle 'kindness'" in out and "unknown action jump" in out
    # End of input saved the whole dialogue.
    data = json.loads(saved.read_text())
    assert [step["question"]["kind"] for step in data["steps"]] == ["rather-than"]
    assert data["under"] == "utilitarianism"
    resumed = ethasp("dialogue", str(MODELS / "trolley.lp"), "--load", str(saved),
                     "--save", "-", stdin="history\nquit\n", cwd=tmp_path)
    assert "1. why refrain rather than pull (under utilitarianism)" in resumed.stdout
