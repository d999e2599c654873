"""HERA situations, exogenous events and HERA's principles in ethasp, without
HERA itself (tests/test_hera_differential.py compares with it): the mapping,
the events in every encoding that simulates (trace, steps, runs, plan
search), the bundled examples, HModels, goal-less models, formulas, words and
one-line errors."""

from __future__ import annotations

import itertools
import json
import re
import subprocess
import sys

import pytest
from conftest import MODELS, ROOT, only_answer
from hera_situations import situations
from hypothesis import HealthCheck, assume, given, settings

from ethasp import InputError, Model, Plan
from ethasp.planning.readers.situation import name_term, translate_data
from ethasp.planning.validation import validate
from ethasp.principles.formula import Elements, parse_formula
from ethasp.principles.judgement import counterfactuals, judge, query
from ethasp.principles.restriction import plan_with_principles
from ethasp.reasons.reasons import explain

FRANK = MODELS / "hera" / "robot-and-frank.yaml"
TROLLEY = MODELS / "hera" / "trolley.yaml"
LIGHTNING = MODELS / "lightning.lp"
RESTRICTED = [
    "hera-deontology",
    "goal-deontology",
    "avoid-any-harm",
    "avoid-avoidable-harm",
    "hera-utilitarianism",
    "deontology",
    "do-no-harm",
    "utilitarianism",
]


def ethasp(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )


def verdicts(model: Model, plan: Plan | None = None, principles=("all",)) -> dict[str, bool]:
    report = judge(model, plan if plan is not None else model.own_plan(), list(principles))
    return {j.principle: j.permissible for j in report.judgements}


# -- the events in the encodings --------------------------------------------------------

EVENTS = """
variable(a;b;c). init(c). action(go;stay). eff(go,a,true).
event(e;f). event_at(e,1). event_at(f,1). event_at(f,3).
event_pre(e,a,true).
event_effect(e,1,b,true).  event_condition(e,1,c,true).
event_effect(e,2,c,false).
event_effect(f,3,b,false). event_condition(f,3,a,true).
"""
TRACE = ["planning/model.lp", "planning/trace.lp", "planning/trace_events.lp"]


def test_events_happen_after_the_action_of_their_step_and_the_greatest_key_wins():
    # go at step 1: a holds; e fires (b true, c false), f fires too and its key
    # 3 beats e's key 1: b false.  The plan ends at step 1, f is due again at 3.
    answer = only_answer(TRACE, EVENTS + "occurs(go,1).")
    assert {"final(a,true)", "final(b,false)", "final(c,false)", "plan"} <= answer
    # Without the action, e's precondition fails and f's condition too.
    answer = only_answer(TRACE, EVENTS + "occurs(stay,1).")
    assert {"final(a,false)", "final(b,false)", "final(c,true)"} <= answer


def test_equal_keys_let_true_win_and_events_override_the_action():
    model = """variable(v). action(set_v). eff(set_v,v,true).
               event(x;y). event_at(x,1). event_at(y,1).
               event_effect(x,1,v,false). event_effect(y,1,v,true).
               event(z). event_at(z,2). event_effect(z,2,v,false)."""
    assert "final(v,false)" in only_answer(TRACE, model + "occurs(set_v,1).")
    one = only_answer(TRACE, model.replace("event_at(z,2).", "") + "occurs(set_v,1).")
    assert "final(v,true)" in one


def test_trace_steps_runs_and_search_agree_on_events():
    program = EVENTS + "goal(b,false). goal(c,false)."
    steps = only_answer([*TRACE, "planning/steps.lp"], program + "occurs(go,1).")
    assert {
        "event_set(1,b,false)",
        "event_set(1,c,false)",
        "happened(1,e)",
        "happened(1,f)",
        "happened(3,f)",
    } <= steps
    runs = only_answer(
        ["planning/model.lp", "judgement/runs.lp"],
        program + "run(r). run_length(r,1). run_occurs(r,go,1).",
    )
    assert {"run_final(r,a,true)", "run_final(r,b,false)", "run_final(r,c,false)"} <= runs
    model = Model.from_string(program)
    from ethasp.planning.search import find_plan

    assert find_plan(model).plan == Plan.parse("go")


@pytest.mark.slow
@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(situations(max_events=3, max_plan=4))
def test_the_trace_and_the_runs_give_the_same_final_state(data):
    """Two encodings of the events (values where needed; every state) agree."""
    model = Model.from_string(translate_data(data))
    plan = model.own_plan()
    final = set(validate(model, plan).final_state)
    occurs = "".join(
        f"run_occurs(r,{action},{step}). " for step, action in enumerate(plan.actions, 1)
    )
    runs = only_answer(
        ["planning/model.lp", "judgement/runs.lp"],
        "".join(f"{symbol}.\n" for symbol in model.planner.model_symbols())
        + f"run(r). run_length(r,{len(plan)}). "
        + occurs
        + "#show run_final/3.",
    )
    literal = {"true": "", "false": "-"}
    assert final == {
        literal[atom.split(",")[-1][:-1]] + atom[len("run_final(r,") :].rsplit(",", 1)[0]
        for atom in runs
    }


@pytest.mark.slow
@settings(max_examples=25, deadline=None, suppress_health_check=list(HealthCheck))
@given(situations(max_actions=2, max_events=2, max_plan=2, goal=True))
def test_plan_search_with_events_finds_shortest_plans(data):
    """The shortest plan found reaches the goal when traced, and no shorter
    sequence does (brute force over the sequences, each traced)."""
    from ethasp.planning.search import FOUND, find_plan

    assume(data.get("goal"))
    model = Model.from_string(translate_data(data))
    result = find_plan(model, max_horizon=4)
    actions = [name_term(action["name"]) for action in data["actions"]]
    shortest = None
    for length in range(4):
        for sequence in itertools.product(actions, repeat=length):
            if validate(model, Plan(sequence)).valid:
                shortest = length
                break
        if shortest is not None:
            break
    if shortest is None:
        assert result.status != FOUND or result.horizon >= 4
    else:
        assert result.status == FOUND and result.horizon == shortest
        assert validate(model, result.plan).valid


# -- the examples ---------------------------------------------------------------------


def test_overdetermination_the_paper_forbids_what_hera_permits():
    """A match dropped while lightning strikes: the paper's Caused holds (an
    action has the fire as an effect, and it burns on), HERA's but-for
    causation does not (the lightning burns the forest anyway)."""
    model = Model.load([LIGHTNING])
    plan = model.own_plan()
    assert plan == Plan.parse("drop_match")
    result = verdicts(model, plan, ["do-no-harm", "hera-do-no-harm"])
    assert result == {"do-no-harm": False, "hera-do-no-harm": True}
    assert query(model, plan, "Caused(forest_burns)").value
    assert not query(model, plan, "ButFor(forest_burns)").value
    # Without the lightning, HERA's causation credits the match.
    calm = Model.from_string(LIGHTNING.read_text().replace("event_at(lightning,1).", ""))
    assert verdicts(calm, plan, ["hera-do-no-harm"]) == {"hera-do-no-harm": False}
    run = ethasp(
        "judge", "lightning", "--principle", "do-no-harm", "--principle", "hera-do-no-harm"
    )
    assert run.returncode == 0, run.stderr
    assert "would come about even without the camper's action" in run.stdout


def test_robot_and_frank():
    model = Model.load([FRANK])
    lie = verdicts(model)
    assert lie["hera-deontology"] is False and lie["deontology"] is False
    assert lie["do-no-instrumental-harm"] is False  # deceiving Frank is a means
    assert lie["kantian-humanity"] is True  # ... but Frank is also an end
    assert lie["hera-utilitarianism"] is False  # persuading him ends better
    persuade = verdicts(model, Plan.parse("persuade_frank"))
    assert all(persuade.values()), persuade
    assert query(model, model.own_plan(), "Means(frank) and End(frank)").value
    assert query(model, model.own_plan(), "Instrumental(frank_deceived)").value


def test_trolley_in_hera_format():
    model = Model.load([TROLLEY])
    pull = verdicts(model)
    refrain = verdicts(model, Plan.parse("refrain"))
    # The tram kills: pulling has no death as its effect (the paper's Caused),
    # but without the pull the one would live (HERA's ButFor).
    assert pull["do-no-harm"] is True and pull["hera-do-no-harm"] is False
    assert pull["hera-utilitarianism"] is True and refrain["hera-utilitarianism"] is False
    assert pull["double-effect"] is True and refrain["double-effect"] is False
    assert pull["kantian-humanity-2"] is False and refrain["kantian-humanity-2"] is True
    assert refrain["hera-do-no-harm"] is True


def test_a_situation_is_judged_on_its_own_plan_by_default():
    run = ethasp(
        "judge", "robot-and-frank.yaml", "--principle", "hera", "--json", "--reasons-limit", "1"
    )
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data["plan"] == ["lie_to_frank"]
    assert len(data["judgements"]) == 10
    words = {j["principle"]: j["explanation"] for j in data["judgements"]}
    assert words["do-no-instrumental-harm"].startswith("The robot can lie to Frank.")
    assert "is a means to the robot's goal" in words["do-no-instrumental-harm"]
    run = ethasp("judge", "trolley")  # an ASP model without a plan of its own
    assert run.returncode == 2 and "no plan given" in run.stderr


def test_a_plan_that_misses_its_goal_is_judged(tmp_path):
    data = {
        "actions": [
            {
                "name": "step",
                "preconditions": {"alive": True},
                "effects": [{"condition": {}, "effect": {"crossed": True}}],
            }
        ],
        "events": [
            {
                "name": "car",
                "preconditions": {},
                "effects": [{"condition": {}, "effect": {"alive": False}}],
                "timepoints": [0],
            }
        ],
        "utilities": [{"fact": {"alive": False}, "utility": -5}],
        "plan": ["step", "step"],
        "goal": {"crossed": True, "alive": True},
        "initialState": {"alive": True, "crossed": False},
    }
    path = tmp_path / "crossing.json"
    path.write_text(json.dumps(data))
    run = ethasp("judge", str(path), "--principle", "avoid-any-harm", "--json")
    assert run.returncode == 0, run.stderr
    report = json.loads(run.stdout)
    assert report["goal_reached"] is False and report["judgements"][0]["permissible"] is False
    # An ASP model's plan must reach its goal.
    run = ethasp("judge", "trolley", "--plan", "")
    assert run.returncode == 2 and "goal is not reached" in run.stderr


# -- HModels ------------------------------------------------------------------------------


@pytest.mark.slow
@settings(max_examples=15, deadline=None, suppress_health_check=list(HealthCheck))
@given(situations(max_actions=2, max_events=2, max_plan=2))
def test_restrictions_find_shortest_permissible_plans(data):
    """An HPlan is permissible (judged, proven), no shorter sequence reaching
    the goal is, and "none" means that no sequence of up to three actions is
    (brute force, each sequence judged; bounded answers claim nothing)."""
    model = Model.from_string(translate_data(data))
    actions = [name_term(action["name"]) for action in data["actions"]]

    def proven(plan: Plan, principle: str) -> bool | None:
        judgement = judge(model, plan, [principle]).judgements[0]
        return judgement.permissible if judgement.status == "proven" else None

    for principle in RESTRICTED:
        result = plan_with_principles(model, [principle], max_horizon=3)
        shortest, unknown = None, False
        for length in range(4):
            for sequence in itertools.product(actions, repeat=length):
                plan = Plan(sequence)
                if not validate(model, plan).valid:
                    continue
                verdict = proven(plan, principle)
                unknown = unknown or verdict is None
                if verdict:
                    shortest = length
                    break
            if shortest is not None:
                break
        if result.status == "found":
            assert proven(result.plan, principle) is True, principle
            if shortest is not None and not unknown:
                assert result.horizon == shortest, principle
        elif result.status == "none":
            assert shortest is None, principle


def test_principles_without_a_restriction_say_so_in_one_line():
    for principle in (
        "hera-do-no-harm",
        "do-no-instrumental-harm",
        "kantian-humanity",
        "kantian-humanity-2",
        "double-effect",
    ):
        run = ethasp("plan", "robot-and-frank.yaml", "--principle", principle)
        assert run.returncode == 2 and len(run.stderr.splitlines()) == 1
        assert "has no restriction encoding" in run.stderr


def test_goal_less_models():
    """No goal: every state meets it.  Plain plan search refuses; a principle's
    HModel has the shortest permissible action sequences."""
    run = ethasp("plan", "lightning")
    assert run.returncode == 2 and "the model has no goal" in run.stderr
    model = Model.load([LIGHTNING])
    result = plan_with_principles(model, ["hera-deontology"])
    assert result.status == "found" and len(result.plan) == 0
    # The lightning burns the forest whatever the camper does: proven.
    result = plan_with_principles(model, ["avoid-any-harm"])
    assert result.status == "none"
    assert verdicts(model, Plan.parse("keep_match"), ["avoid-avoidable-harm"]) == {
        "avoid-avoidable-harm": False
    }


# -- formulas, words, reasons ------------------------------------------------------------


def test_hera_operators_in_formulas():
    model = Model.load([FRANK])
    elements = Elements.of_model(model)
    for text in [
        "Goal(frank_healthy) and not Finally(-frank_healthy)",
        "ButFor(frank_deceived) -> Instrumental(frank_deceived)",
        "Avoidable(-frank_healthy) or Means2(frank) or not End(frank)",
        "U(frank_healthy & -frank_deceived) >= 2 - U(())",
        "U(frank_healthy) > U(frank_deceived) -> Means(frank)",
    ]:
        formula = parse_formula(text, elements)
        assert str(parse_formula(str(formula), elements)) == str(formula)
    lie = model.own_plan()
    assert query(model, lie, "U(frank_healthy & frank_deceived) = 1").value
    assert query(model, lie, "U(frank_deceived) < 0 and Goal(frank_healthy)").value
    assert not query(model, lie, "Avoidable(frank_healthy)").value
    for bad, message in [
        ("Means(nobody)", "unknown moral patient"),
        ("Goal(lie_to_frank)", "takes facts"),
        ("U(frank_healthy) >", "expected U(...) or a number"),
    ]:
        with pytest.raises(InputError, match=re.escape(message)):
            parse_formula(bad, elements)


def test_counterfactual_facts_of_the_trolley():
    model = Model.load([TROLLEY])
    facts = {str(f) for f in counterfactuals(model, Plan.parse("pull"))}
    assert "counterfactual(but_for(one_dead,true))" in facts
    assert "counterfactual(but_for(five_dead,false))" in facts
    assert "counterfactual(instrumental(switched,true))" in facts


def test_reasons_and_words_of_hera_principles():
    model = Model.load([TROLLEY])
    why = explain(model, Plan.parse("pull"), "hera-do-no-harm")
    assert not why.permissible and why.chosen_reason
    assert "but for the conductor's action, the death of the one person would not" in why.text
    why = explain(model, Plan.parse("refrain"), "double-effect")
    assert not why.permissible
    assert ["not Goal(five_dead)"] not in why.necessary_reasons


def test_moral_patients_are_named_by_their_labels(tmp_path):
    """patient_label/2 (``labels: patients:`` in a situation) names a patient in
    the words; without a label the patient's term does."""
    why = explain(Model.load([FRANK]), Model.load([FRANK]).own_plan(), "kantian-humanity")
    assert why.permissible and "because Frank is treated as an end" in why.text
    unlabelled = Model.from_string(
        "variable(h). action(help). eff(help,h,true). goal(h,true). patient(ann). "
        "affects(ann,h,true,pos)."
    )
    why = explain(unlabelled, Plan.parse("help"), "kantian-humanity")
    assert "ann is treated as an end" in why.text
    labelled = Model.from_string(unlabelled.sources[0].text + ' patient_label(ann,"Ann").')
    assert (
        "Ann is treated as an end" in explain(labelled, Plan.parse("help"), "kantian-humanity").text
    )
    data = {
        "actions": [{"name": "help", "effects": [{"effect": {"h": True}}]}],
        "affects": {"ann": {"pos": [{"h": True}], "neg": []}},
        "initialState": {"h": False},
        "utilities": [],
        "labels": {"patients": {"ann": "Ann", "bob": "Bob"}},
    }
    with pytest.raises(InputError, match="bob is not a patient of the situation"):
        translate_data(data)


# -- the mapping and its errors ------------------------------------------------------------


def test_names_that_are_not_asp_constants_become_strings():
    data = {
        "actions": [
            {"name": "move_rob-a", "effects": [{"condition": {}, "effect": {"4alive": False}}]}
        ],
        "initialState": {"4alive": True},
        "plan": ["move_rob-a"],
    }
    text = translate_data(data)
    assert 'action("move_rob-a").' in text and 'variable("4alive").' in text
    model = Model.from_string(text)
    assert validate(model, model.own_plan()).final_state == ['-"4alive"']


BAD = [
    ({"actions": [], "initialState": {"a": 1}}, "must be true or false"),
    (
        {"actions": [{"name": "x", "intrinsicvalue": "evil"}], "initialState": {"a": True}},
        "intrinsicvalue must be good, bad or neutral",
    ),
    (
        {
            "actions": [],
            "initialState": {"a": True},
            "utilities": [{"fact": {"a": True}, "utility": 0.5}],
        },
        "must be an integer",
    ),
    (
        {
            "actions": [],
            "initialState": {"a": True, "b": True},
            "affects": {"p": {"pos": [{"a": True, "b": True}]}},
        },
        "a fact of one variable",
    ),
    (
        {
            "actions": [],
            "initialState": {"a": True},
            "events": [{"name": "e", "effects": [], "timepoints": [0]}],
        },
        "e has no preconditions",
    ),
    (
        {"actions": [{"name": "x"}, {"name": "x"}], "initialState": {"a": True}},
        "two actions are named x",
    ),
    (
        {
            "actions": [{"name": "x"}],
            "initialState": {"a": True},
            "plan": ["x"],
            "alternatives": [["y"]],
        },
        "names y, which is not an action",
    ),
    ({"actions": []}, "has no initialState"),
    ([1, 2], "must be a mapping"),
]


def test_what_hera_ignores_is_ignored_with_a_warning(tmp_path):
    data = {
        "actions": [],
        "initialState": {"a": True, "b": True},
        "plan": [],
        "utilities": [
            {"fact": {"a": True, "b": True}, "utility": 5},
            {"fact": {"a": True}, "utility": 1},
            {"fact": {"a": True}, "utility": 2},
        ],
    }
    path = tmp_path / "case.json"
    path.write_text(json.dumps(data))
    run = ethasp("judge", str(path), "--principle", "hera-utilitarianism", "--json")
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["utility"] == 1
    assert "utility 1 is of a fact of 2 variables" in run.stderr
    assert "utility 3 is a second utility" in run.stderr


def test_a_plan_action_hera_does_not_know_is_dropped_with_a_warning(tmp_path):
    data = {
        "actions": [{"name": "x", "effects": [{"condition": {}, "effect": {"a": True}}]}],
        "initialState": {"a": False},
        "plan": ["y", "x"],
        "goal": {"a": True},
    }
    path = tmp_path / "case.json"
    path.write_text(json.dumps(data))
    run = ethasp("validate", str(path), "--json")
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["plan"] == ["x"]
    assert "names y, which is not an action of the situation: dropped" in run.stderr


def test_a_variable_initialstate_leaves_out_is_false_until_set_with_a_warning(tmp_path):
    """HERA leaves such a variable undefined; it is read as false until an
    effect sets it, with a warning that says where the situation reads it as
    false (where HERA's answers may then differ)."""
    data = {
        "actions": [
            {"name": "x", "effects": [{"condition": {}, "effect": {"u": True}}]},
            {
                "name": "y",
                "preconditions": {"w": False},
                "effects": [{"condition": {}, "effect": {"v": True}}],
            },
        ],
        "events": [
            {
                "name": "e",
                "preconditions": {},
                "timepoints": [0],
                "effects": [{"condition": {}, "effect": {"z": True}}],
            }
        ],
        "initialState": {"a": True},
        "plan": ["x"],
        "goal": {"u": True},
        "utilities": [{"fact": {"z": True}, "utility": -1}],
    }
    path = tmp_path / "case.json"
    path.write_text(json.dumps(data))
    run = ethasp("validate", str(path), "--json")
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["final_state"] == ["-v", "-w", "a", "u", "z"]
    warnings = run.stderr.splitlines()
    assert len(warnings) == 4, run.stderr  # u, w, v, z
    (w,) = [line for line in warnings if "variable w " in line]
    assert "HERA's answers may differ" in w and "the preconditions of action y" in w
    assert all("may differ" not in line for line in warnings if line is not w)


@pytest.mark.parametrize("data,message", BAD)
def test_what_cannot_be_mapped_gets_one_line(data, message, tmp_path):
    path = tmp_path / "case.json"
    path.write_text(json.dumps(data))
    run = ethasp("judge", str(path), "--plan", "")
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1, run.stderr
    assert message in run.stderr and "Traceback" not in run.stderr


def test_syntax_errors_name_the_file_and_line(tmp_path):
    path = tmp_path / "case.yaml"
    path.write_text("actions:\n  - name: [unclosed\n")
    run = ethasp("validate", str(path))
    assert run.returncode == 2 and f"{path}:" in run.stderr and "not YAML" in run.stderr
    path = tmp_path / "case.json"
    path.write_text('{"actions": [}')
    run = ethasp("validate", str(path))
    assert run.returncode == 2 and f"{path}:1: not JSON" in run.stderr


def test_intra_action_order_is_kept():
    """HERA applies an action's effects in order: the later one wins, also when
    it sets false; ethasp's true-wins rule gets override conditions."""
    data = {
        "actions": [
            {
                "name": "x",
                "effects": [
                    {"condition": {}, "effect": {"a": True}},
                    {"condition": {"b": True}, "effect": {"a": False}},
                ],
            }
        ],
        "initialState": {"a": False, "b": True},
        "plan": ["x"],
    }
    model = Model.from_string(translate_data(data))
    assert "-a" in validate(model, model.own_plan()).final_state
    data["initialState"]["b"] = False
    model = Model.from_string(translate_data(data))
    assert "a" in validate(model, model.own_plan()).final_state


@pytest.mark.parametrize("satisficing", [False, True])
def test_plan_search_sees_the_events_that_exact_reachability_does_not_model(
    satisficing, monkeypatch
):
    """The diagrams know the actions alone: with events, the layers beside plan
    search (started at once here) are explicit ones of configurations, which
    model them.  An event at step 2 reaches the goal (the empty plan is a
    plan), and another at step 1 undoes what an action did (so no 2-step
    plan works)."""
    from ethasp.planning import search
    from ethasp.planning.budget import Budget
    from ethasp.planning.driver.planner import Setting
    from ethasp.planning.search import FOUND, find_plan

    monkeypatch.setattr(search, "LAYERS_AFTER", 0.0)

    given_by_event = Model.from_string(
        "variable(g). action(wait). goal(g,true). "
        "event(e). event_at(e,2). event_effect(e,1,g,true)."
    )
    assert search._Exact(given_by_event.planner, Setting(), Budget(), True).usable
    result = find_plan(given_by_event, satisficing=satisficing)
    assert result.status == FOUND and len(result.plan) == 0
    undone = Model.from_string(
        "variable(g). variable(h). action(set). eff(set,g,true). action(mark). "
        "pre(mark,g,true). eff(mark,h,true). goal(h,true). "
        "event(e). event_at(e,1). event_effect(e,1,g,false)."
    )
    result = find_plan(undone, satisficing=satisficing)
    assert result.status == FOUND
    assert validate(undone, result.plan).valid
    if not satisficing:
        assert [str(a) for a in result.plan.actions] == ["set", "set", "mark"]


def test_an_event_step_beyond_ten_thousand_is_refused():
    """Plan search grounds every step up to the last event: a step is at most
    10,000, so that a far time point cannot make a search ground for ever."""
    base = "variable(x). action(a). eff(a,x,true). goal(x,true). event(e). "
    Model.from_string(base + "event_at(e,10000).")
    with pytest.raises(InputError, match="from 1 to 10000"):
        Model.from_string(base + "event_at(e,10001).")
