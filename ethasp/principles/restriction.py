"""Ethical plan generation: plans of model restrictions (HModels).

The constraint operator Pi x e of the paper (section "Ethical Plan
Generation") restricts plan search so that every plan found, an *HPlan*, is a
plan of the model that satisfies the principle e.  The restriction of each
principle (``encodings/restrictions/``) and of each question constraint
(``encodings/questions/restriction.lp``) compiles into a planning model, the
HModel (:mod:`ethasp.principles.hmodel`); several restrictions together make
one HModel.  Its plans are the HPlans, and plan search in it is plain plan
search, with every engine and every proof: relaxed reachability, exact
layers, the greedy search, mutexes, the loop-free threshold.

Utilitarianism needs the best utility of a reachable state first
(:func:`ethasp.planning.engines.best_state.best_reachable`, exact reachability
or clingo optimisation), proven best or only a lower bound.  Its HModel's
goal asks for a final state at least that good (``goal_utility/1``); when no
goal state is that good, no plan is permissible (proven even where the bound
is only a lower bound); a plan found is proven permissible only where the
best utility is proven, and otherwise reported ``bounded``.

Statuses are those of plan search: ``found`` (a shortest HPlan, permissible
by a proof), ``none`` (proven: no permissible plan exists) or ``bounded``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from ethasp.errors import InputError
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import Constraint, Setting
from ethasp.planning.engines.best_state import PROVEN, BestReachable, best_reachable, unhandled
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan, steps
from ethasp.planning.search import (
    BOUNDED,
    DEFAULT_MAX_HORIZON,
    DEFAULT_SATISFICING_HORIZON,
    FOUND,
    NONE,
    any_plan,
    shortest,
)
from ethasp.principles.hmodel import Restriction, compiled, hmodel, impossible
from ethasp.principles.principle import (
    CAM,
    GROUPS,
    PLAN,
    Principle,
    available_principles,
    select_principles,
)
from ethasp.resources import ENCODINGS

RESTRICTIONS = "restrictions"
# Question constraints that bound the search instead of restricting the model:
# at most N steps (the maximal horizon), a cost below C (the cost bound).
SEARCH_BOUNDS = ("at_most", "cheaper_than")


def chosen_principles(names: Sequence[str], kind: str = PLAN) -> list[Principle]:
    """The principles named for a kind of model (``plan`` or ``cam``), each
    once, each able to restrict plan search; a group (``hera``, ``all``)
    stands for its principles defined for that kind.

    A principle ``NAME`` (``encodings/principles/NAME.lp``) restricts plan
    search with ``encodings/restrictions/NAME.lp``; one without it can judge
    plans but not generate them.  Every principle for causal agency models
    restricts their choices.
    """
    chosen = select_principles(names, kind)
    for principle in chosen:
        if not restricts(principle):
            raise InputError(
                f"principle {principle.name} has no restriction encoding "
                f"({RESTRICTIONS}/{principle.asp_name}.lp): it can judge plans "
                "but not generate them (plans are generated under "
                f"{', '.join(restricting_principles(kind))})"
            )
    return chosen


def restricts(principle: Principle) -> bool:
    """Can the principle restrict plan search (``encodings/restrictions/NAME.lp``)?
    Every principle for causal agency models can: their choices are few, and
    each is judged."""
    if principle.kind == CAM:
        return True
    return (ENCODINGS / RESTRICTIONS / f"{principle.asp_name}.lp").is_file()


def restricting_principles(kind: str = PLAN) -> list[str]:
    """The names of the principles that can restrict plan search (make HPlans
    and contrast plans), in the order of :func:`available_principles`."""
    return [principle.name for principle in available_principles(kind) if restricts(principle)]


def one_restricting_principle(
    name: str, what: str = "contrast plans are made under one of", kind: str = PLAN
) -> str:
    """The one principle a name names, which must restrict plan search: a group
    (``paper``, ``hera``, ``all``) or a principle without a restriction
    encoding is refused with one line naming those that can (``what`` comes
    before their list).  ``kind`` is the kind of model (``cam``: a causal
    agency model)."""
    known = ", ".join(restricting_principles(kind))
    key = name.strip().lower()
    if key == "all" or key in GROUPS:
        raise InputError(f"principle {name!r} names a group, but {what}: {known}")
    principle = select_principles([name], kind)[0]
    if not restricts(principle):
        raise InputError(
            f"principle {principle.name} cannot restrict plan search (it judges "
            f"plans only); {what}: {known}"
        )
    return principle.name


def principle_names(names: Sequence[str]) -> list[str]:
    """The principles named (``do_no_harm`` is read as ``do-no-harm``), each once.

    Raises InputError for an unknown name.
    """
    return [principle.name for principle in chosen_principles(names)]


# -- HPlans ------------------------------------------------------------------


@dataclass
class HPlanResult:
    """The outcome of plan search in the HModel of one or more principles.

    ``plan`` is a shortest plan permissible under every principle in
    ``principles`` (status ``found``), or None; ``plans`` all shortest ones
    when asked for.  ``optimal`` is False for a plan of an any-plan search
    (``satisficing``): permissible, but not proven shortest.  ``status`` is
    ``found``, ``none`` (proven: no plan of the model is permissible under all
    the principles) or ``bounded``; ``proof`` says why.  A ``bounded`` result
    may still have a ``plan``: under utilitarianism, a plan that reaches the
    best utility found, where a better reachable state is not excluded
    (permissible as far as searched).  With utilitarianism, ``best`` is the
    best reachable state found (the plans had to reach its utility), proven
    best or only bounded, and ``utility`` the utility of the plan's final
    state.  With action costs the plan is a cheapest permissible one, of
    ``cost``; a ``bounded`` result may then hold the cheapest permissible
    plan found, not proven cheapest (``optimal`` False).
    """

    status: str
    principles: list[str]
    plan: Plan | None = None
    horizon: int = 0
    proof: str = ""
    plans: list[Plan] = field(default_factory=list)
    best: BestReachable | None = None
    optimal: bool = True
    utility: int | None = None
    cost: int | None = None

    def to_json(self) -> dict:
        data: dict[str, Any] = {
            "status": self.status,
            "plan": self.plan.to_list() if self.plan is not None else None,
            "optimal": self.optimal if self.plan is not None else None,
            **({"cost": self.cost} if self.cost is not None else {}),
            "principles": list(self.principles),
            "horizon": self.horizon,
            "proof": self.proof,
        }
        if self.plans:
            data["plans"] = [plan.to_list() for plan in self.plans]
        if self.utility is not None:
            data["utility"] = self.utility
        if self.best is not None:
            data["best_utility"] = self.best.utility
            data["best_utility_status"] = self.best.status
            data["best_reachable"] = self.best.to_json()
        return data


def derived_variables(model: Model) -> frozenset:
    """The model's derived variables (terms)."""
    return frozenset(atom.arguments[0] for atom in model.planner.get("derived", 1))


def restriction_for(
    model: Model,
    chosen: Sequence[Principle],
    terms: Sequence = (),
    budget: Budget | None = None,
    max_horizon: int = DEFAULT_MAX_HORIZON,
    soft: bool = False,
) -> tuple[Restriction | None, BestReachable | None]:
    """The restriction of the principles and the question constraint terms
    that compile (utilitarianism's best reachable utility searched first),
    and that best reachable state (None without utilitarianism).  The
    restriction is None where no reachable state is valued yet (a limit
    struck).  ``soft``: the goal's items are soft
    (:attr:`ethasp.principles.hmodel.Restriction.soft`), and ``at_most(N)``
    compiles too (``cheaper_than(C)`` never: it bounds the search)."""
    best: BestReachable | None = None
    if any(principle.reads_alternatives for principle in chosen):
        best = best_reachable(model.planner, budget or Budget(), max_horizon)
        if best.utility is None:
            return None, best
    derived = derived_variables(model)
    restriction = Restriction.of(
        [p.asp_name for p in chosen],
        [
            t
            for t in terms
            if compiled(t, derived)
            and (t.name not in SEARCH_BOUNDS or (soft and t.name == "at_most"))
        ],
        best.utility if best is not None else None,
        soft,
    )
    return restriction, best


def _choices(
    model: Model,
    principles: Sequence[str],
    all_plans: bool,
    constraints: Sequence[Constraint],
) -> HPlanResult:
    """The choices of a causal agency model permissible under the principles
    and meeting the constraints: each action is judged, in the model's order
    (:mod:`ethasp.principles.causal`); the first one found, or all with
    ``all_plans``.  Proven either way."""
    from ethasp.principles import causal
    from ethasp.principles.judgement import judge

    names = [principle.name for principle in chosen_principles(principles, CAM)]
    terms = [constraint.term for constraint in constraints]
    found, refused = [], []
    for action in causal.actions(model):
        plan = Plan((action,))
        if terms and not set(terms) <= causal.met_constraints(model, plan, terms):
            continue
        judgements = judge(model, plan, names).judgements if names else []
        forbidding = [j.principle for j in judgements if not j.permissible]
        if forbidding:
            refused.append(f"{model.naming.actions(plan)} under {' and '.join(forbidding)}")
            continue
        found.append(plan)
    under = f" permissible under {' and '.join(names)}" if names else ""
    meeting = " meeting the question" if terms else ""
    if not found:
        what = f"no action{meeting}{under}" if (names or terms) else "no action"
        why = f" (impermissible: {'; '.join(refused)})" if refused else ""
        return HPlanResult(NONE, names, None, 1, f"{what}: every action was judged{why}")
    return HPlanResult(
        FOUND,
        names,
        found[0],
        1,
        f"the first action of the model{meeting}{under} (every action was judged)",
        found if all_plans else [],
        utility=_final_utility(model, found[0]),
    )


def _final_utility(model: Model, plan: Plan) -> int:
    """The utility of the plan's final state (its trace)."""
    from ethasp.principles.judgement import final_utility

    return final_utility(model, plan)


def plan_with_principles(
    model: Model,
    principles: Sequence[str],
    max_horizon: int | None = None,
    time_limit: float | None = None,
    all_plans: bool = False,
    constraints: Sequence[Constraint] = (),
    budget: Budget | None = None,
    satisficing: bool = False,
    max_length: int | None = None,
    below: int | None = None,
) -> HPlanResult:
    """A shortest HPlan: a plan of the model permissible under all the principles.

    ``constraints`` (of contrastive questions) restrict the HModel further;
    ``max_length``: they allow no plan of more steps (``at_most(N)``), so a
    search that refutes every horizon up to it proves that there is none;
    ``below`` (a model with action costs): they allow no plan that costs
    this much or more (``cheaper_than(C)``).
    ``budget`` (or else ``time_limit``) bounds the searches.  With
    ``satisficing``, an HPlan found fast and not proven shortest (an any-plan
    search, :func:`ethasp.planning.search.any_plan`): the restrictions apply
    all the same, so it is permissible by construction.  ``max_horizon``
    defaults to 64, or 256 with ``satisficing``.
    """
    if model.is_cam:
        return _choices(model, principles, all_plans, constraints)
    if satisficing and all_plans:
        raise InputError("all shortest plans cannot be listed by an any-plan search (satisficing)")
    if max_horizon is None:
        max_horizon = DEFAULT_SATISFICING_HORIZON if satisficing else DEFAULT_MAX_HORIZON
    budget = budget or Budget(time_limit)
    chosen = chosen_principles(principles)
    names = [principle.name for principle in chosen]
    best: BestReachable | None = None
    plans = "plan meeting the question" if constraints else "plan"
    under = " and ".join(names)
    permissible = f" permissible under {under}" if names else ""
    if not names:  # the question alone: "no plan meets the question"
        plans_are = "plan meets the question" if constraints else "plan exists"
        if below is not None and not constraints:
            plans_are = f"plan costs less than {below}"
    else:
        plans_are = f"{plans} is{permissible}"
    if any(principle.reads_alternatives for principle in chosen):
        why = unhandled(model.planner)
        if why:
            return HPlanResult(BOUNDED, names, proof=f"no reachable state valued: {why}")
    terms = [constraint.term for constraint in constraints]
    restriction, best = restriction_for(model, chosen, terms, budget, max_horizon)
    if restriction is None:
        assert best is not None
        return HPlanResult(
            BOUNDED,
            names,
            horizon=best.searched,
            best=best,
            proof=f"no reachable state valued yet: {best.proof}",
        )
    if budget.expired() and not restriction.empty:
        # (The HModel's compilation, a program over the whole ground model, is
        # not begun once the limit struck.)
        return HPlanResult(
            BOUNDED,
            names,
            proof=f"no {plans}{permissible} found: {budget.why_stopped()} before the search began",
            best=best,
        )
    # The HModel: a planning model of its own, planned for by every engine.
    derived = derived_variables(model)
    restricted = model if restriction.empty else hmodel(model, restriction)
    against = impossible(model, restriction) if restriction.terms else []
    if against:
        # Known before any search (a constraint against the goal, or one that
        # needs what relaxed reachability excludes).
        term, why = against[0]
        shown = model.naming.constraint(term)
        reason = (
            f"the question's constraint {shown} contradicts the goal"
            if why == "goal"
            else f"the question's constraint {shown} needs an action or a fact that is "
            "unreachable even ignoring delete effects"
        )
        return HPlanResult(NONE, names, None, 0, f"no {plans_are}: {reason}", best=best)
    planner = restricted.planner
    rest = [t for t in terms if not compiled(t, derived)]
    # Constraints that no HModel writes are imposed on its search (in ASP).
    setting = Setting(constraints=frozenset(planner.question(rest)) if rest else frozenset())
    task = f"plan search under {under}" if names else "plan search"
    if satisficing and below is not None:
        raise InputError("a cheaper plan is searched for with its cost proven, not --satisficing")
    result = (
        any_plan(planner, setting, budget, max_horizon, task=task, longest=max_length)
        if satisficing
        else shortest(
            planner,
            setting,
            budget,
            max_horizon,
            all_plans=all_plans,
            task=task,
            longest=max_length,
            threads=restricted is model,
            below=below,
        )
    )
    found = result.plan if result.status == FOUND else None
    if found is not None and best is not None and best.status != PROVEN:
        # A plan reaching the best utility found is no proof: a better state may
        # exist.  The plan is reported, bounded: permissible as far as searched.
        return HPlanResult(
            BOUNDED,
            names,
            result.plan,
            result.horizon,
            best=best,
            optimal=result.optimal,
            utility=_final_utility(model, found),
            cost=result.cost,
            proof=f"a plan of {steps(len(found))} reaches utility {best.utility}, but a "
            f"better reachable state is not excluded ({best.proof})",
        )
    if found is not None:
        least = "shortest" if result.cost is None else "cheapest"
        kind = f"a {least} {plans}" if result.optimal else f"a {plans}"
        return HPlanResult(
            FOUND,
            names,
            result.plan,
            result.horizon,
            f"{kind}{permissible}: {result.proof}",
            result.plans,
            best,
            optimal=result.optimal,
            utility=_final_utility(model, found),
            cost=result.cost,
        )
    if result.status == BOUNDED and result.plan is not None:
        # A model with action costs: the cheapest HPlan found, not proven cheapest.
        return HPlanResult(
            BOUNDED,
            names,
            result.plan,
            result.horizon,
            f"a {plans}{permissible}, not proven cheapest: {result.proof}",
            best=best,
            optimal=False,
            utility=_final_utility(model, result.plan),
            cost=result.cost,
        )
    if result.status == NONE:
        # With utilitarianism the search asked for utility >= best.utility, a lower
        # bound of the best reachable utility: no such goal state, no permissible plan.
        return HPlanResult(
            NONE,
            names,
            None,
            result.horizon,
            result.proof
            if result.proof.startswith(f"no {plans_are}")
            else f"no {plans_are}: {result.proof}",
            best=best,
        )
    return HPlanResult(
        BOUNDED,
        names,
        None,
        result.horizon,
        f"no {plans}{permissible} found: {result.proof}",
        best=best,
    )


# -- what principles cost --------------------------------------------------------


@dataclass
class PrincipleCost:
    """What obeying principles costs, in a model with action costs: the cost of
    a cheapest permissible plan (``permissible``) minus that of a cheapest
    plan (``cheapest``).  ``status``: ``proven`` (both are proven cheapest),
    ``none`` (no plan is permissible: the principles forbid every plan, or no
    plan exists at all) or ``bounded`` (one of them is not proven, or not
    found); ``proof`` says which."""

    principles: list[str]
    status: str
    permissible: int | None
    cheapest: int | None
    proof: str

    @property
    def value(self) -> int | None:
        if self.status != PROVEN or self.permissible is None or self.cheapest is None:
            return None
        return self.permissible - self.cheapest

    def to_json(self) -> dict:
        return {
            "status": self.status,
            "cost": self.value,
            "permissible_plan_cost": self.permissible,
            "cheapest_plan_cost": self.cheapest,
            "proof": self.proof,
        }

    def text(self) -> str:
        """One line: "what deontology costs: 4 (...)"."""
        under = " and ".join(self.principles)
        if self.value is not None:
            return (
                f"what {under} costs: {self.value} (a cheapest permissible plan costs "
                f"{self.permissible}, a cheapest plan {self.cheapest}; both proven)"
            )
        return f"what {under} costs: {self.status}: {self.proof}"


def principle_cost(
    model: Model,
    hplan: HPlanResult,
    max_horizon: int | None = None,
    budget: Budget | None = None,
) -> PrincipleCost:
    """What the principles of ``hplan`` (a result of :func:`plan_with_principles`)
    cost in a model with action costs: the cost of the cheapest permissible
    plan minus that of the cheapest plan, both proven by plan search
    (:func:`ethasp.planning.search.find_plan` for the latter)."""
    from ethasp.planning.search import find_plan

    if not model.planner.has_costs:
        raise InputError("the model has no action costs (cost/2): its principles cost nothing")
    cheapest = find_plan(model, max_horizon, budget=budget)
    if cheapest.status == NONE:
        return PrincipleCost(
            hplan.principles, NONE, None, None, f"no plan exists at all: {cheapest.proof}"
        )
    best = cheapest.cost if cheapest.status == FOUND else None
    if hplan.status == NONE:
        return PrincipleCost(
            hplan.principles,
            NONE,
            None,
            best,
            f"no plan is permissible, though plans exist: {hplan.proof}",
        )
    permissible = hplan.cost if hplan.status == FOUND else None
    if best is not None and permissible is not None:
        return PrincipleCost(
            hplan.principles, PROVEN, permissible, best, f"{hplan.proof}; {cheapest.proof}"
        )
    unproven = []
    if permissible is None:
        unproven.append(f"the cheapest permissible plan is not proven ({hplan.proof})")
    if best is None:
        unproven.append(f"the cheapest plan is not proven ({cheapest.proof})")
    return PrincipleCost(
        hplan.principles,
        BOUNDED,
        hplan.cost,
        cheapest.cost,
        "; ".join(unproven),
    )
