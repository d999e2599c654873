"""Encoding-level tests of conditional effects (ceff/4, cpre/4) and derived
variables (derived/1, axiom/2, axiom_pre/4) through every planning encoding."""

from conftest import answer_sets, only_answer

CHECK = ["planning/model.lp", "planning/check.lp"]
RELAXED = ["planning/model.lp", "planning/relaxed.lp"]
TRACE = ["planning/model.lp", "planning/trace.lp"]
SEARCH = ["planning/model.lp", "planning/relaxed.lp", "planning/transition.lp", "planning/goal.lp"]


def fixed(horizon: int) -> str:
    return f"time(0..{horizon}). step(1..{horizon}). horizon({horizon}).\n"


def plans(model: str, horizon: int, extra=()) -> set[tuple[str, ...]]:
    result = set()
    for answer in answer_sets(SEARCH + list(extra), model + fixed(horizon)):
        steps = sorted(
            (int(a.rsplit(",", 1)[1].rstrip(")")), a[len("occurs(") : a.rindex(",")])
            for a in answer
            if a.startswith("occurs(")
        )
        result.add(tuple(name for _, name in steps))
    return result


def trace(model: str, actions: list[str], show: str = "") -> set[str]:
    occurs = "".join(f"occurs({a},{t}). " for t, a in enumerate(actions, start=1))
    return only_answer(TRACE, model + occurs + show)


# A lamp with a switch: pressing toggles the light (two conditional effects);
# "wire" is cut by "cut", after which pressing does nothing.
LAMP = """
variable(on; wire; done). init(wire).
action(press; cut; finish).
ceff(press,up,on,true).    cpre(press,up,on,false). cpre(press,up,wire,true).
ceff(press,down,on,false). cpre(press,down,on,true). cpre(press,down,wire,true).
eff(cut,wire,false).
pre(finish,on,true). eff(finish,done,true).
goal(done,true).
"""


# -- check.lp -----------------------------------------------------------------------


def test_check_accepts_conditional_effects_and_derived_variables():
    model = (
        LAMP
        + """derived(lit). axiom(lit,1). axiom_pre(lit,1,on,true).
                      pre(finish,lit,true). goal(lit,true)."""
    )
    assert only_answer(CHECK, model) == set()


def test_check_reports_misused_conditional_effects_and_derived_variables():
    model = """
    variable(x). action(a). goal(x,true). derived(d). derived(x).
    ceff(a,k,y,true). cpre(a,k,z,true). cpre(a,j,x,true). ceff(b,k,x,maybe).
    eff(a,d,true). init(d). utility(d,true,1). axiom(e,1). axiom_pre(d,2,x,true).
    derived(p;q). axiom(p,1). axiom_pre(p,1,q,false). axiom(q,1). axiom_pre(q,1,p,true).
    """
    errors = only_answer(CHECK, model)
    assert {
        "error(undeclared_variable(y,ceff(a,k,y,true)))",
        "error(undeclared_variable(z,cpre(a,k,z,true)))",
        "error(condition_without_effect(cpre(a,j,x,true)))",
        "error(undeclared_action(b,ceff(b,k,x,maybe)))",
        "error(bad_value(ceff(b,k,x,maybe)))",
        "error(derived_and_variable(x))",
        "error(derived_misuse(d,eff(a,d,true)))",
        "error(derived_misuse(d,init(d)))",
        "error(derived_misuse(d,utility(d,true,1)))",
        "error(undeclared_derived(e,axiom(e,1)))",
        "error(condition_without_axiom(axiom_pre(d,2,x,true)))",
        "error(unstratified(p,q))",
    } <= errors
    # a positive cycle is fine
    model = """variable(x). goal(x,true). derived(p;q). axiom(p,1). axiom_pre(p,1,q,true).
               axiom(q,1). axiom_pre(q,1,p,true). axiom(q,2). axiom_pre(q,2,x,true)."""
    assert only_answer(CHECK, model) == set()


def test_check_contradicting_effects_only_when_unconditional():
    model = "variable(x). action(a). goal(x,true). eff(a,x,false). ceff(a,k,x,true)."
    assert only_answer(CHECK, model) == set()
    model += "eff(a,x,true)."
    assert "error(contradicting_effects(a,x))" in only_answer(CHECK, model)


# -- relaxed.lp ---------------------------------------------------------------------


def test_relaxed_conditional_effect_needs_reachable_conditions():
    model = """variable(a;b;g). action(x;y). ceff(x,1,g,true). cpre(x,1,a,true).
               eff(y,b,true). goal(g,true). #show reachable/2."""
    assert "unreachable_goal" in only_answer(RELAXED, model)
    answer = only_answer(RELAXED, model + "ceff(y,1,a,true). cpre(y,1,b,true).")
    assert "unreachable_goal" not in answer and "reachable(g,true)" in answer


def test_relaxed_derived_variables_true_and_false():
    model = """variable(a;b). init(a). action(x). pre(x,a,false). eff(x,b,true).
               derived(both;none;never). axiom(both,1). axiom_pre(both,1,a,true).
               axiom_pre(both,1,b,true). axiom(never,1). axiom_pre(never,1,a,false).
               goal(b,true). #show reachable/2."""
    answer = only_answer(RELAXED, model)
    # "a" is never false: x is never usable, b never true, "both" never true
    assert "reachable(both,true)" not in answer and "reachable(both,false)" in answer
    assert "reachable(never,true)" not in answer and "reachable(never,false)" in answer
    # "none" has no axiom: always false
    assert "reachable(none,false)" in answer and "reachable(none,true)" not in answer
    assert "unreachable_goal" in answer
    answer = only_answer(
        RELAXED,
        model.replace("goal(b,true).", "goal(both,false).")
        + "derived(always). axiom(always,1). goal(always,false).",
    )
    assert "reachable(always,true)" in answer and "reachable(always,false)" not in answer
    assert "unreachable_goal" in answer


# -- transition.lp and goal.lp -------------------------------------------------------------


def test_conditional_effects_fire_on_the_state_before():
    assert plans(LAMP, 1) == set()
    assert plans(LAMP, 2) == {("press", "finish")}
    # pressing twice switches the light off again; cutting the wire first disables it
    assert ("press", "press", "finish") not in plans(LAMP, 3)
    assert ("cut", "press", "finish") not in plans(LAMP, 3)
    assert ("press", "cut", "finish") in plans(LAMP, 3)


def test_true_wins_when_effects_set_a_variable_both_ways():
    model = """variable(v;g). action(a;b). eff(a,v,false). ceff(a,k,v,true).
               eff(b,g,true). pre(b,v,true). goal(g,true)."""
    assert plans(model, 2) == {("a", "b")}
    model = """variable(v;g). action(a;b). ceff(a,1,v,false). ceff(a,2,v,true).
               eff(b,g,true). pre(b,v,true). goal(g,true)."""
    assert plans(model, 2) == {("a", "b")}


def test_derived_variables_in_preconditions_and_goals():
    # reach(r) holds for r1 and every room behind an open door from a reached one
    model = """variable(open(r1,r2); open(r2,r3)). action(open(r1,r2); open(r2,r3)).
               eff(open(X,Y),open(X,Y),true) :- action(open(X,Y)).
               derived(reach(r1;r2;r3)). axiom(reach(r1),base).
               axiom(reach(Y),from(X)) :- variable(open(X,Y)).
               axiom_pre(reach(Y),from(X),reach(X),true) :- variable(open(X,Y)).
               axiom_pre(reach(Y),from(X),open(X,Y),true) :- variable(open(X,Y)).
               pre(open(X,Y),reach(X),true) :- action(open(X,Y)).
               goal(reach(r3),true)."""
    assert plans(model, 1) == set()
    assert plans(model, 2) == {("open(r1,r2)", "open(r2,r3)")}


# -- trace.lp ---------------------------------------------------------------------------


def test_trace_final_state_with_conditional_effects():
    answer = trace(LAMP, ["press", "finish"])
    assert "plan" in answer and {"final(on,true)", "final(done,true)"} <= answer
    answer = trace(LAMP, ["press", "press", "finish"])
    assert "failure(3)" in answer and "unmet(3,finish,on,true)" in answer
    answer = trace(LAMP, ["cut", "press"])
    assert "final(on,false)" in answer and "final(wire,false)" in answer
    # effects that do not fire keep the value set long before
    steps = ["press"] + ["cut"] * 20 + ["press", "finish"]
    assert "plan" in trace(LAMP, steps)


def test_trace_caused_counts_only_effects_that_fire():
    show = "#show caused/2."
    assert "caused(on,true)" in trace(LAMP, ["press"], show)
    # after the wire is cut, pressing fires nothing: on stays false, not caused
    answer = trace(LAMP, ["cut", "press"], show)
    assert "caused(on,false)" not in answer and "caused(wire,false)" in answer
    # pressing twice: off is caused (the second press fired "down")
    assert "caused(on,false)" in trace(LAMP, ["press", "press"], show)


def test_trace_derived_preconditions_and_goals():
    model = """variable(a;b). action(x;y). eff(x,a,true). eff(y,b,true).
               derived(both). axiom(both,1). axiom_pre(both,1,a,true). axiom_pre(both,1,b,true).
               derived(none). axiom(none,1). axiom_pre(none,1,both,false).
               pre(y,none,true). goal(both,true)."""
    answer = trace(model, ["x", "y"])
    assert "plan" in answer
    assert not any(atom.startswith("final(both") for atom in answer)
    answer = trace(model, ["x", "y", "y"])
    assert "unmet(3,y,none,true)" in answer and "failure(3)" in answer
    answer = trace(model, ["x"])
    assert "unmet_goal(both,true)" in answer and "plan" not in answer


# -- mutex.lp ------------------------------------------------------------------------------


def test_mutexes_leave_out_variables_set_by_conditional_effects():
    # a and b are exclusive for STRIPS actions; "both" sets b when a holds
    model = """variable(a;b). init(a). action(swap;back;both).
               pre(swap,a,true). eff(swap,a,false). eff(swap,b,true).
               pre(back,b,true). eff(back,b,false). eff(back,a,true).
               ceff(both,1,b,true). cpre(both,1,a,true). #show mutex/4. #show fluent/1."""
    files = [*RELAXED, "planning/mutex.lp"]
    without = only_answer(files, model.replace("ceff(both,1,b,true). cpre(both,1,a,true).", ""))
    assert "mutex(a,true,b,true)" in without
    answer = only_answer(files, model)
    assert not any(atom.startswith("mutex(") and "b," in atom for atom in answer)
    assert "fluent(a)" in answer and "fluent(b)" not in answer
    # the state {a, b} is reachable, and plan search still finds it
    goal = "goal(a,true). goal(b,true)."
    assert plans(model + goal, 1, ["planning/mutex.lp"]) == {("both",)}


# -- restrictions/do_no_harm.lp ---------------------------------------------------------------


def test_do_no_harm_counts_only_effects_that_fire():
    # The lamp is bad when on; a press that does not fire (wire cut) harms nothing.
    from test_encodings_restrictions import hmodel, plans_of

    model = LAMP.replace("pre(finish,on,true).", "") + "utility(on,true,-1)."
    assert ("press", "finish") in plans(model, 2)
    restricted = hmodel(["do_no_harm"], model)
    assert ("press", "finish") not in plans_of(restricted, 2)
    assert ("cut", "press", "finish") in plans_of(restricted, 3)
    answers = answer_sets(
        SEARCH,
        restricted + fixed(3) + ":- not occurs(cut,1). :- not occurs(press,2). #show holds/2.",
    )
    assert answers and not any("produced" in atom for atom in answers[0])


def test_do_no_harm_an_overridden_delete_produces_nothing():
    # a deletes v and, if g holds, adds it back (true wins); "v is false" is bad.
    from test_encodings_restrictions import hmodel, plans_of

    model = """variable(v;g). init(v;g). action(a). eff(a,v,false). ceff(a,k,v,true).
               cpre(a,k,g,true). eff(a,g,false). goal(g,false). utility(v,false,-1)."""
    assert plans_of(hmodel(["do_no_harm"], model), 1) == {("a",)}
    # without g, the delete wins and causes the bad fact
    model = model.replace("init(v;g).", "init(v). variable(h). init(h).").replace(
        "goal(g,false).", "goal(h,true)."
    )
    assert ("a",) not in plans_of(hmodel(["do_no_harm"], model), 1)
