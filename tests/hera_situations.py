"""Random HERA situations (as the data HERA reads from YAML), for differential
tests against the HERA toolbox itself (``ethics.plans``) and for benchmarks.

Situations are small on purpose: HERA decides causation by trying every
subset of events and every way to drop actions from the plan, and its planner
tries every sequence of up to ten actions.  Most of them are dense (every
action and event has effects, facts have utilities, patients are affected,
the plan is not empty), so that the principles' verdicts vary; a few are
sparse, for the corner cases.
"""

from __future__ import annotations

from hypothesis import strategies as st

VARIABLES = ["a", "b", "c", "d"]
VALUES = ("good", "bad", "neutral")


def partial(variables, min_size: int, max_size: int):
    return st.dictionaries(
        st.sampled_from(variables), st.booleans(), min_size=min_size, max_size=max_size
    )


def fact(variables):
    return st.builds(lambda v, b: {v: b}, st.sampled_from(variables), st.booleans())


def conditional_effects(variables, low: int, high: int, dense: bool):
    return st.lists(
        st.fixed_dictionaries(
            {"condition": partial(variables, 0, 2), "effect": partial(variables, int(dense), 2)}
        ),
        min_size=low,
        max_size=high,
    )


@st.composite
def situations(
    draw,
    max_actions: int = 3,
    max_events: int = 2,
    max_plan: int = 3,
    variables: list[str] | None = None,
    goal: bool | None = None,
    undefined: bool = False,
):
    """A HERA situation: actions, events, utilities, patients, goal, plan, initial state.

    With ``undefined``, ``initialState`` may leave out variables that the
    situation never reads as false (in HERA they are then undefined until an
    effect sets them; ethasp reads them as false, which agrees there)."""
    dense = draw(st.integers(0, 4)) > 0
    variables = variables or VARIABLES[: draw(st.integers(2, len(VARIABLES)))]
    count = draw(st.integers(1, max_actions))
    actions = []
    for index in range(count):
        action = {
            "name": f"act{index}",
            "preconditions": draw(partial(variables, 0, 1)),
            "effects": draw(conditional_effects(variables, int(dense), 3, dense)),
        }
        value = draw(st.sampled_from((*VALUES, None)))
        if value is not None:
            action["intrinsicvalue"] = value
        actions.append(action)
    events = []
    for index in range(draw(st.integers(0, max_events))):
        events.append(
            {
                "name": f"ev{index}",
                "preconditions": draw(partial(variables, 0, 1)),
                "effects": draw(conditional_effects(variables, int(dense), 2, dense)),
                "timepoints": sorted(
                    draw(st.sets(st.integers(0, max_plan + 1), min_size=1, max_size=2))
                ),
            }
        )
    utilities = []
    for literal in draw(
        st.lists(
            fact(variables),
            min_size=int(dense) * 2,
            max_size=5,
            unique_by=lambda f: tuple(f.items()),
        )
    ):
        utilities.append(
            {"fact": literal, "utility": draw(st.integers(-3, 3).filter(lambda u: u or not dense))}
        )
    affects = {}
    for index in range(draw(st.integers(int(dense), 2))):
        affects[f"p{index}"] = {
            "pos": draw(st.lists(fact(variables), min_size=int(dense), max_size=2)),
            "neg": draw(st.lists(fact(variables), max_size=2)),
        }
    situation = {
        "actions": actions,
        "events": events,
        "utilities": utilities,
        "affects": affects,
        "plan": [
            action["name"]
            for action in draw(
                st.lists(st.sampled_from(actions), min_size=int(dense), max_size=max_plan)
            )
        ],
        "initialState": {v: draw(st.booleans()) for v in variables},
    }
    if goal is None:
        goal = draw(st.integers(0, 4)) > 0
    # Goals made of what the plan's actions do make instrumentality likelier.
    effects = sorted(
        {
            (variable, value)
            for action in actions
            if action["name"] in situation["plan"]
            for effect in action["effects"]
            for variable, value in effect["effect"].items()
        }
    )
    if goal and effects and draw(st.booleans()):
        chosen = draw(st.lists(st.sampled_from(effects), min_size=1, max_size=2))
        situation["goal"] = dict(chosen)
    elif goal:
        situation["goal"] = draw(partial(variables, int(dense), 2))
    if undefined:
        read_false = set()
        for part in actions + events:
            read_false |= {v for v, b in part["preconditions"].items() if not b}
            for effect in part["effects"]:
                read_false |= {v for v, b in effect["condition"].items() if not b}
        read_false |= {v for v, b in situation.get("goal", {}).items() if not b}
        read_false |= {v for u in utilities for v, b in u["fact"].items() if not b}
        read_false |= {
            v
            for sides in affects.values()
            for side in sides.values()
            for f in side
            for v, b in f.items()
            if not b
        }
        left_out = [v for v in variables if v not in read_false]
        for variable in draw(st.lists(st.sampled_from(left_out), unique=True)) if left_out else []:
            del situation["initialState"][variable]
    return situation
