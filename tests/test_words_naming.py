"""Words in the model's own names: a PDDL task's explanations, reasons,
contrastive texts, constraints and messages name actions and facts in PDDL
form (as its plans and states are printed), and a permissible plan of several
actions under deontology is explained by all of its actions, not by one."""

from __future__ import annotations

import os
import re
import subprocess
import sys

import clingo
import pytest
from conftest import MODELS, ROOT

from ethasp import InputError, Model, Plan, parse_formula, query
from ethasp.interfaces.answer_words import answer_text
from ethasp.planning.naming import Naming, PddlNaming
from ethasp.principles.formula import Elements
from ethasp.questions.contrast import ask
from ethasp.reasons.reasons import explain

PDDL = MODELS / "pddl"
CARE = [PDDL / "care-domain.pddl", PDDL / "care-problem.pddl", PDDL / "care-utility.lp"]
# A permissible plan under deontology (8 steps) and an impermissible one.
ROUND = Plan.parse(
    "(move kitchen hall) (enter-bedroom hall bedroom bob) (move bedroom store-room) "
    "(pick-up pills-ann store-room) (enter-bedroom store-room bedroom bob) "
    "(move bedroom hall) (move hall living-room) (give pills-ann ann living-room)"
)
SHORTCUT_TEXT = (
    "(pick-up pills-bob kitchen) (move kitchen hall) (move hall living-room) "
    "(give-other-medicine pills-bob ann bob living-room pills-ann)"
)
SHORTCUT = Plan.parse(SHORTCUT_TEXT)
# An ASP compound term (move(kitchen,hall), robot_at(hall)): none in a PDDL task's words.
ASP_TERM = re.compile(r"\b[a-z][a-z0-9_']*\([a-z0-9_',]+\)")


@pytest.fixture(scope="module")
def care():
    return Model.load(CARE)


def ethasp(*args: str, stdin: str | None = None) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        input=stdin,
    )


# -- PDDL names -----------------------------------------------------------------------


def test_pddl_explanations_and_reasons_use_pddl_names(care):
    permissible = explain(care, ROUND, "deontology")
    assert "(move kitchen hall), then (enter-bedroom hall bedroom bob)" in permissible.text
    assert ["not Bad((move kitchen hall))"] in permissible.necessary_reasons
    harmful = explain(care, SHORTCUT, "do-no-harm")
    assert "this way the fact (deprived bob) is caused by the agent's actions" in harmful.text
    assert harmful.sufficient_reasons == [["Bad((deprived bob))", "Caused((deprived bob))"]]
    bad = explain(care, SHORTCUT, "deontology")
    assert bad.text.endswith(
        "because action (give-other-medicine pills-bob ann bob living-room "
        "pills-ann) is inherently bad."
    )
    worse = explain(care, SHORTCUT, "utilitarianism")
    assert re.search(r"because the fact \(.*\) is worse than the fact \(.*\)\.$", worse.text)
    assert worse.chosen_reason[0].startswith("not GEq((")
    for explanation in (permissible, harmful, bad, worse):
        words = " ".join(
            [explanation.text]
            + [
                literal
                for reason in explanation.sufficient_reasons + explanation.necessary_reasons
                for literal in reason
            ]
        )
        assert not ASP_TERM.search(words), ASP_TERM.search(words)


def test_printed_reasons_are_formulas_of_the_model(care):
    """A reason printed in PDDL names reads back as a formula that holds."""
    elements = Elements.of_model(care)
    for plan, principle in (
        (ROUND, "deontology"),
        (SHORTCUT, "do-no-harm"),
        (SHORTCUT, "utilitarianism"),
    ):
        explanation = explain(care, plan, principle)
        for reason in explanation.sufficient_reasons:
            formula = " and ".join(f"({literal})" for literal in reason)
            parse_formula(formula, elements)
            if principle != "utilitarianism":  # GEq needs the compared state
                assert query(care, plan, formula).value, formula


def test_formulas_read_pddl_atoms_and_name_them_as_typed(care):
    elements = Elements.of_model(care)
    same = [
        parse_formula(text, elements).term
        for text in (
            "Caused(-deprived(bob))",
            "Caused(-(deprived bob))",
            "Caused((not (deprived bob)))",
            "Caused((NOT  (Deprived BOB)))",
        )
    ]
    assert len(set(same)) == 1
    with pytest.raises(InputError, match=r"unknown action or variable '\(flying pig\)'"):
        parse_formula("Caused((flying  pig))", elements)
    with pytest.raises(InputError, match=r"'\(move kitchen hall\)' is an action; only facts"):
        parse_formula("Bad((not (move kitchen hall)))", elements)


def test_constraints_and_messages_in_pddl_names(care):
    naming = care.naming
    term = clingo.parse_term("before(move(kitchen,hall),pick_up(pills_ann,store_room))")
    assert naming.constraint(term) == "before((move kitchen hall),(pick-up pills-ann store-room))"
    assert Naming().constraint(term) == str(term)
    assert PddlNaming().name(clingo.parse_term("living_room")) == "living-room"
    with pytest.raises(InputError, match=r"plan: unknown action \(fly kitchen\) at step 1"):
        from ethasp import validate

        validate(care, Plan.parse("(fly kitchen)"))


TWO_ROOMS = """(define (domain rooms)
  (:predicates (at ?r) (door ?a ?b) (marked ?r))
  (:action move :parameters (?a ?b) :precondition (and (at ?a) (door ?a ?b))
    :effect (and (not (at ?a)) (at ?b)))
  (:action mark :parameters (?r) :precondition (at ?r) :effect (marked ?r)))
"""
TWO_ROOMS_PROBLEM = """(define (problem p) (:domain rooms) (:objects a b)
  (:init (at a) (door a b)) (:goal (at b)))
"""


def test_contrastive_text_and_constraints_in_pddl_names(tmp_path):
    """A question that no plan can meet: the contrastive text names the
    conflicting constraint in PDDL form, as the dialogue's lines do."""
    (tmp_path / "d.pddl").write_text(TWO_ROOMS)
    (tmp_path / "p.pddl").write_text(TWO_ROOMS_PROBLEM)
    (tmp_path / "u.lp").write_text("utility(marked(R), true, -1) :- variable(marked(R)).\n")
    model = Model.load([tmp_path / "d.pddl", tmp_path / "p.pddl", tmp_path / "u.lp"])
    answer = ask(model, "why (move a b)", Plan.parse("(mark a) (move a b)"), "deontology")
    assert answer.contrast is None
    assert "no plan can avoid action (move a b)" in answer.explanation
    assert "The agent could (mark a), then (move a b)." in answer.explanation
    assert "neither action (mark a) nor action (move a b) is inherently bad" in answer.explanation
    text = answer_text(answer, model.naming)
    assert "constraints: unused((move a b))" in text
    assert not ASP_TERM.search(text), ASP_TERM.search(text)


def test_command_line_words_of_a_pddl_task_have_no_asp_terms():
    run = ethasp("judge", *map(str, CARE), "--plan", SHORTCUT_TEXT)
    assert run.returncode == 0, run.stderr
    assert "(give-other-medicine pills-bob ann bob living-room pills-ann)" in run.stdout
    assert not ASP_TERM.search(run.stdout), ASP_TERM.search(run.stdout)


# -- deontology on plans of several actions -----------------------------------------------


def test_deontology_names_every_action_of_a_permissible_plan():
    rescue = Model.load([MODELS / "rescue.lp"])
    plan = Plan.parse("take_key move(r1,r2) move(r2,r3) unlock_door move(r3,r4)")
    explanation = explain(rescue, plan, "deontology")
    assert explanation.permissible
    assert explanation.text.endswith(
        "Doing so is permissible because none of the rescue robot's 5 actions is inherently bad."
    )
    # the reasons themselves are unchanged: each action is a necessary reason
    assert len(explanation.necessary_reasons) == 5
    assert all(len(reason) == 1 for reason in explanation.necessary_reasons)


def test_deontology_on_short_plans_names_the_actions():
    model = Model.from_string(
        "variable(p;q;r). action(a;b;c). eff(a,p,true). eff(b,q,true). "
        "eff(c,r,true). goal(r,true). utility(a,1). "
        'action_label(a, "act a", "doing a"). '
        'action_label(b, "act b", "doing b"). '
        'action_label(c, "act c", "doing c").'
    )
    one = explain(model, Plan.parse("c"), "deontology")
    assert one.text.endswith("permissible because doing c is not inherently bad.")
    two = explain(model, Plan.parse("a c"), "deontology")
    assert two.text.endswith("permissible because neither doing a nor doing c is inherently bad.")
    three = explain(model, Plan.parse("b a c"), "deontology")
    assert three.text.endswith(
        "permissible because none of doing a, doing b and doing c is inherently bad."
    )
    # limited to one reason of each kind: still all of them in the words
    limited = explain(model, Plan.parse("b a c"), "deontology", limit=1)
    assert limited.text == three.text


def test_deontology_with_several_bad_actions():
    model = Model.from_string(
        "variable(p;q). action(a;b). eff(a,p,true). eff(b,q,true). "
        "goal(q,true). utility(a,-1). utility(b,-2)."
    )
    explanation = explain(model, Plan.parse("a b"), "deontology")
    assert explanation.text.endswith(
        "impermissible because action a and action b are inherently bad."
    )


def test_the_paper_sentences_stay():
    trolley = Model.load([MODELS / "trolley.lp"])
    assert explain(trolley, Plan.parse("pull"), "deontology").text == (
        "The man can pull the lever. Doing so is permissible because pulling a lever is not "
        "inherently bad."
    )
    assert explain(trolley, Plan.parse("pull"), "do-no-harm").text.endswith(
        "impermissible because this way the death of the one person is caused by the man's action."
    )


def test_an_action_without_a_label_reads_as_words():
    """A step without a label is named in words, its arguments after it, not
    in the model's syntax (``put_down(p2,r2)``: "put down (p2, r2)")."""
    model = Model.from_string(
        "variable(done). variable(here(p2)). action(put_down(p2,r2)). action(wait_a_bit).\n"
        "eff(put_down(p2,r2), here(p2), true). pre(wait_a_bit, here(p2), true).\n"
        "eff(wait_a_bit, done, true). goal(done, true). utility(put_down(p2,r2), -1).\n"
    )
    text = explain(model, Plan.parse("put_down(p2,r2) wait_a_bit"), "deontology").text
    assert "put down (p2, r2), then wait a bit" in text, text
    assert "put_down" not in text and "wait_a_bit" not in text
    assert "action put down (p2, r2) is inherently bad" in text, text


def test_several_facts_compared_take_a_plural_verb():
    model = Model.load([MODELS / "rescue.lp"])
    plan = Plan.parse(
        "move(r1,r2) pick_up(p2,r2) move(r2,r3) put_down(p2,r3) break_door move(r3,r4)"
    )
    text = explain(model, plan, "utilitarianism").text
    assert "the person from room 3 left behind are worse than the person from room 2 saved" in text
    assert "then put the person down in room 3, then" in text  # the bundled model's label
    trolley = Model.load([MODELS / "trolley.lp"])
    single = explain(trolley, Plan.parse("pull"), "utilitarianism").text
    assert "five saved lives is better than one saved life" in single, single
