"""Encoding-level tests of the restrictions: their HModels (restrictions/hmodel.lp
and the restrictions' encodings, questions/restriction.lp) computed by clingo,
then planned for with a fixed horizon, as on the clingo command line."""

from conftest import MODELS, answer_sets, only_answer

SEARCH = [
    "planning/model.lp",
    "planning/relaxed.lp",
    "planning/transition.lp",
    "planning/events.lp",
    "planning/goal.lp",
]
COMPILE = ["planning/model.lp", "restrictions/hmodel.lp"]


def fixed(horizon: int) -> str:
    return f"time(0..{horizon}). step(1..{horizon}). horizon({horizon}).\n"


def hmodel(restrictions, model: str, inputs: str = "", questions: bool = False) -> str:
    """The HModel's facts (the arguments of hmodel/1), as program text."""
    files = COMPILE + [f"restrictions/{name}.lp" for name in restrictions]
    if questions:
        files.append("questions/restriction.lp")
    answer = only_answer(files, model + inputs)
    return "".join(f"{atom[len('hmodel(') : -1]}.\n" for atom in sorted(answer))


def plans_of(model: str, horizon: int, files=SEARCH, show: str = "") -> set[tuple[str, ...]]:
    """The action sequences of all answer sets (idle steps dropped)."""
    result = set()
    for answer in answer_sets(files, model + fixed(horizon) + show):
        steps = sorted(
            (int(a.rsplit(",", 1)[1].rstrip(")")), a[len("occurs(") : a.rindex(",")])
            for a in answer
            if a.startswith("occurs(")
        )
        result.add(tuple(name for _, name in steps))
    return result


def plans(restrictions, model: str, horizon: int, inputs: str = "") -> set[tuple[str, ...]]:
    """The plans of the HModel of the restrictions, of at most ``horizon`` steps."""
    return plans_of(hmodel(restrictions, model, inputs), horizon)


TROLLEY = (MODELS / "trolley.lp").read_text()


def test_trolley_under_each_principle():
    assert plans([], TROLLEY, 1) == {("pull",), ("refrain",)}
    assert plans(["deontology"], TROLLEY, 1) == {("pull",), ("refrain",)}
    assert plans(["do_no_harm"], TROLLEY, 1) == {("refrain",)}
    # The best reachable state (five saved, one dies) has utility 5 - 1 = 4.
    assert plans(["utilitarianism"], TROLLEY, 1, "best_utility(4).") == {("pull",)}
    assert plans(["utilitarianism"], TROLLEY, 1, "best_utility(5).") == set()
    assert plans(["utilitarianism", "do_no_harm"], TROLLEY, 1, "best_utility(4).") == set()


def test_the_hmodel_is_a_model_in_the_vocabulary():
    text = hmodel(["do_no_harm", "utilitarianism"], TROLLEY, "best_utility(4).")
    assert "goal_utility(4)." in text
    assert "variable(ethasp(produced(one_will_die,true)))." in text
    assert "eff(pull,ethasp(produced(one_will_die,true)),true)." in text
    # and the model's own facts are all there
    assert "eff(pull,one_will_die,true)." in text and "init(five_will_die)." in text


def test_deontology_removes_the_bad_actions():
    model = """variable(g). action(lie;ask;praise). eff(lie,g,true). eff(ask,g,true).
               eff(praise,g,true). utility(lie,-1). utility(praise,2). goal(g,true)."""
    text = hmodel(["deontology"], model)
    assert "action(lie)." not in text and "eff(lie,g,true)." not in text
    assert plans(["deontology"], model, 1) == {("ask",), ("praise",)}


def test_a_goal_utility_above_the_relaxed_upper_bound_is_unreachable():
    # Relaxed, both the five and the one may live: 5 + 1 = 6 bounds every state.
    for goal, unreachable in (("6", False), ("7", True)):
        program = hmodel(["utilitarianism"], TROLLEY, f"best_utility({goal}).")
        answer = only_answer(
            ["planning/model.lp", "planning/relaxed.lp"],
            program + "#show unreachable_goal/0. #show upper_bound/1.",
        )
        assert answer == {"upper_bound(6)"} | ({"unreachable_goal"} if unreachable else set())


FISH = """variable(alive(fish); fed). init(alive(fish)). action(cook; buy).
          eff(cook, alive(fish), false). eff(cook, fed, true). eff(buy, fed, true).
          goal(fed, true). utility(alive(fish), false, -3)."""


def test_do_no_harm_with_a_bad_negative_fact():
    assert plans([], FISH, 1) == {("cook",), ("buy",)}
    assert plans(["do_no_harm"], FISH, 1) == {("buy",)}


def test_do_no_harm_an_effect_that_holds_already_is_caused():
    # The fish is dead from the start; cooking it still has the bad fact as effect.
    model = FISH.replace("init(alive(fish)).", "")
    assert plans(["do_no_harm"], model, 1) == {("buy",)}


def test_do_no_harm_a_bad_fact_present_initially_is_not_caused():
    model = """variable(hurt; done). init(hurt). action(wait). eff(wait, done, true).
               goal(done, true). utility(hurt, true, -1)."""
    assert plans(["do_no_harm"], model, 1) == {("wait",)}


HEAL = """variable(hurt; done). action(harm; heal).
          eff(harm, hurt, true).
          pre(heal, hurt, true). eff(heal, hurt, false). eff(heal, done, true).
          goal(done, true). utility(hurt, true, -1)."""
PRODUCED = "ethasp(produced(hurt,true))"


def test_do_no_harm_an_undone_harm_is_not_caused():
    assert plans(["do_no_harm"], HEAL, 2) == {("harm", "heal")}
    answers = answer_sets(
        SEARCH, hmodel(["do_no_harm"], HEAL) + fixed(2) + ":- not occurs(harm,1). #show holds/2."
    )
    assert len(answers) == 1
    # the flag is set by the harm and reset by the healing
    assert f"holds({PRODUCED},1)" in answers[0] and f"holds({PRODUCED},2)" not in answers[0]


def test_do_no_harm_a_harm_redone_is_caused():
    model = HEAL.replace("eff(heal, done, true).", "eff(heal, done, true). eff(redo, hurt, true).")
    model += "action(redo). pre(redo, done, true)."
    assert ("harm", "heal", "redo") not in plans(["do_no_harm"], model, 3)
    assert ("harm", "heal", "redo") in plans([], model, 3)


def test_the_produced_flags_are_state_variables_for_the_loop_free_check():
    # With p true initially, "on" sets p again: only the produced flag changes.
    model = """variable(p). init(p). action(on; off). eff(on, p, true). eff(off, p, false).
               goal(p, false). utility(p, true, -1)."""
    loopfree = [
        "planning/model.lp",
        "planning/relaxed.lp",
        "planning/transition.lp",
        "planning/loopfree.lp",
    ]
    assert answer_sets(loopfree, model + "simple_path(c)." + fixed(2)) == []
    compiled = hmodel(["do_no_harm"], model) + "simple_path(c)."
    assert answer_sets(loopfree, compiled + fixed(2)) != []
    assert answer_sets(loopfree, compiled + fixed(3)) == []


# Events: a fact set by an action and undone, or kept, by an event.
STORM = """variable(wet; out; g). action(go; stay). eff(go, out, true). eff(stay, g, true).
           pre(stay, out, true). eff(go, wet, false). goal(g, true).
           event(rain). event_at(rain, 1). event_pre(rain, out, true).
           event_effect(rain, 1, wet, true). init(wet). utility(wet, false, -1)."""


def test_do_no_harm_an_event_undoes_what_the_action_did():
    # go dries (wet false: bad), the rain at step 1 makes wet again: not caused.
    assert plans(["do_no_harm"], STORM, 2) == {("go", "stay")}
    dry = STORM.replace("event_effect(rain, 1, wet, true).", "event_effect(rain, 1, out, true).")
    assert plans(["do_no_harm"], dry, 2) == set()


def test_do_no_harm_an_overridden_delete_that_an_event_completes_is_not_caused():
    # a deletes v and adds it back (true wins): its delete sets nothing; the event
    # at step 1 then deletes v, and "v is false" holds from step 1 on, made by
    # the event, not by a (planning/trace_events.lp).
    model = """variable(v;g). init(v). action(a). eff(a,v,false). ceff(a,k,v,true).
               eff(a,g,true). goal(g,true). utility(v,false,-1).
               event(e). event_at(e,1). event_effect(e,1,v,false)."""
    assert plans([], model, 1) == {("a",)}
    assert plans(["do_no_harm"], model, 1) == {("a",)}
    caused = only_answer(
        ["planning/model.lp", "planning/trace.lp", "planning/trace_events.lp"],
        model + "occurs(a,1). #show caused/2.",
    )
    assert "caused(v,false)" not in caused
    # without the add, the delete of a wins and causes it (the event keeps it)
    model = model.replace("ceff(a,k,v,true).", "")
    assert plans(["do_no_harm"], model, 1) == set()
    caused = only_answer(
        ["planning/model.lp", "planning/trace.lp", "planning/trace_events.lp"],
        model + "occurs(a,1). #show caused/2.",
    )
    assert "caused(v,false)" in caused


def test_do_no_harm_a_harm_an_action_undoes_and_an_event_of_its_step_redoes_is_caused():
    # p makes v (bad) at step 1; u deletes it at step 2 and the event of step 2
    # makes it again: v held after steps 1 and 2 (events included), so p
    # caused it (planning/trace_events.lp); a third step that deletes it
    # again is needed.
    model = """variable(v;w). action(p;u). eff(p,v,true). eff(p,w,true). eff(u,v,false).
               event(e). event_at(e,2). event_effect(e,1,v,true). goal(w,true).
               utility(v,true,-1)."""
    caused = only_answer(
        ["planning/model.lp", "planning/trace.lp", "planning/trace_events.lp"],
        model + "occurs(p,1). occurs(u,2). #show caused/2.",
    )
    assert "caused(v,true)" in caused
    assert plans(["do_no_harm"], model, 2) == set()
    assert plans(["do_no_harm"], model, 3) == {("u", "p", "u"), ("p", "u", "u"), ("p", "p", "u")}


def test_avoid_any_harm_adds_the_opposite_goals():
    text = hmodel(["avoid_any_harm"], FISH)
    assert "goal(alive(fish),true)." in text
    assert plans(["avoid_any_harm"], FISH, 1) == {("buy",)}


def test_goal_deontology_with_a_bad_goal_has_no_plan():
    model = "variable(g). action(a). eff(a,g,true). goal(g,true). utility(g,true,-1)."
    text = hmodel(["goal_deontology"], model)
    assert "goal(ethasp(unreachable),true)." in text
    assert plans(["goal_deontology"], model, 3) == set()


# -- questions ---------------------------------------------------------------------------

ROUTES = """variable(g; x). action(a; b; c). eff(a, g, true). eff(b, x, true).
            pre(c, x, true). eff(c, g, true). goal(g, true)."""


def question_plans(model: str, contrasts: str, horizon: int) -> set[tuple[str, ...]]:
    return plans_of(hmodel([], model, contrasts, questions=True), horizon)


def test_question_constraints_as_hmodels():
    assert question_plans(ROUTES, "contrast(q,unused(a)).", 2) == {("b", "c")}
    assert question_plans(ROUTES, "contrast(q,used(b)).", 2) == {("b", "c"), ("b", "a"), ("a", "b")}
    # a b, and no a before the first b
    assert question_plans(ROUTES, "contrast(q,before(b,a)).", 2) == {("b", "a"), ("b", "c")}
    found = question_plans(ROUTES, "contrast(q,before(b,a)).", 3)
    assert ("b", "a", "a") in found and ("b", "b", "c") in found
    assert not any("a" in plan[: plan.index("b")] for plan in found if "b" in plan)
    assert all("b" in plan for plan in found)
    assert question_plans(ROUTES, "contrast(q,used(b)). contrast(q,unused(b)).", 3) == set()


def test_utilitarianism_accepts_every_best_goal_state():
    # Two different goal states of the best utility, and a worse one.
    model = """variable(a; b; g). action(x; y; z).
               eff(x, a, true). eff(x, g, true). eff(y, b, true). eff(y, g, true).
               eff(z, g, true). utility(a, true, 2). utility(b, true, 2). goal(g, true)."""
    assert plans(["utilitarianism"], model, 1, "best_utility(2).") == {("x",), ("y",)}
