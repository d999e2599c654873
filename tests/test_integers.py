"""Integers never wrap: literals beyond clingo's 32 bits and utilities whose
sums could leave the range are refused; at the bound, sums are exact."""

from __future__ import annotations

import contextlib
import io
import json

import pytest

from ethasp import Model, Plan, judge, query
from ethasp.errors import InputError
from ethasp.interfaces.cli import main
from ethasp.planning.terms import INT_MAX, INT_MIN, parse_symbol

BASE = "variable(v;w). action(a). eff(a,v,true). eff(a,w,false). init(w). goal(v,true).\n"


def model(*utilities: str) -> Model:
    return Model.from_string(BASE + "\n".join(utilities) + "\n", name="m.lp")


@pytest.mark.parametrize(
    "literal",
    [
        "2147483648",
        "3000000000",
        "99999999999999999999",
        "0x80000000",
        "0o20000000000",
        "0b" + "1" * 32,
    ],
)
def test_literals_beyond_32_bits_are_refused_with_their_place(literal):
    with pytest.raises(InputError, match=rf"m\.lp:2:\d+: the integer {literal} is out of range"):
        model(f"utility(a,{literal}).")


def test_the_largest_literal_is_read_as_written():
    m = Model.from_string(BASE + "mine(2147483647). mine(-2147483647).\n")
    atoms = {str(symbol) for symbol in m.planner.get("mine", 1)}
    assert {"mine(2147483647)", "mine(-2147483647)"} <= atoms
    assert parse_symbol("f(2147483647)").arguments[0].number == INT_MAX
    with pytest.raises(InputError, match="out of range"):
        parse_symbol("f(2147483648)")


def test_numbers_in_strings_and_comments_are_not_integers():
    Model.from_string(
        BASE + 'fact_label(v,true,"3000000000 lives").  % 3000000000\n%* 99999999999 *%\n'
    )


@pytest.mark.parametrize("count", [1, 2, 3, 7])
def test_the_bound_is_the_range_divided_by_the_number_of_valued_elements(count):
    variables = " ".join(f"variable(x{i})." for i in range(count - 1))
    bound = INT_MAX // count
    base = BASE.replace("variable(v;w).", "variable(v;w). " + variables) + "".join(
        f"utility(x{i},false,{bound})." for i in range(count - 1)
    )
    # With one valued element the bound is the largest integer: beyond it, the literal.
    beyond = (
        r"the integer 2147483648 is out of range"
        if count == 1
        else rf"\|utility\| must be at most {bound} \(= \(2\^31 - 1\) / {count}\)"
    )
    for sign in (1, -1):
        Model.from_string(base + f"utility(a,{sign * bound}).\n")
        with pytest.raises(InputError, match=beyond):
            Model.from_string(base + f"utility(a,{sign * (bound + 1)}).\n")


def test_zero_utilities_do_not_count():
    model("utility(a,0).", "utility(w,true,0).", f"utility(v,true,{INT_MAX}).")
    with pytest.raises(InputError, match="too large"):
        model("utility(a,1).", f"utility(v,true,{INT_MAX}).")


def test_the_most_negative_integer_is_refused():
    with pytest.raises(InputError, match="too large"):
        Model.from_string(BASE + f"utility(a,{INT_MIN + 1} - 1).\n")


def test_sums_at_the_bound_are_exact():
    """Three valued facts at (2^31-1)/3: the final state's utility and every GEq
    comparison are computed without wrapping."""
    bound = INT_MAX // 3
    m = model(
        f"utility(v,true,{bound}).", f"utility(w,false,{bound}).", f"utility(w,true,{-bound})."
    )
    report = judge(m, Plan.parse("a"), ["utilitarianism"])
    assert report.utility == 2 * bound
    assert report.judgements[0].permissible
    assert query(m, Plan.parse("a"), "GEq(v & -w, -v & w)").value
    assert not query(m, Plan.parse("a"), "GEq(-v & w, v & -w)").value


def test_the_cli_never_prints_a_wrapped_utility(tmp_path):
    path = tmp_path / "m.lp"
    path.write_text(BASE + "utility(v,true,3000000000).\n")
    assert main(["judge", str(path), "--plan", "a", "--json"]) == 2
    path.write_text(BASE + f"utility(v,true,{INT_MAX // 2}). utility(w,false,{INT_MAX // 2}).\n")
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["judge", str(path), "--plan", "a", "--json"]) == 0
    assert json.loads(out.getvalue())["utility"] == 2 * (INT_MAX // 2)
