"""PDDL as people write it: the ADL fragment, derived predicates, leniency
(undeclared requirements, constants declared only by the problem, either
types, action costs), Caused and do-no-harm under conditional effects, and the
IPC domains."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT

from ethasp import InputError, Model, Plan, find_plan, judge, query, validate
from ethasp.principles.restriction import plan_with_principles
from ethasp.vocabulary import Action

DATA = Path(__file__).resolve().parent / "data" / "ipc"


def ethasp(*args: str, cwd=ROOT) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
    )


def load(tmp_path: Path, domain: str, problem: str, *annotations: str) -> Model:
    (tmp_path / "domain.pddl").write_text(domain)
    (tmp_path / "problem.pddl").write_text(problem)
    paths = [tmp_path / "domain.pddl", tmp_path / "problem.pddl"]
    for index, text in enumerate(annotations):
        (tmp_path / f"annotation{index}.lp").write_text(text)
        paths.append(tmp_path / f"annotation{index}.lp")
    return Model.load(paths)


def actions_of(model: Model) -> set[str]:
    return {str(a.name.symbol) for a in model.facts([Action]).query(Action).all()}


def length(model: Model) -> int | None:
    result = find_plan(model, max_horizon=20)
    assert result.status in ("found", "none"), result
    if result.plan is not None:
        assert validate(model, result.plan).valid
    return None if result.plan is None else len(result.plan)


# -- conditional and universal effects -------------------------------------------------

BRIEFCASE = """
(define (domain briefcase)
  (:requirements :adl)
  (:types portable location)
  (:predicates (at ?y - portable ?x - location) (in ?x - portable) (is-at ?x - location))
  (:action move
    :parameters (?m ?l - location)
    :precondition (and (is-at ?m) (not (= ?m ?l)))
    :effect (and (is-at ?l) (not (is-at ?m))
                 (forall (?x - portable)
                   (when (in ?x) (and (at ?x ?l) (not (at ?x ?m)))))))
  (:action take-out :parameters (?x - portable) :precondition (in ?x) :effect (not (in ?x)))
  (:action put-in
    :parameters (?x - portable ?l - location)
    :precondition (and (not (in ?x)) (at ?x ?l) (is-at ?l))
    :effect (in ?x)))
"""
BRIEFCASE_PROBLEM = """
(define (problem get-paid) (:domain briefcase)
  (:objects home office - location dictionary paycheck - portable)
  (:init (is-at home) (at dictionary home) (at paycheck home) (in paycheck))
  (:goal (and (at dictionary office) (forall (?x - portable) (not (in ?x))) (is-at home))))
"""


def test_conditional_universal_effects_briefcase(tmp_path):
    model = load(tmp_path, BRIEFCASE, BRIEFCASE_PROBLEM)
    assert length(model) == 5
    check = validate(model, Plan.parse("(move home office)"))
    assert "at(paycheck,office)" in check.final_state and "-at(paycheck,home)" in check.final_state
    assert "at(dictionary,home)" in check.final_state
    check = validate(model, Plan.parse("(take-out paycheck) (move home office)"))
    assert "at(paycheck,home)" in check.final_state


# -- disjunctive, implied, quantified preconditions and goals ----------------------------------

SHOP = """
(define (domain shop)
  (:requirements :adl)
  (:types box)
  (:predicates (full ?b - box) (closed ?b - box) (raining) (umbrella) (out) (key)
               (open-door) (inside))
  (:action fill :parameters (?b - box) :precondition (not (closed ?b)) :effect (full ?b))
  (:action close :parameters (?b - box) :precondition (full ?b) :effect (closed ?b))
  (:action take-key :parameters () :effect (key))
  (:action take-umbrella :parameters () :effect (umbrella))
  (:action enter :parameters () :precondition (or (key) (open-door)) :effect (inside))
  (:action leave :parameters ()
    :precondition (and (inside) (imply (raining) (umbrella))
                       (exists (?b - box) (full ?b)) (forall (?b - box) (closed ?b)))
    :effect (out)))
"""
SHOP_PROBLEM = """
(define (problem errand) (:domain shop)
  (:objects b1 b2 - box)
  (:init {init})
  (:goal (out)))
"""


@pytest.mark.parametrize(
    "init,steps",
    [
        ("(raining) (open-door)", 7),
        ("(open-door)", 6),
        ("(raining)", 8),
        ("(closed b1)", 5),
        ("(closed b1) (closed b2)", None),
    ],
)
def test_disjunction_implication_and_quantifiers_in_preconditions(tmp_path, init, steps):
    assert length(load(tmp_path, SHOP, SHOP_PROBLEM.format(init=init))) == steps


def test_the_unmet_complex_precondition_is_named(tmp_path):
    model = load(tmp_path, SHOP, SHOP_PROBLEM.format(init="(open-door)"))
    check = validate(model, Plan.parse("(enter) (leave)"))
    assert check.failure_step == 2 and check.unmet_preconditions
    assert all(re.fullmatch(r"-?formula_\d+", literal) for literal in check.unmet_preconditions)


def test_quantified_and_disjunctive_goals(tmp_path):
    goal = "(or (forall (?b - box) (full ?b)) (and (key) (umbrella)))"
    problem = SHOP_PROBLEM.format(init="").replace("(:goal (out))", f"(:goal {goal})")
    assert length(load(tmp_path, SHOP, problem)) == 2
    goal = "(exists (?b - box) (and (closed ?b) (imply (full ?b) (inside))))"
    problem = SHOP_PROBLEM.format(init="").replace("(:goal (out))", f"(:goal {goal})")
    assert length(load(tmp_path, SHOP, problem)) == 4  # fill, close, take-key, enter


# -- derived predicates --------------------------------------------------------------------

ROOMS = """
(define (domain rooms)
  (:requirements :strips :typing :derived-predicates :disjunctive-preconditions
                 :existential-preconditions :universal-preconditions :equality)
  (:types room)
  (:predicates (door ?a ?b - room) (open ?a ?b - room) (at ?r - room) (reach ?r - room)
               (lit ?r - room) (dark))
  (:derived (reach ?r - room) (at ?r))
  (:derived (reach ?r - room) (exists (?s - room) (and (reach ?s) (open ?s ?r))))
  (:derived (dark) (forall (?r - room) (imply (reach ?r) (not (lit ?r)))))
  (:action open :parameters (?a ?b - room)
    :precondition (and (reach ?a) (door ?a ?b))
    :effect (and (open ?a ?b) (open ?b ?a)))
  (:action switch :parameters (?a - room) :precondition (and (at ?a) (dark)) :effect (lit ?a))
  (:action go :parameters (?a ?b - room)
    :precondition (and (at ?a) (reach ?b) (not (= ?a ?b)))
    :effect (and (not (at ?a)) (at ?b))))
"""
ROOMS_PROBLEM = """
(define (problem corridor) (:domain rooms)
  (:objects r1 r2 r3 r4 - room)
  (:init (at r1) (door r1 r2) (door r2 r3) (door r3 r4))
  (:goal (and (at r4) (not (dark)))))
"""


def test_derived_predicates_recursive_and_negated(tmp_path):
    model = load(tmp_path, ROOMS, ROOMS_PROBLEM)
    result = find_plan(model)
    assert result.status == "found" and len(result.plan) == 5
    # one of the shortest plans (go to r4 last, or switch the light on there last)
    assert validate(model, result.plan).valid
    assert str(result.plan.actions[-1]) in ("go(r1,r4)", "switch(r4)")
    check = validate(model, Plan.parse("(open r1 r2) (go r1 r3)"))
    assert check.failure_step == 2 and check.unmet_preconditions == ["reach(r3)"]
    # derived facts are not part of the state
    check = validate(model, Plan.parse("(switch r1)"))
    assert not any("reach" in literal or "dark" in literal for literal in check.final_state)


def test_derived_predicates_cannot_be_set_or_named(tmp_path):
    bad = ROOMS.replace("(:effect (lit ?a))", "(:effect (and (lit ?a) (dark)))")
    bad = bad.replace(":effect (lit ?a))", ":effect (and (lit ?a) (dark)))")
    with pytest.raises(InputError, match="effect on the derived predicate dark"):
        load(tmp_path, bad, ROOMS_PROBLEM)
    with pytest.raises(InputError, match="derived predicate reach in the initial state"):
        load(tmp_path, ROOMS, ROOMS_PROBLEM.replace("(at r1)", "(at r1) (reach r2)"))
    with pytest.raises(InputError, match="derived variable dark in utility"):
        load(tmp_path, ROOMS, ROOMS_PROBLEM, "utility(dark,true,-1).")
    model = load(tmp_path, ROOMS, ROOMS_PROBLEM)
    with pytest.raises(InputError, match="unknown action or variable"):
        query(model, Plan.parse("(switch r1)"), "Caused(dark)")


def test_unstratified_derived_predicates_are_refused(tmp_path):
    domain = ROOMS.replace(
        "(:derived (dark) (forall (?r - room) (imply (reach ?r) (not (lit ?r)))))",
        "(:derived (dark) (not (dark)))",
    )
    with pytest.raises(InputError, match="must be stratified"):
        load(tmp_path, domain, ROOMS_PROBLEM)


# -- leniency: requirements, constants, either types, action costs --------------------------


def test_undeclared_requirements_warn_one_line_per_file(tmp_path):
    domain = ROOMS.replace(
        """:requirements :strips :typing :derived-predicates :disjunctive-preconditions
                 :existential-preconditions :universal-preconditions :equality""",
        ":requirements",
    )
    (tmp_path / "d.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text(ROOMS_PROBLEM)
    run = ethasp("plan", "d.pddl", "p.pddl", cwd=tmp_path)
    assert run.returncode == 0 and "plan of 5 steps" in run.stdout, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 2, lines
    assert lines[0].startswith("d.pddl: warning: requirements ") and "(read anyway)" in lines[0]
    for requirement in (
        ":derived-predicates",
        ":equality",
        ":existential-preconditions",
        ":negative-preconditions",
        ":typing",
        ":universal-preconditions",
    ):
        assert requirement in lines[0]
    assert lines[1] == (
        "p.pddl: warning: requirements :negative-preconditions, :typing used "
        "but not declared (read anyway)"
    )


def test_miconic_reads_with_a_warning():
    files = [
        str(DATA / "elevator-strips-simple-typed" / name) for name in ("domain.pddl", "p1.pddl")
    ]
    run = ethasp("plan", *files, "--json")
    assert run.returncode == 0, run.stderr
    assert len(json.loads(run.stdout)["plan"]) == 4
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 2 and all(":typing used but not declared" in line for line in lines)


CONSTANTS = """
(define (domain house)
  (:requirements :strips :typing)
  (:types room)
  (:predicates (at ?r - room) (closed ?r - room))
  (:action go :parameters (?r - room) :precondition (not (closed door)) :effect (at ?r))
  (:action open :parameters () :effect (not (closed door))))
"""
CONSTANTS_PROBLEM = """
(define (problem p) (:domain house)
  (:objects kitchen {door} - room)
  (:init (closed door))
  (:goal (at kitchen)))
"""


def test_problem_objects_used_as_domain_constants(tmp_path, capsys):
    assert length(load(tmp_path, CONSTANTS, CONSTANTS_PROBLEM.format(door="door"))) == 2
    assert "constant" not in capsys.readouterr().err
    # Declared nowhere: an object, with a warning (as plan-explainer's reader has it).
    assert length(load(tmp_path, CONSTANTS, CONSTANTS_PROBLEM.format(door=""))) == 2
    assert "constant door used but not declared (read as objects)" in capsys.readouterr().err


EITHER = """
(define (domain parking)
  (:requirements :strips :typing)
  (:types car bike person)
  (:constants lot - (either car bike))
  (:predicates (parked ?v - (either car bike)) (walked ?p - person))
  (:action park :parameters (?v - (either car bike)) :effect (parked ?v))
  (:action walk :parameters (?p - person) :effect (walked ?p)))
"""
EITHER_PROBLEM = """
(define (problem p) (:domain parking)
  (:objects c - car b - bike ann - person)
  (:init)
  (:goal (and (parked c) (parked b) (walked ann))))
"""


def test_either_types_in_parameters_predicates_and_objects(tmp_path):
    model = load(tmp_path, EITHER, EITHER_PROBLEM)
    assert actions_of(model) == {"park(c)", "park(b)", "park(lot)", "walk(ann)"}
    assert length(model) == 3


COSTS = """
(define (domain costly)
  (:requirements :strips :action-costs)
  (:predicates (a) (b))
  (:functions (total-cost) - number (price) - number)
  (:action cheap :parameters () :effect (and (a) (increase (total-cost) 1)))
  (:action dear :parameters () :precondition (a) :effect (and (b) (increase (total-cost) (price)))))
"""
COSTS_PROBLEM = """
(define (problem p) (:domain costly)
  (:init (= (total-cost) 0) (= (price) 10))
  (:goal (b))
  (:metric minimize (total-cost)))
"""


def test_action_costs_are_read_with_the_metric_and_ignored_without_it(tmp_path):
    (tmp_path / "d.pddl").write_text(COSTS)
    (tmp_path / "p.pddl").write_text(COSTS_PROBLEM)
    run = ethasp("plan", "d.pddl", "p.pddl", cwd=tmp_path)
    assert run.returncode == 0 and "plan of 2 steps, cost 11: (cheap) (dear)" in run.stdout
    assert run.stderr == ""
    (tmp_path / "p.pddl").write_text(COSTS_PROBLEM.replace("(:metric minimize (total-cost))", ""))
    run = ethasp("plan", "d.pddl", "p.pddl", cwd=tmp_path)
    assert run.returncode == 0 and "plan of 2 steps: (cheap) (dear)" in run.stdout, run.stderr
    assert run.stderr.strip().splitlines() == [
        "d.pddl: warning: action costs are ignored: the problem has no (:metric minimize "
        "(total-cost)) (plans are shortest in number of actions)",
    ]
    (tmp_path / "p.pddl").write_text(
        COSTS_PROBLEM.replace("(:metric minimize (total-cost))", "(:metric maximize (total-cost))")
    )
    run = ethasp("plan", "d.pddl", "p.pddl", cwd=tmp_path)
    assert run.returncode == 0 and "plan of 2 steps: (cheap) (dear)" in run.stdout, run.stderr
    assert run.stderr.strip().splitlines()[1] == (
        "p.pddl: warning: the metric is ignored: only (:metric minimize (total-cost)) is read "
        "(plans are shortest in number of actions)"
    )


@pytest.mark.parametrize(
    "domain,problem,needle",
    [
        (
            SHOP.replace("(full ?b))\n  (:action close", "(fill ?b))\n  (:action close"),
            SHOP_PROBLEM,
            "unknown predicate fill",
        ),
        (
            SHOP.replace(":effect (out)", ":effect (out ?b)"),
            SHOP_PROBLEM,
            "predicate out takes 0 arguments, found 1",
        ),
        (SHOP, SHOP_PROBLEM.replace("(out)", "(closed ?x)"), "unknown variable ?x"),
        (SHOP, SHOP_PROBLEM.replace("(:init {init})", "(:init (full b9))"), "unknown constant b9"),
    ],
)
def test_bad_adl_input_is_one_line(tmp_path, domain, problem, needle):
    with pytest.raises(InputError) as error:
        load(tmp_path, domain, problem.replace("{init}", ""))
    assert needle in str(error.value) and "\n" not in str(error.value)


# -- Caused and do-no-harm under conditional effects ---------------------------------------

VACUUM = """
(define (domain vacuum)
  (:requirements :strips :typing :conditional-effects)
  (:types room)
  (:predicates (clean ?r - room) (cat-in ?r - room) (scared))
  (:action vacuum :parameters (?r - room)
    :effect (and (clean ?r) (when (cat-in ?r) (scared))))
  (:action shoo :parameters (?r ?s - room)
    :precondition (and (cat-in ?r) (not (= ?r ?s)))
    :effect (and (not (cat-in ?r)) (cat-in ?s))))
"""
VACUUM_PROBLEM = """
(define (problem living) (:domain vacuum)
  (:objects living garden - room)
  (:init (cat-in living))
  (:goal (clean living)))
"""
VACUUM_UTILITY = "utility(scared,true,-3).\n"


def test_caused_and_do_no_harm_count_effects_that_fire(tmp_path):
    model = load(tmp_path, VACUUM, VACUUM_PROBLEM, VACUUM_UTILITY)
    assert str(find_plan(model).plan) == "vacuum(living)"
    assert query(model, Plan.parse("(vacuum living)"), "Caused(scared)").value
    shoo_first = Plan.parse("(shoo living garden) (vacuum living)")
    assert not query(model, shoo_first, "Caused(scared)").value
    hplan = plan_with_principles(model, ["do-no-harm"])
    assert hplan.status == "found" and hplan.plan == shoo_first
    verdicts = {
        j.principle: j.permissible
        for j in judge(model, Plan.parse("(vacuum living)"), ["do-no-harm"]).judgements
    }
    assert verdicts == {"do-no-harm": False}


# -- the IPC domains --------------------------------------------------------------------------

# Optimal plan lengths (Fast Downward's astar(lmcut()) agrees).
OPTIMAL = {
    ("blocks-strips-typed", "p1"): 6,
    ("blocks-strips-typed", "p2"): 10,
    ("depots-strips-automatic", "p1"): 10,
    ("depots-strips-automatic", "p2"): 15,
    ("elevator-strips-simple-typed", "p1"): 4,
    ("elevator-strips-simple-typed", "p2"): 3,
    ("gripper-round-1-strips", "p1"): 11,
    ("gripper-round-1-strips", "p2"): 17,
    ("logistics-strips-typed", "p1"): 20,
    ("logistics-strips-typed", "p2"): 19,
}


def _plan_length(folder: Path, instance: str) -> int:
    model = Model.load([folder / "domain.pddl", folder / f"{instance}.pddl"])
    result = find_plan(model, max_horizon=30)
    assert result.status == "found", result
    assert validate(model, result.plan).valid
    return len(result.plan)


@pytest.mark.slow
@pytest.mark.parametrize("instance", sorted(f"{d}/{p}" for d, p in OPTIMAL))
def test_ipc_instances_plan_with_optimal_length(instance):
    domain, problem = instance.split("/")
    assert _plan_length(DATA / domain, problem) == OPTIMAL[(domain, problem)]


@pytest.mark.slow
def test_every_ipc_instance_kept_is_read():
    domains = sorted(path for path in DATA.iterdir() if (path / "domain.pddl").is_file())
    assert len(domains) == 5
    for folder in domains:
        for problem in sorted(folder.glob("p*.pddl")):
            model = Model.load([folder / "domain.pddl", problem])  # read, translated, checked
            assert model.sources[0].text.count("\naction(") > 0, problem


def test_pddl_1_2_requirements_declared_without_their_sections_are_read(tmp_path):
    """The ADL domains of the first competitions declare :domain-axioms (and
    :ucpop, which implies it) without a single (:axiom ...): they are read;
    an (:axiom ...) or (:safety ...) section is refused with one line."""
    problem = "(define (problem p) (:domain d) (:init) (:goal (done)))"
    for requirements in (":adl :domain-axioms", ":ucpop", ":strips :safety-constraints"):
        model = load(
            tmp_path,
            f"(define (domain d) (:requirements {requirements}) (:predicates (done))"
            " (:action finish :parameters () :precondition (not (done)) :effect (done)))",
            problem,
        )
        assert length(model) == 1
    for section, words in (
        ("(:axiom :vars () :context (done) :implies (done))", "PDDL 1.2 axioms (:axiom"),
        ("(:safety (done))", "safety constraints (:safety)"),
    ):
        with pytest.raises(InputError, match=re.escape(words)) as refused:
            load(
                tmp_path,
                f"(define (domain d) (:requirements :adl :ucpop) (:predicates (done)) {section}"
                " (:action finish :parameters () :effect (done)))",
                problem,
            )
        assert "\n" not in str(refused.value)
