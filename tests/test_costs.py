"""Action costs (cost/2, PDDL's :action-costs): the vocabulary and its checks,
costs in traces and HModels, cheapest plans and their proofs, what a
principle costs, the question 'why not a cheaper plan', PDDL costs, and the
command line's words and JSON (asp/errand.lp, and small models written here).
Random models against the oracle are in test_properties_costs.py and
test_cheapest.py."""

from __future__ import annotations

import json
import time

import pytest
from conftest import MODELS, answer_sets, ethasp_process

import ethasp.planning.cost_search as cost_search
from ethasp import InputError, Model, Plan, find_plan, plan_with_principles, validate
from ethasp.principles.restriction import principle_cost
from ethasp.questions.contrast import ask
from ethasp.questions.question import Question

ERRAND = MODELS / "errand.lp"

# Walking costs nothing but takes three steps; the taxi costs 5, the bus 1
# after a free wait (cost 0) at the stop.
TOWN = """
variable(home; stop; waited; town).
init(home).
action(walk1; walk2; walk3; taxi; go_to_stop; wait; bus).
variable(w1; w2).
pre(walk1,home,true). eff(walk1,w1,true). eff(walk1,home,false).
pre(walk2,w1,true). eff(walk2,w2,true). eff(walk2,w1,false).
pre(walk3,w2,true). eff(walk3,town,true). eff(walk3,w2,false).
pre(taxi,home,true). eff(taxi,town,true). eff(taxi,home,false).
pre(go_to_stop,home,true). eff(go_to_stop,stop,true). eff(go_to_stop,home,false).
pre(wait,stop,true). eff(wait,waited,true).
pre(bus,waited,true). eff(bus,town,true). eff(bus,stop,false).
goal(town,true).
cost(taxi,5). cost(bus,1). cost(go_to_stop,0). cost(wait,0).
"""


# -- the vocabulary --------------------------------------------------------------------


def test_actions_cost_one_without_costs_and_zero_without_their_own():
    without = answer_sets(
        ["planning/model.lp"], "action(a;b). #show action_cost/2. #show costs_given/0."
    )[0]
    assert without == {"action_cost(a,1)", "action_cost(b,1)"}
    given = answer_sets(
        ["planning/model.lp"], "action(a;b). cost(a,3). #show action_cost/2. #show costs_given/0."
    )[0]
    assert given == {"action_cost(a,3)", "action_cost(b,0)", "costs_given"}


@pytest.mark.parametrize(
    "facts,needle",
    [
        ("cost(go,-1).", "a cost must be an integer from 0 to 1000000 in cost(go,-1)"),
        ("cost(go,1000001).", "in cost(go,1000001)"),
        ('cost(go,"1").', "a cost must be an integer"),
        ("cost(go,1). cost(go,2).", "two different costs for one action"),
        ("cost(fly,1).", "unknown action fly in cost(fly,1)"),
    ],
)
def test_bad_costs_are_one_line(facts, needle):
    with pytest.raises(InputError) as error:
        Model.from_string("variable(a). action(go). eff(go,a,true). goal(a,true). " + facts)
    assert needle in str(error.value) and "\n" not in str(error.value)


@pytest.mark.parametrize("cost", [0, 1, 1000000])
def test_costs_at_the_bounds_are_accepted(cost):
    model = Model.from_string(
        f"variable(a). action(go). eff(go,a,true). goal(a,true). cost(go,{cost})."
    )
    assert validate(model, Plan.parse("go")).cost == cost


def test_a_plans_cost_is_in_its_trace_and_its_validation():
    model = Model.load([ERRAND])
    assert validate(model, Plan.parse("drive hand_over")).cost == 9
    assert validate(model, Plan.parse("drive hand_over")).to_json()["cost"] == 9
    trolley = Model.load([MODELS / "trolley.lp"])
    assert validate(trolley, Plan.parse("pull")).cost is None
    assert "cost" not in validate(trolley, Plan.parse("pull")).to_json()


def test_hmodels_keep_the_costs_and_say_so():
    answer = answer_sets(
        ["planning/model.lp", "restrictions/hmodel.lp"],
        "variable(a). action(x;y;z). eff(x,a,true). cost(x,2). removed(z). #show hmodel/1.",
    )[0]
    assert {"hmodel(cost(x,2))", "hmodel(cost(y,0))"} <= answer
    assert not any("cost(z" in atom for atom in answer)


# -- cheapest plans ----------------------------------------------------------------------


def test_cheapest_plans_are_found_and_proven():
    model = Model.load([ERRAND])
    result = find_plan(model)
    assert result.status == "found" and result.cost == 2
    assert result.plan == Plan.parse("cross_lawn hand_over")
    assert result.to_json()["cost"] == 2
    every = find_plan(model, all_plans=True)
    assert every.plans == [Plan.parse("cross_lawn hand_over")]


@pytest.fixture
def solver_alone(monkeypatch):
    """The solver's proofs alone (no uniform-cost search beside it)."""
    monkeypatch.setattr(cost_search, "UNIFORM_COST", False)


def test_the_least_cheapest_plan_is_solved_on_a_control_of_its_own(monkeypatch):
    """Which cheapest plan is reported must not depend on the search's
    history (solves that another engine ended at a moment of the machine's
    load leave learnt clauses and groundings behind, which change whether the
    least plan is found within its conflicts): the least plan's solve is made
    on a planner of its own, which finds the plan on every run."""
    model = Model.from_string(TOWN)
    searched = model.planner
    solved_on = []
    solve = cost_search.Planner.solve

    def recording(self, horizon, setting, *args, **kwargs):
        if setting.least:
            solved_on.append(self)
        return solve(self, horizon, setting, *args, **kwargs)

    monkeypatch.setattr(cost_search.Planner, "solve", recording)
    result = find_plan(model)
    assert result.status == "found" and result.cost == 0
    assert result.plan == Plan.parse("walk1 walk2 walk3")
    assert solved_on and all(planner is not searched for planner in solved_on)


def test_the_least_action_cost_proves_a_plan_cheapest(solver_alone):
    result = find_plan(Model.load([ERRAND]))
    assert result.status == "found" and result.cost == 2
    assert result.proof == "no plan costs less than 2"  # one text, whichever proof


def test_with_actions_of_cost_0_the_loop_free_threshold_proves_it(solver_alone):
    model = Model.from_string(TOWN)
    result = find_plan(model, max_horizon=10)
    assert result.status == "found" and result.cost == 0
    assert result.plan == Plan.parse("walk1 walk2 walk3")  # cheapest, 3 steps
    # The bus (cost 1) is cheaper than the taxi (5), and longer.
    dear = Model.from_string(TOWN + "cost(walk1,2). cost(walk2,2). cost(walk3,2).")
    result = find_plan(dear, max_horizon=10)
    assert result.status == "found" and result.cost == 1
    assert result.plan == Plan.parse("go_to_stop wait bus")
    assert result.proof == "no plan costs less than 1"


def test_all_cheapest_plans_where_every_action_costs_0():
    """Every action costs 0: the cost's level of optimisation is kept all the
    same, so that the bound on the cost (0) does not fall on the steps (before,
    listing the plans of cost 0 found none but the one found first)."""
    model = Model.from_string(
        "variable(v). action(a;b). eff(a,v,true). eff(b,v,true). goal(v,true). "
        "cost(a,0). cost(b,0)."
    )
    result = find_plan(model, all_plans=True)
    assert result.status == "found" and result.cost == 0
    assert result.plans == [Plan.parse("a"), Plan.parse("b")]


def test_a_horizon_too_small_to_prove_is_bounded_with_the_plan_found(solver_alone):
    dear = Model.from_string(TOWN + "cost(walk1,2). cost(walk2,2). cost(walk3,2).")
    result = find_plan(dear, max_horizon=1)
    assert result.status == "bounded" and result.plan == Plan.parse("taxi")
    assert result.cost == 5 and result.optimal is False
    assert "a longer one may" in result.proof


@pytest.fixture
def engine_first(monkeypatch):
    """Uniform-cost search has ended before the solver starts (the order of
    the race that a fast engine or a loaded machine gives)."""
    start = cost_search._Engine.__init__

    def started_and_ended(self, *args, **kwargs):
        start(self, *args, **kwargs)
        if self.engine is not None:
            deadline = time.monotonic() + 120  # (a busy machine; the search is tiny)
            while self.engine.status.working and time.monotonic() < deadline:
                self.engine.news.wait(0.05)
            assert not self.engine.status.working, "uniform-cost search did not end"

    monkeypatch.setattr(cost_search._Engine, "__init__", started_and_ended)


def test_a_cheaper_plan_beyond_the_horizon_found_first_leaves_the_search_bounded(engine_first):
    # Uniform-cost search finds the bus plan (3 steps) first: beyond the
    # maximal horizon, it ends nothing; the solver's plan within the horizon
    # is the answer, as when the solver is first (this once searched forever).
    dear = Model.from_string(TOWN + "cost(walk1,2). cost(walk2,2). cost(walk3,2).")
    result = find_plan(dear, max_horizon=1, time_limit=30)
    assert result.status == "bounded" and result.plan == Plan.parse("taxi")
    assert result.cost == 5 and result.optimal is False
    assert "the maximal horizon is 1" in result.proof


def test_the_bounded_text_on_the_command_line(tmp_path):
    path = tmp_path / "town.lp"
    path.write_text(TOWN + "cost(walk1,2). cost(walk2,2). cost(walk3,2).\n")
    run = ethasp_process("plan", str(path), "--max-horizon", "1")
    assert run.returncode == 0, run.stderr
    # Uniform-cost search finds the bus plan, of 3 steps: beyond the maximal
    # horizon, so the taxi is not proven cheapest (the same on every run).
    assert run.stdout.splitlines()[0] == (
        "bounded: plan of 1 step, cost 5 (not proven cheapest): taxi"
    )


def test_an_any_plan_search_reports_the_cost():
    result = find_plan(Model.load([ERRAND]), satisficing=True)
    assert result.status == "found" and result.cost is not None and result.optimal is False


def test_a_bound_below_the_least_cost_proves_none():
    model = Model.load([ERRAND])
    result = plan_with_principles(model, [], below=2)
    assert result.status == "none" and result.proof == "no plan costs less than 2"
    result = plan_with_principles(model, [], below=3)
    assert result.status == "found" and result.cost == 2
    with pytest.raises(InputError, match="action costs"):
        plan_with_principles(Model.load([MODELS / "trolley.lp"]), [], below=3)


# -- principles ---------------------------------------------------------------------------


def test_cheapest_hplans_and_what_a_principle_costs():
    model = Model.load([ERRAND])
    hplan = plan_with_principles(model, ["deontology"])
    assert hplan.status == "found" and hplan.cost == 5 and hplan.to_json()["cost"] == 5
    assert hplan.plan == Plan.parse("bus(depot,market) bus(market,house) hand_over")
    price = principle_cost(model, hplan)
    assert (price.status, price.value, price.permissible, price.cheapest) == ("proven", 3, 5, 2)
    assert price.to_json()["cost"] == 3
    assert price.text().startswith("what deontology costs: 3 (a cheapest permissible plan")
    # Utilitarianism asks for the delivered parcel and no harm: the bus too.
    assert principle_cost(model, plan_with_principles(model, ["utilitarianism"])).value == 3


def test_a_principle_that_forbids_every_plan():
    model = Model.from_string(
        "variable(a). action(go). eff(go,a,true). goal(a,true). cost(go,1). utility(go,-1)."
    )
    hplan = plan_with_principles(model, ["deontology"])
    price = principle_cost(model, hplan)
    assert (
        price.status == "none" and price.value is None and "no plan is permissible" in price.proof
    )
    with pytest.raises(InputError, match="no action costs"):
        trolley = Model.load([MODELS / "trolley.lp"])
        principle_cost(trolley, plan_with_principles(trolley, ["deontology"]))


# -- why not a cheaper plan ---------------------------------------------------------------


def test_the_question_is_read_and_written():
    for text in ("why not a cheaper plan", "Why not cheaper?", "why not a cheaper plan?"):
        question = Question.parse(text)
        assert question.kind == "cheaper" and str(question) == "why not a cheaper plan"
        assert Question.from_json(question.to_json()) == question
    with pytest.raises(InputError, match="names nothing"):
        Question("cheaper", action="a")


def test_why_not_a_cheaper_plan():
    model = Model.load([ERRAND])
    plan = Plan.parse("bus(depot,market) bus(market,house) hand_over")
    answer = ask(model, "why not a cheaper plan", plan, principle="deontology")
    assert [str(c.term) for c in answer.constraints] == ["cheaper_than(5)"]
    assert answer.contrast is not None and answer.contrast.plan == Plan.parse(
        "cross_lawn hand_over"
    )
    assert answer.contrast.cost == 2 and answer.original.cost == 5
    assert answer.principle_dropped  # no cheaper plan is permissible under deontology
    # The cheapest plan: none is cheaper (proven).
    answer = ask(model, "why not a cheaper plan", Plan.parse("cross_lawn hand_over"))
    assert answer.contrast is None and answer.status == "none"
    assert "no plan can cost less than 2" in answer.explanation


def test_why_not_a_cheaper_plan_needs_costs_and_a_plan_that_costs():
    with pytest.raises(InputError, match="no action costs"):
        ask(Model.load([MODELS / "trolley.lp"]), "why not a cheaper plan", Plan.parse("pull"))
    free = Model.from_string("variable(a). action(go). eff(go,a,true). goal(a,true). cost(go,0).")
    with pytest.raises(InputError, match="the plan costs 0"):
        ask(free, "why not a cheaper plan", Plan.parse("go"))


# -- the command line ---------------------------------------------------------------------


def test_the_command_line_shows_costs():
    run = ethasp_process("plan", "errand")
    assert run.stdout == "plan of 2 steps, cost 2: cross_lawn hand_over\n", run.stderr
    run = ethasp_process("plan", "errand", "--all")
    assert run.stdout.splitlines()[0] == "1 cheapest plans of 2 steps, cost 2:"
    run = ethasp_process("plan", "errand", "--principle", "do-no-harm", "--json")
    data = json.loads(run.stdout)
    assert data["cost"] == 5 and data["principle_cost"]["cost"] == 3
    run = ethasp_process("plan", "errand", "--principle", "deontology")
    assert run.stdout.splitlines()[0].startswith(
        "plan of 3 steps, cost 5, permissible under deontology:"
    )
    assert run.stdout.splitlines()[-1].startswith("what deontology costs: 3")
    run = ethasp_process(
        "judge", "errand", "--plan", "drive hand_over", "--principle", "deontology"
    )
    assert "plan: drive hand_over (cost 9)" in run.stdout.splitlines()
    run = ethasp_process("validate", "errand", "--plan", "drive hand_over")
    assert run.stdout.startswith("valid plan of 2 steps, cost 9;")
    run = ethasp_process("explain", "errand", "--plan", "drive hand_over", "--json")
    assert json.loads(run.stdout)["cost"] == 9
    run = ethasp_process("explain", "errand", "--plan", "drive hand_over")
    assert run.stdout.startswith("plan of 2 steps, cost 9: drive hand_over")
    run = ethasp_process("plan", "errand", "--satisficing")
    assert "(not proven cheapest)" in run.stdout or "cost 2:" in run.stdout


def test_pictures_show_costs(tmp_path):
    picture = tmp_path / "errand.svg"
    run = ethasp_process("plan", "errand", "--svg", str(picture))
    assert run.returncode == 0, run.stderr
    svg = picture.read_text()
    assert "step 1 \u00b7 cost 1" in svg and "cost 2</text>" in svg


# -- PDDL -----------------------------------------------------------------------------

ROADS = """
(define (domain roads) (:requirements :typing :action-costs)
  (:types place)
  (:predicates (at ?p - place) (road ?a ?b - place))
  (:functions (total-cost) (length ?a ?b - place))
  (:action drive :parameters (?a ?b - place) :precondition (and (at ?a) (road ?a ?b))
    :effect (and (not (at ?a)) (at ?b) (increase (total-cost) (length ?a ?b))))
  (:action fly :parameters (?a ?b - place) :precondition (at ?a)
    :effect (and (not (at ?a)) (at ?b) (increase (total-cost) 20) (increase (total-cost) 1))))
"""
TRIP = """
(define (problem trip) (:domain roads) (:objects a b c - place)
  (:init (at a) (road a b) (road b c) (road a c)
         (= (length a b) 2) (= (length b c) 3) (= (length a c) 9) (= (total-cost) 0))
  (:goal (at c)) (:metric minimize (total-cost)))
"""


def load_pddl(tmp_path, domain: str, problem: str) -> Model:
    (tmp_path / "d.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text(problem)
    return Model.load([tmp_path / "d.pddl", tmp_path / "p.pddl"])


def test_pddl_costs_of_numbers_and_functions(tmp_path):
    model = load_pddl(tmp_path, ROADS, TRIP)
    costs = {str(action): cost for action, cost in model.planner.action_costs().items()}
    assert costs["drive(a,b)"] == 2 and costs["drive(a,c)"] == 9 and costs["fly(a,c)"] == 21
    result = find_plan(model)
    assert result.cost == 5 and result.plan == Plan.parse("(drive a b) (drive b c)")
    # An instance whose cost reads a function without a value cannot be applied.
    model = load_pddl(tmp_path, ROADS, TRIP.replace(" (= (length b c) 3)", ""))
    assert "drive(b,c)" not in {str(a) for a in model.planner.action_costs()}
    assert find_plan(model).cost == 9


@pytest.mark.parametrize(
    "domain,problem,needle",
    [
        (
            ROADS.replace("(increase (total-cost) 20)", "(when (at b) (increase (total-cost) 20))"),
            TRIP,
            "conditional action costs",
        ),
        (
            ROADS.replace("(total-cost) 20)", "(total-cost) 2.5)"),
            TRIP,
            "must be integers, found 2.5",
        ),
        (ROADS, TRIP.replace("(length a b) 2)", "(length a b) 2.5)"), "must be integers"),
        (ROADS.replace("(total-cost) 20)", "(total-cost) -30)"), TRIP, "a cost must be an integer"),
    ],
)
def test_bad_pddl_costs_are_one_line(tmp_path, domain, problem, needle):
    with pytest.raises(InputError) as error:
        load_pddl(tmp_path, domain, problem)
    assert needle in str(error.value) and "\n" not in str(error.value)
