"""Reasons and explanations: the paper's examples through the encodings, the
Python API, the words, and the command line."""

import json
import subprocess
import sys

import clingo
import pytest
from conftest import ENCODINGS, MODELS, ROOT, answer_sets
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from ethasp import Model, Plan
from ethasp.reasons.reasons import explain
from ethasp.reasons.words import option_sentence, principle_phrase, reason_clause

TROLLEY = MODELS / "trolley.lp"
BASE = ["planning/model.lp", "planning/trace.lp", "judgement/language.lp"]
CORE = ["reasons/literals.lp", "reasons/theory.lp", "reasons/evaluate.lp"]
ENUMERATE = ("0", "--heuristic=Domain", "--enum-mode=domRec")

# The paper's example: a1 is good, a2 and a3 are bad.
ABC = """
variable(done). action(a1;a2;a3). eff(a3,done,true). goal(done,true).
utility(a1,1). utility(a2,-1). utility(a3,-1).
occurs(a1,1). occurs(a2,2). occurs(a3,3).
"""


def optimal_answers(files, program: str) -> list[set[str]]:
    """The optimal answer sets (all of them) of encodings plus a program."""
    ctl = clingo.Control(
        ["0", "--opt-mode=optN", "--opt-strategy=usc"], logger=lambda code, message: None
    )
    for name in files:
        ctl.load(str(ENCODINGS / name))
    ctl.add("base", [], program)
    ctl.ground([("base", [])])
    found: list[set[str]] = []

    def keep(model: clingo.Model) -> None:
        if model.optimality_proven:
            found.append({str(s) for s in model.symbols(shown=True)})

    ctl.solve(on_model=keep)
    return found


def reason_sets(principle: str, kind: list[str], program: str, arguments=ENUMERATE):
    files = [*BASE, f"principles/{principle}.lp", *CORE, *kind]
    program += f"\nexplain({principle})."
    answers = (
        optimal_answers(files, program)
        if arguments == OPTIMAL
        else answer_sets(files, program, arguments)
    )
    return {frozenset(a for a in answer if a.startswith("reason(")) for answer in answers}


SUFFICIENT = ["reasons/shape.lp", "reasons/sufficient.lp"]
NECESSARY = ["reasons/necessary.lp"]
RELEVANT = ["reasons/necessary.lp", "reasons/relevance.lp"]
OPTIMAL = "optimal"


def trolley(plan: str) -> str:
    return TROLLEY.read_text() + f"\noccurs({plan},1)."


# -- encodings ---------------------------------------------------------------------


def test_paper_example_deontology():
    assert reason_sets("deontology", SUFFICIENT, ABC) == {
        frozenset({"reason(bad(action(a2)),true)"}),
        frozenset({"reason(bad(action(a3)),true)"}),
    }
    assert reason_sets("deontology", NECESSARY, ABC) == {
        frozenset({"reason(bad(action(a2)),true)", "reason(bad(action(a3)),true)"})
    }


def test_trolley_do_no_harm_refrain_uses_not_caused_five_will_die():
    necessary = reason_sets("do_no_harm", NECESSARY, trolley("refrain"))
    assert frozenset({"reason(caused(five_will_die,true),false)"}) in necessary
    # the optimal (most relevant) necessary reasons under the relevance rule
    optimal = reason_sets("do_no_harm", RELEVANT, trolley("refrain"), OPTIMAL)
    assert optimal == {frozenset({"reason(caused(five_will_die,true),false)"})}


def test_trolley_do_no_harm_pull_is_caused_one_will_die():
    assert reason_sets("do_no_harm", SUFFICIENT, trolley("pull")) == {
        frozenset(
            {"reason(caused(one_will_die,true),true)", "reason(bad(fact(one_will_die,true)),true)"}
        )
    }
    assert reason_sets("do_no_harm", NECESSARY, trolley("pull")) == {
        frozenset({"reason(caused(one_will_die,true),true)"}),
        frozenset({"reason(bad(fact(one_will_die,true)),true)"}),
    }
    optimal = reason_sets("do_no_harm", RELEVANT, trolley("pull"), OPTIMAL)
    assert optimal == {frozenset({"reason(caused(one_will_die,true),true)"})}


def test_trolley_utilitarianism_pull_compares_with_refrain():
    alternative = (
        "alternative(s). conj(s,five_will_die,true). conj(s,one_will_die,false). conj(s,done,true)."
    )
    reasons = reason_sets("utilitarianism", NECESSARY, trolley("pull") + alternative)
    assert reasons == {frozenset({"reason(geq(final,s),true)"})}
    answers = answer_sets(
        [*BASE, "principles/utilitarianism.lp", *CORE, "reasons/comparison.lp"],
        trolley("pull") + alternative + "explain(utilitarianism).",
    )
    assert {
        "mention(geq(final,s),left,five_will_die,false)",
        "mention(geq(final,s),right,one_will_die,false)",
        "comparison(geq(final,s),better)",
    } <= answers[0]


def test_the_facts_a_comparison_names_compare_as_its_sides_do():
    """Gains first would name only ``arrived`` (+1 against 0) where the harm
    ``blocked`` (-2) makes the final state worse: every valued differing fact
    is named then, and their sums compare as the sides do."""
    model = """
        variable(arrived;blocked). action(drive). eff(drive,arrived,true).
        eff(drive,blocked,true). goal(arrived,true).
        utility(arrived,true,1). utility(blocked,true,-2). occurs(drive,1).
        alternative(s). conj(s,arrived,false). conj(s,blocked,false).
        explain(utilitarianism).
    """
    answers = answer_sets(
        [*BASE, "principles/utilitarianism.lp", *CORE, "reasons/comparison.lp"], model
    )
    mentioned = {atom for atom in answers[0] if atom.startswith("mention(")}
    assert mentioned == {
        "mention(geq(final,s),left,arrived,true)",
        "mention(geq(final,s),left,blocked,true)",
        "mention(geq(final,s),right,arrived,false)",
        "mention(geq(final,s),right,blocked,false)",
    }
    assert "comparison(geq(final,s),worse)" in answers[0]


def test_theory_rules_out_impossible_literal_sets():
    # Caused(v) and Caused(-v) cannot both hold: not Caused(v) or not Caused(-v) is
    # entailed by nothing, so its only sufficient reason is empty.
    program = (
        "formula(q,or(neg(caused(v,true)),neg(caused(v,false)))). explain(q). verdict(q,true)."
    )
    assert {frozenset(r) for r in reason_sets_raw(program, SUFFICIENT)} == {frozenset()}
    assert reason_sets_raw(program, NECESSARY) == []
    # at least one of Good, Bad, Neutral when all three occur
    program = (
        "formula(q,any(i)). member(i,good(action(a))). member(i,bad(action(a))). "
        "member(i,neutral(action(a))). explain(q). verdict(q,true). "
        "satisfied(bad(action(a)))."
    )
    assert {frozenset(r) for r in reason_sets_raw(program, SUFFICIENT)} == {frozenset()}


def reason_sets_raw(program: str, kind: list[str]):
    return [
        {a for a in answer if a.startswith("reason(")}
        for answer in answer_sets(CORE + kind, program, ENUMERATE)
    ]


def test_other_state_prefers_goal_states_on_ties():
    program = (
        "time(0..1). step(1). horizon(1). other_state(s). "
        "other_than(s,five_will_die,false). other_than(s,one_will_die,true). "
        "other_than(s,done,true)."
    )
    answers = optimal_answers(
        [
            "planning/model.lp",
            "planning/relaxed.lp",
            "planning/transition.lp",
            "judgement/best.lp",
            "judgement/state.lp",
            "reasons/other_state.lp",
            TROLLEY,
        ],
        program,
    )
    assert answers and all(
        "at_horizon(done,true,1)" in a and "occurs(refrain,1)" in a for a in answers
    )


# -- API and words -------------------------------------------------------------------

PAPER_TEXTS = {
    ("deontology", "pull"): "The man can pull the lever. Doing so is permissible because "
    "pulling a lever is not inherently bad.",
    ("utilitarianism", "pull"): "The man can pull the lever. Doing so is permissible because "
    "five saved lives is better than one saved life.",
    ("do-no-harm", "pull"): "The man can pull the lever. Doing so is impermissible because "
    "this way the death of the one person is caused by the man's action.",
    ("do-no-harm", "refrain"): "The man can refrain from action. Doing so is permissible "
    "because this way the death of the five persons is not caused "
    "by the man's action.",
    ("utilitarianism", "refrain"): "The man can refrain from action. Doing so is impermissible "
    "because one saved life is worse than five saved lives.",
}


@pytest.fixture(scope="module")
def trolley_model():
    return Model.load([TROLLEY])


@pytest.mark.parametrize("case", sorted(PAPER_TEXTS))
def test_user_study_texts(trolley_model, case):
    principle, plan = case
    assert explain(trolley_model, Plan.parse(plan), principle).text == PAPER_TEXTS[case]


def test_api_reasons_of_the_trolley(trolley_model):
    pull = explain(trolley_model, Plan.parse("pull"), "do-no-harm")
    assert not pull.permissible and not pull.truncated
    assert pull.sufficient_reasons == [["Bad(one_will_die)", "Caused(one_will_die)"]]
    assert sorted(pull.necessary_reasons) == [["Bad(one_will_die)"], ["Caused(one_will_die)"]]
    assert pull.chosen_reason == ["Caused(one_will_die)"]
    refrain = explain(trolley_model, Plan.parse("refrain"), "do-no-harm")
    assert refrain.chosen_reason == ["not Caused(five_will_die)"]
    assert ["not Caused(five_will_die)"] in refrain.necessary_reasons
    useful = explain(trolley_model, Plan.parse("pull"), "utilitarianism")
    assert useful.chosen_reason == [
        "GEq(done & -five_will_die & one_will_die, done & five_will_die & -one_will_die)"
    ]
    assert useful.alternative == ["-one_will_die", "done", "five_will_die"]


def test_building_blocks_for_contrastive_texts(trolley_model):
    refrain = explain(trolley_model, Plan.parse("refrain"), "do-no-harm")
    assert (
        option_sentence(refrain.labels, refrain.plan, "could")
        == "The man could refrain from action."
    )
    assert (
        reason_clause(refrain.literals, refrain.labels, refrain.comparisons, pronoun=True)
        == "this way the death of the five persons is not caused by his action"
    )
    assert principle_phrase(refrain.principle) == "the do-no-harm principle"


def test_paper_example_through_the_api():
    model = Model.from_string(ABC.replace("occurs(a1,1). occurs(a2,2). occurs(a3,3).", ""))
    result = explain(model, Plan.parse("a1 a2 a3"), "deontology")
    assert sorted(result.sufficient_reasons) == [["Bad(a2)"], ["Bad(a3)"]]
    assert result.necessary_reasons == [["Bad(a2)", "Bad(a3)"]]
    # without labels the words come from the terms; literals of one kind share a clause
    assert result.text == (
        "The agent can a1, then a2, then a3. Doing so is impermissible "
        "because action a2 and action a3 are inherently bad."
    )


def test_limit_truncates_lazily():
    # 12 caused bad facts: 2^12 necessary reasons, 12 sufficient ones
    text = (
        "\n".join(
            f"variable(x({i})). action(a({i})). eff(a({i}),x({i}),true). utility(x({i}),true,-1)."
            for i in range(12)
        )
        + "\ngoal(x(0),true)."
    )
    plan = Plan.parse(" ".join(f"a({i})" for i in range(12)))
    result = explain(Model.from_string(text), plan, "do-no-harm", limit=3)
    assert result.truncated
    assert len(result.sufficient_reasons) == 3 and len(result.necessary_reasons) == 3
    assert all(len(reason) == 12 for reason in result.necessary_reasons)
    assert len(result.chosen_reason) == 12
    assert all(literal.startswith("Caused(") for literal in result.chosen_reason)


def test_empty_plan_is_permissible_in_any_case():
    model = Model.from_string("variable(v). action(a). eff(a,v,true). goal(v,false).")
    result = explain(model, Plan.parse(""), "deontology")
    assert result.permissible and result.sufficient_reasons == [[]]
    assert result.necessary_reasons == [] and result.chosen_reason == []
    assert result.text == "The agent can do nothing. Doing so is permissible in any case."


def test_bad_input(trolley_model):
    from ethasp import InputError

    with pytest.raises(InputError, match="not a plan"):
        explain(trolley_model, Plan.parse(""), "do-no-harm")
    with pytest.raises(InputError, match="unknown action jump"):
        explain(trolley_model, Plan.parse("jump"), "deontology")
    with pytest.raises(InputError, match="not a plan"):
        explain(trolley_model, Plan.parse(""), "utilitarianism")
    with pytest.raises(InputError, match="unknown principle"):
        explain(trolley_model, Plan.parse("pull"), "kant")
    with pytest.raises(InputError, match="at least 1"):
        explain(trolley_model, Plan.parse("pull"), "deontology", limit=0)


# -- command line -------------------------------------------------------------------


def ethasp_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )


def test_cli_judge_json_has_reasons_and_explanation():
    run = ethasp_cli("judge", str(TROLLEY), "--plan", "pull", "--json")
    assert run.returncode == 0, run.stderr
    judgements = {j["principle"]: j for j in json.loads(run.stdout)["judgements"]}
    harm = judgements["do-no-harm"]
    assert harm["sufficient_reasons"] == [["Bad(one_will_die)", "Caused(one_will_die)"]]
    assert sorted(harm["necessary_reasons"]) == [["Bad(one_will_die)"], ["Caused(one_will_die)"]]
    assert harm["explanation"] == PAPER_TEXTS[("do-no-harm", "pull")]
    assert judgements["deontology"]["explanation"] == PAPER_TEXTS[("deontology", "pull")]
    assert judgements["utilitarianism"]["explanation"] == PAPER_TEXTS[("utilitarianism", "pull")]


def test_cli_judge_text_shows_the_explanation_first_and_limits():
    run = ethasp_cli(
        "judge", "trolley", "--plan", "refrain", "--principle", "do-no-harm", "--reasons-limit", "1"
    )
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert lines[0] == "do-no-harm: " + PAPER_TEXTS[("do-no-harm", "refrain")]
    assert "limit reached" in lines[1]
    run = ethasp_cli("judge", "trolley", "--plan", "refrain", "--reasons-limit", "0", "--json")
    assert "explanation" not in json.loads(run.stdout)["judgements"][0]


def test_cli_bad_reasons_limit():
    run = ethasp_cli("judge", "trolley", "--plan", "pull", "--reasons-limit", "-2")
    assert run.returncode == 2 and run.stderr.count("\n") == 1
    assert "Traceback" not in run.stderr


def test_comparison_words_fall_back_to_counterparts():
    model = Model.load([MODELS / "heist.lp"])
    result = explain(model, Plan.parse("scout steal give_jewels"), "utilitarianism")
    assert result.text.endswith(
        "impermissible because the owner's loss of the jewels is "
        "worse than the owner keeping the jewels."
    )


def test_utilitarian_explanations_compare_with_a_state_that_differs_in_what_matters():
    from ethasp.principles.restriction import plan_with_principles

    model = Model.load([MODELS / "rescue.lp"])
    hplan = plan_with_principles(model, ["utilitarianism"])
    why = explain(model, hplan.plan, "utilitarianism")
    # Another best state differs only in where the robot stands (worth nothing):
    # the explanation compares with a state that differs in a valued fact.
    assert why.permissible and why.text.endswith(
        "is permissible because the intact door is better than the broken door."
    )


# -- "truncated": only when a reason beyond the limit exists ----------------------------


@pytest.mark.parametrize(
    "principle, limit, truncated",
    [
        ("deontology", 1, False),  # exactly one sufficient and one necessary reason
        ("do-no-harm", 2, False),  # exactly two necessary reasons
        ("do-no-harm", 1, True),
    ],
)
def test_reasons_are_truncated_only_when_more_exist(principle, limit, truncated):
    model = Model.load([TROLLEY])
    result = explain(model, Plan.parse("pull"), principle, limit=limit)
    assert result.truncated is truncated
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "ethasp.interfaces.cli",
            "judge",
            str(TROLLEY),
            "--plan",
            "pull",
            "--principle",
            principle,
            "--reasons-limit",
            str(limit),
            "--json",
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert json.loads(run.stdout)["judgements"][0]["reasons_truncated"] is truncated
    text = subprocess.run(
        [
            sys.executable,
            "-m",
            "ethasp.interfaces.cli",
            "judge",
            str(TROLLEY),
            "--plan",
            "pull",
            "--principle",
            principle,
            "--reasons-limit",
            str(limit),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    ).stdout
    assert ("limit reached" in text) is truncated
    if principle == "do-no-harm" and limit == 1:
        # two necessary reasons, one sufficient, two INUS reasons (the
        # necessary ones): the first and the last kinds are cut
        assert result.necessary_truncated and not result.sufficient_truncated
        assert result.inus_truncated
        assert text.count("(limit reached; more may exist)") == 2


# (About half the drawn models have no plan; 20 of the others.)
@settings(max_examples=20, deadline=None)
@given(
    st.integers(min_value=0, max_value=10**9),
    st.sampled_from(["deontology", "do-no-harm", "utilitarianism"]),
)
def test_truncated_says_whether_a_reason_beyond_the_limit_exists(seed, principle):
    """With the limit at the number of reasons of each kind, nothing is
    truncated; one less, and something is."""
    import random

    from oracle import features, plan_through, random_model

    spec = random_model(seed, **features(seed))
    plan = plan_through(spec, random.Random(seed), seed % 4)
    assume(plan is not None)
    model = Model.from_string(spec.to_asp())
    whole = explain(model, Plan.parse(" ".join(plan)), principle, limit=1000)
    assert not whole.truncated
    most = max(len(whole.sufficient_reasons), len(whole.necessary_reasons))
    assert not explain(model, Plan.parse(" ".join(plan)), principle, limit=most).truncated
    if most > 1:
        assert explain(model, Plan.parse(" ".join(plan)), principle, limit=most - 1).truncated


# -- the INUS program's ground size ------------------------------------------------

INUS_FILES = [*CORE, "reasons/shape.lp", "reasons/evaluate_copies.lp", "reasons/inus.lp"]


def inus_ground(program: str) -> tuple[list[str], set[frozenset]]:
    """The copies that the INUS program grounds (copy/1 atoms) and its INUS
    reasons, for a formula given as facts."""
    ctl = clingo.Control(["0", "--project=show"], logger=lambda code, message: None)
    for name in INUS_FILES:
        ctl.load(str(ENCODINGS / name))
    ctl.add("base", [], program)
    ctl.ground([("base", [])])
    copies = sorted(
        str(atom.symbol.arguments[0]) for atom in ctl.symbolic_atoms.by_signature("copy", 1)
    )
    found: set[frozenset] = set()
    ctl.solve(on_model=lambda model: found.add(frozenset(map(str, model.symbols(shown=True)))))
    return copies, found


def test_inus_reasons_of_a_read_once_formula_ground_one_witness_copy():
    # Deontology over 30 actions, none bad: the one sufficient reason has
    # all 30 literals, and each is an INUS reason of its own.  A read-once
    # formula needs one witness (G alone), not one per candidate literal,
    # whose copies of the formula made long plans' reasons quadratic.
    n = 30
    lines = ["formula(q,all(q)).", "explain(q).", "verdict(q,true)."]
    lines += [f"member(q,neg(bad(action(a{i}))))." for i in range(n)]
    lines += [f"sufficient_member(1,bad(action(a{i})))." for i in range(n)]
    copies, found = inus_ground("\n".join(lines))
    assert copies == ["g"]
    assert found == {frozenset({f"reason(bad(action(a{i})),false)"}) for i in range(n)}


def test_inus_reasons_of_a_formula_with_a_theory_link_ground_a_witness_per_candidate():
    # Good(a) and Bad(a) cannot both hold: not read-once, so each candidate
    # literal gets a witness of its own (and the saturation checks
    # entailment).  Good(a) | Bad(a) | Good(b) with a and b good has the
    # sufficient reasons {Good(a)} and {Good(b)} and the necessary reason
    # {Good(a), Good(b)}, within neither: no INUS reason.
    lines = [
        "formula(q,or(good(action(a)),or(bad(action(a)),good(action(b))))).",
        "explain(q).",
        "verdict(q,true).",
        "satisfied(good(action(a))).",
        "satisfied(good(action(b))).",
        "sufficient_member(1,good(action(a))).",
        "sufficient_member(2,good(action(b))).",
    ]
    copies, found = inus_ground("\n".join(lines))
    assert copies == ["w(good(action(a)))", "w(good(action(b)))"]
    assert found == set()
    # Without Good(b) the one sufficient reason {Good(a)} is also necessary.
    lines = ["formula(q,or(good(action(a)),bad(action(a))))."]
    lines += ["explain(q).", "verdict(q,true).", "satisfied(good(action(a)))."]
    lines.append("sufficient_member(1,good(action(a))).")
    copies, found = inus_ground("\n".join(lines))
    assert copies == ["w(good(action(a)))"]
    assert found == {frozenset({"reason(good(action(a)),true)"})}
