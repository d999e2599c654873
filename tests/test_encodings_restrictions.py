"""Encoding-level tests of the restrictions (HModels): clingo with a fixed horizon."""

from conftest import MODELS, answer_sets

SEARCH = ["planning/model.lp", "planning/relaxed.lp", "planning/transition.lp", "planning/goal.lp"]


def fixed(horizon: int) -> str:
    return f"time(0..{horizon}). step(1..{horizon}). horizon({horizon}).\n"


def plans(restrictions, model: str, horizon: int, files=SEARCH) -> set[tuple[str, ...]]:
    """The action sequences of all answer sets (idle steps dropped)."""
    files = list(files) + [f"restrictions/{name}.lp" for name in restrictions]
    result = set()
    for answer in answer_sets(files, model + fixed(horizon)):
        steps = sorted((int(a.rsplit(",", 1)[1].rstrip(")")), a[len("occurs("):a.rindex(",")])
                       for a in answer if a.startswith("occurs("))
        result.add(tuple(name for _, name in steps))
    return result


TROLLEY = (MODELS / "trolley.lp").read_text()


def test_trolley_under_each_principle():
    assert plans([], TROLLEY, 1) == {("pull",), ("refrain",)}
    assert plans(["deontology"], TROLLEY, 1) == {("pull",), ("refrain",)}
    assert plans(["do_no_harm"], TROLLEY, 1) == {("refrain",)}
    # The best reachable state (five saved, one dies) has utility 5 - 1 = 4.
    assert plans(["utilitarianism"], TROLLEY + "best_utility(4).", 1) == {("pull",)}
    assert plans(["utilitarianism"], TROLLEY + "best_utility(5).", 1) == set()
    assert plans(["utilitarianism", "do_no_harm"], TROLLEY + "best_utility(4).", 1) == set()


def test_deontology_forbids_bad_actions_only():
    model = """variable(g). action(lie;ask;praise). eff(lie,g,true). eff(ask,g,true).
               eff(praise,g,true). utility(lie,-1). utility(praise,2). goal(g,true)."""
    assert plans(["deontology"], model, 1) == {("ask",), ("praise",)}


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


def test_do_no_harm_an_undone_harm_is_not_caused():
    assert plans(["do_no_harm"], HEAL, 2) == {("harm", "heal")}
    shown = "#show produced/3. #show reset/3."
    answers = answer_sets(SEARCH + ["restrictions/do_no_harm.lp"], HEAL + fixed(2) + shown)
    assert len(answers) == 1
    assert {"produced(hurt,true,1)", "reset(hurt,true,2)"} <= answers[0]
    assert "produced(hurt,true,2)" not in answers[0]


def test_do_no_harm_a_harm_redone_is_caused():
    model = HEAL.replace("eff(heal, done, true).", "eff(heal, done, true). eff(redo, hurt, true).")
    model += "action(redo). pre(redo, done, true)."
    assert ("harm", "heal", "redo") not in plans(["do_no_harm"], model, 3)
    assert ("harm", "heal", "redo") in plans([], model, 3)


def test_produced_flags_are_part_of_the_state_for_the_loop_free_check():
    # With p true initially, "on" sets p again: only the produced flag changes.
    model = """variable(p). init(p). action(on; off). eff(on, p, true). eff(off, p, false).
               goal(p, false). utility(p, true, -1). simple_path(c)."""
    loopfree = ["planning/model.lp", "planning/relaxed.lp", "planning/transition.lp", "planning/loopfree.lp"]
    assert answer_sets(loopfree, model + fixed(2)) == []
    assert answer_sets(loopfree + ["restrictions/do_no_harm.lp"], model + fixed(2)) != []
    assert answer_sets(loopfree + ["restrictions/do_no_harm.lp"], model + fixed(3)) == []


def test_utilitarianism_accepts_every_best_goal_state():
    # Two different goal states of the best utility, and a worse one.
    model = """variable(a; b; g). action(x; y; z).
               eff(x, a, true). eff(x, g, true). eff(y, b, true). eff(y, g, true).
               eff(z, g, true). utility(a, true, 2). utility(b, true, 2). goal(g, true)."""
    assert plans(["utilitarianism"], model + "best_utility(2).", 1) == {("x",), ("y",)}
