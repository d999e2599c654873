"""The same input gives the same answer: engines race for speed, never for
the answer.

A shortest plan search reports the least shortest plan (plans of the length
compared step by step by their actions' terms), whichever engine found the
length; each kind of claim has one proof text; and commands print the same
bytes run after run, on a loaded machine too."""

from __future__ import annotations

import json
import subprocess
import sys
import threading

import pytest
from conftest import MODELS
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from oracle import random_model

import ethasp.planning.search as search_module
from ethasp import Model, find_plan
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import Setting
from ethasp.planning.engines.layers import Atoms, Layers

# Which engine delivers the plan: the exact layers started with the search
# (they usually win on these models), or the solver alone.
ENGINES = {
    "layers": {"LAYERS_AT_ONCE_ACTIONS": 0},
    "solver": {
        "LAYERS_AFTER": float("inf"),
        "LAYERS_AT_ONCE_ACTIONS": 10**9,
        "LAYERS_AT_ONCE_VARIABLES": 10**9,
    },
}


def plan_names(plan) -> list[str]:
    return [str(action) for action in plan]


@pytest.mark.slow
@pytest.mark.parametrize("engine", sorted(ENGINES))
@settings(max_examples=60, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.booleans(), st.booleans(), st.booleans())
def test_plan_search_reports_the_least_shortest_plan(engine, seed, conditional, derived, events):
    spec = random_model(
        seed,
        max_actions=5,
        conditional=conditional,
        derived=derived,
        far_goal=seed % 2 == 0,
        events=events,
    )
    expected = spec.least_shortest_plan()
    with pytest.MonkeyPatch.context() as patch:
        for name, value in ENGINES[engine].items():
            patch.setattr(search_module, name, value)
        result = find_plan(Model.from_string(spec.to_asp()))
    if expected is None:
        assert result.status == "none" and result.plan is None, result
    else:
        assert result.status == "found" and plan_names(result.plan) == expected, (result, expected)
        assert result.proof == (
            f"no plan has fewer than {len(expected)} step{'' if len(expected) == 1 else 's'}"
            if expected
            else "the goal holds in the initial state"
        )


@pytest.mark.slow
@settings(max_examples=60, deadline=None)
@given(st.integers(min_value=0, max_value=10**9), st.booleans(), st.booleans(), st.booleans())
def test_every_engine_reads_off_the_least_shortest_plan(seed, conditional, derived, events):
    """The exact layers (diagrams; explicit configurations with events) and the
    solver's least-plan heuristic each give the oracle's least plan."""
    spec = random_model(
        seed,
        max_actions=5,
        conditional=conditional,
        derived=derived,
        far_goal=seed % 2 == 1,
        events=events,
    )
    expected = spec.least_shortest_plan()
    assume(expected is not None and len(expected) > 0)
    model = Model.from_string(spec.to_asp())
    layers = Layers(Atoms(model.planner), Budget(None)).start()
    try:
        while layers.status.working:
            layers.news.wait(0.05)
            layers.news.clear()
    finally:
        layers.stop()
    assert layers.status.plan is not None, layers.status
    assert plan_names(layers.status.plan) == expected
    planner = model.planner
    planner.use_least()
    outcome = planner.solve(len(expected), Setting(least=True, optimize=True), Budget(None))
    assert outcome.satisfiable
    assert plan_names(search_module.plans_of([outcome.symbols])[0]) == expected


def test_all_shortest_plans_come_in_order():
    result = find_plan(Model.load([MODELS / "trolley.lp"]), all_plans=True)
    assert [plan_names(plan) for plan in result.plans] == [["pull"], ["refrain"]]
    assert plan_names(result.plan) == ["pull"]


# -- whole commands, run after run, on a loaded machine ---------------------------------------

RANDOM = """\
variable(v0). variable(v1). variable(v2).
action(a1). action(a2). action(a3). action(a4).
pre(a1,v0,false). eff(a1,v0,true).
pre(a2,v0,true). eff(a2,v1,true).
eff(a3,v2,true). eff(a3,v0,false).
pre(a4,v1,false). eff(a4,v2,true).
goal(v2,true). goal(v1,true).
utility(a1,-1). utility(v2,true,2). utility(v1,false,-2). utility(v0,true,-1).
"""

COMMANDS = [
    ["plan", "rescue", "--json"],
    ["plan", "rescue", "--satisficing", "--json"],
    ["plan", "trolley", "--principle", "utilitarianism", "--json"],
    ["plan", "rescue", "--max-horizon", "2", "--json"],
    ["judge", "heist", "--plan", "scout steal give_jewels", "--principle", "all", "--json"],
    ["ask", "rescue", "--question", "why take_key", "--json"],
    [
        "ask",
        "trolley",
        "--principle",
        "do-no-harm",
        "--question",
        "why refrain rather than pull",
        "--json",
    ],
    [
        "ask",
        "{random}",
        "--plan",
        "a4 a1 a2",
        "--question",
        "why a1 before a2",
        "--principle",
        "do-no-harm",
        "--max-horizon",
        "5",
        "--json",
    ],
    ["explain", "rescue", "--json"],
    # Action costs: cheapest plans, what a principle costs, a cheaper contrast.
    ["plan", "errand", "--json"],
    ["plan", "errand", "--principle", "do-no-harm", "--json"],
    [
        "ask",
        "errand",
        "--principle",
        "deontology",
        "--question",
        "why not a cheaper plan",
        "--json",
    ],
    [
        "plan",
        str(MODELS / "pddl" / "gripper-domain.pddl"),
        str(MODELS / "pddl" / "gripper-problem.pddl"),
        "--json",
    ],
]


def _run(arguments: list[str]) -> str:
    done = subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *arguments],
        capture_output=True,
        text=True,
        timeout=300,
    )
    return f"{done.returncode}\n{done.stdout}\n{done.stderr}"


@pytest.mark.slow
def test_commands_answer_byte_for_byte_the_same_under_load(tmp_path):
    model = tmp_path / "random.lp"
    model.write_text(RANDOM)
    commands = [[str(model) if a == "{random}" else a for a in c] for c in COMMANDS]
    first = [_run(command) for command in commands]
    for text in first:
        assert text.startswith("0\n"), text
        json.loads(text.split("\n", 1)[1].rsplit("\n", 2)[0] or "{}")
    stop = threading.Event()

    def burn() -> None:  # two busy processes: the machine's cores are taken
        with subprocess.Popen([sys.executable, "-c", "while True: pass"]) as busy:
            stop.wait()
            busy.kill()

    burners = [threading.Thread(target=burn) for _ in range(2)]
    for burner in burners:
        burner.start()
    try:
        for _ in range(2):
            assert [_run(command) for command in commands] == first
    finally:
        stop.set()
        for burner in burners:
            burner.join()
