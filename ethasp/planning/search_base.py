"""What the plan searches share: their result and statuses, the checks made
before a search, and the words of their proofs (shortest plans,
:mod:`ethasp.planning.search`; cheapest plans, :mod:`ethasp.planning.cost_search`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ethasp.errors import InputError
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import Planner, Setting
from ethasp.planning.plan import Plan, steps

FOUND, NONE, BOUNDED = "found", "none", "bounded"


@dataclass
class SearchResult:
    """The outcome of a plan search.

    ``plan`` is a plan (or None): a shortest one when ``optimal``, else (an
    any-plan search, ``satisficing``) just a plan; ``plans`` all shortest
    plans when they were asked for, ``horizon`` the last horizon searched,
    and ``proof`` says why there is no plan (status ``none``), why the plan
    is a shortest one or how it was found (status ``found``) or what cut the
    search short (status ``bounded``).  With action costs
    (:mod:`ethasp.planning.cost_search`) the plan is a cheapest one, of
    ``cost``; a ``bounded`` result may then hold the cheapest plan found,
    not proven cheapest (``optimal`` False).
    """

    status: str
    plan: Plan | None = None
    horizon: int = 0
    proof: str = ""
    plans: list[Plan] = field(default_factory=list)
    optimal: bool = True
    cost: int | None = None

    def to_json(self) -> dict:
        return {
            "status": self.status,
            "plan": self.plan.to_list() if self.plan is not None else None,
            "optimal": self.optimal if self.plan is not None else None,
            **({"cost": self.cost} if self.cost is not None else {}),
            "horizon": self.horizon,
            "proof": self.proof,
            **({"plans": [plan.to_list() for plan in self.plans]} if self.plans else {}),
        }


def checkpoints(limit: int) -> set[int]:
    """The horizons after which the loop-free check runs: powers of four and the
    limit (each check costs a solve; they only prove that no plan exists)."""
    result, power = {limit}, 1
    while power <= limit:
        result.add(power)
        power *= 4
    return result


def plans_of(models: list) -> list[Plan]:
    """The plans of answer sets (their ``occurs/2`` atoms), without repeats."""
    plans = [Plan.from_symbols(symbols) for symbols in models]
    return list(dict.fromkeys(plans))


def one_plan_wanted(setting: Setting) -> bool:
    """Does a search under this setting want just some plan of each length (so
    that independent actions may be taken in one order, ``planning/
    canonical.lp``)?  Not with utility thresholds, states to avoid or
    optimisation (they read the states a plan passes)."""
    return (
        setting.goal
        and setting.at_least is None
        and setting.other_state is None
        and not setting.optimize
    )


def before_search(budget: Budget, planner: Planner) -> str:
    """Why a search stopped before its first solve."""
    grounding = " (while grounding its first parts)" if planner.grounding else ""
    return f"{budget.why_stopped()} before the search began{grounding}"


# One proof text for each kind of claim, whichever engine proved it first.
# "None" proven by exhausting a search space: forward (every reachable state,
# or every one that is no dead end), or backward (every state from which a
# goal state is reachable, the initial state not among them).  One text for
# every engine, which raced to it is not said.
SEARCHED = "no goal state is reachable (an exhaustive search proved it)"
GREEDY_PROOF = "a plan found by greedy forward search (not proven shortest)"


def checked(planner: Planner, actions, engine: str, constraints=()) -> Plan:
    """A plan that an engine proposed, checked by its trace (the encodings),
    and by ``questions/questions.lp`` to meet the question ``constraints``
    (those the engine was given as its goal's facts)."""
    plan = Plan(tuple(actions))
    answer = planner.trace(plan)
    if not answer.get("plan", 0):
        raise RuntimeError(f"{engine} proposed {plan}, which the encodings refute")
    terms = [constraint.term for constraint in constraints]
    if terms and not set(terms) <= planner.met(plan, terms):
        raise RuntimeError(f"{engine} proposed {plan}, which the question's encodings refute")
    return plan


def impossible_constraint(planner: Planner, setting: Setting) -> str:
    """Why no plan meets the setting's question constraints, if the grounding
    knows it before any search (a constraint against the goal, or one that
    needs what relaxed reachability excludes); else the empty text."""
    if not setting.goal or not setting.constraints:
        return ""
    found = planner.impossible(sorted(setting.constraints, key=str))
    if not found:
        return ""
    constraint, why = found[0]
    if why == "goal":
        return f"the question's constraint {constraint} contradicts the goal"
    return (
        f"the question's constraint {constraint} needs an action or a fact that is "
        "unreachable even ignoring delete effects"
    )


def too_long(longest: int) -> str:
    """Why no plan exists when every plan has more steps than the question allows."""
    return f"no plan has at most {steps(longest)}, and the question allows no more"


def settled_before(
    planner: Planner,
    setting: Setting,
    budget: Budget,
    max_horizon: int,
    start: int,
    longest: int | None,
) -> SearchResult | None:
    """What a search for a best plan (shortest, cheapest) answers before it
    solves anything, if anything: the budget spent before it began, a goal
    that relaxed reachability excludes, a question constraint that no plan can
    meet, a lower bound beyond the most steps the question allows; else
    None.  (InputError for a negative maximal horizon.)"""
    if max_horizon < 0:
        raise InputError("the maximal horizon must be at least 0")
    if budget.expired() or not planner.prepare(budget, relaxed=True):
        return SearchResult(BOUNDED, horizon=start, proof=before_search(budget, planner))
    if setting.goal and planner.is_fact("unreachable_goal"):
        return SearchResult(
            NONE, horizon=0, proof="the goal is unreachable even ignoring delete effects"
        )
    impossible = impossible_constraint(planner, setting)
    if impossible:
        return SearchResult(NONE, horizon=0, proof=impossible)
    if longest is not None and start > longest:
        return SearchResult(NONE, horizon=longest, proof=too_long(longest))
    return None
