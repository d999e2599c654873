"""ethasp: ethical plan explanation with Answer Set Programming.

An implementation, with clingo, of the system of Krarup, Lindner, Krivic and
Long, "Understanding a Robot's Guiding Ethical Principles via Automatically
Generated Explanations" (IEEE CASE 2021).
"""

from ethasp.errors import InputError
from ethasp.model import Model
from ethasp.plan import Plan
from ethasp.search import SearchResult, find_plan
from ethasp.validation import Validation, validate

__all__ = [
    "InputError",
    "Model",
    "Plan",
    "SearchResult",
    "Validation",
    "find_plan",
    "validate",
]
