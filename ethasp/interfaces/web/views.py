"""The JSON the page shows: the model at a glance, a dialogue's state, its answers."""

from __future__ import annotations

import hashlib
from pathlib import Path

from ethasp.interfaces.version import package_version
from ethasp.interfaces.web.workspace import Session, Workspace
from ethasp.planning.plan import Plan
from ethasp.principles.causal import actions, model_kind
from ethasp.principles.principle import available_principles
from ethasp.principles.restriction import restricting_principles
from ethasp.questions.dialogue import Step


def model_json(workspace: Workspace) -> dict:
    """The model at a glance, the principles, defaults and limits."""
    names = [Path(path).name for path in workspace.files]
    # The page keeps its dialogue under this key: the files' paths, and the text
    # of a model read from standard input (which has no path).
    texts = [
        source.text
        for source in workspace.model.sources
        if source.path is None and not source.generated
    ]
    key = hashlib.sha256(
        "\n".join([str(Path(p).resolve()) for p in workspace.files] + texts).encode()
    ).hexdigest()[:16]
    limits = workspace.limits
    model = workspace.model
    kind = model_kind(model)
    principles = available_principles(kind)
    # A causal agency model's plans are its actions, chosen one at a time.
    choices = (
        [{"term": str(a), "shown": model.naming.action(a)} for a in actions(model)]
        if model.is_cam
        else None
    )
    return {
        "name": " ".join(names) or "model",
        "files": names,
        "key": key,
        "version": package_version(),
        "principle": workspace.principle,
        "principles": [p.name for p in principles],
        "restricting": restricting_principles(kind),
        "choices": choices,
        "model": workspace.pictures.valuation.to_json(workspace.model.naming),
        "limits": {"question": limits.question, "plan": limits.plan, "questions": limits.questions},
        "options": {
            "max_horizon": workspace.options.max_horizon,
            "time_limit": workspace.options.time_limit,
            "reasons_limit": workspace.options.reasons_limit,
        },
    }


def _actions(workspace: Workspace, plan: Plan) -> list[dict]:
    naming = workspace.model.naming
    return [{"term": str(action), "shown": naming.action(action)} for action in plan]


def _step_json(workspace: Workspace, number: int, step: Step) -> dict:
    answer = step.answer
    data = answer.to_json()
    data["original"]["shown"] = _actions(workspace, answer.original.plan)
    if answer.contrast is not None:
        data["contrast"]["shown"] = _actions(workspace, answer.contrast.plan)
    naming = workspace.model.naming
    data["constraints_shown"] = [naming.constraint(c.term) for c in answer.constraints]
    data["conflict_shown"] = [naming.constraint(c.term) for c in answer.conflict]
    own = [
        str(c)
        for c in answer.constraints
        if answer.constraints and c.question == answer.constraints[-1].question
    ]
    return {
        "number": number,
        "question": str(step.question),
        "under": step.under,
        "own_constraints": own,
        "answer": data,
    }


def state_json(workspace: Workspace, session: Session) -> dict:
    """A session's dialogue: the current plan judged under every principle,
    the questions asked with their answers, and the job running (if any)."""
    data: dict = {
        "session": session.id,
        "job": session.job.to_json() if session.job is not None else None,
        "dialogue": None,
    }
    dialogue = session.dialogue
    if dialogue is None:
        return data
    plan = dialogue.current_plan
    report = workspace.report(plan)
    naming = workspace.model.naming
    current = report.to_json()
    current["shown"] = _actions(workspace, plan)
    current["final_shown"] = [naming.fact(literal) for literal in report.final_state]
    current["principle"] = dialogue.current_principle
    # Which question's contrast plan this is (0: the first plan), and whether
    # it was made without the principle (dropped on a proof).
    source = dialogue.current_step
    current["from_question"] = source
    current["made_without_principle"] = (
        source > 0 and dialogue.steps[source - 1].answer.principle_dropped
    )
    data.update(
        {
            "dialogue": dialogue.to_json(),
            "principle": dialogue.principle,
            "under": dialogue.under,
            "first_plan": _actions(workspace, dialogue.plan),
            "current": current,
            "steps": [
                _step_json(workspace, number, step)
                for number, step in enumerate(dialogue.steps, start=1)
            ],
            "unmeetable": dialogue.unmeetable is not None,
        }
    )
    return data


def explain_json(workspace: Workspace, session: Session, step: int | None = None) -> dict:
    """The current plan explained step by step (``why step T`` with ``step``)."""
    dialogue = session.require()
    explanation = workspace.explained(dialogue.current_plan)
    naming = workspace.model.naming
    data = explanation.to_json(naming)
    data["lines"] = explanation.lines()
    data["shown"] = _actions(workspace, dialogue.current_plan)
    if step is not None:
        data["step"] = step
        data["step_text"] = explanation.step_text(step)
    return data
