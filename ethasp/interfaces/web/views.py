"""The JSON the page shows: the model at a glance, a dialogue's state, its answers."""

from __future__ import annotations

import hashlib
from pathlib import Path

from ethasp.interfaces.version import package_version
from ethasp.interfaces.web.workspace import Session, Workspace
from ethasp.planning.plan import Plan
from ethasp.principles.causal import model_kind
from ethasp.principles.principle import available_principles
from ethasp.principles.restriction import restricting_principles
from ethasp.questions.dialogue import Step
from ethasp.reasons.words import option_sentence, verdict_sentence


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
    choices = workspace.glance.choices
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
    impasse = answer.impasse
    if impasse is not None and impasse.repair is not None and impasse.repair.repairs:
        best = impasse.repair.repairs[0]
        if best.plan is not None:
            data["repair"]["shown"] = _actions(workspace, best.plan)
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
    shown = session.shown
    if shown is None:
        return data
    dialogue, report = shown.dialogue, shown.report
    plan = dialogue.current_plan
    naming = workspace.model.naming
    current = report.to_json()
    current["shown"] = _actions(workspace, plan)
    # The plan in words once ("The man can pull the lever."), and each
    # judgement's verdict without it ("Doing so is ..."); from the
    # explanations' labels (the planner is not touched here: a job may use it).
    explained = [j for j in report.judgements if j.explanation is not None]
    if explained:
        current["plan_words"] = option_sentence(explained[0].explanation.labels, plan)
        for entry, judgement in zip(current["judgements"], report.judgements, strict=True):
            if judgement.explanation is not None:
                entry["verdict_words"] = verdict_sentence(judgement.explanation)
    # Whether "why not in N-1 steps" can have a contrast at all: for a plan of
    # one step, only when the empty plan is a plan.
    current["empty_plan_is_plan"] = workspace.glance.empty_plan_is_plan
    for judgement, entry in zip(report.judgements, current["judgements"], strict=True):
        if judgement.better_plan is not None:  # utilitarianism: a better reachable state
            entry["better_plan_shown"] = _actions(workspace, judgement.better_plan)
    current["final_shown"] = [naming.fact(literal) for literal in report.final_state]
    current["principle"] = dialogue.current_principle
    # Which question's contrast plan this is (0: the first plan), and whether
    # it was made without the principle (dropped on a proof).
    source = dialogue.current_step
    current["from_question"] = source
    # (the plan's cost, in a model with action costs: in the report's JSON)
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
    session.require()
    explanation = session.shown.explained  # (of the current plan)
    naming = workspace.model.naming
    data = explanation.to_json(naming)
    data["lines"] = explanation.lines()
    data["link_lines"] = explanation.link_lines()
    data["shown"] = _actions(workspace, explanation.plan)
    if step is not None:
        data["step"] = step
        data["step_text"] = explanation.step_text(step)
    return data
