"""The textual syntax of L: parsing, printing, round trips and error messages."""

import clingo
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ethasp import InputError, format_formula, format_literal, parse_formula
from ethasp.principles.formula import Elements

F = clingo.Function
ELEMENTS = Elements(
    actions=frozenset({F("pull"), F("refrain"), F("push", [F("man")]), F("both")}),
    variables=frozenset(
        {
            F("five_will_die"),
            F("one_will_die"),
            F("done"),
            F("at", [F("robot"), F("r1")]),
            F("both"),
        }
    ),
)


def parse(text: str):
    return parse_formula(text, ELEMENTS)


@pytest.mark.parametrize(
    "text, term",
    [
        ("Bad(pull)", "bad(action(pull))"),
        ("Good(push(man))", "good(action(push(man)))"),
        ("Neutral(-done)", "neutral(fact(done,false))"),
        ("Good(at(robot,r1))", "good(fact(at(robot,r1),true))"),
        ("Caused(one_will_die)", "caused(one_will_die,true)"),
        ("Caused(-five_will_die)", "caused(five_will_die,false)"),
        ("Caused( - five_will_die )", "caused(five_will_die,false)"),
        ("not Bad(pull)", "neg(bad(action(pull)))"),
        ("not not Bad(pull)", "neg(neg(bad(action(pull))))"),
        (
            "Bad(pull) and Good(pull) and Bad(refrain)",
            "and(and(bad(action(pull)),good(action(pull))),bad(action(refrain)))",
        ),
        (
            "Bad(pull) or Good(pull) and Bad(refrain)",
            "or(bad(action(pull)),and(good(action(pull)),bad(action(refrain))))",
        ),
        ("not Bad(pull) and Good(pull)", "and(neg(bad(action(pull))),good(action(pull)))"),
        (
            "Bad(pull) -> Good(pull) -> Bad(refrain)",
            "imp(bad(action(pull)),imp(good(action(pull)),bad(action(refrain))))",
        ),
        (
            "Bad(pull) or Good(pull) -> Bad(refrain)",
            "imp(or(bad(action(pull)),good(action(pull))),bad(action(refrain)))",
        ),
        (
            "(Bad(pull) -> Good(pull)) -> Bad(refrain)",
            "imp(imp(bad(action(pull)),good(action(pull))),bad(action(refrain)))",
        ),
        ("not (Bad(pull) or Good(pull))", "neg(or(bad(action(pull)),good(action(pull))))"),
        ("bad(pull) AND good(pull)", None),  # keywords are lower case
        ("BAD(pull) and GOOD(pull)", "and(bad(action(pull)),good(action(pull)))"),
        ("true or false", "or(all(empty),any(empty))"),
    ],
)
def test_parse(text, term):
    if term is None:
        with pytest.raises(InputError):
            parse(text)
    else:
        assert str(parse(text).term) == term


def test_geq_conjunctions_become_conj_facts():
    formula = parse(
        "GEq(-five_will_die & one_will_die & done, five_will_die & -one_will_die & done)"
    )
    assert str(formula.term) == "geq(c(1),c(2))"
    facts = {str(fact) for fact in formula.facts("q")}
    assert facts == {
        "formula(q,geq(c(1),c(2)))",
        "conj(c(1),five_will_die,false)",
        "conj(c(1),one_will_die,true)",
        "conj(c(1),done,true)",
        "conj(c(2),five_will_die,true)",
        "conj(c(2),one_will_die,false)",
        "conj(c(2),done,true)",
    }
    assert str(formula) == (
        "GEq(-five_will_die & one_will_die & done, five_will_die & -one_will_die & done)"
    )
    assert str(parse("GEq((), done)")) == "GEq((), done)"


@pytest.mark.parametrize(
    "text, message",
    [
        ("Bad(pull", "formula: column 9: expected ')'"),
        ("(Bad(pull)", "formula: column 11: expected ')'"),
        ("Bad(pull))", "formula: column 10: unexpected ')'"),
        ("Bad(pull) and", "formula: column 14: expected a formula"),
        ("Bad(pull) Good(pull)", "formula: column 11: unexpected 'Good'"),
        ("Evil(pull)", "formula: column 1: expected a formula"),
        ("Bad()", "formula: column 5: expected an action or a fact"),
        ("Bad(jump)", "formula: column 5: unknown action or variable 'jump'"),
        ("Good(both)", "formula: column 6: 'both' is both an action and a variable"),
        ("Caused(pull)", "formula: column 8: Caused takes facts, but 'pull' is an action"),
        ("Good(-pull)", "formula: column 6: 'pull' is an action; only facts can be negated"),
        ("GEq(done & pull, done)", "formula: column 12: GEq takes facts, but 'pull' is an action"),
        ("GEq(done)", "formula: column 9: expected ','"),
        ("Good(done, pull)", "formula: column 10: expected ')'"),
        ("Good(1+)", "formula: column 6: not an action or variable name"),
        ("   ", "formula: empty formula"),
    ],
)
def test_errors_name_the_column(text, message):
    with pytest.raises(InputError) as error:
        parse(text)
    assert str(error.value).startswith(message), str(error.value)
    assert "\n" not in str(error.value)


@pytest.mark.parametrize(
    "text",
    [
        "Bad(pull)",
        "not Caused(-five_will_die) and Good(push(man)) or Neutral(at(robot,r1))",
        "Bad(pull) -> Good(pull) -> Bad(refrain)",
        "(Bad(pull) -> Good(pull)) -> Bad(refrain)",
        "Bad(pull) and (Good(pull) and Bad(refrain))",
        "Bad(pull) or (Good(pull) or Bad(refrain))",
        "not (Bad(pull) and Good(pull))",
        "not not Bad(pull)",
        "(Bad(pull) or Good(pull)) and Bad(refrain)",
        "GEq(-five_will_die & one_will_die & done, five_will_die & -one_will_die & done)",
        "true and not false",
    ],
)
def test_round_trip_of_normal_forms(text):
    formula = parse(text)
    assert str(formula) == text
    assert parse(str(formula)).term == formula.term


def test_printer_for_principle_formulas_and_literals():
    members = {
        F("deontology"): [
            clingo.parse_term("neg(bad(action(pull)))"),
            clingo.parse_term("neg(bad(action(refrain)))"),
        ]
    }
    assert (
        format_formula(F("all", [F("deontology")]), members=members)
        == "not Bad(pull) and not Bad(refrain)"
    )
    assert (
        format_formula(F("any", [F("deontology")]), members=members)
        == "not Bad(pull) or not Bad(refrain)"
    )
    assert format_formula(F("all", [F("nothing")])) == "true"
    dnh = clingo.parse_term("imp(bad(fact(one_will_die,true)),neg(caused(one_will_die,true)))")
    assert (
        format_formula(F("all", [F("p")]), members={"p": [dnh]})
        == "Bad(one_will_die) -> not Caused(one_will_die)"
    )
    conj = {
        "final": [(F("one_will_die"), "true"), (F("five_will_die"), False)],
        "best": [(F("done"), F("true"))],
    }
    geq = clingo.parse_term("geq(final,best)")
    assert format_literal(geq, conj) == "GEq(one_will_die & -five_will_die, done)"
    assert format_literal(F("neg", [geq]), conj) == "not GEq(one_will_die & -five_will_die, done)"
    assert (
        format_literal(clingo.parse_term("neg(caused(five_will_die,false))"))
        == "not Caused(-five_will_die)"
    )
    with pytest.raises(ValueError):
        format_literal(clingo.parse_term("and(good(action(a)),good(action(b)))"))


# -- random round trips ---------------------------------------------------------

ELEMENT_TEXT = [
    "pull",
    "push(man)",
    "five_will_die",
    "-five_will_die",
    "at(robot,r1)",
    "-at(robot,r1)",
]
FACT_TEXT = ["five_will_die", "-one_will_die", "done", "at(robot,r1)"]

atoms = st.one_of(
    st.builds(
        lambda op, e: f"{op}({e})",
        st.sampled_from(["Good", "Bad", "Neutral"]),
        st.sampled_from(ELEMENT_TEXT),
    ),
    st.builds(lambda f: f"Caused({f})", st.sampled_from(FACT_TEXT)),
    st.builds(
        lambda a, b: f"GEq({' & '.join(a)}, {' & '.join(b)})",
        st.lists(st.sampled_from(FACT_TEXT), min_size=1, max_size=3),
        st.lists(st.sampled_from(FACT_TEXT), min_size=1, max_size=3),
    ),
    st.sampled_from(["true", "false"]),
)

texts = st.recursive(
    atoms,
    lambda inner: st.one_of(
        st.builds(lambda f: f"not ({f})", inner),
        st.builds(
            lambda f, g, op: f"({f}) {op} ({g})", inner, inner, st.sampled_from(["and", "or", "->"])
        ),
    ),
    max_leaves=8,
)


@settings(max_examples=150, deadline=None)
@given(texts)
def test_printing_then_parsing_gives_the_same_term(text):
    formula = parse(text)
    printed = str(formula)
    again = parse(printed)
    assert again.term == formula.term
    assert list(again.conjunctions.values()) == list(formula.conjunctions.values())
    assert str(again) == printed
