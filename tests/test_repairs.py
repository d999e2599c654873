"""Conflicts and repairs on examples: the encodings alone (the soft HModel,
the repaired model, the changes to try, the map of MARCO), the API, the
command line (ethasp plan --principle when no plan is permissible, ethasp
repair), the answers whose principle is dropped, the page, PDDL annotation
files and HERA situations."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import clingo
import pytest
from conftest import ENCODINGS

from ethasp import InputError, Model, Plan, goal_conflicts, repair
from ethasp.planning.validation import validate
from ethasp.principles.repair import allowed_changes, declares_changes, distance, repaired_model
from ethasp.questions.contrast import ask

ROOT = Path(__file__).resolve().parent.parent
TROLLEY = (ROOT / "asp" / "trolley.lp").read_text()
# The trolley problem with a second goal, saving the five, which costs 5 to
# drop, and an alarm that a repair may add (docs/repairs.md).
ALARM = """
goal(five_will_die,false). goal_cost(five_will_die,false,5).
creative(alarm,2). eff(alarm,done,true). eff(alarm,five_will_die,false).
action_label(alarm,"sound the alarm","sounding the alarm").
"""
# A second goal, safe, that only pulling reaches.
SAFE = "variable(safe). goal(safe,true). eff(pull,safe,true).\n"


def cli(*arguments: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *arguments],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=ROOT,
    )


def texts(model: Model, sets) -> list[list[str]]:
    return [[item.text(model.naming) for item in items] for items in sets]


# -- the encodings -------------------------------------------------------------------


def shown(encodings: list[str], program: str) -> list[str]:
    ctl = clingo.Control(["--warn=none"])
    for name in encodings:
        ctl.load(str(ENCODINGS / name))
    ctl.add("base", [], program)
    ctl.ground([("base", [])])
    found: list[str] = []
    ctl.solve(on_model=lambda m: found.extend(str(s) for s in m.symbols(shown=True)))
    return sorted(found)


def test_the_soft_hmodel_leaves_the_goals_items_out_and_names_them():
    atoms = shown(
        ["planning/model.lp", "restrictions/hmodel.lp", "questions/restriction.lp"],
        TROLLEY + "contrast(q,unused(refrain)). contrast(q,at_most(1)). soft_goals.\n"
        "#show goal_of/3.",
    )
    assert "goal_of(goal(done,true),done,true)" in atoms
    assert "goal_of(unused(refrain),ethasp(used(refrain)),false)" in atoms
    assert "goal_of(at_most(1),ethasp(longer(1)),false)" in atoms
    assert not any(atom.startswith("hmodel(goal(") for atom in atoms)
    # without soft goals: the action is removed, and the goal kept
    atoms = shown(
        ["planning/model.lp", "restrictions/hmodel.lp", "questions/restriction.lp"],
        TROLLEY + "contrast(q,unused(refrain)).",
    )
    assert "hmodel(goal(done,true))" in atoms and "hmodel(action(refrain))" not in atoms


def test_goal_deontology_ties_its_unreachable_goal_to_the_bad_goal_fact():
    model = "variable(v). action(a). eff(a,v,true). goal(v,true). utility(v,true,-1). soft_goals."
    atoms = shown(
        ["planning/model.lp", "restrictions/hmodel.lp", "restrictions/goal_deontology.lp"],
        model + "#show goal_of/3.",
    )
    assert "goal_of(goal(v,true),ethasp(unreachable),true)" in atoms
    assert "hmodel(variable(ethasp(unreachable)))" in atoms


def test_the_repaired_model_is_a_difference_of_facts():
    atoms = shown(
        ["planning/model.lp", "repairs/repaired.lp"],
        TROLLEY + ALARM + "changeable(one_will_die). event(e). event_at(e,2). preventable(e).\n"
        "repair(add(alarm)). repair(initial(one_will_die)). repair(prevent(e)). "
        "repair(drop(done,true)). repair(add(nothing)).",
    )
    assert atoms == [
        "repair_adds(action(alarm))",
        "repair_adds(init(one_will_die))",
        "repair_removes(event_at(e,2))",
        "repair_removes(goal(done,true))",
        "repair_unknown(add(nothing))",
    ]


def test_the_changes_to_try_come_cheapest_first():
    program = TROLLEY + ALARM + "changeable(one_will_die,1). changeable(done,3)."
    ctl = clingo.Control(["--opt-mode=optN", "0"])
    for name in ("planning/model.lp", "repairs/changes.lp"):
        ctl.load(str(ENCODINGS / name))
    ctl.add("base", [], program + "tried(0). tried(1). tried_change(1,initial(one_will_die)).")
    ctl.ground([("base", [])])
    optimal = []
    ctl.solve(
        on_model=lambda m: optimal.append(
            sorted(str(s) for s in m.symbols(shown=True)) if m.optimality_proven else None
        )
    )
    # the empty set and {initial(one_will_die)} were tried: next, the alarm (cost 2)
    assert [found for found in optimal if found is not None] == [["chosen(add(alarm))"]]


# -- conflicts ------------------------------------------------------------------------


def test_conflicts_of_the_trolley_with_a_goal_only_pulling_reaches():
    model = Model.from_string(TROLLEY + SAFE)
    result = goal_conflicts(model, ["do-no-harm"])
    assert result.status == "proven" and not result.empty_goal_fails
    assert texts(model, result.conflicts) == [["safe"]]
    assert [(texts(model, [s.items])[0], str(s.plan)) for s in result.goal_subsets] == [
        (["done"], "refrain")
    ]
    assert goal_conflicts(model, ["deontology"]).conflicts == []


def test_no_permissible_plan_even_without_a_goal_is_the_empty_conflict():
    model = Model.load([ROOT / "asp" / "lightning.lp"])
    result = goal_conflicts(model, ["avoid-any-harm"])
    assert result.status == "proven" and result.empty_goal_fails
    assert result.conflicts == [[]] and result.goal_subsets == []


def test_a_questions_constraint_counts_like_a_goal_fact():
    model = Model.load([ROOT / "asp" / "trolley.lp"])
    constraints = model.planner.question([clingo.parse_term("used(pull)")])
    result = goal_conflicts(model, ["do-no-harm"], constraints)
    assert texts(model, result.conflicts) == [["used(pull)"]]
    assert texts(model, [s.items for s in result.goal_subsets]) == [["done"]]


def test_limit_zero_computes_nothing():
    model = Model.from_string(TROLLEY + SAFE)
    result = goal_conflicts(model, ["do-no-harm"], limit=0)
    assert result.conflicts == [] and result.conflicts_truncated


def test_plan_prints_the_conflicts_when_no_plan_is_permissible(tmp_path):
    extra = tmp_path / "safe.lp"
    extra.write_text(SAFE)
    done = cli("plan", "trolley", str(extra), "--principle", "do-no-harm")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith("no permissible plan exists: ")
    assert lines[1].startswith("No plan is permissible under the do-no-harm principle. ")
    assert "The shortest plan that does (pull the lever) is impermissible" in lines[1]
    assert lines[2:] == [
        "minimal conflicts (proven):",
        "  {safe}",
        "maximal goal subsets, each with a shortest permissible plan:",
        "  {done}: refrain",
    ]
    asked = ("plan", "trolley", str(extra), "--principle", "do-no-harm")
    data = json.loads(cli(*asked, "--json").stdout)
    assert data["conflicts"] == [["safe"]]
    assert data["goal_subsets"] == [{"literals": ["done"], "plan": ["refrain"]}]
    assert data["conflicts_status"] == "proven"
    assert data["conflicts_truncated"] is False and data["goal_subsets_truncated"] is False
    quiet = cli(*asked, "--json", "--reasons-limit", "0")
    assert "conflicts" not in json.loads(quiet.stdout)


# -- repairs ---------------------------------------------------------------------------


def test_the_cheapest_repair_adds_the_alarm():
    model = Model.from_string(TROLLEY + ALARM)
    assert declares_changes(model)
    assert [str(c.term) for c in allowed_changes(model)] == [
        "add(alarm)",
        "drop(done,true)",
        "drop(five_will_die,false)",
    ]
    result = repair(model, ["do-no-harm"])
    assert result.status == "found" and result.cost == 2 and not result.truncated
    (found,) = result.repairs
    assert [change.text(model.naming) for change in found.changes] == [
        "add the creative alternative alarm"
    ]
    assert str(found.plan) == "alarm" and found.optimal
    assert [(j.principle, j.permissible) for j in found.judgements] == [("do-no-harm", True)]
    # the repaired model has the alarm, the model has not
    assert validate(found.model, Plan.parse("alarm")).valid
    with pytest.raises(InputError, match="creative alternative"):
        validate(model, Plan.parse("alarm"))


def test_without_the_cost_of_the_goal_dropping_it_is_cheapest():
    model = Model.from_string(TROLLEY + ALARM.replace("goal_cost(five_will_die,false,5).", ""))
    result = repair(model, ["do-no-harm"])
    assert result.cost == 1
    assert [[str(c.term) for c in r.changes] for r in result.repairs] == [
        ["drop(five_will_die,false)"]
    ]
    assert str(result.repairs[0].plan) == "refrain"


def test_no_change_needed_and_no_change_helps():
    model = Model.load([ROOT / "asp" / "trolley.lp"])
    result = repair(model, ["do-no-harm"])
    assert result.status == "found" and result.cost == 0
    assert result.repairs[0].changes == [] and str(result.repairs[0].plan) == "refrain"
    fixed = Model.load([ROOT / "asp" / "lightning.lp"])
    none = repair(fixed, ["avoid-any-harm"])
    assert none.status == "none" and none.repairs == [] and none.cost is None


def test_repairs_towards_a_plan_keep_its_actions():
    model = Model.from_string(TROLLEY + ALARM + "creative(wave,2). eff(wave,done,true).")
    result = repair(model, ["do-no-harm"], plan=Plan.parse("alarm"))
    assert [str(r.plan) for r in result.repairs] == ["alarm"]
    assert result.repairs[0].distance == 0
    assert distance(Plan.parse("a b a"), Plan.parse("a c")) == 3


def test_a_changeable_initial_value_and_a_preventable_event():
    model = Model.from_string(
        "variable(hurt). variable(done). action(go). eff(go,done,true). goal(done,true).\n"
        "goal_fixed(done,true). utility(hurt,true,-1).\n"
        "event(storm). event_at(storm,1). event_effect(storm,k,hurt,true). preventable(storm,3).\n"
        "init(hurt). changeable(hurt,2).\n"
    )
    result = repair(model, ["avoid-any-harm"])
    assert [[c.text(model.naming) for c in r.changes] for r in result.repairs] == [
        ["start with -hurt", "prevent the event storm"]
    ]
    assert result.cost == 5


def test_the_repaired_model_of_no_change_is_the_model():
    model = Model.load([ROOT / "asp" / "trolley.lp"])
    assert repaired_model(model, []) is model


def test_the_repair_command(tmp_path):
    extra = tmp_path / "alarm.lp"
    extra.write_text(ALARM)
    done = cli("repair", "trolley", str(extra), "--principle", "do-no-harm")
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [
        "1 repair of cost 2 (least, proven): no repair costs less than 2: every set of "
        "changes costing less was tried",
        "  1. add the creative alternative alarm (2)",
        "     plan of 1 step permissible under do-no-harm (shortest plan): alarm",
    ]
    asked = ("repair", "trolley", str(extra), "--principle", "do-no-harm")
    data = json.loads(cli(*asked, "--json", "--plan", "pull").stdout)
    assert data["status"] == "found" and data["cost"] == 2 and data["towards"] == ["pull"]
    (found,) = data["repairs"]
    assert found["changes"] == [
        {
            "kind": "add",
            "cost": 2,
            "action": "alarm",
            "text": "add the creative alternative alarm",
        }
    ]
    assert found["plan"] == ["alarm"] and found["distance"] == 2
    assert found["judgements"][0]["permissible"] is True
    none = cli("repair", "lightning", "--principle", "avoid-any-harm")
    assert none.stdout.startswith("no repair: no change the model allows admits")


# -- when a question's principle is dropped ------------------------------------------


def test_an_answer_whose_principle_is_dropped_shows_the_conflict_and_the_cheapest_repair():
    alarm = ALARM.replace("goal(five_will_die,false). goal_cost(five_will_die,false,5).", "")
    model = Model.from_string(TROLLEY + alarm)
    answer = ask(model, "why five_will_die", Plan.parse("refrain"), principle="do-no-harm")
    assert answer.principle_dropped and answer.impasse is not None
    impasse = answer.impasse
    assert texts(model, impasse.conflicts.conflicts) == [["ends(five_will_die,false)"]]
    assert impasse.repair is not None and impasse.repair.cost == 2
    assert str(impasse.repair.repairs[0].plan) == "alarm"
    assert (
        "The cheapest change that would admit a plan permissible under the do-no-harm "
        "principle: add the creative alternative alarm (cost 2); then the man could sound "
        "the alarm." in impasse.text
    )
    data = answer.to_json()
    assert data["conflicts"] == [["ends(five_will_die,false)"]]
    assert data["repair"]["repairs"][0]["plan"] == ["alarm"]
    # the paper's words stay as they were
    assert "cheapest" not in answer.explanation


def test_without_declared_changes_the_answer_has_no_repair():
    model = Model.load([ROOT / "asp" / "trolley.lp"])
    answer = ask(model, "why refrain rather than pull", principle="do-no-harm")
    assert answer.impasse is not None and answer.impasse.repair is None
    assert texts(model, answer.impasse.conflicts.conflicts) == [
        ["used(pull)"],
        ["done", "unused(refrain)"],
    ]


# -- the model forms -------------------------------------------------------------------


def test_a_pddl_instance_declared_creative_is_added_by_a_repair(tmp_path):
    pddl = ROOT / "asp" / "pddl"
    extra = tmp_path / "creative.lp"
    extra.write_text("creative(pull,2).\n")
    files = [
        pddl / "trolley-domain.pddl",
        pddl / "trolley-problem.pddl",
        pddl / "trolley-utility.lp",
        extra,
    ]
    model = Model.load(files)
    assert [str(a.arguments[0]) for a in model.planner.get("action", 1)] == ["refrain"]
    assert [str(c.term) for c in allowed_changes(model)] == ["add(pull)", "drop(done,true)"]


def test_a_hera_situation_declares_its_changes(tmp_path):
    situation = tmp_path / "frank.yaml"
    situation.write_text(
        """
initialState: {frank_deceived: false, frank_motivated: false, frank_healthy: false}
actions:
  - name: lie_to_frank
    intrinsicvalue: bad
    preconditions: {}
    effects: [{condition: {}, effect: {frank_deceived: true, frank_motivated: true}}]
events:
  - name: frank_walks
    preconditions: {frank_motivated: true}
    effects: [{condition: {}, effect: {frank_healthy: true}}]
    timepoints: [1]
goal: {frank_healthy: true}
changes:
  actions:
    - name: call_daughter
      preconditions: {}
      effects: [{condition: {}, effect: {frank_motivated: true}}]
      cost: 2
  initialState: {frank_motivated: 3}
  events: {frank_walks: 4}
  goal: {frank_healthy: fixed}
labels:
  actions:
    call_daughter: [call Frank's daughter, calling Frank's daughter]
"""
    )
    model = Model.load([situation])
    assert [(str(c.term), c.cost) for c in allowed_changes(model)] == [
        ("add(call_daughter)", 2),
        ("initial(frank_motivated)", 3),
        ("prevent(frank_walks)", 4),
    ]
    result = repair(model, ["hera-deontology"])
    assert result.cost == 2 and str(result.repairs[0].plan) == "call_daughter"
