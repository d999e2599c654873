"""Conflicts in words: why no plan is permissible, and what a permissible plan
can still reach.

For each minimal conflict (:mod:`ethasp.principles.conflict`) the words say
whether some plan reaches it without the principles: then a shortest such
plan is judged, in the model whose goal is the conflict's goal facts, and
its reason tells why it is impermissible ("a shortest plan that does, pull
the lever, is impermissible because this way the death of the one person is
caused by the man's action"); that plan is an example, not a claim about
every plan (the conflict's proof is).  Otherwise no plan reaches the
conflict at all, whatever the principles.  Each goal subset is named with a
shortest permissible plan that reaches it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import clingo

from ethasp.planning.budget import Budget
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.planning.search import DEFAULT_MAX_HORIZON, FOUND
from ethasp.principles.conflict import Conflicts
from ethasp.principles.goal_items import GoalItems, Item
from ethasp.principles.repair import Change, repaired_model
from ethasp.reasons import words
from ethasp.reasons.explanation import Labels
from ethasp.reasons.reasons import judge, model_labels


@dataclass
class Example:
    """A conflict's example: a shortest plan that reaches it without the
    principles (None: no plan reaches it at all), and the principle that
    forbids it, with the reason in words."""

    plan: Plan | None
    principle: str = ""
    reason: str = ""


@dataclass
class ConflictWords:
    """The conflicts in words: ``text``, and an example per conflict."""

    text: str
    examples: list[Example] = field(default_factory=list)


def item_phrase(labels: Labels, item: Item) -> str:
    """What a plan does to meet an item: "end with the decision", "include
    pulling a lever"."""
    fact = item.fact
    if fact is not None:
        value = clingo.Function("true" if fact[1] else "false")
        return words.constraint_phrase(labels, clingo.Function("ends", [fact[0], value]))
    return words.constraint_phrase(labels, item.term)


def items_phrase(labels: Labels, items: Sequence[Item]) -> str:
    """What a plan does to meet the items: the goal facts in one phrase ("end
    with the decision and the fact safe"), then the constraints."""
    facts = [item.fact for item in items if item.fact is not None]
    phrases = []
    if facts:
        phrases.append(
            "end with " + words.join([words.fact_phrase(labels, v, b) for v, b in facts])
        )
    phrases += [item_phrase(labels, item) for item in items if item.fact is None]
    return words.join(phrases)


def explain_conflicts(
    model: Model,
    conflicts: Conflicts,
    terms: Sequence[clingo.Symbol] = (),
    max_horizon: int = DEFAULT_MAX_HORIZON,
    budget: Budget | None = None,
    reasons_limit: int = 3,
) -> ConflictWords:
    """The words of the conflicts (see the module docstring); ``terms`` are the
    question constraints the conflicts were computed with."""
    budget = budget or Budget()
    labels = model_labels(model)
    under = words.join([words.principle_phrase(p) for p in conflicts.principles])
    none = "No plan meeting the questions is" if terms else "No plan is"
    sentences = [f"{none} permissible under {under}."] if conflicts.conflicts else []
    examples = []
    unrestricted: GoalItems | None = None
    for conflict in conflicts.conflicts:
        if unrestricted is None:
            unrestricted = GoalItems(model, [], terms, budget, max_horizon)
        example = _example(
            model, unrestricted, conflict, conflicts, budget, max_horizon, reasons_limit
        )
        examples.append(example)
        sentences.append(_conflict_sentence(labels, conflict, example))
    if conflicts.conflicts_truncated and conflicts.conflicts:
        sentences.append("More conflicts may exist.")
    for subset in conflicts.goal_subsets:
        sentences.append(
            _subset_sentence(labels, subset.items, subset.plan, bool(conflicts.conflicts))
        )
    if conflicts.status != "proven":
        sentences.append(f"(As far as searched: {conflicts.proof}.)")
    return ConflictWords(" ".join(sentences), examples)


def _conflict_sentence(labels: Labels, conflict: list[Item], example: Example) -> str:
    if conflict:
        opening = f"No permissible plan can {items_phrase(labels, conflict)}"
        shortest = "The shortest plan that does"
    else:
        opening = "Even without a goal, every way the world may go is impermissible"
        shortest = "The shortest plan"
    if example.plan is None:
        return f"{opening}; no plan at all can, whatever the principle."
    if not example.reason:
        return f"{opening}."
    doing = words.plan_phrase(labels, example.plan)
    return (
        f"{opening}. {shortest} ({doing}) is impermissible under "
        f"{words.principle_phrase(example.principle)} because {example.reason}."
    )


def _subset_sentence(labels: Labels, items: list[Item], plan: Plan | None, some: bool) -> str:
    doing = words.plan_phrase(labels, plan) if plan is not None else "(none found in time)"
    if not items:
        return f"A permissible plan reaches none of the goal: {doing}."
    whole = "" if some else " (the whole goal)"
    return f"A permissible plan can {items_phrase(labels, items)}{whole}: {doing}."


def _example(
    model: Model,
    unrestricted: GoalItems,
    conflict: list[Item],
    conflicts: Conflicts,
    budget: Budget,
    max_horizon: int,
    reasons_limit: int,
) -> Example:
    """A shortest plan that reaches the conflict without the principles, and
    why the first principle that forbids it does."""
    index = {item.term: number for number, item in enumerate(unrestricted.items)}
    numbers = [index[item.term] for item in conflict if item.term in index]
    result = unrestricted.shortest(numbers)
    if result.status != FOUND:
        return Example(None if result.status == "none" else Plan(()), "", "")
    plan = result.plan
    kept = {item.term for item in conflict}
    drops = [
        Change(clingo.Function("drop", list(item.term.arguments)), 0)
        for item in conflicts.items
        if item.is_goal_fact and item.term not in kept
    ]
    reduced = repaired_model(model, drops)
    report = judge(
        reduced, plan, conflicts.principles, max_horizon, reasons_limit=reasons_limit, budget=budget
    )
    for judgement in report.judgements:
        if not judgement.permissible and judgement.explanation is not None:
            reason = words.explanation_clause(judgement.explanation, True)
            return Example(plan, judgement.principle, reason)
    return Example(plan)
