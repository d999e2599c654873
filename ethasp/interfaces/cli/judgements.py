"""Judgements in text, as ``ethasp judge`` and ``ethasp plan --principle`` print
them: the explanations and their reasons, the verdicts, the states compared."""

from __future__ import annotations

import shutil
import sys
from typing import TYPE_CHECKING

from ethasp.planning.model import Model
from ethasp.planning.plan import steps

if TYPE_CHECKING:
    from ethasp.principles.judgement import JudgementReport


def state_text(model: Model, literals: list[str]) -> str:
    """A whole state in words: for a PDDL task the atoms that hold (PDDL's
    closed world), for other models every variable's value."""
    from ethasp.planning.naming import PddlNaming

    if isinstance(model.naming, PddlNaming):
        literals = [literal for literal in literals if not literal.startswith("-")]
    return model.naming.facts(literals)


def judgement_text(report: JudgementReport, model: Model) -> str:
    naming = model.naming
    cost = f" (cost {report.cost})" if report.cost is not None else ""
    if model.is_cam:  # a choice: its action, its world, what the action causes
        lines = [
            f"action: {naming.actions(report.plan)}",
            f"world: {naming.facts(report.final_state)} (utility of the consequences "
            f"{report.utility})",
            f"caused: {naming.facts(report.caused or []) or 'nothing'}",
        ]
    else:
        lines = [
            f"plan: {naming.actions(report.plan)}{cost}" if len(report.plan) else "plan: (empty)",
            f"final state: {state_text(model, report.final_state)} (utility {report.utility})",
        ]
        if not report.goal_reached:  # (a HERA situation's plan, judged as HERA does)
            lines.append(
                f"goal: not reached ({state_text(model, report.unmet_goal)} "
                f"{'does' if len(report.unmet_goal) == 1 else 'do'} not hold at the end)"
            )
    for judgement in report.judgements:
        verdict = "permissible" if judgement.permissible else "impermissible"
        if judgement.status == "bounded":
            verdict = f"{verdict} as far as searched (bounded, not proven)"
        else:
            verdict = f"{verdict} (proven)"
        if judgement.compared is None and judgement.best_reachable is None:
            lines.append(f"{judgement.principle}: {verdict}")
            continue
        lines.append(f"{judgement.principle}: {verdict}: {judgement.proof}")
        compared, best = judgement.compared, judgement.best_reachable
        final = set(report.final_state)
        if compared is not None and (best is None or best.found is not compared):
            kind = "a better reachable state" if not judgement.permissible else "compared with"
            lines.append(
                f"  {kind}: {_state_words(compared.literals, final, naming)} "
                f"(utility {compared.utility}, {steps(compared.distance)} away)"
            )
        better = judgement.better_plan
        if better is not None:
            lines.append(f"  the better plan: {naming.actions(better) or '(empty)'}")
        if best is not None and best.found is not None:
            lines.append(
                f"  best reachable state: {_state_words(best.state, final, naming)} "
                f"(utility {best.utility}, {steps(best.horizon)} away; "
                f"{best.status}: {best.proof})"
            )
    return "\n".join(lines)


def _state_words(literals: list[str], final: set[str], naming) -> str:
    """A state, as its difference from the final state when that is shorter."""
    if set(literals) == final:
        return "the final state"
    differing = [literal for literal in literals if literal not in final]
    if len(differing) * 2 < len(literals):
        return f"the final state but {naming.facts(differing)}"
    return naming.facts(literals)


def explanation_text(report: JudgementReport) -> list[str]:
    """Each judgement's explanation, then its reasons (ethasp/reasons/reasons.py),
    long ones shortened (ethasp/interfaces/shortening.py; --json has them whole)."""
    from ethasp.interfaces.shortening import WIDTH, reasons_lines

    width = WIDTH
    if sys.stdout.isatty():
        width = max(WIDTH, shutil.get_terminal_size((WIDTH, 24)).columns - 1)
    lines, shortened = [], False
    for judgement in report.judgements:
        explanation = judgement.explanation
        if explanation is None:
            continue
        lines.append(f"{judgement.principle}: {explanation.text}")
        for kind, reasons, truncated in (
            ("necessary", explanation.necessary_reasons, explanation.necessary_truncated),
            ("sufficient", explanation.sufficient_reasons, explanation.sufficient_truncated),
            ("INUS", explanation.inus_reasons, explanation.inus_truncated),
        ):
            kind_lines, cut = reasons_lines(kind, reasons, truncated, width)
            lines += kind_lines
            shortened = shortened or cut
    if shortened:
        lines.append("(long reasons are shortened here; --json prints them whole)")
    return lines


def choices_table(reports: list[JudgementReport], model: Model) -> str:
    """Every action of a causal agency model under every principle: a row per
    principle, a column per action (+ permissible, - impermissible)."""
    actions = [model.naming.actions(report.plan) for report in reports]
    principles = [judgement.principle for judgement in reports[0].judgements] if reports else []
    width = max([len("principle"), *map(len, principles)])
    columns = [max(len(action), 1) for action in actions]
    head = "  ".join(
        ["principle".ljust(width)] + [a.ljust(c) for a, c in zip(actions, columns, strict=True)]
    )
    lines = [head.rstrip()]
    for index, principle in enumerate(principles):
        cells = [
            ("+" if report.judgements[index].permissible else "-").ljust(column)
            for report, column in zip(reports, columns, strict=True)
        ]
        lines.append("  ".join([principle.ljust(width), *cells]).rstrip())
    lines.append("(+ permissible, - impermissible; every verdict proven)")
    return "\n".join(lines)
