"""Work for the tests of models and symbols sent to worker processes:
module-level functions, so that a worker started by a forkserver can import
them."""

from __future__ import annotations

import clingo

from ethasp.questions.dialogue import Dialogue


def grounded_before(dialogue: Dialogue) -> tuple[bool, int]:
    """Was the dialogue's model grounded in this process when it arrived?
    Grounds it, and says which grounding it has."""
    before = dialogue.model.grounded()
    return before, id(dialogue.model.planner)


def ask(dialogue: Dialogue, question: str) -> Dialogue:
    dialogue.ask(question)
    return dialogue


def symbols() -> list[clingo.Symbol]:
    """Symbols made in this process (none of them known to the process that
    receives them)."""
    return [
        clingo.Function("f", [clingo.String('caf\u00e9 "quoted" \\ back'), clingo.Number(-3)]),
        clingo.Function("", [clingo.Function("a")]),
        clingo.Tuple_([]),
        clingo.Function("g", [clingo.Function("x")], False),
        clingo.Infimum,
        clingo.Supremum,
    ]
