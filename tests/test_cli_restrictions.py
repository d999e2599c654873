"""ethasp plan --principle: HPlans on the command line, and the HPlanResult API."""

import json
import subprocess
import sys

from conftest import MODELS, ROOT

from ethasp import Model, Plan
from ethasp.principles.restriction import plan_with_principles

TROLLEY = str(MODELS / "trolley.lp")


def ethasp(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )


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
    run = ethasp(
        "plan", "footbridge", "--principle", "deontology", "--principle", "utilitarianism", "--json"
    )
    data = json.loads(run.stdout)
    assert run.returncode == 0
    assert data["status"] == "none" and data["plan"] is None
    assert data["principles"] == ["deontology", "utilitarianism"] and data["best_utility"] == 4
    text = ethasp(
        "plan", "footbridge", "--principle", "deontology", "--principle", "utilitarianism"
    ).stdout
    assert text.startswith("no permissible plan exists")


def test_text_output_names_the_principle_and_the_verdict():
    run = ethasp("plan", TROLLEY, "--principle", "do-no-harm")
    assert run.stdout.startswith("plan of 1 step permissible under do-no-harm: refrain")
    assert "do-no-harm: permissible (proven)" in run.stdout
    # The HPlan's explanation is shown, as ethasp judge shows it.
    assert (
        "The man can refrain from action. Doing so is permissible because this way the "
        "death of the five persons is not caused by the man's action."
    ) in run.stdout


def test_bounded_is_not_none():
    run = ethasp("plan", "rescue", "--principle", "utilitarianism", "--max-horizon", "3", "--json")
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


# -- the edges of the horizon (bounded only where the horizon cut the search) --------

EDGE = (
    "variable(p;q). action(s1;s2). eff(s1,p,true). pre(s2,p,true). eff(s2,q,true). "
    "goal(q,false). utility(p,true,-10). utility(q,true,5)."
)


def test_states_closed_at_the_maximal_horizon_are_a_proof(tmp_path):
    """The farthest reachable state is 2 steps away: with --max-horizon 2 the
    layers up to 2 are closed under every action, which proves the best
    reachable utility; no 'bounded'."""
    path = tmp_path / "edge.lp"
    path.write_text(EDGE)
    for horizon in ("2", "3"):
        data = json.loads(
            ethasp(
                "plan",
                str(path),
                "--principle",
                "utilitarianism",
                "--max-horizon",
                horizon,
                "--json",
            ).stdout
        )
        assert data["status"] == "found" and data["plan"] == [], data
        assert data["best_utility_status"] == "proven"
    data = json.loads(
        ethasp(
            "plan", str(path), "--principle", "utilitarianism", "--max-horizon", "1", "--json"
        ).stdout
    )
    assert data["status"] == "bounded"  # layer 2 holds new states: cut by the horizon


def test_plan_search_proves_none_at_the_maximal_horizon(tmp_path):
    """No plan within 2 steps and no simple path of 3 steps: proven at the
    maximal horizon 2 itself (here by the loop-free check: events keep the
    exact layers out)."""
    path = tmp_path / "none.lp"
    path.write_text(
        "variable(p;q;g). action(s1;s2). eff(s1,p,true). pre(s2,p,true). "
        "eff(s2,q,true). goal(g,true). event(e). event_at(e,1). "
        "event_effect(e,1,p,true). event_pre(e,q,true)."
    )
    data = json.loads(ethasp("plan", str(path), "--max-horizon", "2", "--json").stdout)
    assert data["status"] == "none", data


def test_a_bounded_hplan_is_reported_with_its_plan(tmp_path):
    """Under utilitarianism a plan that reaches the best utility found, where
    a better state is not excluded, is reported: status bounded, the plan,
    its utility (the event due at step 8 keeps the loop-free proof beyond
    the maximal horizon 5)."""
    path = tmp_path / "never.lp"
    path.write_text(
        "variable(g;x;y;h). action(a;b;c). eff(a,x,true). pre(b,x,true). "
        "eff(b,g,true). eff(c,y,true). goal(g,true). utility(g,true,5). "
        "utility(h,true,10). event(e). event_at(e,8). event_pre(e,y,true). "
        "event_pre(e,x,false). event_effect(e,1,h,true). event_condition(e,1,g,true)."
    )
    run = ethasp("plan", str(path), "--principle", "utilitarianism", "--max-horizon", "5", "--json")
    data = json.loads(run.stdout)
    assert data["status"] == "bounded" and data["plan"] == ["a", "b"], data
    assert data["utility"] == 5 and data["best_utility_status"] == "bounded"
    text = ethasp("plan", str(path), "--principle", "utilitarianism", "--max-horizon", "5").stdout
    assert text.startswith(
        "bounded: plan of 2 steps, permissible under utilitarianism as far "
        "as searched (not proven): a b"
    )


def test_a_restricted_search_that_only_the_engines_prove_none_is_proven():
    """Every plan needs the bad action, and paths without repeated states are
    longer than the maximal horizon: the loop-free threshold could not prove
    "none", but the HModel of deontology lacks the bad action, and relaxed
    reachability in it refutes the goal at once.  Likewise a question whose
    constraint needs an action that only a long path makes applicable."""
    ladder = " ".join(
        f"variable(s{i}). action(up{i}). pre(up{i},s{i},true). "
        f"eff(up{i},s{i},false). eff(up{i},s{i + 1},true)."
        for i in range(80)
    )
    text = (
        ladder + " variable(s80). init(s0). variable(g). action(cheat). eff(cheat,g,true). "
        "utility(cheat,-1). goal(g,true)."
    )
    model = Model.from_string(text)
    result = plan_with_principles(model, ["deontology"], max_horizon=64)
    assert result.status == "none", result
    assert "unreachable even ignoring delete effects" in result.proof
    assert plan_with_principles(model, []).status == "found"
    from ethasp.questions.contrast import ask

    answer = ask(
        model,
        "why cheat",
        plan=Plan.parse("cheat"),
        principle="deontology",
        under="deontology",
        max_horizon=64,
    )
    assert answer.status == "none" and answer.contrast is None


def test_a_restriction_that_changes_nothing_keeps_the_model_and_its_grounding():
    """Deontology on a model without bad actions: the HModel is the model
    itself, so plans under it are plain plan search on the one grounding."""
    from ethasp.principles.hmodel import Restriction, hmodel

    model = Model.from_string("variable(g). action(a). eff(a,g,true). goal(g,true).")
    assert hmodel(model, Restriction.of(["deontology"])) is model
    assert hmodel(model, Restriction.of(["do_no_harm"])) is model  # nothing is bad
    bad = Model.from_string(
        "variable(g). action(a;b). eff(a,g,true). eff(b,g,true). goal(g,true). utility(b,-1)."
    )
    assert hmodel(bad, Restriction.of(["deontology"])) is not bad
