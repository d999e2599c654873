"""When a question's principle is dropped: which goals and constraints the
principle rules out together, and the cheapest change that would admit a
permissible plan.

A contrast plan is made without its principle when no plan meeting the
questions is permissible under it (proven).  The answer then also says why:
the minimal conflicts of the goal's facts and the questions' constraints
under the principle (:mod:`ethasp.principles.conflict`, in words by
:mod:`ethasp.reasons.conflicts`), and, where the model declares what a repair
may change, the cheapest repair (:mod:`ethasp.principles.repair`) that admits
a permissible plan meeting the questions (their constraints are kept).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ethasp.planning.budget import Budget
from ethasp.planning.driver.planner import Constraint
from ethasp.planning.model import Model
from ethasp.planning.naming import Naming
from ethasp.principles.conflict import Conflicts, goal_conflicts
from ethasp.principles.repair import RepairResult, declares_changes, repair
from ethasp.principles.restriction import SEARCH_BOUNDS
from ethasp.reasons import words
from ethasp.reasons.conflicts import explain_conflicts
from ethasp.reasons.reasons import model_labels


@dataclass
class Impasse:
    """The conflicts of a dropped principle (``conflicts``, ``text`` in
    words) and the cheapest repair (None where the model declares no
    changes)."""

    conflicts: Conflicts
    text: str
    repair: RepairResult | None
    naming: Naming

    def to_json(self) -> dict[str, Any]:
        data: dict[str, Any] = self.conflicts.to_json(self.naming)
        data["conflicts_explanation"] = self.text
        data["repair"] = self.repair.to_json(self.naming) if self.repair is not None else None
        return data


def impasse(
    model: Model,
    under: str,
    constraints: Sequence[Constraint],
    max_horizon: int,
    budget: Budget,
    limit: int,
    unreachable: bool = False,
) -> Impasse:
    """The conflicts of the goal and the constraints under the principle
    ``under`` (at most ``limit``), and the cheapest repair.  ``unreachable``:
    the contrast's search proved that no plan permissible under ``under``
    meets the goal and the constraints (the conflicts do not decide it again,
    unless the constraints bound the plan's length or cost: that search then
    answered another question than the goal's items ask)."""
    bounds = any(constraint.term.name in SEARCH_BOUNDS for constraint in constraints)
    conflicts = goal_conflicts(
        model,
        [under],
        constraints,
        max_horizon,
        budget=budget,
        limit=limit,
        unreachable=unreachable and not bounds,
    )
    terms = [constraint.term for constraint in constraints]
    explained = explain_conflicts(model, conflicts, terms, max_horizon, budget)
    text = explained.text
    found = None
    if declares_changes(model) and not budget.expired():
        found = repair(
            model, [under], constraints=constraints, max_horizon=max_horizon, budget=budget, limit=1
        )
        text = f"{text} {repair_sentence(model, found, under)}"
    return Impasse(conflicts, text, found, model.naming)


def repair_sentence(model: Model, result: RepairResult, under: str) -> str:
    """The cheapest repair in words."""
    principle = words.principle_phrase(under)
    if not result.repairs:
        if result.status == "none":
            return f"No change the model allows would admit a plan permissible under {principle}."
        return f"No change that would admit a plan permissible under {principle} was found."
    labels = model_labels(model)
    best = result.repairs[0]
    changes = words.join([change.text(model.naming) for change in best.changes])
    cheapest = "The cheapest change" if result.status == "found" else "A change found"
    sentence = (
        f"{cheapest} that would admit a plan permissible under {principle}: {changes} "
        f"(cost {best.cost})"
    )
    if best.plan is not None:
        sentence += f"; then {words.agent(labels)} could {words.plan_phrase(labels, best.plan)}"
    return sentence + "."
