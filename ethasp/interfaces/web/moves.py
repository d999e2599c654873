"""The moves of the page's dialogues, as a worker process makes them.

The server keeps each dialogue as data and sends it, with the move to make,
to one of its workers (:mod:`ethasp.interfaces.web.workers`); the dialogue's
model arrives as a reference to the model the worker keeps warm (grounded
once, with the results kept for it: :mod:`ethasp.planning.model`).  Each
move is a module-level function that returns a :class:`Shown`: the dialogue
after the move and everything the page shows of it that needs clingo (the
current plan judged under every principle and explained step by step, and
the timelines of the plans drawn), so that the server answers the page's
other requests from what it keeps, without clingo and without a worker.
"""

from __future__ import annotations

import contextlib
import threading
from collections import OrderedDict
from dataclasses import dataclass, field

from ethasp.interfaces.pictures import Pictures, repaired_timeline
from ethasp.planning.model import Model, kept
from ethasp.planning.plan import Plan
from ethasp.planning.timeline import Timeline, Valuation
from ethasp.planning.validation import validate
from ethasp.principles.causal import actions
from ethasp.principles.judgement import JudgementReport
from ethasp.questions.dialogue import Dialogue
from ethasp.questions.question import Question
from ethasp.questions.steps import StepsExplanation, explain_steps
from ethasp.reasons.reasons import judge

PlanKey = tuple[str, ...]

# Judgements kept per worker: the most recently used plans, proven ones only.
REPORTS = 64


@dataclass(frozen=True)
class Settings:
    """The search options of every dialogue of the page (the command line's)."""

    max_horizon: int
    time_limit: float | None
    reasons_limit: int

    def dialogue(self) -> dict:
        return {
            "max_horizon": self.max_horizon,
            "time_limit": self.time_limit,
            "reasons_limit": self.reasons_limit,
        }


@dataclass(frozen=True)
class Glance:
    """What the server needs to know of its model, read once by a worker: the
    model's elements for the page and its pictures, its own plan (a HERA
    situation's), if any, and whether the empty plan is a plan (the goal
    holds at the start: only then may a plan of one step be asked why not
    in 0 steps); for a causal agency model, its actions to choose from
    (``choices``: term and name, in the order of its file)."""

    valuation: Valuation
    own_plan: Plan | None
    empty_plan_is_plan: bool = False
    choices: list[dict] | None = None


@dataclass
class Shown:
    """A dialogue and what the page shows of it: the current plan judged
    under every principle (``report``) and explained step by step
    (``explained``), and the timeline of every plan of the dialogue."""

    dialogue: Dialogue
    report: JudgementReport
    explained: StepsExplanation | None  # None for a causal agency model's choice
    timelines: dict[PlanKey, Timeline] = field(default_factory=dict)
    note: str = ""
    # the timelines of the cheapest repairs' plans, by question number
    repairs: dict[int, Timeline] = field(default_factory=dict)


def plan_key(plan: Plan) -> PlanKey:
    return tuple(plan.to_list())


def plans_of(dialogue: Dialogue) -> list[Plan]:
    """The plans the page may draw: the first and the current plan, and the
    plans of every answer."""
    plans = [dialogue.plan, dialogue.current_plan]
    for step in dialogue.steps:
        plans.append(step.answer.original.plan)
        if step.answer.contrast is not None:
            plans.append(step.answer.contrast.plan)
    return plans


def drawn_plans(dialogue: Dialogue, report: JudgementReport) -> list[Plan]:
    """The plans the page may draw (:func:`plans_of`), and the better plans of
    the current plan's judgements (utilitarianism: a better reachable state)."""
    better = [j.better_plan for j in report.judgements if j.better_plan is not None]
    return [*plans_of(dialogue), *better]


# -- what a worker keeps ------------------------------------------------------------------

_lock = threading.Lock()
_pictures: dict[str, Pictures] = {}
_reports: OrderedDict[tuple, JudgementReport] = OrderedDict()


def _pictures_of(model: Model) -> Pictures:
    with _lock:
        pictures = _pictures.get(model.key)
        if pictures is None or pictures.model is not model:
            _pictures.clear()  # a worker serves one model
            pictures = _pictures[model.key] = Pictures(model)
        return pictures


def warm(model: Model) -> None:
    """A new worker's first work: keep the model, ground it, and read what
    every move needs (the valuation of its pictures).  An error here is left
    to the first move, which meets it again and says it."""
    model = kept(model)
    with contextlib.suppress(Exception):
        _pictures_of(model).valuation  # noqa: B018 (grounds the model and reads its facts)


def glance(model: Model) -> Glance:
    """Check the model (one line if it is not a planning task) and read what
    the server needs to know of it."""
    model = kept(model)
    if not model.checked:
        model.check()
    valuation = _pictures_of(model).valuation
    if model.is_cam:
        choices = [{"term": str(a), "shown": model.naming.action(a)} for a in actions(model)]
        return Glance(valuation, model.own_plan(), False, choices)
    return Glance(valuation, model.own_plan(), validate(model, Plan(())).valid)


def _report(dialogue: Dialogue) -> JudgementReport:
    """The current plan judged and explained under the default principles
    (the paper's three), kept when proven."""
    key = (
        dialogue.model.key,
        plan_key(dialogue.current_plan),
        dialogue.max_horizon,
        dialogue.reasons_limit,
    )
    with _lock:
        if key in _reports:
            _reports.move_to_end(key)
            return _reports[key]
    report = judge(
        dialogue.model,
        dialogue.current_plan,
        None,
        dialogue.max_horizon,
        dialogue.time_limit,
        dialogue.reasons_limit,
    )
    if all(judgement.status == "proven" for judgement in report.judgements):
        with _lock:
            _reports[key] = report
            while len(_reports) > REPORTS:
                _reports.popitem(last=False)
    return report


def shown(dialogue: Dialogue, have: frozenset[PlanKey] = frozenset(), note: str = "") -> Shown:
    """What the page shows of the dialogue; the timelines of the plans in
    ``have`` (which the server keeps already) are left out."""
    if dialogue.model.is_cam:  # a choice: no timelines, no steps to explain
        return Shown(dialogue, _report(dialogue), None, {}, note)
    pictures = _pictures_of(dialogue.model)
    report = _report(dialogue)
    timelines = {}
    goal_plans = {plan_key(plan) for plan in plans_of(dialogue)}
    for plan in drawn_plans(dialogue, report):
        key = plan_key(plan)
        if key not in have and key not in timelines:
            # (a better plan reaches a better state, not always the goal)
            timelines[key] = pictures.timeline(plan, reach_goal=key in goal_plans)
    repairs = {}
    for number, step in enumerate(dialogue.steps, 1):
        repaired = repaired_timeline(step.answer)
        if repaired is not None:
            repairs[number] = repaired
    return Shown(
        dialogue,
        report,
        explain_steps(dialogue.model, dialogue.current_plan),
        timelines,
        note,
        repairs,
    )


# -- the moves ---------------------------------------------------------------------------


def start(
    model: Model, principle: str, plan: Plan | None, files: list[str], settings: Settings
) -> Shown:
    """A new dialogue about ``plan``, or about the model's own plan, or about
    the plan made under ``principle``."""
    dialogue = Dialogue.start(kept(model), principle, plan, files, **settings.dialogue())
    return shown(dialogue, note=f"a new dialogue under {dialogue.principle}")


def ask(dialogue: Dialogue, question: Question, have: frozenset[PlanKey]) -> Shown:
    """Ask a question about the current plan."""
    dialogue.ask(question)
    return shown(dialogue, have, f"answered: {question}")


def undo(dialogue: Dialogue, have: frozenset[PlanKey]) -> Shown:
    """Take back the last question."""
    step = dialogue.undo()
    return shown(dialogue, have, f"took back: {step.question}")


def load(
    data: dict, model: Model, files: list[str], settings: Settings, name: str, note: str
) -> Shown:
    """A saved dialogue, its questions asked again about the served model."""
    dialogue = Dialogue.from_json(data, kept(model), **settings.dialogue())
    dialogue.model_files = list(files)
    return shown(dialogue, note=f"loaded {name} ({len(dialogue.steps)} questions){note}")
