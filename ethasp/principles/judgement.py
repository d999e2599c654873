"""Judgements of plans under ethical principles, and queries in the language L.

Data flow, each step computed once: the plan's trace (the model's planner:
validity, final state, Caused, the final state's utility,
``encodings/planning/trace.lp`` and ``encodings/judgement/judge.lp``); for
principles that compare with reachable states, the state to compare with
(:mod:`ethasp.planning.engines.best_state`); then one small program over the
trace's facts evaluates the language L (``encodings/judgement/language.lp``)
for the formula of every principle chosen (``encodings/principles/``).  This
module reads the ``verdict/2`` atoms back, and keeps the atoms of the
formulas that the reasons read (:mod:`ethasp.reasons.reasons`).

Every judgement has a status.  Deontology and do-no-harm depend on the plan
alone: ``proven``.  Utilitarianism compares the final state with the
reachable states:

* a reachable state better than the final state is found: ``impermissible``,
  ``proven``, at once (the search for a *best* state stops there);
* no reachable state is better, proven (exact reachability, or the upper
  bound): ``permissible``, ``proven``;
* otherwise ``permissible`` as far as searched, ``bounded``: a better
  reachable state may exist.

HERA's principles (``encodings/principles/``, see docs/principles.md) evaluate in the
same program.  Those whose formulas use counterfactual operators (ButFor,
Instrumental, Means, Means2) are given the counterfactual facts of the plan
first, the brave consequences of ``encodings/judgement/counterfactual.lp``
(one more clingo call per plan, exact: ``proven``); avoid-avoidable-harm is
given whether a plan reaches the goal (plan search: ``proven`` when it found
one or proved that none exists, else ``bounded``).  A HERA situation's plan
is judged even where it misses its goal, as HERA does.

In a causal agency model (HERA's CAM) a plan is one action, the agent's
choice; its evaluation is the one program of :mod:`ethasp.principles.causal`,
which computes every world its principles read: every verdict is ``proven``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import clingo
from clorm import unify

from ethasp.errors import InputError
from ethasp.memo import results
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import (
    TRACE_ENCODINGS,
    Answer,
    occurrences,
    solve_configuration,
)
from ethasp.planning.engines.best_state import (
    BOUNDED,
    PROVEN,
    BestReachable,
    ReachableState,
    best_reachable,
    better_state,
    unhandled,
)
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.planning.search import DEFAULT_MAX_HORIZON, FOUND, NONE, find_plan
from ethasp.planning.validation import TRACE_ATOMS, Validation, read_validation, validate
from ethasp.principles import causal
from ethasp.principles.formula import Elements, parse_formula
from ethasp.principles.principle import (
    COUNTERFACTUALS,
    DEFAULT,
    GOAL_REACHABLE,
    Principle,
    formula_needs,
    select_principles,
)
from ethasp.vocabulary import UtilityOfFinal, Verdict

if TYPE_CHECKING:  # ethasp.reasons imports this module
    from ethasp.reasons.explanation import Explanation

# The program that evaluates formulas over a plan's trace.
LANGUAGE = "judgement/language.lp"
RUNS = "judgement/runs.lp"
FORMULAS = ("planning/model.lp", LANGUAGE, RUNS)
# The counterfactual facts of a plan (brave consequences).
COUNTERFACTUAL = ("planning/model.lp", RUNS, "judgement/counterfactual.lp")
QUERY_NAME = clingo.Function("query")

# What reasons read of an evaluation of formulas (its #show statements).
EVIDENCE = "judgement/evidence.lp"


@dataclass
class Judgement:
    """The verdict of one principle on a plan.

    ``permissible`` is the verdict of the principle's formula; ``status`` is
    ``proven`` or ``bounded`` (a verdict against the states searched so far,
    which a better reachable state could overturn), and ``proof`` says why.
    Principles that compare with reachable states report the state compared
    with (``compared``: a better state when impermissible, a best one when
    permissible), each with a plan that reaches it (checked by its trace:
    for an impermissible verdict, :attr:`better_plan`), and
    ``best_reachable`` when a best state was established.
    ``formula`` is the ASP name of the principle's formula (``formula(N,F)``).
    ``explanation`` holds its reasons and words (:mod:`ethasp.reasons.reasons`).
    """

    principle: str
    permissible: bool
    status: str
    proof: str
    formula: str
    best_reachable: BestReachable | None = None
    compared: ReachableState | None = None
    explanation: Explanation | None = None

    @property
    def better_plan(self) -> Plan | None:
        """For an impermissible verdict that a better reachable state decided
        (utilitarianism), a plan that reaches that state: the better plan."""
        if self.permissible or self.compared is None:
            return None
        return self.compared.plan

    def to_json(self) -> dict:
        """The judgement as one JSON object (the single place that builds it)."""
        data: dict = {
            "principle": self.principle,
            "permissible": self.permissible,
            "status": self.status,
            "proof": self.proof,
        }
        if self.compared is not None:
            data["compared_with"] = self.compared.to_json()
        if self.better_plan is not None:
            data["better_plan"] = self.better_plan.to_list()
        if self.best_reachable is not None:
            data["best_reachable"] = self.best_reachable.to_json()
        if self.explanation is not None:
            data.update(self.explanation.to_json())
        return data


@dataclass
class JudgementReport:
    """A plan, its final state (literals ``v`` / ``-v``) and utility, and its
    judgements; ``goal_reached`` is False for a HERA situation's plan that
    misses its goal (judged all the same, as HERA does), and ``unmet_goal``
    the goal literals it misses; ``cost``: the plan's
    cost, in a model with action costs.  For a choice in a causal agency model
    the plan is the action, the final state its world, the utility that of its
    consequences, and ``caused`` the facts of consequences that the action
    causes."""

    plan: Plan
    final_state: list[str]
    utility: int
    judgements: list[Judgement] = field(default_factory=list)
    goal_reached: bool = True
    cost: int | None = None
    caused: list[str] | None = None
    unmet_goal: list[str] = field(default_factory=list)

    def to_json(self) -> dict:
        data = {
            "plan": self.plan.to_list(),
            **({"cost": self.cost} if self.cost is not None else {}),
            "final_state": self.final_state,
            "utility": self.utility,
            "judgements": [judgement.to_json() for judgement in self.judgements],
        }
        if not self.goal_reached:
            data["goal_reached"] = False
            data["unmet_goal"] = self.unmet_goal
        if self.caused is not None:
            data["caused"] = self.caused
        return data


@dataclass
class QueryResult:
    """The truth value of a formula of L for a model and a plan."""

    plan: Plan
    formula: str
    value: bool

    def to_json(self) -> dict:
        return {"plan": self.plan.to_list(), "formula": self.formula, "value": self.value}


def require_plan(model: Model, validation: Validation) -> None:
    """Raise InputError unless the sequence can be judged: a plan of the model,
    or, for a HERA situation, any sequence (its actions are always applicable;
    HERA judges a plan that misses its goal too)."""
    if validation.valid:
        return
    if model.is_situation and validation.failure_step is None:
        return
    raise InputError(f"not a plan: {validation.message(model.naming)}")


_require_plan = require_plan


def check_plan(model: Model, plan: Plan) -> None:
    """Raise InputError unless the plan can be judged in the model: a plan of
    a planning model (:func:`require_plan`), or one action of a causal agency
    model."""
    if model.is_cam:
        causal.chosen_action(model, plan)
    else:
        require_plan(model, validate(model, plan))


@dataclass
class Inputs:
    """What searches established for principles that need it (see
    :data:`ethasp.principles.principle.COUNTERFACTUALS`): the facts for the
    evaluation, and for whether a plan reaches the goal its status and proof."""

    facts: list[clingo.Symbol] = field(default_factory=list)
    status: str = PROVEN
    proof: str = "the principle depends on the plan alone"


def counterfactuals(model: Model, plan: Plan) -> list[clingo.Symbol]:
    """The counterfactual facts of a plan (``counterfactual(F)``, F a
    ``but_for/2`` or ``instrumental/2`` atom that holds): the brave consequences
    of ``encodings/judgement/counterfactual.lp``, computed once per plan."""
    memo = results(model.planner)
    key = ("counterfactuals", plan)
    if key not in memo:
        ctl = model.planner.program(COUNTERFACTUAL, symbols=occurrences(plan))
        config = solve_configuration(ctl)
        config.enum_mode = "brave"
        config.models = "0"
        last: list[clingo.Symbol] = []

        def keep(answer: clingo.Model) -> None:
            last[:] = answer.symbols(shown=True)

        ctl.solve(on_model=keep)
        memo[key] = sorted(
            clingo.Function("counterfactual", [atom.arguments[0]])
            for atom in last
            if atom.name == "witness"
        )
    return memo[key]


def goal_reachable(model: Model, budget: Budget, max_horizon: int) -> tuple[bool | None, str]:
    """Does a plan reach the goal (None: not known within the limits), and why."""
    memo = results(model.planner)
    key = ("goal_reachable", max_horizon)
    if key in memo:
        return memo[key]
    if not model.planner.get("goal", 2):
        return True, "the model has no goal: every state meets it"
    result = find_plan(model, max_horizon, budget=budget)
    if result.status == FOUND:
        answer = (True, f"a plan of {result.horizon} steps reaches the goal")
    elif result.status == NONE:
        answer = (False, f"no plan reaches the goal: {result.proof}")
    else:
        return None, f"whether a plan reaches the goal is not known: {result.proof}"
    memo[key] = answer
    return answer


def _inputs(
    model: Model, plan: Plan, needs: Iterable[str], budget: Budget, max_horizon: int
) -> Inputs:
    inputs = Inputs()
    needs = set(needs)
    if COUNTERFACTUALS in needs:
        inputs.facts += counterfactuals(model, plan)
    if GOAL_REACHABLE in needs:
        reachable, proof = goal_reachable(model, budget, max_horizon)
        if reachable:
            inputs.facts.append(clingo.Function("goal_reachable"))
        inputs.proof = proof
        if reachable is None:
            inputs.status = BOUNDED
            inputs.proof = f"{proof}; judged as if no plan reached it"
    return inputs


def evaluation(
    model: Model,
    plan: Plan,
    principles: Iterable[Principle] = (),
    budget: Budget | None = None,
    max_horizon: int = DEFAULT_MAX_HORIZON,
) -> Answer:
    """The plan's evaluation, computed once per plan by the model's planner: its
    trace (validity, final state, Caused, utility) and the formula of the
    paper's principles that depend on the plan alone and of the ``principles``
    given (those that compare with reachable states excepted), with the atoms
    reasons read (``judgement/evidence.lp``).  Principles that need
    counterfactual facts or the goal's reachability get them first."""
    return _evaluation(model, plan, principles, budget or Budget(), max_horizon)[0]


def _evaluation(
    model: Model, plan: Plan, principles: Iterable[Principle], budget: Budget, max_horizon: int
) -> tuple[Answer, Inputs]:
    if model.is_cam:
        encodings = [p.encoding for p in principles]
        return causal.evaluation(model, plan, encodings), Inputs(
            proof="every world the principle reads was computed"
        )
    chosen = [
        p for p in list(select_principles(DEFAULT)) + list(principles) if not p.reads_alternatives
    ]
    encodings = sorted({p.encoding for p in chosen})
    needs = set().union(*(p.needs for p in chosen))
    if not needs:
        return model.planner.trace(plan, [LANGUAGE, RUNS, EVIDENCE, *encodings]), Inputs()
    inputs = _inputs(model, plan, needs, budget, max_horizon)
    key = ("evaluation", plan, tuple(encodings), tuple(inputs.facts))
    memo = results(model.planner)
    if key not in memo:
        memo[key] = model.planner.solve_program(
            [*list(TRACE_ENCODINGS), LANGUAGE, RUNS, EVIDENCE, *encodings],
            symbols=occurrences(plan) + inputs.facts,
        )
    return memo[key], inputs


def trace_facts(model: Model, plan: Plan) -> list[clingo.Symbol]:
    """A valid plan's trace as atoms: ``occurs/2``, ``final/2``, ``caused/2``."""
    trace = model.planner.trace(plan)
    return occurrences(plan) + trace.select([("final", 2), ("caused", 2)])


def final_utility(model: Model, plan: Plan) -> int:
    """u(s_n) of a plan's final state (``utility_of_final/1`` of judge.lp); of
    a choice in a causal agency model, the utility of its consequences."""
    if model.is_cam:
        return causal.world(model, causal.evaluation(model, plan))[1]
    answer = unify([UtilityOfFinal], model.planner.trace(plan).get("utility_of_final", 1))
    return next(iter(answer.query(UtilityOfFinal).all())).utility


def evaluate(
    model: Model,
    plan: Plan,
    encodings: Sequence[str],
    facts: Iterable = (),
    inputs: Iterable[clingo.Symbol] = (),
) -> Answer:
    """Evaluate formulas of L (given by principle encodings and facts, clingo
    symbols or clorm facts: for instance a state to compare with) over a plan's
    trace: the verdicts and the atoms that reasons read (``judgement/evidence.lp``).
    ``inputs`` are the counterfactual facts and ``goal_reachable``, if needed."""
    symbols = (
        trace_facts(model, plan) + [getattr(fact, "raw", fact) for fact in facts] + list(inputs)
    )
    return model.planner.solve_program(
        [*list(FORMULAS), EVIDENCE, *list(encodings)], symbols=symbols
    )


@dataclass
class _Compared:
    """What the comparing principles are judged against."""

    permissible: bool
    status: str
    proof: str
    state: ReachableState | None
    best: BestReachable | None


def _compare(
    model: Model, plan: Plan, utility: int, budget: Budget, max_horizon: int, want_best: bool
) -> _Compared:
    """Decide whether a reachable state is better than the final state."""
    planner = model.planner
    why = unhandled(planner)
    if why:
        return _Compared(True, BOUNDED, f"{why}; a better reachable state may exist", None, None)
    comparison = better_state(planner, utility, budget, max_horizon)
    best = comparison.best
    if want_best and (best is None or best.status != PROVEN):
        best = best_reachable(planner, budget, max_horizon)
    if comparison.better is not None:
        return _Compared(
            False,
            PROVEN,
            comparison.proof + f", more than the final state's {utility}",
            comparison.better,
            best,
        )
    if comparison.status == PROVEN:
        if best is None or best.found is None:
            # No reachable state is better, and the final state is reachable: it is a best one.
            final = [
                (s.arguments[0], s.arguments[1].name == "true")
                for s in planner.trace(plan).get("final", 2)
            ]
            best = BestReachable(
                PROVEN,
                f"the final state is reachable and {comparison.proof}",
                ReachableState(final, utility, len(plan), plan),
            )
        return _Compared(True, PROVEN, comparison.proof, None, best)
    return _Compared(
        True, BOUNDED, f"{comparison.proof}; a better reachable state may exist", None, best
    )


def judge(
    model: Model,
    plan: Plan,
    principles: Iterable[str] | None = None,
    max_horizon: int = DEFAULT_MAX_HORIZON,
    time_limit: float | None = None,
    budget: Budget | None = None,
    best: bool = False,
) -> JudgementReport:
    """Judge a plan under the principles (the paper's three when None; see
    :func:`ethasp.principles.principle.select_principles`), without explanations.

    ``max_horizon`` and ``budget`` (or ``time_limit``) bound the search for a
    reachable state better than the final state (utilitarianism); with
    ``best`` the search goes on to a best reachable state.  Raises InputError
    if the plan is not a plan.  (:func:`ethasp.reasons.reasons.judge` adds the
    explanations.)
    """
    budget = budget or Budget(time_limit)
    if model.is_cam:
        return _judge_choice(model, plan, principles)
    chosen = select_principles(principles)
    if any(principle.needs for principle in chosen):
        _require_plan(model, validate(model, plan))  # before searching for inputs
    answer, inputs = _evaluation(model, plan, chosen, budget, max_horizon)
    validation = read_validation(plan, answer.select(TRACE_ATOMS), model)
    _require_plan(model, validation)
    utility = final_utility(model, plan)
    compared = None
    facts: list = []
    comparing = [principle for principle in chosen if principle.reads_alternatives]
    if comparing:
        compared = _compare(model, plan, utility, budget, max_horizon, best)
        if compared.state is not None:
            facts = compared.state.asp_facts()
        elif compared.best is not None and compared.best.found is not None:
            facts = compared.best.found.asp_facts()
        comparison = evaluate(model, plan, [p.encoding for p in comparing], facts)
        answer = Answer(answer.get("verdict", 2) + comparison.get("verdict", 2))
    verdicts = {
        str(atom.name.symbol): atom.value == "true"
        for atom in unify([Verdict], answer.get("verdict", 2)).query(Verdict).all()
    }
    judgements = []
    for principle in chosen:
        permissible = verdicts[principle.asp_name]
        if not principle.reads_alternatives:
            if GOAL_REACHABLE in principle.needs:
                status, proof = inputs.status, inputs.proof
            elif principle.needs:
                status, proof = (
                    PROVEN,
                    (
                        "the counterfactual facts of the plan are known "
                        "(every variant of the plan was considered)"
                    ),
                )
            else:
                status, proof = PROVEN, "the principle depends on the plan alone"
            judgements.append(
                Judgement(principle.name, permissible, status, proof, principle.asp_name)
            )
            continue
        assert compared is not None
        if permissible != compared.permissible:
            raise RuntimeError(
                f"{principle.name}: the formula's verdict disagrees with the "
                "comparison of reachable states"
            )
        judgements.append(
            Judgement(
                principle.name,
                permissible,
                compared.status,
                compared.proof,
                principle.asp_name,
                compared.best,
                compared.state,
            )
        )
    return JudgementReport(
        plan,
        validation.final_state,
        utility,
        judgements,
        goal_reached=not validation.unmet_goals,
        cost=validate(model, plan).cost if model.planner.has_costs else None,
        unmet_goal=list(validation.unmet_goals),
    )


def _verdicts(answer: Answer) -> dict[str, bool]:
    return {
        str(atom.name.symbol): atom.value == "true"
        for atom in unify([Verdict], answer.get("verdict", 2)).query(Verdict).all()
    }


def _judge_choice(model: Model, plan: Plan, principles: Iterable[str] | None) -> JudgementReport:
    """Judge the choice of an action in a causal agency model (one program)."""
    chosen = select_principles(principles, causal.CAM)
    answer = causal.evaluation(model, plan, [p.encoding for p in chosen])
    world, utility, caused = causal.world(model, answer)
    verdicts = _verdicts(answer)
    proof = "every world the principle reads was computed"
    judgements = [
        Judgement(p.name, verdicts[p.asp_name], PROVEN, proof, p.asp_name) for p in chosen
    ]
    return JudgementReport(plan, world, utility, judgements, caused=caused)


def query(model: Model, plan: Plan, formula: str) -> QueryResult:
    """Evaluate a formula of L (text, see :mod:`ethasp.principles.formula`) for a
    plan, or for the choice of an action in a causal agency model."""
    parsed = parse_formula(formula, Elements.of_model(model))
    if model.is_cam:
        answer = causal.evaluation(
            model, plan, facts=[fact.raw for fact in parsed.facts(QUERY_NAME)]
        )
        return QueryResult(plan, str(parsed), _verdicts(answer).get("query", False))
    _require_plan(model, validate(model, plan))
    inputs = _inputs(model, plan, formula_needs(parsed.term), Budget(), DEFAULT_MAX_HORIZON)
    if inputs.status != PROVEN:
        raise InputError(f"formula: cannot decide Avoidable: {inputs.proof}")
    answer = evaluate(model, plan, [], parsed.facts(QUERY_NAME), inputs.facts)
    verdicts = unify([Verdict], answer.get("verdict", 2)).query(Verdict).all()
    value = any(str(atom.name.symbol) == "query" and atom.value == "true" for atom in verdicts)
    return QueryResult(plan, str(parsed), value)
