"""Random HERA situations (as the data HERA reads from YAML), for differential
tests against the HERA toolbox itself (``ethics.plans``) and for benchmarks.

Situations are small on purpose: HERA decides causation by trying every
subset of events and every way to drop actions from the plan, and its planner
tries every sequence of up to ten actions.
"""

from __future__ import annotations

from hypothesis import strategies as st

VARIABLES = ["a", "b", "c", "d"]
VALUES = ("good", "bad", "neutral")


def partial(variables, max_size: int):
    return st.dictionaries(st.sampled_from(variables), st.booleans(), max_size=max_size)


def fact(variables):
    return st.builds(lambda v, b: {v: b}, st.sampled_from(variables), st.booleans())


def conditional_effects(variables, max_effects: int = 3):
    return st.lists(st.fixed_dictionaries({"condition": partial(variables, 2),
                                           "effect": partial(variables, 2)}),
                    min_size=0, max_size=max_effects)


@st.composite
def situations(draw, max_actions: int = 3, max_events: int = 2, max_plan: int = 3,
               variables: list[str] | None = None, goal: bool | None = None):
    """A HERA situation: actions, events, utilities, patients, goal, plan, initial state."""
    variables = variables or VARIABLES[:draw(st.integers(2, len(VARIABLES)))]
    count = draw(st.integers(1, max_actions))
    actions = []
    for index in range(count):
        action = {"name": f"act{index}",
                  "preconditions": draw(partial(variables, 1)),
                  "effects": draw(conditional_effects(variables))}
        value = draw(st.sampled_from(VALUES + (None,)))
        if value is not None:
            action["intrinsicvalue"] = value
        actions.append(action)
    events = []
    for index in range(draw(st.integers(0, max_events))):
        events.append({"name": f"ev{index}",
                       "preconditions": draw(partial(variables, 1)),
                       "effects": draw(conditional_effects(variables, 2)),
                       "timepoints": sorted(draw(st.sets(st.integers(0, max_plan + 1),
                                                         min_size=1, max_size=2)))})
    utilities = []
    for literal in draw(st.lists(fact(variables), max_size=4, unique_by=lambda f: tuple(f.items()))):
        utilities.append({"fact": literal, "utility": draw(st.integers(-3, 3))})
    affects = {}
    for index in range(draw(st.integers(0, 2))):
        affects[f"p{index}"] = {"pos": draw(st.lists(fact(variables), max_size=2)),
                                "neg": draw(st.lists(fact(variables), max_size=2))}
    situation = {
        "actions": actions,
        "events": events,
        "utilities": utilities,
        "affects": affects,
        "plan": [action["name"] for action in draw(st.lists(st.sampled_from(actions),
                                                             max_size=max_plan))],
        "initialState": {v: draw(st.booleans()) for v in variables},
    }
    if goal is None:
        goal = draw(st.booleans())
    if goal:
        situation["goal"] = draw(partial(variables, 2))
    return situation
