"""The iterative explanation process (step 6 of the paper) as a dialogue.

A dialogue starts from a plan (given, or the model's own plan, or made by
plan search under a principle).  Each question asked is about the current
plan; its constraints join those of the questions before (the HModel grows),
and the contrast plan found becomes the current plan.  A question that no
plan can meet together with those before stays imposed until it is taken
back (:attr:`Dialogue.unmeetable` says so; later questions are then answered
at once, without a search).  Questions can be undone, the principle the next
contrast must satisfy can be switched (to a principle that can restrict plan
search), the causal explanation of a step of the current plan can be asked
for (:meth:`Dialogue.explain_step`), and the whole dialogue can be saved to
JSON and loaded again (loading asks the saved questions anew).
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ethasp.errors import InputError
from ethasp.planning.budget import Budget, Progress
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan, parse_action
from ethasp.planning.search import DEFAULT_MAX_HORIZON
from ethasp.planning.terms import read_text
from ethasp.principles.causal import model_kind
from ethasp.principles.judgement import JudgementReport
from ethasp.principles.restriction import one_restricting_principle
from ethasp.questions.contrast import (
    Answer,
    Constraint,
    answer_questions,
    one_principle,
    original_plan,
)
from ethasp.questions.question import Question
from ethasp.reasons.reasons import DEFAULT_LIMIT, judge

FORMAT = "ethasp-dialogue"
VERSION = 1

# The most questions a saved dialogue may hold: loading asks each one again.
MAX_STEPS = 1000


@dataclass
class Step:
    """One question of the dialogue, the principle it was asked under, its answer."""

    question: Question
    under: str
    answer: Answer


@dataclass
class Dialogue:
    """An exploration of contrastive questions about a plan.

    ``principle`` is the principle the first plan is made and judged under;
    ``under`` the principle that the next contrast plan must satisfy (switch
    it with :meth:`switch_principle`).  ``model_files`` are recorded when the
    dialogue is saved, so that :meth:`load` can find the model again.
    """

    model: Model
    principle: str
    plan: Plan
    under: str = ""
    steps: list[Step] = field(default_factory=list)
    model_files: list[str] = field(default_factory=list)
    max_horizon: int = DEFAULT_MAX_HORIZON
    time_limit: float | None = None
    reasons_limit: int = DEFAULT_LIMIT
    on_progress: Callable[[Progress], None] | None = None
    satisficing: bool = False

    def budget(self) -> Budget:
        """A budget for one move: the dialogue's time limit, its progress callback."""
        return Budget(self.time_limit, self.on_progress)

    @classmethod
    def start(
        cls,
        model: Model,
        principle: str,
        plan: Plan | None = None,
        model_files: Sequence[str] = (),
        max_horizon: int = DEFAULT_MAX_HORIZON,
        time_limit: float | None = None,
        reasons_limit: int = DEFAULT_LIMIT,
        budget: Budget | None = None,
        satisficing: bool = False,
    ) -> Dialogue:
        """A dialogue about ``plan``, or else about the plan the model comes
        with (a HERA situation's), or else about the plan made under
        ``principle``, which is also the principle the contrast plans must
        satisfy (one that can restrict plan search).  With ``satisficing``,
        the plans searched (the first one, and every contrast plan) come from
        any-plan searches, not proven shortest."""
        principle = one_restricting_principle(
            principle,
            "a dialogue starts under the principle that its contrast plans must satisfy, one of",
            model_kind(model),
        )
        if plan is None:
            plan = model.own_plan()
        if plan is None:
            plan = original_plan(
                model, principle, max_horizon, time_limit, budget=budget, satisficing=satisficing
            )
        return cls(
            model,
            principle,
            plan,
            principle,
            [],
            list(model_files),
            max_horizon,
            time_limit,
            reasons_limit,
            satisficing=satisficing,
        )

    # -- state --------------------------------------------------------------------

    @property
    def current_plan(self) -> Plan:
        """The plan now discussed: the last contrast plan found, else the first plan."""
        for step in reversed(self.steps):
            if step.answer.contrast is not None:
                return step.answer.contrast.plan
        return self.plan

    @property
    def current_principle(self) -> str:
        """The principle the current plan is judged under: the one it was made
        under (or, when no plan meeting the questions was permissible under it,
        proven, the one it was made without)."""
        for step in reversed(self.steps):
            if step.answer.contrast is not None:
                return step.under
        return self.principle

    @property
    def current_step(self) -> int:
        """The number of the question whose contrast plan is the current plan
        (0: the first plan)."""
        for number in range(len(self.steps), 0, -1):
            if self.steps[number - 1].answer.contrast is not None:
                return number
        return 0

    @property
    def constraints(self) -> list[Constraint]:
        """The constraints of every question asked so far."""
        return self.steps[-1].answer.constraints if self.steps else []

    @property
    def unmeetable(self) -> Answer | None:
        """The last answer, if no plan meets the constraints imposed so far
        (proven, with a minimal conflict): every later question fails too,
        until that question is taken back (:meth:`undo`)."""
        if self.steps and self.steps[-1].answer.unmeetable:
            return self.steps[-1].answer
        return None

    def current(self, budget: Budget | None = None) -> JudgementReport:
        """The current plan, judged and explained under its principle."""
        return judge(
            self.model,
            self.current_plan,
            [self.current_principle],
            self.max_horizon,
            reasons_limit=self.reasons_limit,
            budget=budget or self.budget(),
        )

    # -- moves --------------------------------------------------------------------

    def ask(self, question: str | Question, budget: Budget | None = None) -> Answer:
        """Ask about the current plan; the question's constraints are kept.

        ``budget`` bounds the searches (by default the dialogue's time limit,
        for this question); cancel it to stop them.
        """
        if not isinstance(question, Question):
            question = Question.parse(question)
        blocked = self.unmeetable
        answer = answer_questions(
            self.model,
            [question],
            self.current_plan,
            self.current_principle,
            self.under,
            self.constraints,
            self.max_horizon,
            reasons_limit=self.reasons_limit,
            budget=budget or self.budget(),
            satisficing=self.satisficing,
            conflicting=blocked.conflict if blocked else (),
        )
        self.steps.append(Step(question, self.under, answer))
        return answer

    def undo(self) -> Step:
        """Take back the last question (and its constraints)."""
        if not self.steps:
            raise InputError("nothing to undo: no question asked yet")
        return self.steps.pop()

    def switch_principle(self, name: str) -> str:
        """The principle the next contrast plans must satisfy: one principle
        that can restrict plan search (a group, or a principle that can only
        judge, is refused with one line naming those that can)."""
        self.under = one_restricting_principle(name, kind=model_kind(self.model))
        return self.under

    def explain_step(self, step: int):
        """The causal explanation of one step of the current plan (``why step
        T``): :class:`ethasp.questions.steps.StepsExplanation` of the plan,
        with ``step`` checked to be one of its steps."""
        from ethasp.questions.steps import explain_steps

        plan = self.current_plan
        if not 1 <= step <= len(plan):
            raise InputError(
                f"why step {step}: the current plan has "
                f"{'no steps' if not len(plan) else f'steps 1 to {len(plan)}'}"
            )
        return explain_steps(self.model, plan)

    # -- saving -------------------------------------------------------------------

    def to_json(self) -> dict:
        return {
            "format": FORMAT,
            "version": VERSION,
            "model": list(self.model_files),
            "principle": self.principle,
            "plan": self.plan.to_list(),
            "under": self.under,
            "steps": [
                {
                    "question": step.question.to_json(),
                    "under": step.under,
                    "answer": step.answer.to_json(),
                }
                for step in self.steps
            ],
        }

    def save(self, path: str | Path) -> None:
        """Write the whole dialogue to a JSON file (InputError if it cannot be written)."""
        text = json.dumps(self.to_json(), indent=2) + "\n"
        try:
            Path(path).write_text(text, encoding="utf-8")
        except (OSError, ValueError) as error:
            reason = getattr(error, "strerror", None) or " ".join(str(error).split())
            raise InputError(f"{path}: the dialogue cannot be saved ({reason})") from None

    @classmethod
    def from_json(
        cls,
        data: dict,
        model: Model | None = None,
        max_horizon: int = DEFAULT_MAX_HORIZON,
        time_limit: float | None = None,
        reasons_limit: int = DEFAULT_LIMIT,
        source: str = "saved dialogue",
        budget: Budget | None = None,
        satisficing: bool = False,
    ) -> Dialogue:
        """Rebuild a saved dialogue, asking its questions again in order (under
        ``budget`` if given, else each under the dialogue's time limit).

        The data is checked first (types, at most :data:`MAX_STEPS` questions);
        plans and questions are read as terms, never as rule text.  Errors name
        ``source`` (the file, when loaded).
        """
        try:
            _check_saved(data)
        except InputError as error:
            raise InputError(f"{source}: {error}") from None
        if model is None:
            if not data.get("model"):
                raise InputError("the saved dialogue names no model files; give the model")
            model = Model.load(data["model"])
        try:
            plan = Plan(tuple(parse_action(action) for action in data["plan"]))
            dialogue = cls(
                model,
                one_principle(data["principle"], model_kind(model)),
                plan,
                data["principle"],
                [],
                list(data.get("model", [])),
                max_horizon,
                time_limit,
                reasons_limit,
                satisficing=satisficing,
            )
            for step in data.get("steps", []):
                dialogue.switch_principle(step["under"])
                dialogue.ask(Question.from_json(step["question"]), budget)
            dialogue.switch_principle(data.get("under", dialogue.principle))
        except InputError as error:
            raise InputError(f"{source}: {error}") from None
        return dialogue

    @classmethod
    def load(cls, path: str | Path, model: Model | None = None, **options) -> Dialogue:
        """Load a dialogue saved with :meth:`save`."""
        text = read_text(Path(path))
        try:
            data = json.loads(text)
        except (json.JSONDecodeError, RecursionError) as error:
            reason = "nested too deeply" if isinstance(error, RecursionError) else str(error)
            raise InputError(f"{path}: not a saved dialogue ({reason})") from None
        return cls.from_json(data, model, **options, source=str(path))


def _check_saved(data) -> None:
    """Raise InputError unless ``data`` has the shape :meth:`Dialogue.to_json` writes."""

    def wrong(what: str) -> InputError:
        return InputError(what)

    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise InputError('not a saved ethasp dialogue (no "format": "ethasp-dialogue")')
    version = data.get("version", VERSION)
    if not isinstance(version, int) or isinstance(version, bool) or version > VERSION:
        raise wrong(f"version {version!r} is not one this ethasp reads (up to {VERSION})")
    for key in ("principle", "plan"):
        if key not in data:
            raise wrong(f"missing '{key}'")
    if not isinstance(data["principle"], str):
        raise wrong("'principle' must be a principle's name")
    if "under" in data and not isinstance(data["under"], str):
        raise wrong("'under' must be a principle's name")
    if not isinstance(data["plan"], list) or not all(isinstance(a, str) for a in data["plan"]):
        raise wrong("'plan' must be a list of actions (strings)")
    model = data.get("model", [])
    if not isinstance(model, list) or not all(isinstance(name, str) for name in model):
        raise wrong("'model' must be a list of file names")
    steps = data.get("steps", [])
    if not isinstance(steps, list):
        raise wrong("'steps' must be a list")
    if len(steps) > MAX_STEPS:
        raise wrong(f"{len(steps)} questions, more than {MAX_STEPS} (the limit of ethasp)")
    for number, step in enumerate(steps, start=1):
        if (
            not isinstance(step, dict)
            or not isinstance(step.get("under"), str)
            or not isinstance(step.get("question"), dict)
        ):
            raise wrong(
                f"step {number} must have 'question' (an object) and 'under' (a principle's name)"
            )
        question = step["question"]
        for key in ("kind", "action", "other", "what"):
            if key in question and question[key] is not None and not isinstance(question[key], str):
                raise wrong(f"step {number}: the question's '{key}' must be a string")
        for key in ("at", "steps"):
            if (
                key in question
                and question[key] is not None
                and (not isinstance(question[key], int) or isinstance(question[key], bool))
            ):
                raise wrong(f"step {number}: the question's '{key}' must be a whole number")
        window = question.get("within")
        if window is not None and (
            not isinstance(window, list)
            or len(window) != 2
            or not all(isinstance(t, int) and not isinstance(t, bool) for t in window)
        ):
            raise wrong(f"step {number}: the question's 'within' must be two whole numbers")
