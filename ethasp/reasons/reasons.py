"""Non-contrastive explanations: sufficient and necessary reasons, by clingo.

After Lindner and Moellney (2019), as used in section "Non-Contrastive Moral
Explanations" of the paper: the formula of a principle is taken
propositionally over its atomic subformulas (``encodings/reasons/literals.lp``)
under a background theory (``theory.lp``).  The **sufficient reasons** are
the subset-minimal sets of actual literals that entail the formula's actual
truth value (``sufficient.lp``, a saturation check); the **necessary reasons**
are the minimal hitting sets of the sufficient reasons (``necessary.lp``, the
minimal sets of actual literals a countermodel must flip).  Both are
enumerated lazily, at most ``limit`` of each, by clingo's domain-heuristic
enumeration of subset-minimal answer sets.  The reason an explanation uses is
the most relevant necessary reason, chosen by optimisation
(``relevance.lp``); its words are chosen in ``comparison.lp`` and rendered by
:mod:`ethasp.reasons.words`.

For utilitarianism, whose formula ranges over all reachable states, the
formula is explained against one alternative: a best reachable state other
than the final state (``other_state.lp``, by optimisation; states are never
listed).  The conjunction over all reachable states has the same truth value
as GEq(s_n, s) for that state s; its reasons are those of this one comparison.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable, Sequence

import clingo
from clorm import Raw, unify

from ethasp.errors import InputError
from ethasp.principles.formula import format_literal
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.principles.principle import Principle, select_principles
from ethasp.planning.search import DEFAULT_MAX_HORIZON
from ethasp.principles.utilitarianism import best_reachable
from ethasp.planning.validation import read_validation, validate
from ethasp.principles.judgement import JudgementReport
from ethasp.principles.judgement import judge as judge_verdicts
from ethasp.reasons.explanation import Comparison, Explanation, Labels, Literal
from ethasp.reasons.words import non_contrastive
from ethasp.vocabulary import (ActionLabel, AgentLabel, Alternative, ComparisonAtom, Conj,
                               Conjunct, Explain, FactLabel, Mention, OtherThan,
                               ReasonAtom, Verdict)

DEFAULT_LIMIT = 10

BASE = ("planning/model.lp", "planning/trace.lp", "judgement/language.lp")
REASONS = ("reasons/literals.lp", "reasons/theory.lp", "reasons/evaluate.lp")
ENUMERATION = ("--heuristic=Domain", "--enum-mode=domRec")
# Core-guided optimisation: the relevance criteria count literals, and each
# violated conjunct is a core; model-guided optimisation stalls on large ones.
RELEVANCE = ("--opt-mode=opt", "--opt-strategy=usc")

# The name of the alternative state compared with for utilitarianism (conj/3).
OTHER = clingo.Function("other")


# -- clingo calls ---------------------------------------------------------------

def _solve(model: Model, files: Sequence[str], facts: Iterable, arguments: Sequence[str],
           models: int) -> tuple[list[list[clingo.Symbol]], bool]:
    """Models (shown atoms) of model + encodings + facts, and whether the
    search was exhausted.  ``models`` is clingo's model limit (0: all; with
    optimisation only the last, optimal, model is kept)."""
    ctl = model.ground(files, facts, [*arguments, str(models)])
    found: list[list[clingo.Symbol]] = []
    with ctl.solve(yield_=True) as handle:
        for answer in handle:
            found.append(list(answer.symbols(shown=True)))
        exhausted = handle.get().exhausted
    return found, exhausted


def _literals(symbols: Iterable[clingo.Symbol]) -> list[Literal]:
    atoms = unify([ReasonAtom], symbols).query(ReasonAtom).all()
    return sorted((Literal(a.atom.symbol, a.value == "true") for a in atoms),
                  key=lambda lit: (str(lit.atom), lit.value))


def best_other_state(model: Model, final: Sequence[tuple[clingo.Symbol, str]],
                     max_horizon: int = DEFAULT_MAX_HORIZON,
                     time_limit: float | None = None) -> list[tuple[clingo.Symbol, str]] | None:
    """A best reachable state other than ``final`` (variable, value pairs),
    goal states first among equally good ones; None if there is none.

    :func:`ethasp.utilitarianism.best_reachable` with ``reasons/other_state.lp``;
    when the search is cut (``max_horizon``, ``time_limit``), the best found.
    """
    facts = [OtherThan(variable=Raw(v), value=b) for v, b in final]
    best = best_reachable(model, max_horizon, time_limit, ["reasons/other_state.lp"], facts)
    return best.facts if best.state is not None else None


def _labels(symbols: Iterable[clingo.Symbol]) -> Labels:
    answer = unify([AgentLabel, ActionLabel, FactLabel], symbols)
    labels = Labels()
    for agent in answer.query(AgentLabel).all():
        labels.agent, labels.possessive = agent.name, agent.possessive
    for action in answer.query(ActionLabel).all():
        labels.actions[action.action.symbol] = (action.phrase, action.gerund)
    for fact in answer.query(FactLabel).all():
        labels.facts[(fact.variable.symbol, fact.value == "true")] = fact.phrase
    return labels


def _comparisons(symbols: Iterable[clingo.Symbol]) -> dict[clingo.Symbol, Comparison]:
    answer = unify([Mention, ComparisonAtom], symbols)
    result: dict[clingo.Symbol, Comparison] = {}
    for atom in answer.query(ComparisonAtom).all():
        result[atom.atom.symbol] = Comparison([], [], atom.relation)
    for mention in sorted(answer.query(Mention).all(), key=str):
        side = result[mention.atom.symbol]
        pair = (mention.variable.symbol, mention.value == "true")
        (side.left if mention.side == "left" else side.right).append(pair)
    return result


# -- the API --------------------------------------------------------------------

def explain(model: Model, plan: Plan, principle: str | Principle, limit: int = DEFAULT_LIMIT,
            alternative: Sequence[tuple[clingo.Symbol, str]] | None = None,
            max_horizon: int = DEFAULT_MAX_HORIZON,
            time_limit: float | None = None) -> Explanation:
    """Sufficient and necessary reasons for the verdict of one principle on a
    plan, at most ``limit`` of each, and the explanation text.

    ``alternative`` (variable, value pairs) is the state utilitarianism
    compares with; by default a best reachable state other than the final
    state is searched (``max_horizon``, ``time_limit``).  Raises InputError if
    the plan is not a plan or the principle unknown.
    """
    if limit < 1:
        raise InputError("the reasons limit must be at least 1")
    chosen = principle if isinstance(principle, Principle) else select_principles([principle])[0]
    facts: list = list(plan.facts()) + [Explain(name=Raw(clingo.Function(chosen.asp_name)))]
    compared: list[str] | None = None
    if chosen.reads_alternatives:
        if alternative is None:
            validation = validate(model, plan)  # before a search that may be long
            if not validation.valid:
                raise InputError(f"not a plan: {validation.message(model.naming)}")
            final = [(clingo.parse_term(lit.lstrip("-")), "false" if lit.startswith("-") else "true")
                     for lit in validation.final_state]
            alternative = best_other_state(model, final, max_horizon, time_limit)
        if alternative is not None:
            facts.append(Alternative(name=Raw(OTHER)))
            facts += [Conj(name=Raw(OTHER), variable=Raw(v), value=b) for v, b in alternative]
            compared = sorted(str(v) if b == "true" else f"-{v}" for v, b in alternative)
    base = list(BASE) + [chosen.encoding] + list(REASONS)

    words = ["reasons/comparison.lp", "reasons/labels.lp"]
    best, _ = _solve(model, base + ["reasons/necessary.lp", "reasons/relevance.lp"] + words,
                     facts, RELEVANCE, 0)
    literals: list[Literal] = _literals(best[-1]) if best else []
    if not best:
        # No countermodel: the verdict holds whatever the atoms' values.
        best, _ = _solve(model, base + words, facts, [], 1)
    symbols = best[-1]
    validation = read_validation(plan, symbols)
    if not validation.valid:
        raise InputError(f"not a plan: {validation.message(model.naming)}")
    verdict = unify([Verdict], symbols).query(Verdict).all()
    permissible = any(v.value == "true" for v in verdict)
    conj: dict[clingo.Symbol, list[tuple[clingo.Symbol, str]]] = {}
    for member in unify([Conjunct], symbols).query(Conjunct).all():
        conj.setdefault(member.name.symbol, []).append((member.variable.symbol, member.value))
    for members in conj.values():
        members.sort(key=lambda pair: str(pair[0]))

    def texts(reason: list[Literal]) -> list[str]:
        return [format_literal(lit.term(), conj) for lit in reason]

    necessary, necessary_done = _solve(model, base + ["reasons/necessary.lp"], facts,
                                       ENUMERATION, limit)
    sufficient, sufficient_done = _solve(model, base + ["reasons/shape.lp",
                                                        "reasons/sufficient.lp"], facts,
                                         ENUMERATION, limit)
    explanation = Explanation(
        principle=chosen.name, plan=plan, permissible=permissible,
        sufficient_reasons=[texts(_literals(s)) for s in sufficient],
        necessary_reasons=[texts(_literals(s)) for s in necessary],
        chosen_reason=texts(literals), text="",
        truncated=not (necessary_done and sufficient_done),
        alternative=compared, literals=literals, comparisons=_comparisons(symbols),
        labels=_labels(symbols))
    explanation.text = non_contrastive(explanation)
    return explanation


def judge(model: Model, plan: Plan, principles: Iterable[str] | None = None,
          max_horizon: int = DEFAULT_MAX_HORIZON, time_limit: float | None = None,
          reasons_limit: int | None = DEFAULT_LIMIT) -> JudgementReport:
    """Judge a plan under the principles (all when None) and explain each verdict.

    Each judgement gets an explanation with at most ``reasons_limit``
    sufficient and necessary reasons (none when 0 or None).  Raises InputError
    if the plan is not a plan.
    """
    report = judge_verdicts(model, plan, principles, max_horizon, time_limit)
    chosen = select_principles(principles)
    for principle, judgement in zip(chosen, report.judgements):
        if reasons_limit:
            # An impermissible utilitarian plan is explained against the better
            # state found; otherwise explain() searches a best other state.
            best = judgement.best_reachable
            other = best.facts if best is not None and not judgement.permissible else None
            judgement.explanation = explain(model, plan, principle, reasons_limit, other,
                                            max_horizon, time_limit)
    return report
