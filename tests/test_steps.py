"""Step-by-step causal explanations (ethasp.questions.steps, encodings/questions/
links.lp and removable.lp) on hand-made models: links through conditional
effects, derived variables and exogenous events, removable steps with events,
the words and the JSON."""

import pytest
from conftest import MODELS, answer_sets

from ethasp import InputError, Model, Plan
from ethasp.questions.steps import MAX_STEPS, explain_steps

FILES = [
    "planning/model.lp",
    "planning/trace.lp",
    "planning/trace_events.lp",
    "planning/steps.lp",
    "questions/links.lp",
    "questions/removable.lp",
]


def shown(model: str, plan: str, prefix: str) -> set[str]:
    occurs = " ".join(f"occurs({a},{t})." for t, a in enumerate(plan.split(), start=1))
    answer = answer_sets(FILES, model + occurs)[0]
    return {atom for atom in answer if atom.startswith(prefix)}


def test_links_skip_nothing_and_the_latest_setter_provides():
    model = (
        "variable(p;q;g). action(a;b;c). eff(a,p,true). eff(b,p,true). "
        "pre(c,p,true). eff(c,g,true). goal(g,true)."
    )
    assert shown(model, "a b c", "link(") == {
        "link(step(2),step(3),p,true,precondition,none)",
        "link(step(3),goal,g,true,goal,none)",
    }
    assert shown(model, "a b c", "removable(") == {"removable(1)", "removable(2)"}


def test_conditional_effects_provide_where_they_fire_and_their_conditions_are_needs():
    model = (
        "variable(p;q;g). action(a;b;c). eff(a,p,true). "
        "ceff(b,k,q,true). cpre(b,k,p,true). ceff(c,k,g,true). cpre(c,k,q,true). "
        "goal(g,true)."
    )
    assert shown(model, "a b c", "link(") == {
        "link(step(1),step(2),p,true,condition(k),none)",
        "link(step(2),step(3),q,true,condition(k),none)",
        "link(step(3),goal,g,true,goal,none)",
    }
    assert shown(model, "a b c", "removable(") == set()


def test_derived_variables_link_through_the_state_variables_they_read():
    model = (
        "variable(p;q;g). derived(d). axiom(d,1). axiom_pre(d,1,p,true). "
        "axiom_pre(d,1,q,false). action(a;c). eff(a,p,true). pre(c,d,true). "
        "eff(c,g,true). goal(g,true)."
    )
    assert shown(model, "a c", "link(") == {
        "link(step(1),step(2),p,true,precondition,d)",
        "link(step(2),goal,g,true,goal,none)",
    }  # q false initially: no link


# An event at step 1 sets p as well: the value the action at step 2 reads is the event's.
EVENTS = (
    "variable(p;g). action(a;b). eff(a,p,true). pre(b,p,true). eff(b,g,true). "
    "goal(g,true). event(e). event_at(e,1). event_effect(e,k,p,true). "
    "event_condition(e,k,p,true)."
)


def test_events_provide_and_break_links():
    links = shown(EVENTS, "a b", "link(")
    assert links == {
        "link(step(1),event(1,e),p,true,event,none)",
        "link(event(1,e),step(2),p,true,precondition,none)",
        "link(step(2),goal,g,true,goal,none)",
    }
    # Without step 1, b would come at step 1, where p is false: not removable.
    assert shown(EVENTS, "a b", "removable(") == set()
    assert shown(EVENTS, "a b", "goal_chain(1,") == {
        "goal_chain(1,0,step(1))",
        "goal_chain(1,1,event(1,e))",
        "goal_chain(1,2,step(2))",
        "goal_chain(1,3,goal)",
    }


def test_removable_steps_keep_events_at_their_steps():
    # The event at step 2 needs q after the action of step 2.
    model = (
        "variable(q;r;g). action(w;s;f). eff(s,q,true). eff(f,g,true). pre(f,r,true). "
        "goal(g,true). event(e). event_at(e,2). event_effect(e,k,r,true). "
        "event_condition(e,k,q,true)."
    )
    # Without a w, the later actions move one step earlier; the event stays at step 2.
    assert shown(model, "s w w f", "removable(") == {"removable(2)", "removable(3)"}
    assert shown(model, "w s w f", "removable(") == {"removable(1)", "removable(3)"}
    # w s f: without w, f would come at step 2, before the event sets r.
    assert shown(model, "w s f", "removable(") == set()


def test_api_words_and_json():
    model = Model.load([MODELS / "trolley.lp"])
    explanation = explain_steps(model, Plan.parse("refrain pull"))
    assert explanation.text.startswith(
        "Step 1, refrain from action, is not needed: the plan without it is still a plan. "
        "Step 2, pull the lever, brings about the goal (the decision). It is not needed, "
        "though: the plan without it is still a plan."
    )
    data = explanation.to_json()
    assert data["steps"][1] == {
        "step": 2,
        "action": "pull",
        "links": [{"variable": "done", "value": True, "to": "goal", "kind": "goal"}],
        "removable": True,
        "utility": 0,
        "bad": False,
        "harms": [{"variable": "one_will_die", "value": True, "utility": -1}],
        "goods": [{"variable": "five_will_die", "value": False, "utility": 5}],
        "serves_goal": True,
        "chain": [2, "goal"],
    }
    assert "It serves no goal fact, directly or through later steps. " in explanation.step_text(1)
    assert explanation.step_text(2).endswith(
        "; it results in the decision, which fulfils the goal."
    )
    with pytest.raises(InputError, match="not a plan"):
        explain_steps(model, Plan.parse(""))
    with pytest.raises(InputError, match=f"at most {MAX_STEPS} steps"):
        explain_steps(model, Plan.parse("refrain " * (MAX_STEPS + 1)))


def test_events_in_words():
    model = Model.from_string(EVENTS)
    explanation = explain_steps(model, Plan.parse("a b"))
    assert explanation.lines() == [
        "Step 1, a, lets the event e of step 1 happen (the fact p).",
        "The event e of step 1 lets step 2 b (the fact p).",
        "Step 2, b, brings about the goal (the fact g).",
    ]
    assert "It serves the goal through the event e of step 1 and step 2. " in explanation.step_text(
        1
    )
    # Step 1 and the event after it both produce p for step 2: two E-links.
    assert explanation.link_lines() == [
        "Step 1, a: the fact not g and the fact not p hold initially and require it; it "
        "results in the fact p, which enables step 2 (b).",
        "Step 2, b: the fact not g holds initially and requires it; it results in the fact g, "
        "which fulfils the goal.",
        "The event e of step 1 results in the fact p, which enables step 2 (b).",
    ]
    assert explanation.to_json()["events"] == [
        {
            "step": 1,
            "event": "e",
            "links": [{"variable": "p", "value": True, "to": 2, "kind": "precondition"}],
        }
    ]
