"""An answer to contrastive questions in words: the explanation, then the
plans with their verdicts, the constraints and the reasons that differ (what
``ethasp ask`` and the dialogue's prompt print)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ethasp.interfaces.shortening import shorten_literal

if TYPE_CHECKING:
    from ethasp.questions.contrast import Answer


def answer_text(answer: Answer, naming) -> str:
    """An answer in words, then the plans, verdicts and constraints."""
    lines = [answer.explanation]
    if answer.impasse is not None:
        lines.append(answer.impasse.text)
    original = answer.original
    lines.append(
        f"  plan asked about: {naming.actions(original.plan) or '(empty)'} "
        f"({original.principle}: {_verdict(original)}{_cost(original.cost)})"
    )
    if answer.contrast is not None:
        contrast = answer.contrast
        lines.append(
            f"  contrast plan: {naming.actions(contrast.plan) or '(empty)'} "
            f"({contrast.principle}: {_verdict(contrast)}{_cost(contrast.cost)})"
        )
    elif answer.status == "bounded":
        lines.append(f"  no contrast plan found (bounded): {answer.proof}")
    else:
        lines.append(f"  no contrast plan: {answer.proof}")
    if answer.principle_dropped:
        lines.append(
            f"  the principle {answer.under} was dropped for the contrast: "
            f"{answer.dropped_because}; the contrast plan was made without it and "
            f"is judged under it"
        )
    if answer.note:
        lines.append(f"  note: {answer.note}")
    if answer.impasse is not None:
        lines += impasse_lines(answer.impasse, naming, answer.under)
    constraints = ", ".join(naming.constraint(c.term) for c in answer.constraints)
    lines.append(f"  constraints: {constraints}")
    if answer.conflict:
        lines.append(
            f"  conflicting constraints: "
            f"{', '.join(naming.constraint(c.term) for c in answer.conflict)}"
        )
    difference = answer.difference
    if difference["original_only"] or difference["contrast_only"]:
        lines.append(
            f"  reasons only for the plan asked about: "
            f"{_literals(difference['original_only'])}; "
            f"only for the contrast: {_literals(difference['contrast_only'])}"
        )
    return "\n".join(lines)


def _cost(cost: int | None) -> str:
    """``; cost 5`` for a plan of a model with action costs."""
    return f"; cost {cost}" if cost is not None else ""


def impasse_lines(impasse, naming, under: str) -> list[str]:
    """The conflicts of a dropped principle and the cheapest repair, in lines."""
    conflicts = impasse.conflicts

    def shown(items) -> str:
        return "{" + ", ".join(item.text(naming) for item in items) + "}"

    found = "; ".join(shown(conflict) for conflict in conflicts.conflicts) or "none"
    more = ", more may exist" if conflicts.conflicts_truncated else ""
    lines = [f"  conflicts under {under} ({conflicts.status}{more}): {found}"]
    result = impasse.repair
    if result is not None:
        if result.repairs:
            best = result.repairs[0]
            changes = "; ".join(change.text(naming) for change in best.changes)
            status = "least, proven" if result.status == "found" else "bounded"
            plan = naming.actions(best.plan) if best.plan is not None else "(none found)"
            lines.append(
                f"  cheapest repair (cost {best.cost}, {status}): {changes}; plan: "
                f"{plan or '(empty plan)'}"
            )
        else:
            lines.append(f"  no repair ({result.status}): {result.proof}")
    return lines


def _literals(literals: list[str]) -> str:
    """Literals of reasons, long ones shortened (``--json`` has them whole)."""
    return ", ".join(shorten_literal(literal) for literal in literals) or "none"


def unmeetable_text(answer: Answer, naming) -> str:
    """What the dialogue says when no plan can meet the questions imposed."""
    conflict = ", ".join(naming.constraint(c.term) for c in answer.conflict)
    return (
        "No plan can meet the questions asked so far together (conflicting constraints: "
        f"{conflict}); they stay imposed, so every later question would have no contrast "
        "plan either. Type drop to take back the last question."
    )


def _verdict(side) -> str:
    word = "permissible" if side.judgement.permissible else "impermissible"
    return word if side.judgement.status == "proven" else f"{word}, bounded"
