"""Judgements and queries through the API and the command line: the paper's cases."""

import json
import subprocess
import sys

import pytest
from conftest import MODELS, ROOT

from ethasp import InputError, Model, Plan, judge, query
from ethasp.planning.budget import Budget
from ethasp.planning.engines.best_state import best_reachable
from ethasp.principles.principle import available_principles, select_principles

TROLLEY = str(MODELS / "trolley.lp")
FOOTBRIDGE = str(MODELS / "footbridge.lp")

# (model, plan) -> permissible under deontology, do-no-harm, utilitarianism
PAPER = {
    (TROLLEY, "refrain"): (True, True, False),
    (TROLLEY, "pull"): (True, False, True),
    (FOOTBRIDGE, "push"): (False, False, True),
    (FOOTBRIDGE, "refrain"): (True, True, False),
}


def ethasp(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )


@pytest.mark.parametrize("case", list(PAPER))
def test_paper_cases_through_the_api(case):
    path, plan = case
    report = judge(Model.load([path]), Plan.parse(plan))
    verdicts = {j.principle: (j.permissible, j.status) for j in report.judgements}
    expected = dict(zip(["deontology", "do-no-harm", "utilitarianism"], PAPER[case], strict=True))
    assert verdicts == {name: (value, "proven") for name, value in expected.items()}


@pytest.mark.parametrize("case", list(PAPER))
def test_paper_cases_through_the_command_line(case):
    path, plan = case
    run = ethasp("judge", path, "--plan", plan, "--json")
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    assert data["plan"] == [plan]
    assert [j["principle"] for j in data["judgements"]] == [
        "deontology",
        "do-no-harm",
        "utilitarianism",
    ]
    assert tuple(j["permissible"] for j in data["judgements"]) == PAPER[case]
    assert all(j["status"] == "proven" for j in data["judgements"])
    # Utilitarianism: decided by a better state, or the final state is a best one.
    utilitarian = data["judgements"][2]
    state = utilitarian["best_reachable" if PAPER[case][2] else "compared_with"]
    assert state["utility"] == 4
    assert "-five_will_die" in state["state"] and "done" in state["state"]
    assert ("compared_with" in utilitarian) != PAPER[case][2]
    run = ethasp(
        "judge",
        path,
        "--plan",
        plan,
        "--json",
        "--best",
        "--principle",
        "utilitarianism",
        "--reasons-limit",
        "0",
    )
    best = json.loads(run.stdout)["judgements"][0]["best_reachable"]
    assert best["utility"] == 4 and best["status"] == "proven" and best["horizon"] == 1


def test_json_report_of_pull():
    data = json.loads(ethasp("judge", TROLLEY, "--plan", "pull", "--json").stdout)
    assert data["final_state"] == ["-five_will_die", "done", "one_will_die"]
    assert data["utility"] == 4
    assert set(data["judgements"][0]) == {
        "principle",
        "permissible",
        "status",
        "proof",
        "sufficient_reasons",
        "necessary_reasons",
        "inus_reasons",
        "chosen_reason",
        "explanation",
        "reasons_truncated",
        "necessary_reasons_truncated",
        "sufficient_reasons_truncated",
        "inus_reasons_truncated",
    }


def test_text_report_and_principle_selection():
    run = ethasp(
        "judge",
        "trolley",
        "--plan",
        "pull",
        "--principle",
        "do-no-harm",
        "--principle",
        "deontology",
    )
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    lines = lines[lines.index("plan: pull") :]  # after the explanations
    assert lines[0] == "plan: pull"
    assert lines[1] == "final state: -five_will_die done one_will_die (utility 4)"
    assert lines[2:] == ["do-no-harm: impermissible (proven)", "deontology: permissible (proven)"]
    run = ethasp("judge", "trolley", "--plan", "refrain", "--principle", "utilitarianism")
    assert "utilitarianism: impermissible (proven)" in run.stdout
    assert (
        "a better reachable state: -five_will_die done one_will_die (utility 4, 1 step away)"
        in run.stdout
    )


@pytest.mark.parametrize(
    "args, message",
    [
        (["judge", TROLLEY, "--plan", "jump"], "unknown action jump"),
        (["judge", "rescue", "--plan", "move(r1,r2)"], "not a plan: the goal is not reached"),
        (["judge", "rescue", "--plan", "move(r2,r3)"], "not a plan: step 1"),
        (["judge", TROLLEY, "--plan", "pull", "--principle", "kant"], "unknown principle 'kant'"),
        (["query", TROLLEY, "--plan", "pull", "Bad(pull"], "formula: column 9: expected ')'"),
        (["query", TROLLEY, "--plan", "pull", "Bad(jump)"], "unknown action or variable 'jump'"),
        (["query", "rescue", "--plan", "move(r1,r2)", "Bad(break_door)"], "not a plan"),
    ],
)
def test_bad_input_is_one_line_with_exit_code_2(args, message):
    run = ethasp(*args)
    assert run.returncode == 2
    assert message in run.stderr and len(run.stderr.strip().splitlines()) == 1, run.stderr
    assert "Traceback" not in run.stderr


def test_invalid_plan_through_the_api():
    model = Model.load([str(MODELS / "rescue.lp")])
    for principles in (None, ["deontology"]):
        with pytest.raises(InputError, match="not a plan"):
            judge(model, Plan.parse("move(r1,r2)"), principles)


def test_query_through_the_api_and_the_command_line():
    model = Model.load([TROLLEY])
    pull = Plan.parse("pull")
    geq = "GEq(-five_will_die & one_will_die & done, five_will_die & -one_will_die & done)"
    assert query(model, pull, geq).value
    assert not query(model, pull, "Caused(-one_will_die)").value
    assert query(model, pull, "Caused(-five_will_die) and Caused(one_will_die)").value
    assert query(model, Plan.parse("refrain"), "not Caused(five_will_die)").value
    assert query(model, pull, "Bad(one_will_die) -> not Caused(one_will_die)").value is False
    run = ethasp("query", TROLLEY, "--plan", "pull", geq)
    assert run.returncode == 0 and run.stdout.strip() == "true"
    run = ethasp("query", TROLLEY, "--plan", "refrain", geq.replace("GEq", "not GEq"), "--json")
    data = json.loads(run.stdout)
    assert data == {"plan": ["refrain"], "formula": "not " + geq, "value": False}


def test_principles_are_discovered_from_the_folder():
    names = [p.name for p in available_principles()]
    assert {"deontology", "do-no-harm", "utilitarianism"} <= set(names)
    assert [p.asp_name for p in select_principles(["do_no_harm", "do-no-harm"])] == ["do_no_harm"]
    assert [p.name for p in available_principles() if p.reads_alternatives] == ["utilitarianism"]
    # Without names, the paper's three; groups name several.
    assert [p.name for p in select_principles(None)] == [
        "deontology",
        "do-no-harm",
        "utilitarianism",
    ]
    assert len(select_principles(["all"])) == len(names)


# -- the best reachable state and honest statuses ----------------------------------

# A chain: each go step moves one position further; only position 6 is good.
# u(initial state) = u(-at(6)) = -2, and so is every state before at(6) is
# reached (at(0) false gives 1, some at(P) true gives -1); at(6) gives 5 + 1 = 6,
# which is also the upper bound.  harm is very bad for the final state.
CHAIN = """
pos(0..6). variable(at(P)) :- pos(P). variable(done; hurt).
action(go(P)) :- pos(P), pos(P+1).
pre(go(P),at(P),true) :- action(go(P)).
eff(go(P),at(P),false) :- action(go(P)).
eff(go(P),at(P+1),true) :- action(go(P)).
action(finish). eff(finish,done,true).
action(harm). eff(harm,hurt,true).
init(at(0)). goal(done,true).
utility(at(6),true,5). utility(at(6),false,-2). utility(at(0),false,1).
utility(at(P),true,-1) :- pos(P), P > 0, P < 6.
utility(hurt,true,-10).
"""
TO_THE_END = "go(0) go(1) go(2) go(3) go(4) go(5) finish"


def test_best_reachable_is_found_and_proven():
    best = best_reachable(Model.from_string(CHAIN).planner, Budget())
    assert best.status == "proven" and best.utility == 6 and "at(6)" in best.state
    assert best.horizon == 6  # exact reachability: at(6) is 6 steps away
    assert "upper bound" in best.proof


def test_best_reachable_is_bounded_by_the_horizon():
    best = best_reachable(Model.from_string(CHAIN).planner, Budget(), max_horizon=4)
    assert best.status == "bounded" and best.utility == -2 and best.searched == 4


def test_permissible_needs_the_proven_optimum():
    model = Model.from_string(CHAIN)
    # within 2 steps no state beats -2, but a better one exists
    judgement = judge(model, Plan.parse("finish"), ["utilitarianism"], max_horizon=2).judgements[0]
    assert judgement.permissible and judgement.status == "bounded"
    judgement = judge(model, Plan.parse("finish"), ["utilitarianism"]).judgements[0]
    assert not judgement.permissible and judgement.status == "proven"
    # the best plan: permissible, proven even with a small horizon (its final
    # state attains the upper bound, so no search is needed)
    judgement = judge(model, Plan.parse(TO_THE_END), ["utilitarianism"], max_horizon=2).judgements[
        0
    ]
    assert judgement.permissible and judgement.status == "proven"
    assert "upper bound" in judgement.proof
    judgement = judge(model, Plan.parse(TO_THE_END), ["utilitarianism"]).judgements[0]
    assert judgement.permissible and judgement.status == "proven"


def test_impermissible_is_proven_by_any_better_state_found():
    model = Model.from_string(CHAIN)
    report = judge(model, Plan.parse("harm finish"), ["utilitarianism"], max_horizon=2)
    judgement = report.judgements[0]
    assert report.utility == -12
    assert judgement.best_reachable is None and judgement.compared.utility > -12
    assert not judgement.permissible and judgement.status == "proven"


def test_time_limit_gives_bounded(tmp_path):
    path = tmp_path / "chain.lp"
    path.write_text(CHAIN)
    run = ethasp(
        "judge",
        str(path),
        "--plan",
        "finish",
        "--principle",
        "utilitarianism",
        "--max-horizon",
        "1",
        "--json",
    )
    judgement = json.loads(run.stdout)["judgements"][0]
    assert judgement["status"] == "bounded" and judgement["permissible"]
    run = ethasp(
        "judge",
        str(path),
        "--plan",
        "finish",
        "--principle",
        "utilitarianism",
        "--max-horizon",
        "1",
    )
    assert "permissible as far as searched (bounded, not proven)" in run.stdout
    cancelled = Budget()
    cancelled.cancel()
    report = judge(
        Model.from_string(CHAIN), Plan.parse("finish"), ["utilitarianism"], budget=cancelled
    )
    assert report.judgements[0].status == "bounded"
    assert "cancelled" in report.judgements[0].proof


def test_large_models_are_probed_by_short_searches_first():
    """More than 300 variables: a better state one step away is found by a short
    search before any diagram is built (and the verdict is proven)."""
    lines = ["variable(done). action(finish). eff(finish,done,true). goal(done,true)."]
    for i in range(320):
        lines.append(f"variable(on({i})). action(switch({i})). eff(switch({i}),on({i}),true).")
    lines.append("utility(on(7),true,3).")
    model = Model.from_string("\n".join(lines))
    judgement = judge(model, Plan.parse("finish"), ["utilitarianism"]).judgements[0]
    assert not judgement.permissible and judgement.status == "proven"
    assert judgement.proof.startswith("a state of utility 3 is reachable within ")
    assert model.planner.reachability_pending()  # no diagram was needed


# -- utilitarianism with exogenous events: the upper bound counts what events do ----

ARMED = (
    "variable(armed;happy). action(arm;idle). eff(arm,armed,true). event(e). "
    "event_at(e,1). event_effect(e,1,happy,true). event_condition(e,1,armed,true). "
    "utility(happy,true,5)."
)


def test_the_relaxed_facts_include_what_events_may_set():
    from conftest import only_answer

    answer = only_answer(
        ["planning/model.lp", "planning/relaxed.lp", "judgement/best.lp"],
        ARMED + "#show reachable/2.",
    )
    assert "reachable(happy,true)" in answer
    assert "upper_bound(5)" in answer


@pytest.mark.parametrize(
    "source, plan, final",
    [
        (ARMED, "idle", 0),
        (str(MODELS / "hera" / "robot-and-frank.yaml"), "wait", -1),
    ],
)
def test_a_state_only_an_event_makes_better_decides_utilitarianism(source, plan, final):
    """A better final state that only an event produces: the upper bound of the
    relaxed facts must count it, so the verdict is impermissible, never a
    proven "permissible" (a false proof)."""
    model = Model.load([source]) if source.endswith(".yaml") else Model.from_string(source)
    report = judge(model, Plan.parse(plan), ["utilitarianism"])
    judgement = report.judgements[0]
    assert report.utility == final
    assert (judgement.permissible, judgement.status) == (False, "proven"), judgement
    assert judgement.compared.utility > final
    assert "impermissible" in judgement.explanation.text
