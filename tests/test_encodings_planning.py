"""Encoding-level tests of the planning core: clingo on small programs."""

from conftest import MODELS, answer_sets, only_answer

TRACE = ["planning/model.lp", "planning/trace.lp"]
CHECK = ["planning/model.lp", "planning/check.lp"]

SMALL = """
variable(a;b;c). action(x;y;z).
pre(x,a,false). eff(x,a,true).
pre(y,a,true). eff(y,b,true). eff(y,a,false).
pre(z,b,true). pre(z,c,false). eff(z,c,true).
goal(c,true).
"""


def plans(horizon: int, model: str) -> set[tuple[str, ...]]:
    result = set()
    for answer in answer_sets(
        ["planning/plan.lp"], model, arguments=("0", "-c", f"horizon={horizon}")
    ):
        steps = sorted(
            (int(a.split(",")[-1].rstrip(")")), a[len("occurs(") : a.rindex(",")])
            for a in answer
            if a.startswith("occurs(")
        )
        result.add(tuple(name for _, name in steps))
    return result


def test_fixed_horizon_trolley_from_command_line_encoding():
    trolley = (MODELS / "trolley.lp").read_text()
    assert plans(1, trolley) == {("pull",), ("refrain",)}
    assert plans(0, trolley) == set()


def test_fixed_horizon_finds_exactly_the_plans_up_to_the_horizon():
    assert plans(2, SMALL) == set()
    assert plans(3, SMALL) == {("x", "y", "z")}
    four = plans(4, SMALL)
    assert ("x", "y", "z") in four and all(len(p) in (3, 4) for p in four)
    assert ("x", "y", "x", "z") in four


def test_relaxed_reachability_proves_unreachable_goal():
    model = "variable(a;b). action(x). pre(x,a,true). eff(x,b,true). goal(b,true)."
    assert "unreachable_goal" in only_answer(["planning/model.lp", "planning/relaxed.lp"], model)
    model = "variable(a;b). init(a). action(x). pre(x,a,true). eff(x,b,true). goal(b,true)."
    assert "unreachable_goal" not in only_answer(
        ["planning/model.lp", "planning/relaxed.lp"], model
    )
    contradictory = "variable(a). action(x). eff(x,a,true). goal(a,true). goal(a,false)."
    assert "unreachable_goal" in only_answer(
        ["planning/model.lp", "planning/relaxed.lp"], contradictory
    )


def test_trace_of_a_valid_plan():
    answer = only_answer(TRACE, SMALL + "occurs(x,1). occurs(y,2). occurs(z,3).")
    assert "plan" in answer
    assert {"final(a,false)", "final(b,true)", "final(c,true)"} <= answer


def test_trace_reports_first_failing_step_and_precondition():
    answer = only_answer(TRACE, SMALL + "occurs(y,1). occurs(z,2).")
    assert "failure(1)" in answer
    assert "unmet(1,y,a,true)" in answer
    assert [a for a in answer if a.startswith("unmet(")] == ["unmet(1,y,a,true)"]
    assert "plan" not in answer


def test_trace_reports_unmet_goal():
    answer = only_answer(TRACE, SMALL + "occurs(x,1).")
    assert "unmet_goal(c,true)" in answer and "plan" not in answer
    assert not any(a.startswith("failure") for a in answer)


def test_trace_precondition_sees_value_set_long_before():
    steps = "occurs(x,1). " + " ".join(f"occurs(w,{t})." for t in range(2, 40)) + " occurs(y,40)."
    model = SMALL + "action(w). variable(d). eff(w,d,true)."
    answer = only_answer(TRACE, model + steps)
    assert not any(a.startswith("unmet(") for a in answer)


def test_trace_malformed_sequences():
    answer = only_answer(TRACE, SMALL + "occurs(q,1). occurs(x,3).")
    assert "invalid(unknown_action(q,1))" in answer
    assert "invalid(missing_step(2))" in answer
    answer = only_answer(TRACE, SMALL + "occurs(x,1). occurs(y,1).")
    assert "invalid(two_actions(1))" in answer


def test_empty_sequence_is_a_plan_when_goal_holds_initially():
    answer = only_answer(TRACE, "variable(a). init(a). goal(a,true).")
    assert "plan" in answer and "final(a,true)" in answer


def test_check_reports_each_defect():
    model = """
    variable(x). action(a). goal(x,true).
    eff(a,y,true). pre(b,x,true). utility(c,1). utility(a,big).
    eff(a,x,true). eff(a,x,false). utility(x,maybe,1). utility(x,true,1). utility(x,true,2).
    """
    answer = only_answer(CHECK, model)
    assert answer == {
        "error(undeclared_variable(y,eff(a,y,true)))",
        "error(undeclared_action(b,pre(b,x,true)))",
        "error(undeclared_action(c,utility(c,1)))",
        "error(not_integer(utility(a,big)))",
        "error(contradicting_effects(a,x))",
        "error(bad_value(utility(x,maybe,1)))",
        "error(ambiguous_utility(utility(x,true,1)))",
    }
    # A model without a goal has the empty goal; a model without variables and
    # actions is empty.
    assert only_answer(CHECK, "variable(x).") == set()
    assert "error(empty)" in only_answer(CHECK, "#defined variable/1.")
    assert only_answer(CHECK, (MODELS / "trolley.lp").read_text()) == set()


def test_weights_default_to_zero():
    answer = answer_sets(
        ["planning/model.lp"], "variable(x). action(a). utility(x,true,3). #show weight/2."
    )[0]
    assert answer == {"weight(action(a),0)", "weight(fact(x,true),3)", "weight(fact(x,false),0)"}


def test_encodings_without_markers_are_added_whole_as_their_split_would():
    """The planner adds an encoding that no marker can be in as text
    (incremental.plain_text); split, it is one part of its statements as
    they are, so both ways give the same program."""
    import clingo

    from ethasp.planning.driver import incremental
    from ethasp.planning.driver.planner import MODEL_ENCODINGS, RELAXED_ENCODING
    from ethasp.resources import encoding

    for name in (*MODEL_ENCODINGS, RELAXED_ENCODING):
        text = incremental.plain_text(encoding(name))
        assert text is not None, name
        parts, _ = incremental._split_file(str(encoding(name)), "step", None, "base", "check")
        assert list(parts) == ["base"], name
        statements = []
        clingo.ast.parse_string(text, statements.append)
        assert [str(s) for s in statements[1:]] == [str(s) for s in parts["base"]], name
    assert incremental.plain_text(encoding("planning/transition.lp")) is None  # step(T)
