"""Causal agency models: the reader, the semantics in ASP, the four principles
that HERA cannot evaluate (on cases derived by hand from their published
definitions), queries, questions and the command line.

The agreement with HERA's verdicts and reasons is tested in
``tests/test_hera_cam_differential.py``.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from ethasp import Model, Plan, query
from ethasp.errors import InputError
from ethasp.planning.readers.cam import translate_data
from ethasp.planning.readers.hera_formulas import FormulaError, parse_hera_formula
from ethasp.principles.judgement import judge
from ethasp.questions.contrast import ask
from ethasp.reasons.reasons import explain

DATA = Path(__file__).parent / "data" / "cam"
ROOT = Path(__file__).resolve().parent.parent

SWITCH = {
    "description": "a tram, one worker on the side track, five on the main track",
    "actions": ["switch", "wait"],
    "patients": ["five", "one"],
    "consequences": ["main_hit", "side_hit"],
    "mechanisms": {"side_hit": "'switch'", "main_hit": "Not('switch')"},
    "utilities": {"side_hit": -1, "main_hit": -5, "Not('side_hit')": 1, "Not('main_hit')": 5},
    "intentions": {"switch": ["switch", "Not('main_hit')"], "wait": ["wait"]},
    "goals": {"switch": ["Not('main_hit')"], "wait": []},
    "affects": {
        "main_hit": [["five", "-"]],
        "side_hit": [["one", "-"]],
        "Not('main_hit')": [["five", "+"]],
        "Not('side_hit')": [["one", "+"]],
    },
}


def load(data: dict, tmp_path: Path, name: str = "cam.json") -> Model:
    path = tmp_path / name
    path.write_text(json.dumps(data))
    return Model.load([path])


def verdicts(model: Model, action: str, principles: list[str]) -> dict[str, bool]:
    report = judge(model, Plan.parse(action), principles)
    assert all(j.status == "proven" for j in report.judgements)
    return {j.principle: j.permissible for j in report.judgements}


# -- HERA's formula strings -------------------------------------------------------


@pytest.mark.parametrize(
    "text,parsed",
    [
        ("'pull'", ("var", "pull")),
        ("pull", ("var", "pull")),
        ('"pull"', ("var", "pull")),
        ("people in building die", ("var", "people in building die")),
        ("Not('d1')", ("not", ("var", "d1"))),
        ("And('a', Not('b'))", ("and", [("var", "a"), ("not", ("var", "b"))])),
        ("Or('a', 'b', 'c')", ("or", [("var", "a"), ("var", "b"), ("var", "c")])),
        ("Impl(a, BiImpl(b, c))", ("imp", ("var", "a"), ("iff", ("var", "b"), ("var", "c")))),
        ("Atom('x y')", ("var", "x y")),
        ("True", ("const", True)),
        (False, ("const", False)),
        ("help", ("var", "help")),  # HERA would evaluate Python's help function
        ("'it\\'s'", ("var", "it's")),
    ],
)
def test_heras_formula_strings_are_parsed(text, parsed):
    assert parse_hera_formula(text) == parsed


@pytest.mark.parametrize(
    "text", ["And('a')", "Xor('a', 'b')", "Not('a'", "'a", "And('a', 'b'))", None]
)
def test_a_formula_that_does_not_parse_is_refused(text):
    with pytest.raises(FormulaError):
        parse_hera_formula(text)


# -- the reader -----------------------------------------------------------------------


def test_the_reader_writes_the_vocabulary_of_cam_model_lp():
    text, warnings = translate_data(SWITCH)
    facts = set(text.splitlines())
    assert warnings == []
    assert {
        "cam_action(switch,1).",
        "cam_action(wait,2).",
        "cam_consequence(main_hit,1).",
        "cam_mechanism(side_hit,var(switch)).",
        "cam_mechanism(main_hit,neg(var(switch))).",
        "utility(main_hit,false,5).",
        "cam_intention(switch,main_hit,false).",
        "cam_goal(switch,main_hit,false).",
        "affects(five,main_hit,true,neg).",
        "patient(one).",
        "variable(wait).",
    } <= facts


def test_names_that_are_no_constants_become_strings():
    data = dict(SWITCH, actions=["shoot it down", "wait"])
    data["mechanisms"] = {"side_hit": "'shoot it down'", "main_hit": "Not('shoot it down')"}
    data["intentions"] = {}
    text, _ = translate_data(data)
    assert 'cam_action("shoot it down",1).' in text
    assert 'cam_mechanism(side_hit,var("shoot it down")).' in text


def test_the_older_layout_is_read_where_its_meaning_is_clear():
    data = {
        "action": "bomb",
        "consequences": {"bomb": ["hit", "noise"], "hit": ["end"], "noise": ["end"]},
        "utilities": {"hit": -1, "end": 10},
        "intended": ["bomb", "end"],
    }
    text, _ = translate_data(data)
    assert "cam_action(bomb,1)." in text
    assert "cam_mechanism(hit,var(bomb))." in text
    assert "cam_mechanism(end,or(var(hit),var(noise)))." in text
    assert "cam_intention(bomb,end,true)." in text


@pytest.mark.parametrize(
    "change,fragment",
    [
        (
            {"mechanisms": {"side_hit": "'swich'", "main_hit": "Not('switch')"}},
            "mechanisms: side_hit: unknown variable 'swich'",
        ),
        (
            {"mechanisms": {"side_hit": "'main_hit'", "main_hit": "'side_hit'"}},
            "a cycle among mechanisms: ",
        ),
        (
            {"mechanisms": {"side_hit": "And('switch'", "main_hit": "Not('switch')"}},
            "mechanisms: side_hit: cannot read the formula",
        ),
        ({"mechanisms": {"main_hit": "Not('switch')"}}, "consequence side_hit has no mechanism"),
        ({"actions": []}, "actions: a causal agency model needs at least one action"),
        ({"actions": ["switch", "switch"]}, "actions: switch is already an action"),
        ({"utilities": {"side_hit": 1.5}}, "utilities: the utility of side_hit must be an integer"),
        ({"affects": {"side_hit": [["one", "?"]]}}, "the sign must be + or -"),
        ({"world": {"switch": True}}, "world: switch is an action"),
        ({"world": {"side_hit": True}}, "world: side_hit is a consequence"),
        ({"action": "switch"}, "both action (HERA's older layout) and actions are given"),
        ({"consequences": {"switch": ["x"]}}, "cannot be combined with mechanisms"),
    ],
)
def test_a_bad_file_gets_one_line_naming_the_field(change, fragment, tmp_path):
    with pytest.raises(InputError) as error:
        load(dict(SWITCH, **change), tmp_path)
    message = str(error.value)
    assert message.startswith(str(tmp_path / "cam.json")) and "\n" not in message
    assert fragment in message


def test_what_hera_ignores_is_ignored_with_a_warning():
    data = dict(SWITCH)
    data["utilities"] = {"side_hit": -1, 'Not("side_hit")': 2, "unknown": 3, "'side_hit'": 4}
    data["intentions"] = {"switch": ["switch", "And('a','b')"], "nobody": ["x"]}
    data["affects"] = {"side_hit": [["stranger", "-"]]}
    data["colour"] = "blue"
    text, warnings = translate_data(data, "m.json")
    joined = "\n".join(warnings)
    for fragment in (
        "'colour' is not a key",
        "read as the negation of side_hit (HERA matches only the spelling Not('side_hit'))",
        "'unknown' is not a variable of the model: ignored",
        "is not a variable or its negation: ignored",
        "intentions: nobody is not an action: ignored",
        "stranger is not listed in patients",
        "a second utility of \"'side_hit'\": ignored (HERA uses the first)",
    ):
        assert fragment in joined
    assert "utility(side_hit,false,2)." in text


def test_a_cam_is_told_from_a_situation_by_its_content(tmp_path):
    model = load(SWITCH, tmp_path, "choice.yml")
    assert model.is_cam and not model.is_situation
    situation = ROOT / "asp" / "hera" / "trolley.yaml"
    assert Model.load([situation]).is_situation
    (tmp_path / "neither.json").write_text('{"description": "nothing"}')
    with pytest.raises(InputError, match="has no initialState"):
        Model.load([tmp_path / "neither.json"])
    (tmp_path / "list.json").write_text("[1, 2]")
    with pytest.raises(InputError, match="the file must be a mapping"):
        Model.load([tmp_path / "list.json"])


def test_the_world_gives_background_variables_and_events(tmp_path):
    model = Model.load([DATA / "footbridge.json"])  # its world: the tram comes
    assert not judge(model, Plan.parse("shove"), ["hera-do-no-harm"]).judgements[0].permissible
    assert query(model, Plan.parse("shove"), "Caused(tram_strikes)").value
    dry = Model.load([DATA / "footbridge.json"], world={"tram_coming": False})
    assert judge(dry, Plan.parse("shove"), ["hera-do-no-harm"]).judgements[0].permissible
    assert not query(dry, Plan.parse("shove"), "Caused(tram_strikes)").value
    with pytest.raises(InputError, match="the model is none"):
        Model.load([ROOT / "asp" / "trolley.lp"], world={"x": True})


# -- the semantics -----------------------------------------------------------------------


@pytest.mark.parametrize(
    "action,formula,value",
    [
        ("switch", "Finally(side_hit) and Finally(-main_hit)", True),
        ("switch", "Caused(side_hit) and Caused(-main_hit) and ButFor(side_hit)", True),
        ("wait", "Caused(main_hit)", False),  # the tram kills the five whatever waiting does
        ("switch", "Causes(switch, side_hit) and not Causes(side_hit, -main_hit)", True),
        ("switch", "Causes(switch | wait, side_hit)", False),  # switch alone causes it
        ("switch", "Do(-switch, main_hit) and not Do(-switch & wait, side_hit)", True),
        ("switch", "I(-main_hit) and not I(side_hit) and Goal(-main_hit)", True),
        ("switch", "Instrumental(switch) and not Instrumental(side_hit)", True),
        ("switch", "End(five) and not End(one) and not Means(one) and Means2(one)", True),
        ("wait", "Means2(one)", False),  # no action affects the one, and waiting causes nothing
        ("switch", "U(side_hit & -main_hit) > 0 and GEq(side_hit & -main_hit, main_hit)", True),
        ("switch", "AffectsNeg(side_hit, one) and not AffectsPos(side_hit, one)", True),
        ("switch", "Bad(side_hit) and Good(-main_hit) and Neutral(switch)", True),
    ],
)
def test_hera_notions_over_a_choice(action, formula, value, tmp_path):
    model = load(SWITCH, tmp_path)
    assert query(model, Plan.parse(action), formula).value is value


def test_operators_of_one_kind_of_model_are_refused_for_the_other(tmp_path):
    model = load(SWITCH, tmp_path)
    with pytest.raises(InputError, match="Avoidable is defined for plans only"):
        query(model, Plan.parse("switch"), "Avoidable(side_hit)")
    plans = Model.load([ROOT / "asp" / "trolley.lp"])
    with pytest.raises(InputError, match="defined for causal agency models only"):
        query(plans, Plan.parse("pull"), "I(one_will_die)")


def test_a_choice_is_one_action_of_the_model(tmp_path):
    model = load(SWITCH, tmp_path)
    with pytest.raises(InputError, match="unknown action jump"):
        judge(model, Plan.parse("jump"))
    with pytest.raises(InputError, match="is one action, not 2"):
        judge(model, Plan.parse("switch wait"))


def test_principles_are_defined_per_kind_of_model(tmp_path):
    model = load(SWITCH, tmp_path)
    with pytest.raises(InputError, match="avoid-any-harm is not defined for causal agency"):
        judge(model, Plan.parse("switch"), ["avoid-any-harm"])
    with pytest.raises(InputError, match="pareto is not defined for plans"):
        judge(Model.load([ROOT / "asp" / "trolley.lp"]), Plan.parse("pull"), ["pareto"])
    names = [j.principle for j in judge(model, Plan.parse("switch"), ["hera"]).judgements]
    assert len(names) == 15 and names[0] == "hera-deontology" and names[-1] == "universality"


def test_planning_commands_refuse_a_cam_in_one_line(tmp_path):
    from ethasp.planning.search import find_plan
    from ethasp.planning.validation import validate
    from ethasp.principles.conflict import goal_conflicts
    from ethasp.principles.repair import repair

    model = load(SWITCH, tmp_path)
    for call in (
        lambda: find_plan(model),
        lambda: validate(model, Plan.parse("switch")),
        lambda: repair(model, ["double-effect"]),  # a CAM has no goal and no changes
        lambda: goal_conflicts(model, ["double-effect"]),
    ):
        with pytest.raises(InputError, match="is a causal agency model"):
            call()


# -- the principles that HERA cannot evaluate, derived by hand ------------------------------

# A physician can give a drug with a side effect, or wait while the illness
# kills the patient (which waiting does not cause).
DRUG = {
    "actions": ["give", "wait"],
    "patients": ["patient"],
    "consequences": ["side_effect", "death"],
    "mechanisms": {"side_effect": "'give'", "death": "Not('give')"},
    "utilities": {"side_effect": -2, "death": -10},
    "affects": {"side_effect": [["patient", "-"]], "death": [["patient", "-"]]},
}


def test_minimize_harm_weighs_the_harms_the_action_causes(tmp_path):
    model = load(DRUG, tmp_path)
    # give causes the side effect (-2); wait causes nothing (the illness kills): 0 > -2
    assert verdicts(model, "give", ["minimize-harm"]) == {"minimize-harm": False}
    assert verdicts(model, "wait", ["minimize-harm"]) == {"minimize-harm": True}


def test_minimax_harm_compares_the_worst_harms(tmp_path):
    model = load(DRUG, tmp_path)
    # the worst harm of give is -2, of wait -10 (caused or not)
    assert verdicts(model, "give", ["minimax-harm"]) == {"minimax-harm": True}
    assert verdicts(model, "wait", ["minimax-harm"]) == {"minimax-harm": False}
    # giving harms twice (-3, -1), waiting once (-2): the worst harm of giving
    # is worse, although not every harm of giving is worse than waiting's (as
    # HERA's code would require)
    two = dict(DRUG, consequences=["side_effect", "itch", "death"])
    two["mechanisms"] = dict(DRUG["mechanisms"], itch="'give'")
    two["utilities"] = {"side_effect": -3, "itch": -1, "death": -2}
    model = load(two, tmp_path, "two.json")
    assert verdicts(model, "give", ["minimax-harm"]) == {"minimax-harm": False}
    assert verdicts(model, "wait", ["minimax-harm"]) == {"minimax-harm": True}


def test_discourse_needs_the_approval_of_every_affected_patient(tmp_path):
    model = load(SWITCH, tmp_path)
    assert verdicts(model, "switch", ["discourse"]) == {"discourse": False}  # the one objects
    assert verdicts(model, "wait", ["discourse"]) == {"discourse": False}  # the five object
    flowers = Model.load([DATA / "bouquet.yaml"])
    assert verdicts(flowers, "give", ["discourse"]) == {"discourse": True}
    assert verdicts(flowers, "skip", ["discourse"]) == {"discourse": False}


def test_universality_needs_consequences_every_patient_prefers(tmp_path):
    model = load(DRUG, tmp_path)
    # the patient is harmed under both: neither choice is worse for them
    assert verdicts(model, "give", ["universality", "discourse"]) == {
        "universality": True,
        "discourse": False,
    }
    assert verdicts(model, "wait", ["universality"]) == {"universality": True}
    flowers = Model.load([DATA / "bouquet.yaml"])
    # skipping harms the receiver and the friend, whom giving makes glad
    assert verdicts(flowers, "give", ["universality"]) == {"universality": True}
    assert verdicts(flowers, "skip", ["universality"]) == {"universality": False}
    switch = load(SWITCH, tmp_path, "switch.json")
    assert verdicts(switch, "switch", ["universality"]) == {"universality": False}


def test_a_large_model_that_clasp_preprocessed_wrongly():
    """A random model of 30 variables (background variables, events, every
    connective) whose evaluations clasp's equivalence preprocessing found
    unsatisfiable: every action is judged under every principle, and
    utilitarianism permits exactly the actions whose consequences are worth most."""
    model = Model.load([Path(__file__).parent / "data" / "cam-large" / "random30.json"])
    reports = [judge(model, Plan.parse(action), ["hera"]) for action in ("a0", "a1", "a2")]
    best = max(report.utility for report in reports)
    for report in reports:
        assert len(report.judgements) == 15
        assert all(j.status == "proven" for j in report.judgements)
        ours = {j.principle: j.permissible for j in report.judgements}
        assert ours["hera-utilitarianism"] == (report.utility == best)


# -- the classic pair -------------------------------------------------------------------


def test_the_bombers_and_the_double_effect_principle():
    model = Model.load([DATA / "terror.json"])
    report = judge(model, Plan.parse("bomb"), ["double-effect", "intention-deontology"])
    assert [j.permissible for j in report.judgements] == [False, False]
    assert report.caused[:2] == ['"school hit"', '"children die"']


# -- reasons ----------------------------------------------------------------------------


def test_inus_reasons_of_a_choice(tmp_path):
    model = load(SWITCH, tmp_path)
    explanation = explain(model, Plan.parse("switch"), "hera-do-no-harm")
    assert explanation.inus_reasons == [["Bad(side_hit)"], ["Caused(side_hit)"]]
    assert explanation.to_json()["inus_reasons"] == explanation.inus_reasons
    assert "side hit" in explanation.text or "side_hit" in explanation.text


def test_inus_reasons_are_cut_by_the_limit(tmp_path):
    model = load(SWITCH, tmp_path)
    explanation = explain(model, Plan.parse("switch"), "hera-do-no-harm", limit=1)
    assert len(explanation.inus_reasons) == 1 and explanation.inus_truncated


def test_the_search_for_inus_reasons_is_cut_by_its_conflicts(monkeypatch):
    """The saturation over a formula that is not read-once may take minutes
    for a few INUS reasons more (the bombers' do-no-instrumental-harm-
    without-intentions took over 30 s for 10): its search stops after a fixed
    number of conflicts, and the list says that more may exist."""
    import ethasp.reasons.reasons as reasons

    model = Model.load(["cam/bombers.yaml"])
    plan = Plan.parse("bomb_factory")
    principle = "do-no-instrumental-harm-without-intentions"
    full = explain(model, plan, principle, limit=10)
    assert full.inus_reasons and full.inus_truncated  # cut by the conflicts, not by 10
    assert len(full.inus_reasons) < 10
    monkeypatch.setattr(reasons, "INUS_CONFLICTS", 1)
    cut = explain(Model.load(["cam/bombers.yaml"]), plan, principle, limit=10)
    assert cut.inus_truncated and len(cut.inus_reasons) <= len(full.inus_reasons)


def test_inus_reasons_of_plans_too():
    model = Model.load([ROOT / "asp" / "trolley.lp"])
    explanation = explain(model, Plan.parse("refrain"), "do-no-harm")
    assert explanation.inus_reasons and explanation.to_json()["inus_reasons_truncated"] is False


# -- questions --------------------------------------------------------------------------


def test_why_one_action_rather_than_another(tmp_path):
    model = load(SWITCH, tmp_path)
    answer = ask(model, "why switch rather than wait", Plan.parse("switch"), "hera-do-no-harm")
    assert answer.contrast.plan == Plan.parse("wait") and not answer.principle_dropped
    assert not answer.original.judgement.permissible and answer.contrast.judgement.permissible
    answer = ask(model, "why not main_hit", Plan.parse("switch"), "hera-utilitarianism")
    assert answer.contrast.plan == Plan.parse("wait") and answer.principle_dropped


def test_questions_about_steps_are_refused_for_a_choice(tmp_path):
    model = load(SWITCH, tmp_path)
    with pytest.raises(InputError, match="is one action"):
        ask(model, "why switch before wait", Plan.parse("switch"), "hera-deontology")


# -- the command line -------------------------------------------------------------------


def ethasp(*arguments: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *arguments],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )


def test_judge_without_a_plan_gives_a_table_of_every_action(tmp_path):
    run = ethasp("judge", str(DATA / "switch.json"), "--principle", "hera-do-no-harm")
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines()[:3] == [
        "principle        switch  wait",
        "hera-do-no-harm  -       +",
        "(+ permissible, - impermissible; every verdict proven)",
    ]
    run = ethasp("judge", str(DATA / "switch.json"), "--principle", "pareto", "--json")
    data = json.loads(run.stdout)
    assert [c["plan"] for c in data["choices"]] == [["switch"], ["wait"]]


def test_judge_a_choice_in_the_shape_of_a_plans_judgement():
    run = ethasp("judge", str(DATA / "switch.json"), "--plan", "switch", "--json")
    data = json.loads(run.stdout)
    assert set(data) == {"plan", "final_state", "utility", "judgements", "caused"}
    assert data["caused"] == ["-main_hit", "side_hit"] and data["utility"] == 4
    assert {"inus_reasons", "sufficient_reasons"} <= set(data["judgements"][0])


def test_world_on_the_command_line():
    run = ethasp(
        "query",
        str(DATA / "footbridge.json"),
        "--plan",
        "shove",
        "--world",
        "tram_coming=false",
        "Caused(tram_strikes)",
    )
    assert run.stdout.strip() == "false"
    run = ethasp("judge", str(DATA / "footbridge.json"), "--world", "tram_coming=maybe")
    assert run.returncode == 2 and "NAME=VALUE" in run.stderr


def test_plan_under_a_group_takes_the_principles_of_a_cam():
    for group, first in (("hera", "hera-deontology"), ("all", "discourse")):
        run = ethasp("plan", "cam/bombers.yaml", "--principle", group, "--json")
        assert run.returncode == 0, run.stderr
        data = json.loads(run.stdout)
        assert data["status"] == "none" and len(data["principles"]) == 15
        assert data["principles"][0] == first
        # every action was judged, and each is named with the principles against it
        assert "bomb_factory under " in data["proof"] and "refrain under " in data["proof"]
    run = ethasp(
        "plan", "cam/bombers.yaml", "--principle", "hera", "--principle", "kantian-humanity"
    )
    assert run.returncode == 0 and "minimal conflicts" not in run.stdout  # a CAM has no goal
    for name in ("paper", "utilitarianism"):
        run = ethasp("plan", "cam/bombers.yaml", "--principle", name)
        assert run.returncode == 2 and len(run.stderr.splitlines()) == 1
        assert "not defined for causal agency models" in run.stderr


def test_batch_plans_a_cam_under_its_own_principles(tmp_path):
    output = tmp_path / "lines.jsonl"
    run = ethasp(
        "batch", "cam/bombers.yaml", "--task", "plan", "--principle", "discourse",
        "--workers", "1", "--output", str(output), "--quiet",
    )  # fmt: skip
    assert run.returncode == 0, run.stdout + run.stderr
    lines = [json.loads(line) for line in output.read_text().splitlines()]
    assert lines and all(line["status"] == "none" for line in lines)


def test_equal_direct_harms_make_one_literal():
    # both bombings kill the children (their only direct harm): one term, one literal
    run = ethasp(
        "judge", "cam/bombers.yaml", "--plan", "refrain", "--principle", "minimize-harm", "--json"
    )
    assert run.returncode == 0, run.stderr
    (judgement,) = json.loads(run.stdout)["judgements"]
    assert judgement["permissible"] is True
    for kind in ("necessary_reasons", "sufficient_reasons", "inus_reasons"):
        assert judgement[kind] == [["GEq((), children_die)"]]
