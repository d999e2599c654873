"""Contrastive questions: the typed grammar and the constraint encoding."""

import pytest
from conftest import answer_sets

from ethasp import InputError
from ethasp.questions.question import Question

SETUP = [
    "planning/model.lp",
    "planning/relaxed.lp",
    "planning/transition.lp",
    "planning/goal.lp",
    "questions/questions.lp",
]

# a -> b -> c in any order; goal c.
CHAIN = """
variable(x;y;z). action(a;b;c;d).
eff(a,x,true). pre(b,x,true). eff(b,y,true). pre(c,y,true). eff(c,z,true). eff(d,x,true).
goal(z,true).
"""


@pytest.mark.parametrize(
    "text,kind,action,other",
    [
        ("why pull", "why", "pull", None),
        ("Why not pull?", "why-not", "pull", None),
        ("why refrain rather than pull", "rather-than", "refrain", "pull"),
        ("why  refrain  RATHER THAN  pull ?", "rather-than", "refrain", "pull"),
        ("why a1 before a2", "before", "a1", "a2"),
        ("why move(r1, r2) before take_key", "before", "move(r1, r2)", "take_key"),
        ("why (push man bridge)", "why", "(push man bridge)", None),
    ],
)
def test_grammar(text, kind, action, other):
    question = Question.parse(text)
    assert (question.kind, question.action, question.other) == (kind, action, other)
    assert Question.parse(str(question)) == question
    assert Question.from_json(question.to_json()) == question


@pytest.mark.parametrize(
    "text", ["", "why", "how pull", "pull", "why not", "why a before", "why rather than b"]
)
def test_malformed_questions(text):
    with pytest.raises(InputError, match="question"):
        Question.parse(text)


def test_bad_json_question():
    with pytest.raises(InputError):
        Question.from_json({"kind": "sometimes", "action": "a"})
    with pytest.raises(InputError):
        Question.from_json({"kind": "before", "action": "a"})


def plans(program: str, horizon: int) -> set[tuple[str, ...]]:
    time = f"time(0..{horizon}). step(1..{horizon}). horizon({horizon})."
    result = set()
    for answer in answer_sets(SETUP, CHAIN + program + time):
        steps = sorted(
            (a for a in answer if a.startswith("occurs(")),
            key=lambda a: int(a.rstrip(")").split(",")[-1]),
        )
        result.add(tuple(a[len("occurs(") : a.rindex(",")] for a in steps))
    return result


def test_constraints_only_when_active():
    free = plans("contrast(q,used(d)).", 3)
    assert free == {("a", "b", "c"), ("d", "b", "c")}
    assert plans("contrast(q,used(d)). active(q,used(d)).", 3) == {("d", "b", "c")}
    assert plans("contrast(q,used(c)). contrast(q,unused(c)). active(q,used(c)).", 3) == {
        ("a", "b", "c"),
        ("d", "b", "c"),
    }
    assert (
        plans(
            "contrast(q,used(c)). contrast(q,unused(c)). active(q,used(c)). active(q,unused(c)).", 4
        )
        == set()
    )


def test_unused_and_before():
    assert plans("contrast(q,unused(a)). active(q,unused(a)).", 3) == {("d", "b", "c")}
    # "why a before d": contrast a d, and no a before the first d.
    ordered = plans("contrast(q,before(d,a)). active(q,before(d,a)).", 4)
    assert ("d", "a", "b", "c") in ordered and ("a", "d", "b", "c") not in ordered
    assert ("d", "b", "c") in ordered  # no a at all
    assert all("d" in p and "a" not in p[: p.index("d")] for p in ordered)
    reverse = plans("contrast(q,before(a,d)). active(q,before(a,d)).", 4)
    assert ("a", "d", "b", "c") in reverse and ("d", "a", "b", "c") not in reverse
    assert all("a" in p and "d" not in p[: p.index("a")] for p in reverse)


def test_met_and_unknown_actions_on_a_given_plan():
    given = "occurs(a,1). occurs(b,2). occurs(c,3). time(0..3). step(1..3). horizon(3)."
    facts = (
        "contrast(q,used(a)). contrast(q,unused(d)). contrast(q,before(b,a)). "
        "contrast(q,before(a,c)). contrast(r,used(jump))."
    )
    answer = answer_sets(["planning/model.lp", "questions/questions.lp"], CHAIN + given + facts)[0]
    met = {a for a in answer if a.startswith("met(")}
    assert met == {"met(q,used(a),3)", "met(q,unused(d),3)", "met(q,before(a,c),3)"}
    assert "unknown_action(r,jump)" in answer
    assert not any(a.startswith("answered(") for a in answer)
    facts = "contrast(q,used(a)). contrast(q,unused(d)). contrast(r,used(d))."
    answer = answer_sets(["planning/model.lp", "questions/questions.lp"], CHAIN + given + facts)[0]
    assert {a for a in answer if a.startswith("answered(")} == {"answered(q,3)"}


# -- the whole question language ------------------------------------------------------


@pytest.mark.parametrize(
    "text,fields",
    [
        ("why a after b", {"kind": "after", "action": "a", "other": "b"}),
        ("why pull at 2", {"kind": "why", "action": "pull", "at": 2}),
        ("Why not pull AT 3?", {"kind": "why-not", "action": "pull", "at": 3}),
        ("why pull within 1..3", {"kind": "why", "action": "pull", "within": (1, 3)}),
        ("why not pull within 2 .. 4", {"kind": "why-not", "action": "pull", "within": (2, 4)}),
        ("why door_open", {"kind": "why", "action": "door_open"}),
        ("why not at(r4)", {"kind": "why-not", "action": "at(r4)"}),
        ("why (robot-at kitchen) at 2", {"kind": "why", "action": "(robot-at kitchen)", "at": 2}),
        ("why fact door at 2", {"kind": "why", "action": "door", "at": 2, "what": "fact"}),
        ("why not action door", {"kind": "why-not", "action": "door", "what": "action"}),
        ("why not in 3 steps", {"kind": "length", "steps": 3}),
        ("why not in 1 step?", {"kind": "length", "steps": 1}),
        ("why not in 0 steps", {"kind": "length", "steps": 0}),
        ("why at at 2", {"kind": "why", "action": "at", "at": 2}),
        ("why action", {"kind": "why", "action": "action"}),
    ],
)
def test_grammar_of_steps_outcomes_and_length(text, fields):
    question = Question.parse(text)
    expected = Question(**fields)
    assert question == expected
    assert Question.parse(str(question)) == question
    assert Question.from_json(question.to_json()) == question


@pytest.mark.parametrize(
    "text,message",
    [
        ("why a at", "missing step at the end"),
        ("why a at x", "expected a step number"),
        ("why a at 0", "must be from 1"),
        ("why a at 2 3", "one step number after 'at'"),
        ("why a at 99999999", "must be from 1 to 1,000,000"),
        ("why a within 3..1", "empty"),
        ("why a within 1-3", "window of steps T1..T2"),
        ("why not in x steps", "a number of steps"),
        ("why not a before b", "'why not' does not go with 'before'"),
        ("why fact a after b", "compares actions, not facts"),
        ("why fact x within 1..2", "applies to actions"),
        ("why after b", "missing action before 'after'"),
        ("why step 3", "causal explanation of a step"),
    ],
)
def test_malformed_questions_of_the_new_forms(text, message):
    with pytest.raises(InputError, match="question") as error:
        Question.parse(text)
    assert message in str(error.value)


def test_bad_json_questions_of_the_new_forms():
    for data in (
        {"kind": "length"},
        {"kind": "length", "steps": -1},
        {"kind": "why", "action": "a", "at": 0},
        {"kind": "why", "action": "a", "within": [3, 1]},
        {"kind": "why", "action": "a", "within": [1]},
        {"kind": "after", "action": "a"},
        {"kind": "why", "action": "a", "what": "thing"},
    ):
        with pytest.raises(InputError):
            Question.from_json(data)


def test_step_questions():
    from ethasp.questions.question import step_question

    assert step_question("why step 3") == 3 and step_question(" Why STEP 12 ? ") == 12
    assert step_question("why steal") is None and step_question("why step") is None
    with pytest.raises(InputError, match="step number"):
        step_question("why step x")


def active(*terms: str) -> str:
    return " ".join(f"contrast(q,{t}). active(q,{t})." for t in terms)


def test_action_at_steps_and_windows():
    assert plans(active("at(d,1)"), 3) == {("d", "b", "c")}
    assert plans(active("not_at(a,1)"), 3) == {("d", "b", "c")}
    within = plans(active("within(d,2,3)"), 4)
    assert within and all("d" in p[1:3] for p in within)
    assert ("d", "a", "b", "c") not in within
    outside = plans(active("not_within(a,1,2)", "not_within(d,1,2)"), 4)
    assert outside == set()  # x must be set at step 1 or 2 for c at 3 or 4
    assert plans(active("not_within(a,1,1)"), 3) == {("d", "b", "c")}


# A variable that goes back and forth, for questions about facts.
TOGGLE = """
variable(p;g;d). action(on;off;go). derived(d). axiom(d,1). axiom_pre(d,1,p,true).
pre(on,p,false). eff(on,p,true). pre(off,p,true). eff(off,p,false). eff(go,g,true).
goal(g,true).
"""
TOGGLE_SETUP = [
    "planning/model.lp",
    "planning/relaxed.lp",
    "planning/transition.lp",
    "planning/goal.lp",
    "questions/questions.lp",
]


def toggle_plans(program: str, horizon: int) -> set[tuple[str, ...]]:
    time = f"time(0..{horizon}). step(1..{horizon}). horizon({horizon})."
    result = set()
    for answer in answer_sets(TOGGLE_SETUP, TOGGLE + program + time):
        steps = sorted(
            (a for a in answer if a.startswith("occurs(")),
            key=lambda a: int(a.rstrip(")").split(",")[-1]),
        )
        result.add(tuple(a[len("occurs(") : a.rindex(",")] for a in steps))
    return result


def test_facts_at_the_end_and_after_a_step():
    assert toggle_plans(active("ends(p,true)"), 2) == {("on", "go"), ("go", "on")}
    assert toggle_plans(active("ends(d,true)"), 2) == {("on", "go"), ("go", "on")}
    after = toggle_plans(active("fact_at(p,true,1)"), 2)
    assert after == {("on", "go")}
    # After step 3 of a plan of fewer steps: its final state.
    short = toggle_plans(active("fact_at(p,true,3)"), 2)
    assert short == {("on", "go"), ("go", "on")}
    assert ("on", "off", "go") in toggle_plans(active("fact_at(p,false,2)", "used(on)"), 3)
    assert toggle_plans(active("at_most(0)"), 2) == set()
    assert toggle_plans(active("at_most(1)"), 2) == {("go",)}


def test_clock_is_tracked_up_to_the_largest_step_named():
    program = (
        TOGGLE + "contrast(q,at(go,5)). contrast(q,fact_at(p,true,2)). "
        "time(0..3). step(1..3). horizon(3)."
    )
    answer = answer_sets([*TOGGLE_SETUP, "planning/loopfree.lp"], program + "#show track/2.")[0]
    clocks = {a for a in answer if a.startswith("track(clock(")}
    assert clocks == {
        "track(clock(q,0),0)",
        "track(clock(q,1),1)",
        "track(clock(q,2),2)",
        "track(clock(q,3),3)",
    }


def test_given_plan_meets_facts_and_steps():
    files = [
        "planning/model.lp",
        "planning/trace.lp",
        "planning/trace_events.lp",
        "planning/steps.lp",
        "questions/given.lp",
        "questions/questions.lp",
    ]
    facts = (
        "occurs(on,1). occurs(go,2). contrast(q,ends(p,true)). contrast(q,ends(d,false)). "
        "contrast(q,fact_at(p,false,1)). contrast(q,fact_at(p,true,7)). "
        "contrast(q,at(go,2)). contrast(q,not_within(on,1,1)). contrast(q,at_most(2)). "
        "contrast(q,at_most(1)). contrast(r,ends(nothing,true))."
    )
    answer = answer_sets(files, TOGGLE + facts)[0]
    met = {a for a in answer if a.startswith("met(")}
    assert met == {
        "met(q,ends(p,true),2)",
        "met(q,fact_at(p,true,7),2)",
        "met(q,at(go,2),2)",
        "met(q,at_most(2),2)",
    }
    assert "unknown_variable(r,nothing)" in answer


def test_constraints_known_impossible_before_any_search():
    program = (
        TOGGLE + "contrast(q,ends(g,false)). contrast(q,used(jump)). action(jump). "
        "variable(never). pre(jump,never,true). contrast(q,ends(p,true)). "
        "contrast(q,fact_at(never,true,2)). time(0). horizon(0)."
    )
    files = ["planning/model.lp", "planning/relaxed.lp", "questions/questions.lp"]
    answer = answer_sets(
        files, program + "#show question_against_goal/2. #show question_unreachable/2."
    )[0]
    assert {a for a in answer if a.startswith("question_")} == {
        "question_against_goal(q,ends(g,false))",
        "question_unreachable(q,used(jump))",
        "question_unreachable(q,fact_at(never,true,2))",
    }
