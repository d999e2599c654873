"""Contrastive questions: the typed grammar and the constraint encoding."""

import pytest

from conftest import answer_sets
from ethasp import InputError
from ethasp.questions.question import Question

SETUP = ["planning/model.lp", "planning/relaxed.lp", "planning/transition.lp", "planning/goal.lp", "questions/questions.lp"]

# a -> b -> c in any order; goal c.
CHAIN = """
variable(x;y;z). action(a;b;c;d).
eff(a,x,true). pre(b,x,true). eff(b,y,true). pre(c,y,true). eff(c,z,true). eff(d,x,true).
goal(z,true).
"""


@pytest.mark.parametrize("text,kind,action,other", [
    ("why pull", "why", "pull", None),
    ("Why not pull?", "why-not", "pull", None),
    ("why refrain rather than pull", "rather-than", "refrain", "pull"),
    ("why  refrain  RATHER THAN  pull ?", "rather-than", "refrain", "pull"),
    ("why a1 before a2", "before", "a1", "a2"),
    ("why move(r1, r2) before take_key", "before", "move(r1, r2)", "take_key"),
    ("why (push man bridge)", "why", "(push man bridge)", None),
])
def test_grammar(text, kind, action, other):
    question = Question.parse(text)
    assert (question.kind, question.action, question.other) == (kind, action, other)
    assert Question.parse(str(question)) == question
    assert Question.from_json(question.to_json()) == question


@pytest.mark.parametrize("text", ["", "why", "how pull", "pull", "why not", "why a before",
                                  "why rather than b"])
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
        steps = sorted((a for a in answer if a.startswith("occurs(")),
                       key=lambda a: int(a.rstrip(")").split(",")[-1]))
        result.add(tuple(a[len("occurs("):a.rindex(",")] for a in steps))
    return result


def test_constraints_only_when_active():
    free = plans("contrast(q,used(d)).", 3)
    assert free == {("a", "b", "c"), ("d", "b", "c")}
    assert plans("contrast(q,used(d)). active(q,used(d)).", 3) == {("d", "b", "c")}
    assert plans("contrast(q,used(c)). contrast(q,unused(c)). active(q,used(c)).", 3) == {
        ("a", "b", "c"), ("d", "b", "c")}
    assert plans("contrast(q,used(c)). contrast(q,unused(c)). "
                 "active(q,used(c)). active(q,unused(c)).", 4) == set()


def test_unused_and_before():
    assert plans("contrast(q,unused(a)). active(q,unused(a)).", 3) == {("d", "b", "c")}
    # "why a before d": contrast d before a.
    ordered = plans("contrast(q,before(d,a)). active(q,before(d,a)).", 4)
    assert ("d", "a", "b", "c") in ordered and ("a", "d", "b", "c") not in ordered
    assert all(p.index("d") < len(p) - 1 - p[::-1].index("a") for p in ordered)
    reverse = plans("contrast(q,before(a,d)). active(q,before(a,d)).", 4)
    assert reverse and all(p.index("a") < len(p) - 1 - p[::-1].index("d") for p in reverse)


def test_met_and_unknown_actions_on_a_given_plan():
    given = "occurs(a,1). occurs(b,2). occurs(c,3). time(0..3). step(1..3). horizon(3)."
    facts = ("contrast(q,used(a)). contrast(q,unused(d)). contrast(q,before(b,a)). "
             "contrast(q,before(a,c)). contrast(r,used(jump)).")
    answer = answer_sets(["planning/model.lp", "questions/questions.lp"], CHAIN + given + facts)[0]
    met = {a for a in answer if a.startswith("met(")}
    assert met == {"met(q,used(a),3)", "met(q,unused(d),3)", "met(q,before(a,c),3)"}
    assert "unknown_action(r,jump)" in answer
    assert not any(a.startswith("answered(") for a in answer)
    facts = "contrast(q,used(a)). contrast(q,unused(d)). contrast(r,used(d))."
    answer = answer_sets(["planning/model.lp", "questions/questions.lp"], CHAIN + given + facts)[0]
    assert {a for a in answer if a.startswith("answered(")} == {"answered(q,3)"}
