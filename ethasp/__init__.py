"""ethasp: ethical plan explanation with Answer Set Programming.

An implementation, with clingo, of the system of Krarup, Lindner, Krivic and
Long, "Understanding a Robot's Guiding Ethical Principles via Automatically
Generated Explanations" (IEEE CASE 2021).
"""

from importlib import import_module
from typing import TYPE_CHECKING, Any

# Names are imported on first use, so that a command (ethasp plan) loads only
# the modules it needs.
_HOMES = {
    "InputError": "ethasp.errors",
    "Formula": "ethasp.principles.formula",
    "format_formula": "ethasp.principles.formula",
    "format_literal": "ethasp.principles.formula",
    "parse_formula": "ethasp.principles.formula",
    "Judgement": "ethasp.principles.judgement",
    "JudgementReport": "ethasp.principles.judgement",
    "QueryResult": "ethasp.principles.judgement",
    "judge": "ethasp.reasons.reasons",
    "query": "ethasp.principles.judgement",
    "Model": "ethasp.planning.model",
    "Plan": "ethasp.planning.plan",
    "Explanation": "ethasp.reasons.reasons",
    "explain": "ethasp.reasons.reasons",
    "explain_steps": "ethasp.questions.steps",
    "HPlanResult": "ethasp.principles.restriction",
    "plan_with_principles": "ethasp.principles.restriction",
    "SearchResult": "ethasp.planning.search",
    "find_plan": "ethasp.planning.search",
    "Validation": "ethasp.planning.validation",
    "validate": "ethasp.planning.validation",
    "batch": "ethasp.batch.run",
    "Conflicts": "ethasp.principles.conflict",
    "goal_conflicts": "ethasp.principles.conflict",
    "RepairResult": "ethasp.principles.repair",
    "repair": "ethasp.principles.repair",
}

if TYPE_CHECKING:  # the same names for type checkers, which do not run __getattr__
    from ethasp.batch.run import batch
    from ethasp.errors import InputError
    from ethasp.planning.model import Model
    from ethasp.planning.plan import Plan
    from ethasp.planning.search import SearchResult, find_plan
    from ethasp.planning.validation import Validation, validate
    from ethasp.principles.conflict import Conflicts, goal_conflicts
    from ethasp.principles.formula import Formula, format_formula, format_literal, parse_formula
    from ethasp.principles.judgement import Judgement, JudgementReport, QueryResult, query
    from ethasp.principles.repair import RepairResult, repair
    from ethasp.principles.restriction import HPlanResult, plan_with_principles
    from ethasp.questions.steps import explain_steps
    from ethasp.reasons.reasons import Explanation, explain, judge


def __getattr__(name: str) -> Any:
    if name not in _HOMES:
        raise AttributeError(f"module 'ethasp' has no attribute {name!r}")
    value = getattr(import_module(_HOMES[name]), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_HOMES))


__all__ = [
    "Conflicts",
    "Explanation",
    "Formula",
    "HPlanResult",
    "InputError",
    "Judgement",
    "JudgementReport",
    "Model",
    "Plan",
    "QueryResult",
    "RepairResult",
    "SearchResult",
    "Validation",
    "batch",
    "explain",
    "explain_steps",
    "find_plan",
    "format_formula",
    "format_literal",
    "goal_conflicts",
    "judge",
    "parse_formula",
    "plan_with_principles",
    "query",
    "repair",
    "validate",
]
