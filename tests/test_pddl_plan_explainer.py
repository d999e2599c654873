"""PDDL as plan-explainer (Lindner and Olz, RO-MAN 2022) reads it, and the E-links
and D-links of ``ethasp explain`` on such files.

The domains here are written for the features plan-explainer's examples have:
no ``:predicates`` section, untyped parameters, names used as constants in
actions that nobody declares, an empty precondition ``()``, negative
preconditions and goals without ``:requirements``, a problem without
``:init``, a typed parameter whose type nobody declares, plans written
``(a);(b)``.  The coke example's links are the ones plan-explainer publishes
for it; the others are worked out from the definitions (see the comments).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from conftest import ethasp_process

from ethasp import InputError, Model, Plan
from ethasp.questions.steps import explain_steps

# plan-explainer's coke example, written anew: serving takes the drink out of
# the fridge, and the goal wants it served and the fridge stocked again.
COKE = """
; a drinks robot
(define (domain Coke)
  (:action Serve :parameters (?d)
     :precondition (inFridge ?d)
     :effect (and (served ?d) (not (inFridge ?d))))
  (:action RefillFridge :parameters (?d)
     :precondition (not (inFridge ?d))
     :effect (inFridge ?d)))
"""
COKE_PROBLEM = """
(define (problem CokeProblem) (:domain Coke)
  (:objects coke)
  (:init (inFridge coke))
  (:goal (and (served coke) (inFridge coke))))
"""

# A robot asks for a door to be opened, walks through and asks for it to be
# closed again (the room is quiet only with the door closed): constants used
# in actions that only the problem declares, an action without parameters
# or precondition, a move with untyped parameters.
HALL = """
(define (domain Hall)
  (:action AskOpen :parameters () :precondition ()
     :effect (and (open gate) (not (quiet study))))
  (:action AskClose :parameters () :precondition ()
     :effect (and (not (open gate)) (quiet study)))
  (:action Walk :parameters (?from ?to)
     :precondition (and (open gate) (in ?from))
     :effect (and (not (in ?from)) (in ?to))))
"""
HALL_PROBLEM = """
(define (problem HallProblem) (:domain Hall)
  (:objects study garden gate)
  (:init (in study) (quiet study))
  (:goal (and (in garden) (quiet study))))
"""

# Passing a person closely reaches the spot but offends them; an apology
# makes up for it.  The spot `spot` is declared nowhere, the problem has no
# :init, and the goal is negative.
PASSING = """
(define (domain Passing)
  (:action Squeeze :parameters () :precondition ()
     :effect (and (at spot) (offended)))
  (:action Apologise :parameters () :precondition ()
     :effect (not (offended))))
"""
PASSING_PROBLEM = """
(define (problem PassingProblem) (:domain Passing)
  (:objects somewhere)
  (:goal (and (at spot) (not (offended)))))
"""


def load(tmp_path: Path, domain: str, problem: str) -> Model:
    (tmp_path / "domain.pddl").write_text(domain)
    (tmp_path / "problem.pddl").write_text(problem)
    return Model.load([tmp_path / "domain.pddl", tmp_path / "problem.pddl"])


def links(model: Model, plan: str) -> tuple[list, list]:
    data = explain_steps(model, Plan.parse(plan)).to_json()
    return (
        [(link["from"], link["variable"], link["value"], link["to"]) for link in data["e_links"]],
        [(link["from"], link["variable"], link["value"], link["to"]) for link in data["d_links"]],
    )


def test_coke_gives_plan_explainers_published_links(tmp_path):
    model = load(tmp_path, COKE, COKE_PROBLEM)
    e_links, d_links = links(model, "(Serve coke);(RefillFridge coke)")
    # plan-explainer: "(not (served coke)) holds initially and requires (Serve
    # coke)"; "(Serve coke) results in (not (inFridge coke)), which requires
    # (RefillFridge coke)".
    assert d_links == [
        ("init", "served(coke)", False, 1),
        (1, "infridge(coke)", False, 2),
    ]
    # "(inFridge coke) holds initially and enables (Serve coke)"; "(Serve coke)
    # results in (served coke), which fulfills the goal"; "(RefillFridge coke)
    # results in (inFridge coke), which fulfills the goal".
    assert e_links == [
        ("init", "infridge(coke)", True, 1),
        (1, "served(coke)", True, "goal"),
        (2, "infridge(coke)", True, "goal"),
    ]
    lines = explain_steps(model, Plan.parse("(serve coke) (refillfridge coke)")).link_lines()
    assert lines == [
        "Step 1, (serve coke): the fact (not (served coke)) holds initially and requires it; "
        "the fact (infridge coke) holds initially and enables it; it results in the fact "
        "(served coke), which fulfils the goal.",
        "Step 2, (refillfridge coke): step 1 ((serve coke)) results in the fact (not (infridge "
        "coke)), which requires it; it results in the fact (infridge coke), which fulfils the "
        "goal.",
    ]


def test_hall_links(tmp_path):
    model = load(tmp_path, HALL, HALL_PROBLEM)
    e_links, d_links = links(model, "(AskOpen) (Walk study garden) (AskClose)")
    # Before step 1, had the gate been open or the robot in the garden, a
    # subsequence of the later steps would have reached the goal; before step
    # 2, had it been in the garden, closing alone would have; before step 3,
    # had the study been quiet, nothing more was needed.
    assert d_links == [
        ("init", "in(garden)", False, 1),
        ("init", "open(gate)", False, 1),
        ("init", "in(garden)", False, 2),
        (1, "quiet(study)", False, 3),
    ]
    assert e_links == [
        ("init", "in(study)", True, 2),
        (1, "open(gate)", True, 2),
        (2, "in(garden)", True, "goal"),
        (3, "quiet(study)", True, "goal"),
    ]


def test_passing_links_with_an_undeclared_constant_and_a_negative_goal(tmp_path):
    model = load(tmp_path, PASSING, PASSING_PROBLEM)
    e_links, d_links = links(model, "(Squeeze) (Apologise)")
    assert d_links == [("init", "at(spot)", False, 1), (1, "offended", True, 2)]
    assert e_links == [(1, "at(spot)", True, "goal"), (2, "offended", False, "goal")]


def test_one_warning_line_and_the_links_in_json(tmp_path):
    (tmp_path / "d.pddl").write_text(PASSING)
    (tmp_path / "p.pddl").write_text(PASSING_PROBLEM)
    run = ethasp_process(
        "explain", "d.pddl", "p.pddl", "--plan", "(Squeeze);(Apologise)", "--json", cwd=tmp_path
    )
    assert run.returncode == 0, run.stderr
    assert run.stderr.splitlines() == [
        "d.pddl: warning: no :predicates section (predicates read from their uses: at/1, "
        "offended/0); constant spot used but not declared (read as objects)",
        "p.pddl: warning: requirement :negative-preconditions used but not declared (read anyway)",
    ]
    data = json.loads(run.stdout)
    assert data["d_links"] == [
        {"from": "init", "variable": "at(spot)", "value": False, "to": 1},
        {"from": 1, "variable": "offended", "value": True, "to": 2},
    ]


def test_an_undeclared_type_of_a_parameter_and_its_objects(tmp_path):
    # An older form of plan-explainer's coke example: typed parameters, the
    # type declared nowhere but given to the problem's objects.
    typed = COKE.replace("(?d)", "(?d - drink)")
    model = load(
        tmp_path, typed, COKE_PROBLEM.replace("(:objects coke)", "(:objects coke - drink)")
    )
    assert links(model, "(serve coke) (refillfridge coke)")[1] == [
        ("init", "served(coke)", False, 1),
        (1, "infridge(coke)", False, 2),
    ]


@pytest.mark.parametrize(
    "domain,problem,needles",
    [
        # A predicate used with two arities: the second use, with its line.
        (
            HALL.replace("(in ?to)", "(in ?to ?from)"),
            HALL_PROBLEM,
            (
                "domain.pddl:9: predicate in is used with 2 arguments here and with 1 at ",
                "domain.pddl:8 (the domain has no :predicates)",
            ),
        ),
        (
            HALL,
            HALL_PROBLEM.replace("(in garden)", "(in garden study)"),
            ("problem.pddl:5: predicate in is used with 2 arguments here", "domain.pddl:8"),
        ),
        # The problem's own names must be declared (objects of the problem or
        # constants the domain uses).
        (
            HALL,
            HALL_PROBLEM.replace("(in study) (quiet", "(in kitchen) (quiet"),
            ("problem.pddl:4: unknown constant kitchen",),
        ),
    ],
)
def test_real_mistakes_stay_one_error_line(tmp_path, domain, problem, needles):
    with pytest.raises(InputError) as error:
        load(tmp_path, domain, problem)
    assert all(needle in str(error.value) for needle in needles), error.value
    assert "\n" not in str(error.value)
