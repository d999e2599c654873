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
    "action."
)
UTILITARIAN = (
    "The man could refrain from action. This would be permissible under the do-no-harm "
    "principle because this way the death of the five persons is not caused by his action. "
    "Alternatively, the man could pull the lever. Doing so is permissible under the "
    "utilitarianism principle because five saved lives is better than one saved life."
)


@pytest.fixture(scope="module")
def trolley():
    return Model.load([MODELS / "trolley.lp"])


def test_conductor_example(trolley):
    answer = ask(trolley, "why refrain rather than pull", principle="do-no-harm")
    assert str(answer.original.plan) == "refrain" and answer.original.judgement.permissible
    assert str(answer.contrast.plan) == "pull" and not answer.contrast.judgement.permissible
    assert answer.principle_dropped and answer.status == "found"
    # a proof that no permissible plan meets it
    assert answer.dropped_because.endswith(
        "no goal state is reachable (an exhaustive search proved it)"
    ), answer.dropped_because
    assert [str(c) for c in answer.constraints] == ["unused(refrain)", "used(pull)"]
    assert answer.difference == {
        "original_only": ["not Caused(five_will_die)"],
        "contrast_only": ["Caused(one_will_die)"],
    }
    assert answer.explanation == CONDUCTOR


def test_conductor_asks_again_under_utilitarianism(trolley):
    answer = ask(
        trolley, "why refrain rather than pull", principle="do-no-harm", under="utilitarianism"
    )
    assert not answer.principle_dropped and answer.contrast.judgement.permissible
    assert answer.explanation == UTILITARIAN
    assert answer.contrast.judgement.explanation.chosen_reason[0].startswith("GEq(")


def test_study_contrastive_deontology(trolley):
    answer = ask(
        trolley, "why pull rather than refrain", plan=Plan.parse("pull"), principle="deontology"
    )
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
        "is worse than five saved lives."
    )


HEIST = MODELS / "heist.lp"


@pytest.mark.parametrize(
    "question,check",
    [
        ("why steal", lambda p: "steal" not in p),
        ("why not buy_flowers", lambda p: "buy_flowers" in p),
        ("why steal rather than buy_flowers", lambda p: "steal" not in p and "buy_flowers" in p),
        (
            "why scout before steal",
            # steal, and no scout before the first steal
            lambda p: "steal" in p and "scout" not in p[: p.index("steal")],
        ),
    ],
)
def test_every_question_form_on_a_multi_step_model(question, check):
    model = Model.load([HEIST])
    answer = ask(
        model,
        question,
        plan=Plan.parse("scout steal give_jewels"),
        principle="utilitarianism",
        under="deontology",
    )
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
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        input=stdin,
        capture_output=True,
        text=True,
        cwd=cwd,
    )


def test_cli_ask_json():
    run = ethasp(
        "ask",
        str(MODELS / "trolley.lp"),
        "--principle",
        "do-no-harm",
        "--question",
        "why refrain rather than pull",
        "--json",
    )
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data["explanation"] == CONDUCTOR
    assert data["original"]["plan"] == ["refrain"] and data["contrast"]["plan"] == ["pull"]
    assert data["contrast"]["permissible"] is False and data["principle_dropped"] is True
    assert data["constraints"] == ["unused(refrain)", "used(pull)"]
    for side in ("original", "contrast"):
        assert {
            "plan",
            "principle",
            "permissible",
            "sufficient_reasons",
            "necessary_reasons",
            "inus_reasons",
        } <= set(data[side])
    assert ["Caused(one_will_die)"] in data["contrast"]["inus_reasons"]


def test_cli_ask_json_on_a_cam_has_inus_reasons():
    run = ethasp(
        "ask",
        str(MODELS / "cam" / "bombers.yaml"),
        "--plan",
        "bomb_factory",
        "--principle",
        "double-effect",
        "--question",
        "why bomb_factory rather than bomb_school",
        "--json",
    )
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert ["not I(children_die)"] in data["original"]["inus_reasons"]
    assert data["contrast"]["plan"] == ["bomb_school"] and "inus_reasons" in data["contrast"]
    # the principle was dropped for the contrast: a CAM has no goal to conflict with
    assert data["principle_dropped"] is True and "conflicts" not in data


def test_cli_ask_errors():
    run = ethasp("ask", str(MODELS / "trolley.lp"), "--question", "how pull")
    assert run.returncode == 2 and "question" in run.stderr and "Traceback" not in run.stderr


def test_cli_dialogue_through_standard_input(tmp_path):
    script = (
        "\n".join(
            [
                "help",
                "why refrain rather than pull",
                "history",
                "undo",
                "principle utilitarianism",
                "why refrain rather than pull",
                "principle kindness",
                "why not jump",
            ]
        )
        + "\n"
    )
    saved = tmp_path / "dialogue.json"
    run = ethasp(
        "dialogue",
        str(MODELS / "trolley.lp"),
        "--principle",
        "do-no-harm",
        "--save",
        str(saved),
        stdin=script,
        cwd=tmp_path,
    )
    assert run.returncode == 0, run.stderr
    out = run.stdout
    assert CONDUCTOR in out and UTILITARIAN in out
    assert "took back: why refrain rather than pull" in out
    assert "error: unknown principle 'kindness'" in out and "unknown action jump" in out
    # End of input saved the whole dialogue.
    data = json.loads(saved.read_text())
    assert [step["question"]["kind"] for step in data["steps"]] == ["rather-than"]
    assert data["under"] == "utilitarianism"
    resumed = ethasp(
        "dialogue",
        str(MODELS / "trolley.lp"),
        "--load",
        str(saved),
        "--save",
        "-",
        stdin="history\nquit\n",
        cwd=tmp_path,
    )
    assert "1. why refrain rather than pull (under utilitarianism)" in resumed.stdout


# -- the whole question language ------------------------------------------------------

# p goes back and forth; only go reaches the goal.
TOGGLE = """variable(p;g). action(on;off;go).
pre(on,p,false). eff(on,p,true). pre(off,p,true). eff(off,p,false). eff(go,g,true).
goal(g,true)."""


@pytest.fixture(scope="module")
def toggle():
    return Model.from_string(TOGGLE)


@pytest.mark.parametrize(
    "question,plan,contrast",
    [
        # The steps before step 5 can only be filled with loops: the step is part of
        # the state the loop-free check compares, else it would "prove" that none exists.
        # Any four steps will do before go (* stands for any action).
        ("why not go at 5", "go", "* * * * go"),
        ("why go within 1..4", "go", "on off on off go"),
        ("why go at 1", "go", "on go"),
        ("why not p", "go", "go on|on go"),
        ("why not p at 4", "go", "go on|on go"),  # after step 4 of a shorter plan: its end
        ("why p at 4", "on go", "go"),
        # go, and no on before the first go: go alone
        ("why go after on", "on go", "go"),
        ("why on before go", "on go", "go"),
        ("why go after on", "on off on go", "go"),
    ],
)
def test_new_forms_give_shortest_contrasts(toggle, question, plan, contrast):
    answer = ask(toggle, question, plan=Plan.parse(plan), max_horizon=10)
    found = str(answer.contrast.plan).split()
    assert answer.status == "found" and any(
        len(found) == len(words) and all(w in ("*", f) for w, f in zip(words, found, strict=True))
        for words in (option.split() for option in contrast.split("|"))
    )
    assert not answer.principle_dropped


def test_questions_no_plan_can_meet_are_proven(toggle):
    answer = ask(toggle, "why not in 0 steps", plan=Plan.parse("go"))
    assert answer.contrast is None and answer.status == "none"
    assert "no plan has at most 0 steps, and the question allows no more" in answer.proof
    assert [str(c) for c in answer.conflict] == ["at_most(0)"]
    assert answer.explanation.endswith(
        "There is no alternative plan: no plan can take at most 0 steps."
    )
    # Against the goal: known before any search.
    answer = ask(toggle, "why g", plan=Plan.parse("go"))
    assert answer.status == "none"
    assert answer.proof.endswith("the question's constraint ends(g,false) contradicts the goal")
    assert answer.explanation.endswith("no plan can end with the fact not g.")


@pytest.mark.parametrize(
    "question,message",
    [
        ("why off", "the plan does not use off (the plan already meets its contrast unused(off))"),
        ("why not go", "the plan already uses go"),
        ("why go at 1", "step 1 of the plan is on"),
        ("why go at 5", "the plan has only 2 steps"),
        ("why not go at 2", "step 2 of the plan already is go"),
        ("why off within 1..2", "the plan does not use off at any step from 1 to 2"),
        ("why not on within 1..2", "the plan already uses on at step 1"),
        ("why g at 1", "g is false after step 1"),
        ("why not p", "p is already true at the end of the plan"),
        ("why not p at 7", "p is true at the end of the plan, which has only 2 steps"),
        ("why not in 2 steps", "the plan has 2 steps, at most 2"),
        ("why off rather than go", "the plan does not use off; ask about what the plan does"),
        ("why off after on", "the plan does not use off; ask about what the plan does"),
        ("why go before off", "the plan does not use off; ask about what the plan does"),
        (
            "why on after go",
            "the plan does not use go before its first on (step 1) (the plan already meets "
            "its contrast before(on,go))",
        ),
        ("why go before on", "the plan does not use go before its first on (step 1)"),
        ("why on after on", "the plan does not use on before its first on (step 1)"),
        ("why on before on", "the plan does not use on before its first on (step 1)"),
    ],
)
def test_failed_presuppositions_get_one_line(toggle, question, message):
    with pytest.raises(InputError) as error:
        ask(toggle, question, plan=Plan.parse("on go"))
    text = str(error.value)
    assert message in text and "\n" not in text and text.startswith(f"question '{question}'")


def test_names_that_are_both_an_action_and_a_variable():
    model = Model.from_string(
        "variable(door;g). action(door;go). eff(door,door,true). eff(go,g,true). goal(g,true)."
    )
    with pytest.raises(
        InputError,
        match="door is both an action and a state variable; say "
        "which: 'why action door' or 'why fact door'",
    ):
        ask(model, "why door", plan=Plan.parse("door go"))
    assert [
        str(c) for c in ask(model, "why action door", plan=Plan.parse("door go")).constraints
    ] == ["unused(door)"]
    assert [
        str(c) for c in ask(model, "why fact door", plan=Plan.parse("door go")).constraints
    ] == ["ends(door,false)"]
    with pytest.raises(InputError, match="unknown state variable go"):
        ask(model, "why fact go", plan=Plan.parse("door go"))
    with pytest.raises(InputError, match="unknown action jump \\(nor a state variable\\)"):
        ask(model, "why jump", plan=Plan.parse("door go"))
    with pytest.raises(InputError, match="a window of steps applies to actions"):
        ask(model, "why g within 1..2", plan=Plan.parse("door go"))


# Regressions: the principle is dropped only on a proof.
EDGE2 = """variable(p;q). action(s1;s2). eff(s1,p,true). pre(s2,p,true). eff(s2,q,true).
utility(p,true,-10). utility(q,true,5).
variable(r). action(w;w2). eff(w,r,true). eff(w2,r,true). goal(r,true)."""


def test_the_principle_is_kept_when_the_search_under_it_is_cut_by_the_horizon():
    model = Model.from_string(EDGE2)
    answer = ask(model, "why w", plan=Plan.parse("w"), principle="utilitarianism", max_horizon=3)
    # Brute force: w2 is a permissible contrast (utility 0 is the best reachable).
    assert not answer.principle_dropped and answer.dropped_because == ""
    assert answer.status in ("found", "bounded")
    if answer.status == "bounded":
        assert answer.contrast is None and "utilitarianism is kept" in answer.note
        assert (
            "No alternative plan permissible under the utilitarianism principle was found "
            "within the search bounds" in answer.explanation
        )
        assert answer.to_json()["principle_dropped"] is False


SETY = """variable(g;good;x;y;z;t). action(setx;sety;setz;mkgood;finish;on;off).
pre(setx,y,true). pre(setx,z,true). eff(setx,x,true). pre(sety,z,false). eff(sety,y,true).
pre(setz,y,false). eff(setz,z,true). eff(mkgood,good,true). eff(finish,g,true).
pre(on,t,false). eff(on,t,true). pre(off,t,true). eff(off,t,false). goal(g,true).
utility(good,true,5). utility(x,true,10)."""


def test_the_principle_is_kept_when_the_time_limit_cuts_the_search():
    from ethasp.planning.budget import Budget

    model = Model.from_string(SETY)
    answer = ask(
        model,
        "why not sety",
        plan=Plan.parse("mkgood finish"),
        principle="utilitarianism",
        budget=Budget(0.0),
    )
    assert answer.status == "bounded" and not answer.principle_dropped
    assert answer.contrast is None and "time limit" in answer.proof
    # Without a limit: a permissible contrast exists (sety, finish, mkgood).
    answer = ask(
        model, "why not sety", plan=Plan.parse("mkgood finish"), principle="utilitarianism"
    )
    assert answer.status == "found" and not answer.principle_dropped
    assert len(answer.contrast.plan) == 3 and answer.contrast.judgement.permissible


# Exogenous events: the alarm goes off at step 3 if the door is open then.
ALARM = """variable(door;alarm;g). action(finish;close).
eff(finish,g,true). eff(finish,door,true). pre(close,door,true). eff(close,door,false).
event(ring). event_at(ring,3). event_effect(ring,k,alarm,true).
event_condition(ring,k,door,true). goal(g,true)."""


def test_states_after_steps_with_events():
    model = Model.from_string(ALARM)
    # After step 2 of a plan of 1 step: its final state, after the event of step 3.
    answer = ask(model, "why alarm at 2", plan=Plan.parse("finish"))
    assert [str(c) for c in answer.constraints] == ["fact_at(alarm,false,2)"]
    contrast = answer.contrast.plan
    assert len(contrast) == 2  # a plan of 1 step ends after the event: alarm on
    with pytest.raises(InputError, match="alarm is false at the end of the plan"):
        ask(model, "why alarm", plan=Plan.parse("finish close"))
    answer = ask(model, "why alarm", plan=Plan.parse("finish"))
    assert str(answer.contrast.plan) == "finish close"


# A derived variable d (d iff v): v can only be false after two steps (c, then
# b), and an event makes the model's search run on explicit layers.
LATE = """variable(v;w;g;x). action(a;b;c). init(v). eff(a,g,true). pre(b,w,true).
eff(b,v,false). eff(c,w,true). derived(d). axiom(d,0). axiom_pre(d,0,v,true).
event(e). event_at(e,1). event_effect(e,1,x,true). goal(g,true)."""


def test_constraints_imposed_in_asp_hold_with_events():
    # fact_at of a derived variable is imposed in ASP, beside the HModel: a
    # shortest plan of the explicit layers (which do not know the constraint)
    # is not a contrast plan; no plan has d false after step 1.
    model = Model.from_string(LATE)
    answer = ask(model, "why d at 1", plan=Plan.parse("a"))
    assert answer.status == "none" and answer.contrast is None
    answer = ask(model, "why d at 2", plan=Plan.parse("a"))
    assert answer.status == "found" and str(answer.contrast.plan) == "c b a"


def test_dialogue_with_a_question_no_plan_can_meet(trolley, monkeypatch):
    from ethasp.questions import contrast as contrast_module

    dialogue = Dialogue.start(trolley, "do-no-harm")
    dialogue.ask("why refrain rather than pull")
    assert dialogue.unmeetable is None
    blocked = dialogue.ask("why pull rather than refrain")
    assert dialogue.unmeetable is blocked and blocked.unmeetable
    # Later questions are answered at once: no plan meets what is imposed.
    monkeypatch.setattr(
        contrast_module,
        "contrast_plan",
        lambda *a, **k: (_ for _ in ()).throw(AssertionError("searched")),
    )
    again = dialogue.ask("why not pull at 2")
    assert again.status == "none" and again.conflict == blocked.conflict
    assert "imposed by the questions before" in again.proof
    monkeypatch.undo()
    dialogue.undo()
    dialogue.undo()
    assert dialogue.unmeetable is None and str(dialogue.current_plan) == "pull"


def test_dialogue_principles_that_cannot_restrict_are_refused(trolley):
    dialogue = Dialogue.start(trolley, "do-no-harm")
    with pytest.raises(
        InputError,
        match=r"principle kantian-humanity cannot restrict plan search .*: "
        r".*deontology, do-no-harm",
    ):
        dialogue.switch_principle("kantian-humanity")
    for group in ("all", "hera", "paper"):
        with pytest.raises(InputError, match=f"principle '{group}' names a group"):
            dialogue.switch_principle(group)
    assert dialogue.under == "do-no-harm"
    with pytest.raises(InputError, match="cannot restrict plan search"):
        Dialogue.start(trolley, "double-effect")
    with pytest.raises(InputError, match="names a group"):
        ask(trolley, "why refrain", principle="all")
    with pytest.raises(InputError, match="cannot restrict plan search"):
        ask(trolley, "why refrain", plan=Plan.parse("refrain"), under="kantian-humanity")


def test_dialogue_starts_from_the_models_own_plan():
    model = Model.load([MODELS / "hera" / "robot-and-frank.yaml"])
    dialogue = Dialogue.start(model, "deontology")
    assert str(dialogue.current_plan) == "lie_to_frank"
    explained = dialogue.explain_step(1)
    assert "Lying to Frank is inherently bad (utility -1)" in explained.step_text(1)
    with pytest.raises(InputError, match="why step 2: the current plan has steps 1 to 1"):
        dialogue.explain_step(2)


def test_the_conflicts_of_a_dropped_principle_trust_the_contrasts_proof(trolley, monkeypatch):
    """The search under the principle proved the whole goal with the question's
    constraints unreachable: the conflicts do not decide that set again, and
    they are those that deciding every set gives."""
    from ethasp.principles import goal_items
    from ethasp.principles.conflict import goal_conflicts

    decided = []
    reach = goal_items.GoalItems.reach

    def recording(self, items):
        decided.append((len(self.items), items))
        return reach(self, items)

    monkeypatch.setattr(goal_items.GoalItems, "reach", recording)
    answer = ask(trolley, "why refrain rather than pull", principle="do-no-harm")
    assert answer.principle_dropped and answer.impasse is not None
    assert decided and all(len(items) < count for count, items in decided), decided
    before = len(decided)
    again = goal_conflicts(trolley, ["do-no-harm"], answer.constraints)
    found = answer.impasse.conflicts
    assert [[i.term for i in c] for c in found.conflicts] == [
        [i.term for i in c] for c in again.conflicts
    ]
    assert found.status == again.status == "proven"
    # Deciding every set (as goal_conflicts alone does) decides the whole one.
    assert any(len(items) == count for count, items in decided[before:])
