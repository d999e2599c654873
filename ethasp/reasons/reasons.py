"""Non-contrastive explanations: sufficient and necessary reasons, by clingo.

After Lindner and Moellney (2019), as used in section "Non-Contrastive Moral
Explanations" of the paper: the formula of a principle is taken
propositionally over its atomic subformulas (``encodings/reasons/literals.lp``)
under a background theory (``theory.lp``).  The **sufficient reasons** are
the subset-minimal sets of actual literals that entail the formula's actual
truth value (``sufficient.lp``); the **necessary reasons** are the minimal
hitting sets of the sufficient reasons (``necessary.lp``, the minimal sets of
actual literals a countermodel must flip).  Both are enumerated lazily, at
most ``limit`` of each, by clingo's domain-heuristic enumeration of
subset-minimal answer sets.  The reason an explanation uses is the most
relevant necessary reason, chosen by optimisation (``relevance.lp``); its
words are chosen in ``comparison.lp`` and rendered by :mod:`ethasp.reasons.words`.

Data flow: the formula is evaluated once over the plan's trace
(:func:`ethasp.principles.judgement.evaluate`); the reasons' programs read
only that evaluation's atoms (the formula, its members and the actual truth
values: :data:`ethasp.principles.judgement.EVIDENCE`), never the model or the
plan again, so their size is that of the formula.  Two programs per
principle and plan: necessary reasons (optimised for the relevant one, then
enumerated, in one control) and sufficient reasons with the words' choices.

For utilitarianism, whose formula ranges over all reachable states, the
formula is explained against one alternative: the better state that decided
an impermissible verdict, or a best reachable state other than the final
state (:func:`ethasp.planning.engines.best_state.best_reachable`, searched once
per model and state).  The conjunction over all reachable states has the
same truth value as GEq(s_n, s) for that state s; its reasons are those of
this one comparison.
"""

from __future__ import annotations

from collections.abc import Iterable

import clingo
from clorm import unify

from ethasp import vocabulary  # (its predicates are made when first read)
from ethasp.errors import InputError
from ethasp.memo import results
from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import GroundingStopped, solve_configuration
from ethasp.planning.engines.best_state import ReachableState, best_reachable, unhandled
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.planning.search import DEFAULT_MAX_HORIZON
from ethasp.principles.causal import model_kind
from ethasp.principles.formula import format_literal
from ethasp.principles.judgement import (
    JudgementReport,
    check_plan,
    evaluate,
    evaluation,
)
from ethasp.principles.judgement import judge as judge_verdicts
from ethasp.principles.principle import Principle, select_principles
from ethasp.reasons import DEFAULT_LIMIT
from ethasp.reasons.explanation import Comparison, Explanation, Labels, Literal
from ethasp.reasons.words import non_contrastive

REASONS = ("reasons/literals.lp", "reasons/theory.lp", "reasons/evaluate.lp")
NECESSARY = (*REASONS, "reasons/necessary.lp", "reasons/relevance.lp")
SUFFICIENT = (*REASONS, "reasons/shape.lp", "reasons/sufficient.lp", "reasons/comparison.lp")
INUS = (*REASONS, "reasons/shape.lp", "reasons/evaluate_copies.lp", "reasons/inus.lp")
# Core-guided optimisation for the relevant reason: the relevance criteria count
# literals, and each violated conjunct is a core; model-guided optimisation
# stalls on large ones.  Domain heuristics make enumerations subset-minimal.
OPTIONS = ("--heuristic=Domain", "--opt-strategy=usc")

# The name of the alternative state compared with for utilitarianism (conj/3).
OTHER = clingo.Function("other")

LABELS = (("agent_label", 2), ("action_label", 3), ("fact_label", 3), ("patient_label", 2))

# The atoms of an evaluation that the reasons' programs read (judgement/evidence.lp).
EVIDENCE = (
    ("formula", 2),
    ("member", 2),
    ("conj", 3),
    ("conj_worth", 2),
    ("term_value", 2),
    ("verdict", 2),
    ("satisfied", 1),
    ("weight", 2),
)


def _literals(symbols: Iterable[clingo.Symbol]) -> list[Literal]:
    atoms = unify([vocabulary.ReasonAtom], symbols).query(vocabulary.ReasonAtom).all()
    return sorted(
        (Literal(a.atom.symbol, a.value == "true") for a in atoms),
        key=lambda lit: (str(lit.atom), lit.value),
    )


def _actual(ctl: clingo.Control) -> frozenset[Literal]:
    """The atoms of the explained formula with their values for the plan
    (``actual_value/2`` of ``reasons/literals.lp``, facts once grounded)."""
    facts = [
        atom.symbol for atom in ctl.symbolic_atoms.by_signature("actual_value", 2) if atom.is_fact
    ]
    atoms = unify([vocabulary.ActualValue], facts).query(vocabulary.ActualValue).all()
    return frozenset(Literal(a.atom.symbol, a.value == "true") for a in atoms)


def _kind(literal: Literal) -> tuple:
    """What a literal says, without what of: its operator, its value and, for
    Good/Bad/Neutral, whether it is about an action or a fact."""
    atom = literal.atom
    element = atom.arguments[0].name if atom.name in ("good", "bad", "neutral") else ""
    return atom.name, literal.value, element


def _answers(
    ctl: clingo.Control, budget: Budget
) -> tuple[list[list[clingo.Symbol]], clingo.SolveResult | None]:
    """The answer sets of a solve (shown atoms, in the order clingo finds
    them), and its result where it ended by itself: None where the budget ran
    out first (the solve is then cancelled; the answer sets found so far)."""
    found: list[list[clingo.Symbol]] = []
    with ctl.solve(yield_=True, async_=True) as handle:
        while True:
            handle.resume()
            if not budget.wait(handle):
                return found, None
            answer = handle.model()
            if answer is None:
                return found, handle.get()
            found.append(list(answer.symbols(shown=True)))


def _enumerate(
    ctl: clingo.Control, limit: int, budget: Budget
) -> tuple[list[list[clingo.Symbol]], bool]:
    """Up to ``limit`` subset-minimal answer sets (shown atoms) and whether
    they are all there are.  One more is asked for: clingo does not say
    ``exhausted`` when it stops at its model limit, so only an answer set
    beyond the ``limit`` proves that more exist (nor are they all where the
    budget ran out first)."""
    config = solve_configuration(ctl)
    config.opt_mode = "ignore"
    config.enum_mode = "domRec"
    config.models = str(limit + 1)
    found, result = _answers(ctl, budget)
    return found[:limit], result is not None and len(found) <= limit


class _Cut(Exception):
    """The budget ran out before the relevant reason was proven optimal."""


# The conflicts within which INUS reasons are searched (the same effort on
# every run): beyond them the list is cut short (more may exist).  The
# saturation of inus.lp over formulas that are not read-once can take
# minutes for a few reasons more.
INUS_CONFLICTS = 20_000


def _inus(
    model: Model,
    program: str,
    sufficient: list[list[clingo.Symbol]],
    limit: int,
    budget: Budget,
) -> tuple[list[list[Literal]], bool]:
    """Up to ``limit`` INUS reasons (``reasons/inus.lp``, one answer set each,
    projected on their literals) of the given sufficient reasons, and whether
    they are all there are (not where :data:`INUS_CONFLICTS` or the budget
    ran out first)."""
    members = "".join(
        f"sufficient_member({number},{literal.atom}).\n"
        for number, reason in enumerate(sufficient, 1)
        for literal in _literals(reason)
    )
    if not members:
        return [], True
    try:
        ctl = model.planner.program(
            INUS, program + members, ("--project=show",), model=False, budget=budget
        )
    except GroundingStopped:
        return [], False
    config = solve_configuration(ctl)
    config.models = str(limit + 1)
    config.solve_limit = str(INUS_CONFLICTS)
    answers, result = _answers(ctl, budget)
    exhausted = result is not None and result.exhausted
    found = [_literals(answer) for answer in answers]
    found.sort(key=lambda reason: (len(reason), [(str(lit.atom), lit.value) for lit in reason]))
    # (Past the conflicts, the search stops: more may exist.)
    return found[:limit], len(found) <= limit and exhausted


def _optimum(ctl: clingo.Control, budget: Budget) -> tuple[list[clingo.Symbol] | None, bool]:
    """The shown atoms of an optimal answer set (None if there is none), and
    whether the search ended by itself (False where the budget ran out before
    the optimum was proven: then no answer set is given)."""
    config = solve_configuration(ctl)
    config.opt_mode = "opt"
    config.models = "0"
    found, result = _answers(ctl, budget)
    if result is None:
        return None, False
    return (found[-1] if found else None), True


def _labels(symbols: Iterable[clingo.Symbol]) -> Labels:
    answer = unify(
        [
            vocabulary.AgentLabel,
            vocabulary.ActionLabel,
            vocabulary.FactLabel,
            vocabulary.PatientLabel,
        ],
        symbols,
    )
    labels = Labels()
    for agent in answer.query(vocabulary.AgentLabel).all():
        labels.agent, labels.possessive = agent.name, agent.possessive
    for action in answer.query(vocabulary.ActionLabel).all():
        labels.actions[action.action.symbol] = (action.phrase, action.gerund)
    for fact in answer.query(vocabulary.FactLabel).all():
        labels.facts[(fact.variable.symbol, fact.value == "true")] = fact.phrase
    for patient in answer.query(vocabulary.PatientLabel).all():
        labels.patients[patient.patient.symbol] = patient.phrase
    return labels


def _comparisons(symbols: Iterable[clingo.Symbol]) -> dict[clingo.Symbol, Comparison]:
    answer = unify([vocabulary.Mention, vocabulary.ComparisonAtom], symbols)
    result: dict[clingo.Symbol, Comparison] = {}
    for atom in answer.query(vocabulary.ComparisonAtom).all():
        result[atom.atom.symbol] = Comparison([], [], atom.relation)
    for mention in sorted(answer.query(vocabulary.Mention).all(), key=str):
        side = result[mention.atom.symbol]
        pair = (mention.variable.symbol, mention.value == "true")
        (side.left if mention.side == "left" else side.right).append(pair)
    return result


# -- the API --------------------------------------------------------------------


def _labels_of(model: Model) -> Labels:
    planner = model.planner
    labels = _labels([symbol for signature in LABELS for symbol in planner.get(*signature)])
    labels.naming = model.naming
    return labels


def model_labels(model: Model) -> Labels:
    """The model's label facts (for words about its actions and facts)."""
    return _labels_of(model)


def other_state(
    model: Model, plan: Plan, budget: Budget, max_horizon: int = DEFAULT_MAX_HORIZON
) -> ReachableState | None:
    """A best reachable state that differs from the plan's final state in a
    morally valued variable (one whose two values are worth differently), so
    that the comparison speaks of what matters; else a best state that differs
    at all.  Goal states first among equally good ones; None if there is none
    or none was found."""
    planner = model.planner
    if unhandled(planner):
        return None
    final = [
        (s.arguments[0], s.arguments[1].name == "true") for s in planner.trace(plan).get("final", 2)
    ]
    weights = planner.fact_weights()
    valued = [(v, b) for v, b in final if weights.get((v, True), 0) != weights.get((v, False), 0)]
    if valued:
        best = best_reachable(planner, budget, max_horizon, other_than=valued)
        if best.found is not None:
            return best.found
    return best_reachable(planner, budget, max_horizon, other_than=final).found


def explain(
    model: Model,
    plan: Plan,
    principle: str | Principle,
    limit: int = DEFAULT_LIMIT,
    alternative: ReachableState | None = None,
    max_horizon: int = DEFAULT_MAX_HORIZON,
    time_limit: float | None = None,
    budget: Budget | None = None,
) -> Explanation:
    """Sufficient and necessary reasons for the verdict of one principle on a
    plan, at most ``limit`` of each, and the explanation text.

    ``alternative`` is the state a comparing principle (utilitarianism)
    compares with; by default a best reachable state other than the final
    state (searched once per model).  Raises InputError if the plan is not a
    plan or the principle unknown.
    """
    if limit < 1:
        raise InputError("the reasons limit must be at least 1")
    budget = budget or Budget(time_limit)
    chosen = (
        principle
        if isinstance(principle, Principle)
        else select_principles([principle], model_kind(model))[0]
    )
    check_plan(model, plan)
    key = (
        "explain",
        plan,
        chosen.asp_name,
        limit,
        None if alternative is None else tuple(alternative.facts),
    )
    memo = results(model.planner)
    if key in memo:
        return memo[key]
    facts: list = []
    compared: list[str] | None = None
    if chosen.reads_alternatives:
        if alternative is None:
            alternative = other_state(model, plan, budget, max_horizon)
        if alternative is not None:
            facts = alternative.asp_facts(OTHER)
            compared = alternative.literals
    answer = (
        evaluate(model, plan, [chosen.encoding], facts)
        if chosen.reads_alternatives
        else evaluation(model, plan, [chosen], budget, max_horizon)
    )
    program = (
        answer.text(EVIDENCE)
        + model.planner.vocabulary_text(LABELS)
        + f"explain({chosen.asp_name}).\n"
    )
    # Each program and solve under the budget: where it runs out, the reasons
    # found so far, said to be cut short (and not kept for later calls).
    actual: frozenset[Literal] = frozenset()
    best: list[clingo.Symbol] | None = None
    necessary: list[list[clingo.Symbol]] = []
    sufficient: list[list[clingo.Symbol]] = []
    inus: list[list[Literal]] = []
    necessary_done = sufficient_done = inus_done = False
    stopped = False
    try:
        necessary_ctl = model.planner.program(
            NECESSARY, program, OPTIONS, model=False, budget=budget
        )
        actual = _actual(necessary_ctl)
        best, proven = _optimum(necessary_ctl, budget)
        if not proven:
            raise _Cut()
        necessary, necessary_done = (
            _enumerate(necessary_ctl, limit, budget) if best is not None else ([], True)
        )
        sufficient_ctl = model.planner.program(
            SUFFICIENT, program, OPTIONS, model=False, budget=budget
        )
        # One more than the limit allows: whether a single sufficient reason is the only one.
        sufficient, sufficient_done = _enumerate(sufficient_ctl, max(limit, 2), budget)
        if len(sufficient) > limit:
            sufficient, sufficient_done = sufficient[:limit], False
        inus, inus_done = _inus(model, program, sufficient, limit, budget)
        stopped = budget.expired() and not (necessary_done and sufficient_done and inus_done)
    except (GroundingStopped, _Cut):
        stopped = True
    inus_done = inus_done and sufficient_done
    literals = _literals(best) if best is not None else []
    words = sufficient[0] if sufficient else []
    # The words say a reason whole when it is the only sufficient reason and its
    # literals are all of one kind ("none of his 8 actions is inherently bad"):
    # each of its literals is then a necessary reason, and naming one alone
    # would read as if the others did not count.
    spoken = literals
    if sufficient_done and len(sufficient) == 1:
        whole = _literals(sufficient[0])
        if len(whole) > 1 and len({_kind(literal) for literal in whole}) == 1:
            spoken = whole
    permissible = any(
        v.value == "true" and str(v.name.symbol) == chosen.asp_name
        for v in unify([vocabulary.Verdict], answer.get("verdict", 2))
        .query(vocabulary.Verdict)
        .all()
    )
    conj: dict[clingo.Symbol, list[tuple[clingo.Symbol, str]]] = {}
    for member in unify([vocabulary.Conjunct], words).query(vocabulary.Conjunct).all():
        conj.setdefault(member.name.symbol, []).append((member.variable.symbol, member.value))
    for members in conj.values():
        members.sort(key=lambda pair: str(pair[0]))

    # Reasons share most of their literals: each literal is put into words once.
    said: dict[Literal, str] = {}

    def text(literal: Literal) -> str:
        if literal not in said:
            said[literal] = format_literal(literal.term(), conj, model.naming)
        return said[literal]

    def texts(reason: list[Literal]) -> list[str]:
        return [text(literal) for literal in reason]

    explanation = Explanation(
        principle=chosen.name,
        plan=plan,
        permissible=permissible,
        sufficient_reasons=[texts(_literals(s)) for s in sufficient],
        necessary_reasons=[texts(_literals(s)) for s in necessary],
        chosen_reason=texts(literals),
        text="",
        truncated=not (necessary_done and sufficient_done and inus_done),
        necessary_truncated=not necessary_done,
        sufficient_truncated=not sufficient_done,
        inus_reasons=[texts(reason) for reason in inus],
        inus_truncated=not inus_done,
        alternative=compared,
        literals=spoken,
        spoken_reason=texts(spoken),
        actual=actual,
        comparisons=_comparisons(words),
        labels=_labels_of(model),
        conjunctions=conj,
    )
    if stopped:
        explanation.cut = budget.why_stopped()
    explanation.text = non_contrastive(explanation)
    if not stopped:
        memo[key] = explanation
    return explanation


def judge(
    model: Model,
    plan: Plan,
    principles: Iterable[str] | None = None,
    max_horizon: int = DEFAULT_MAX_HORIZON,
    time_limit: float | None = None,
    reasons_limit: int | None = DEFAULT_LIMIT,
    budget: Budget | None = None,
    best: bool = False,
) -> JudgementReport:
    """Judge a plan under the principles (the paper's three when None) and
    explain each verdict.

    Each judgement gets an explanation with at most ``reasons_limit``
    sufficient and necessary reasons (none when 0 or None).  Raises InputError
    if the plan is not a plan.
    """
    budget = budget or Budget(time_limit)
    report = judge_verdicts(model, plan, principles, max_horizon, budget=budget, best=best)
    chosen = select_principles(principles, model_kind(model))
    for principle, judgement in zip(chosen, report.judgements, strict=True):
        if reasons_limit:  # (cut short where the budget runs out: explain)
            # An impermissible utilitarian plan is explained against the better
            # state that decided it; a permissible one against a best other state.
            other = judgement.compared if not judgement.permissible else None
            judgement.explanation = explain(
                model, plan, principle, reasons_limit, other, max_horizon, budget=budget
            )
    return report
