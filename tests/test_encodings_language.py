"""Encoding-level tests of the language L (language.lp) and the principles."""

import pytest
from conftest import MODELS, only_answer

LANGUAGE = ["planning/model.lp", "planning/trace.lp", "judgement/language.lp"]

# Utilities: u(x) = -2 (bad action), u(y) = 3 (good), u(z) = 0 (neutral);
# u(a) = 4, u(-a) = -1, u(b) = -3, u(-b) = 0.  Plan: x then y.
# Final state: a true (set by x), b false (set by y after x set it true), c false (untouched).
SMALL = """
variable(a;b;c). action(x;y;z).
eff(x,a,true). eff(x,b,true). eff(y,b,false). eff(z,c,true).
goal(a,true).
utility(x,-2). utility(y,3). utility(z,0).
utility(a,true,4). utility(a,false,-1). utility(b,true,-3).
occurs(x,1). occurs(y,2).
"""


def truth(formula: str, extra: str = "") -> bool:
    answer = only_answer(LANGUAGE, SMALL + extra + f"formula(f, {formula}).")
    assert ("verdict(f,true)" in answer) != ("verdict(f,false)" in answer), answer
    return "verdict(f,true)" in answer


@pytest.mark.parametrize(
    "formula, expected",
    [
        ("good(action(y))", True),
        ("good(action(x))", False),
        ("good(action(z))", False),
        ("bad(action(x))", True),
        ("bad(action(y))", False),
        ("bad(action(z))", False),
        ("neutral(action(z))", True),
        ("neutral(action(x))", False),
        ("good(fact(a,true))", True),
        ("bad(fact(a,false))", True),
        ("bad(fact(a,true))", False),
        ("bad(fact(b,true))", True),
        ("neutral(fact(b,false))", True),
        ("neutral(fact(c,true))", True),
        ("good(fact(c,false))", False),
    ],
)
def test_good_bad_neutral_for_actions_and_facts_of_both_polarities(formula, expected):
    assert truth(formula) is expected


@pytest.mark.parametrize(
    "formula, expected",
    [
        ("caused(a,true)", True),  # x set a, and a holds at the end
        ("caused(b,false)", True),  # y set b to false, and b is false at the end
        ("caused(b,true)", False),  # x set b, but b does not hold at the end
        ("caused(c,false)", False),  # c is false at the end, but no action of the plan set it
        ("caused(c,true)", False),  # z could set c, but it is not in the plan
        ("caused(a,false)", False),
    ],
)
def test_caused_of_both_polarities(formula, expected):
    assert truth(formula) is expected


def test_connectives():
    t, f = "good(action(y))", "bad(action(y))"
    assert truth(f"neg({f})") and not truth(f"neg({t})")
    assert truth(f"and({t},{t})") and not truth(f"and({t},{f})") and not truth(f"and({f},{t})")
    assert truth(f"or({t},{f})") and truth(f"or({f},{t})") and not truth(f"or({f},{f})")
    assert truth(f"imp({f},{f})") and truth(f"imp({f},{t})") and truth(f"imp({t},{t})")
    assert not truth(f"imp({t},{f})")
    assert truth(f"neg(neg({t}))") and truth(f"imp({t},and({t},neg({f})))")


def test_all_and_any_including_empty():
    members = "member(m,good(action(y))). member(m,bad(action(y))). member(t,good(action(y)))."
    assert not truth("all(m)", members) and truth("any(m)", members)
    assert truth("all(t)", members) and truth("any(t)", members)
    assert truth("all(none)") and not truth("any(none)")
    assert not truth("neg(all(none))") and truth("neg(any(none))")


def test_geq_with_negative_facts():
    # u(c1) = u(a) + u(-b) = 4; u(c2) = u(-a) + u(b) = -4; u(c3) = u(-a) = -1
    conj = "conj(c1,a,true). conj(c1,b,false). conj(c2,a,false). conj(c2,b,true). conj(c3,a,false)."
    assert truth("geq(c1,c2)", conj) and not truth("geq(c2,c1)", conj)
    assert truth("geq(c3,c2)", conj) and truth("geq(c1,c1)", conj)
    # the empty conjunction is worth 0
    assert truth("geq(empty,c2)", conj) and not truth("geq(empty,c1)", conj)
    assert truth("geq(c1,empty)", conj)


def test_several_formulas_at_once_do_not_interfere():
    answer = only_answer(
        LANGUAGE, SMALL + "formula(f,bad(action(x))). formula(g,neg(bad(action(x))))."
    )
    assert {"verdict(f,true)", "verdict(g,false)"} <= answer


PRINCIPLES = [
    "planning/model.lp",
    "planning/trace.lp",
    "judgement/language.lp",
    "principles/deontology.lp",
    "principles/do_no_harm.lp",
    "principles/utilitarianism.lp",
]


def verdicts(model: str, plan: str, alternative: list[str]) -> set[str]:
    alt = "alternative(s). " + " ".join(
        f"conj(s,{lit.lstrip('-')},{'false' if lit.startswith('-') else 'true'})."
        for lit in alternative
    )
    answer = only_answer(PRINCIPLES, (MODELS / model).read_text() + plan + alt)
    return {atom for atom in answer if atom.startswith("verdict(")}


def test_principle_encodings_on_the_trolley_problem():
    best = ["-five_will_die", "one_will_die", "done"]
    assert verdicts("trolley.lp", "occurs(pull,1).", best) == {
        "verdict(deontology,true)",
        "verdict(do_no_harm,false)",
        "verdict(utilitarianism,true)",
    }
    assert verdicts("trolley.lp", "occurs(refrain,1).", best) == {
        "verdict(deontology,true)",
        "verdict(do_no_harm,true)",
        "verdict(utilitarianism,false)",
    }


def test_principle_encodings_on_the_footbridge_dilemma():
    best = ["-five_will_die", "heavy_man_will_die", "done"]
    assert verdicts("footbridge.lp", "occurs(push,1).", best) == {
        "verdict(deontology,false)",
        "verdict(do_no_harm,false)",
        "verdict(utilitarianism,true)",
    }
    assert verdicts("footbridge.lp", "occurs(refrain,1).", best) == {
        "verdict(deontology,true)",
        "verdict(do_no_harm,true)",
        "verdict(utilitarianism,false)",
    }


def test_utility_of_final_state():
    answer = only_answer(["planning/model.lp", "planning/trace.lp", "judgement/judge.lp"], SMALL)
    # final: a (4), -b (0), -c (0)
    assert "utility_of_final(4)" in answer
