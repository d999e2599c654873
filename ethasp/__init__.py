"""ethasp: ethical plan explanation with Answer Set Programming.

An implementation, with clingo, of the system of Krarup, Lindner, Krivic and
Long, "Understanding a Robot's Guiding Ethical Principles via Automatically
Generated Explanations" (IEEE CASE 2021).
"""

from ethasp.errors import InputError
from ethasp.formula import Formula, format_formula, format_literal, parse_formula
from ethasp.judgement import Judgement, JudgementReport, QueryResult, judge, query
from ethasp.model import Model
from ethasp.plan import Plan
from ethasp.restriction import HPlanResult, plan_with_principles
from ethasp.search import SearchResult, find_plan
from ethasp.validation import Validation, validate

__all__ = [
    "Formula",
    "InputError",
    "Judgement",
    "JudgementReport",
    "QueryResult",
    "format_formula",
    "format_literal",
    "judge",
    "parse_formula",
    "query",
    "Model",
    "Plan",
    "HPlanResult",
    "plan_with_principles",
    "SearchResult",
    "Validation",
    "find_plan",
    "validate",
]
