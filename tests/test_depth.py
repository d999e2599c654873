"""No recursion limits: formulas, questions, plans, models and saved dialogues
of any depth a user can type are read (iteratively) or refused with one line
at the documented limit (ethasp.planning.terms.MAX_NESTING)."""

from __future__ import annotations

import json
import sys

import clingo
import pytest
from conftest import MODELS

from ethasp import Model, Plan, query
from ethasp.errors import InputError
from ethasp.planning.terms import MAX_NESTING, parse_symbol
from ethasp.principles.formula import Elements, format_formula, parse_formula
from ethasp.questions.dialogue import Dialogue
from ethasp.questions.question import Question

DEEP = sys.getrecursionlimit() * 5  # far beyond Python's recursion limit


@pytest.fixture(scope="module")
def trolley():
    return Model.load([MODELS / "trolley.lp"])


@pytest.fixture(scope="module")
def elements(trolley):
    return Elements.of_model(trolley)


def test_the_issue_example_5000_parentheses(trolley):
    formula = "(" * 5000 + "Bad(one_will_die) -> not Caused(one_will_die)" + ")" * 5000
    assert query(trolley, Plan.parse("pull"), formula).value is False


def test_parentheses_have_no_limit(elements):
    parsed = parse_formula("(" * 200_000 + "not Good(pull)" + ")" * 200_000, elements)
    assert str(parsed) == "not Good(pull)"


@pytest.mark.slow
@pytest.mark.parametrize("operator", ["not ", "and", "or", "->"])
def test_operators_nest_up_to_the_limit(trolley, operator):
    atom = "Good(-five_will_die)"
    count = MAX_NESTING
    text = (
        "not " * count + atom if operator == "not " else f" {operator} ".join([atom] * (count + 1))
    )
    assert query(trolley, Plan.parse("pull"), text).value is True
    deeper = (
        "not " * (count + 1) + atom
        if operator == "not "
        else f" {operator} ".join([atom] * (count + 2))
    )
    with pytest.raises(
        InputError,
        match=rf"formula: column \d+: the formula nests operators "
        rf"more than {MAX_NESTING} deep",
    ):
        parse_formula(deeper, Elements.of_model(trolley))


def test_printing_is_iterative_and_round_trips(elements):
    text = " -> ".join("(not Good(pull) or Caused(-five_will_die))" for _ in range(DEEP))
    parsed = parse_formula(text, elements)
    printed = str(parsed)
    assert parse_formula(printed, elements).term == parsed.term
    term = clingo.Function("bad", [clingo.Function("action", [clingo.Function("pull")])])
    for _ in range(DEEP):
        term = clingo.Function("neg", [term])
    assert format_formula(term) == "not " * DEEP + "Bad(pull)"


def test_printing_members_and_cycles():
    member = clingo.Function("m")
    good = clingo.Function("good", [clingo.Function("action", [clingo.Function("pull")])])
    assert (
        format_formula(clingo.Function("all", [member]), members={member: [good, good]})
        == "Good(pull) and Good(pull)"
    )
    with pytest.raises(ValueError, match="contains itself"):
        format_formula(
            clingo.Function("all", [member]), members={member: [clingo.Function("all", [member])]}
        )


def test_deep_names_are_refused_at_the_limit():
    name = "f(" * MAX_NESTING + "a" + ")" * MAX_NESTING
    assert parse_symbol(name).type == clingo.SymbolType.Function
    for text in ("f(" + name + ")", "f(" * DEEP * 100 + "a" + ")" * DEEP * 100):
        with pytest.raises(InputError, match=f"parentheses nested more than {MAX_NESTING}"):
            parse_symbol(text)
        with pytest.raises(InputError, match="nested more than"):
            Plan.parse(text)


def test_deep_questions_are_read_iteratively(trolley):
    action = "f(" * (DEEP * 100) + "a" + ")" * (DEEP * 100)
    question = Question.parse(f"why {action} rather than pull?")
    assert question.kind == "rather-than" and question.other == "pull"
    with pytest.raises(InputError, match="nested more than"):
        Dialogue.start(trolley, "deontology", Plan.parse("pull")).ask(question)


def test_deep_models_are_refused_before_clingo_reads_them():
    with pytest.raises(InputError, match=f"parentheses nested more than {MAX_NESTING} deep"):
        Model.from_string("p(" + "(" * 300_000 + "1" + ")" * 300_000 + ").")
    with pytest.raises(InputError, match=f"more than {MAX_NESTING} arithmetic operators"):
        Model.from_string("p(" + "+".join(["1"] * 100_000) + ").")
    with pytest.raises(InputError, match="more than"):
        Model.from_string("p(" + "-" * 100_000 + "1).")


def test_deep_saved_dialogues_are_refused(trolley, tmp_path):
    path = tmp_path / "deep.json"
    path.write_text("[" * 100_000 + "]" * 100_000)
    with pytest.raises(InputError, match="nested too deeply"):
        Dialogue.load(path, trolley)
    path.write_text(
        json.dumps(
            {
                "format": "ethasp-dialogue",
                "version": 1,
                "principle": "deontology",
                "plan": ["f(" * 20_000 + "a" + ")" * 20_000],
            }
        )
    )
    with pytest.raises(InputError, match="nested more than"):
        Dialogue.load(path, trolley)
