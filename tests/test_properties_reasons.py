"""Property tests: reasons from clingo against brute-force prime implicants.

Random formulas of L over a few atoms, a random actual situation respecting
the background theory; the encodings must find exactly the sufficient
reasons (prime implicants of the actual value that hold) and the necessary
reasons (their minimal hitting sets) and the INUS reasons (HERA's necessary
reasons within a sufficient reason) of tests/reasons_oracle.py, and the
relevance optimum must be a necessary reason of least cost.
"""

from conftest import answer_sets
from hypothesis import given, settings
from hypothesis import strategies as st
from reasons_oracle import (
    assignments,
    atoms_of,
    evaluate,
    inus_reasons,
    necessary_reasons,
    sufficient_reasons,
    to_asp,
)

CORE = ["reasons/literals.lp", "reasons/theory.lp", "reasons/evaluate.lp"]
ENUMERATE = ("0", "--heuristic=Domain", "--enum-mode=domRec")

POOL = [
    "good(action(a))",
    "bad(action(a))",
    "neutral(action(a))",
    "caused(v,true)",
    "caused(v,false)",
    "caused(w,true)",
    "bad(fact(w,true))",
    "geq(c,d)",
    "geq(d,c)",
    "geq(c,c)",
    "geq(d,e)",
    "geq(c,e)",
]
# The atoms of causal agency models, with their own links of the theory.
CAM_POOL = [
    "intended(v,true)",
    "intended(v,false)",
    "causes(fact(v,true),fact(w,true))",
    "causes(fact(w,true),fact(v,true))",
    "causes(fact(v,true),fact(w,false))",
    "causes(fact(v,true),fact(v,false))",
    "ucompare(gt,num(0),u(c))",
    "ucompare(gt,u(c),num(0))",
    "ucompare(geq,u(c),u(c))",
]


def formulas_of(pool: list[str]):
    return st.recursive(
        st.sampled_from(pool),
        lambda children: st.one_of(
            st.tuples(st.just("neg"), children),
            st.tuples(st.sampled_from(["and", "or", "imp"]), children, children),
            st.tuples(st.sampled_from(["all", "any"]), st.lists(children, max_size=3)),
        ),
        max_leaves=6,
    )


formulas = formulas_of(POOL + CAM_POOL)
plan_formulas = formulas_of(POOL)


def situation(formula, pick: int) -> dict[str, bool]:
    """An actual situation: one of the assignments that respect the theory."""
    models = assignments(atoms_of(formula))
    return models[pick % len(models)]


def program(formula, actual: dict[str, bool]) -> str:
    lines = [to_asp(formula), "explain(q)."]
    lines += [f"satisfied({atom})." for atom, value in actual.items() if value]
    lines.append(f"verdict(q,{'true' if evaluate(formula, actual) else 'false'}).")
    return "\n".join(lines)


def reasons(files, text: str, arguments=ENUMERATE) -> set[frozenset]:
    found = set()
    for answer in answer_sets(CORE + files, text, arguments):
        literals = set()
        for atom in answer:
            if atom.startswith("reason("):
                inner = atom[len("reason(") : -1]
                term, value = inner.rsplit(",", 1)
                literals.add((term, value == "true"))
        found.add(frozenset(literals))
    return found


def interesting(formula) -> bool:
    return len(atoms_of(formula)) <= 6


@settings(max_examples=120, deadline=None)
@given(formulas.filter(interesting), st.integers(0, 10**6))
def test_sufficient_reasons_are_the_prime_implicants_that_hold(formula, pick):
    actual = situation(formula, pick)
    expected = sufficient_reasons(formula, actual)
    assert (
        reasons(["reasons/shape.lp", "reasons/sufficient.lp"], program(formula, actual)) == expected
    )


@settings(max_examples=120, deadline=None)
@given(formulas.filter(interesting), st.integers(0, 10**6))
def test_necessary_reasons_are_the_minimal_hitting_sets(formula, pick):
    actual = situation(formula, pick)
    expected = necessary_reasons(formula, actual)
    assert reasons(["reasons/necessary.lp"], program(formula, actual)) == expected


@settings(max_examples=120, deadline=None)
@given(formulas.filter(interesting), st.integers(0, 10**6))
def test_inus_reasons_are_herAs_necessary_reasons_within_a_sufficient_one(formula, pick):
    actual = situation(formula, pick)
    sufficient = sufficient_reasons(formula, actual)
    members = [
        f"sufficient_member({number},{atom})."
        for number, reason in enumerate(sorted(sufficient, key=sorted), 1)
        for atom, _ in reason
    ]
    text = program(formula, actual) + "\n" + "\n".join(members)
    files = ["reasons/shape.lp", "reasons/evaluate_copies.lp", "reasons/inus.lp"]
    found = reasons(files, text, ("0", "--project=show")) if members else set()
    assert found == inus_reasons(formula, actual)


WEIGHTS = {
    "action(a)": st.integers(-2, 2),
    "fact(v,true)": st.integers(-2, 2),
    "fact(v,false)": st.integers(-2, 2),
    "fact(w,true)": st.integers(-2, 2),
}


def cost(reason: frozenset, weight: dict[str, int], worth: dict[str, int]) -> tuple:
    """The relevance criteria of relevance.lp, as a tuple to minimise."""

    def about(atom: str) -> int:
        if atom.startswith("geq("):
            c, d = atom[4:-1].split(",")
            return abs(worth[c] - worth[d])
        if atom.startswith("caused("):
            variable, value = atom[7:-1].rsplit(",", 1)
            return abs(weight[f"fact({variable},{value})"])
        return abs(weight[atom[atom.index("(") + 1 : -1]])

    magnitudes = [about(atom) for atom, _ in reason]
    valuations = sum(1 for atom, _ in reason if atom.split("(")[0] in ("good", "bad", "neutral"))
    return (sum(1 for m in magnitudes if m == 0), len(reason), valuations, -sum(magnitudes))


@settings(max_examples=80, deadline=None)
@given(
    plan_formulas.filter(interesting),
    st.integers(0, 10**6),
    st.fixed_dictionaries(WEIGHTS),
    st.lists(st.integers(-3, 3), min_size=3, max_size=3),
)
def test_relevance_picks_a_necessary_reason_of_least_cost(formula, pick, weight, worths):
    actual = situation(formula, pick)
    expected = necessary_reasons(formula, actual)
    worth = dict(zip("cde", worths, strict=True))
    text = (
        program(formula, actual)
        + "\n"
        + "\n".join(
            [f"weight({e},{u})." for e, u in weight.items()]
            + [f"conj_worth({c},{w})." for c, w in worth.items()]
        )
    )
    found = answer_sets(
        [*CORE, "reasons/necessary.lp", "reasons/relevance.lp"],
        text,
        ("0", "--opt-mode=opt", "--opt-strategy=usc"),
    )
    if not expected:
        assert found == []
    else:
        _check_least_cost(formula, expected, text, weight, worth)


def _check_least_cost(formula, expected, text, weight, worth) -> None:
    chosen = reasons(
        ["reasons/necessary.lp", "reasons/relevance.lp"],
        text,
        ("0", "--opt-mode=opt", "--opt-strategy=usc"),
    )
    best = min(cost(r, weight, worth) for r in expected)
    # every model printed is an improvement; the last is optimal
    last = frozenset(sorted(chosen, key=lambda r: cost(r, weight, worth))[0])
    assert last in expected and cost(last, weight, worth) == best
