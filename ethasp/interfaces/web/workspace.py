"""What a server holds: one model (named on its command line), its dialogues
(one per page session) and the jobs that change them.

Every move that may search (start a dialogue, ask, undo, load) runs as a job
(:mod:`ethasp.interfaces.web.jobs`) on a copy of the session's dialogue; the
copy replaces the dialogue only when the job ends without being cancelled.
A session runs one job at a time, and the server at most
:attr:`Limits.running` searches at once.
"""

from __future__ import annotations

import json
import secrets
import threading
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

from ethasp.errors import InputError
from ethasp.interfaces.pictures import Pictures
from ethasp.interfaces.web.jobs import Job, searching, start
from ethasp.planning.budget import Budget
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.planning.search import DEFAULT_MAX_HORIZON
from ethasp.principles.causal import model_kind
from ethasp.principles.judgement import JudgementReport
from ethasp.principles.restriction import one_restricting_principle
from ethasp.questions.dialogue import Dialogue
from ethasp.questions.question import Question, step_question
from ethasp.questions.steps import StepsExplanation, explain_steps
from ethasp.reasons.reasons import DEFAULT_LIMIT, judge


class Refused(Exception):
    """A request the server will not carry out: an HTTP status and one line."""

    def __init__(self, status: int, message: str):
        super().__init__(message)
        self.status = status


@dataclass(frozen=True)
class Options:
    """The search options of every dialogue (the command line's)."""

    max_horizon: int = DEFAULT_MAX_HORIZON
    time_limit: float | None = None
    reasons_limit: int = DEFAULT_LIMIT

    def dialogue(self) -> dict:
        return {
            "max_horizon": self.max_horizon,
            "time_limit": self.time_limit,
            "reasons_limit": self.reasons_limit,
        }


@dataclass(frozen=True)
class Limits:
    """Limits on what the page may send and keep."""

    question: int = 500  # characters of a typed question
    plan: int = 10_000  # characters of a typed plan
    name: int = 100  # characters of a principle name or file name
    dialogue: int = 1_000_000  # characters of a saved dialogue to load
    questions: int = 100  # questions in one dialogue
    sessions: int = 32  # dialogues kept (the least recently used idle one goes)
    running: int = 2  # searches running at once (cancelled ones until they end)

    def check(self, what: str, text: object, limit: int) -> str:
        if not isinstance(text, str):
            raise InputError(f"{what}: expected text")
        if len(text) > limit:
            raise InputError(f"{what}: too long ({len(text)} characters; at most {limit})")
        return text


@dataclass
class Session:
    """One page's dialogue and its current (or last) job."""

    id: str
    dialogue: Dialogue | None = None
    job: Job | None = None

    @property
    def busy(self) -> bool:
        return self.job is not None and self.job.running

    def require(self) -> Dialogue:
        if self.dialogue is None:
            raise InputError("no dialogue yet: start one")
        return self.dialogue


class Workspace:
    """The served model, its dialogues, and caches of judgements and pictures."""

    def __init__(
        self,
        model: Model,
        files: list[str],
        principle: str = "deontology",
        options: Options = Options(),
        limits: Limits = Limits(),
    ):
        self.model = model
        self.files = list(files)
        if model.is_cam and principle == "deontology":
            principle = "hera-deontology"  # the same concept, for causal agency models
        self.principle = one_restricting_principle(
            principle,
            "the page starts dialogues under the principle that their contrast "
            "plans must satisfy, one of",
            model_kind(model),
        )
        self.options = options
        self.limits = limits
        self.pictures = Pictures(model)
        self._reports: OrderedDict[tuple[str, ...], JudgementReport] = OrderedDict()
        self._explained: OrderedDict[tuple[str, ...], StepsExplanation] = OrderedDict()
        self._sessions: OrderedDict[str, Session] = OrderedDict()
        self._jobs: list[Job] = []
        self._lock = threading.Lock()

    # -- judgements of plans (under every principle), kept --------------------------

    def report(self, plan: Plan, budget: Budget | None = None) -> JudgementReport:
        """The plan judged and explained under the default principles (the paper's three)."""
        key = tuple(plan.to_list())
        with self._lock:
            if key in self._reports:
                self._reports.move_to_end(key)
                return self._reports[key]
        budget = budget or Budget(self.options.time_limit)
        report = searching(
            judge,
            budget,
            self.model,
            plan,
            None,
            self.options.max_horizon,
            self.options.time_limit,
            self.options.reasons_limit,
        )
        if any(judgement.status != "proven" for judgement in report.judgements):
            return report  # cut short: judge it again next time
        with self._lock:
            self._reports[key] = report
            while len(self._reports) > 64:
                self._reports.popitem(last=False)
        return report

    def explained(self, plan: Plan) -> StepsExplanation:
        """The plan explained step by step (causal links; one clingo call), kept."""
        key = tuple(plan.to_list())
        with self._lock:
            if key in self._explained:
                self._explained.move_to_end(key)
                return self._explained[key]
        explanation = explain_steps(self.model, plan)
        with self._lock:
            self._explained[key] = explanation
            while len(self._explained) > 64:
                self._explained.popitem(last=False)
        return explanation

    def _prepare(self, dialogue: Dialogue, budget: Budget) -> None:
        """Judge and draw the dialogue's current plan (and the last answer's
        plans) inside the job, so that showing them is quick."""
        self.report(dialogue.current_plan, budget)
        if self.model.is_cam:
            return  # a choice has no timeline to draw
        self.pictures.timeline(dialogue.current_plan)
        if dialogue.steps:
            answer = dialogue.steps[-1].answer
            self.pictures.timeline(answer.original.plan)
            if answer.contrast is not None:
                self.pictures.timeline(answer.contrast.plan)

    # -- sessions -----------------------------------------------------------------------

    def new_session(self) -> Session:
        with self._lock:
            idle = [s for s in self._sessions.values() if not s.busy]
            while len(self._sessions) >= self.limits.sessions and idle:
                del self._sessions[idle.pop(0).id]
            if len(self._sessions) >= self.limits.sessions:
                raise Refused(503, "too many dialogues are running; try again shortly")
            session = Session(secrets.token_hex(16))
            self._sessions[session.id] = session
            return session

    def session(self, key: str) -> Session:
        with self._lock:
            session = self._sessions.get(key)
            if session is None:
                raise Refused(
                    404, "unknown session (the server was restarted, or the dialogue was closed)"
                )
            self._sessions.move_to_end(key)  # the least recently used idle one goes first
            return session

    # -- jobs ---------------------------------------------------------------------------

    def running(self) -> int:
        """Searches still working, cancelled ones included."""
        with self._lock:
            self._jobs = [job for job in self._jobs if job.alive]
            return len(self._jobs)

    @staticmethod
    def free(session: Session) -> Session:
        """The session, if no request of it is running."""
        if session.busy:
            raise Refused(
                409, "busy: a request of this dialogue is running; wait for it or cancel it"
            )
        return session

    def submit(
        self,
        session: Session,
        kind: str,
        description: str,
        work: Callable[[Budget], Callable[[], str]],
    ) -> Job:
        """Start a job for the session (one at a time; a few in the server)."""
        self.free(session)
        if self.running() >= self.limits.running:
            raise Refused(
                503,
                f"busy: {self.limits.running} searches are still running "
                "(cancelled searches end with their current solver call); "
                "try again shortly",
            )
        job = Job(secrets.token_hex(8), kind, description, Budget(self.options.time_limit))
        job.budget.on_progress = job.record
        session.job = job
        with self._lock:
            self._jobs.append(job)
        return start(job, work)

    # -- moves ----------------------------------------------------------------------------

    def start(self, session: Session, principle: str | None, plan_text: str = "") -> Job:
        """A new dialogue about the typed plan, or about the plan made under the principle."""
        self.free(session)
        name = self.limits.check("principle", principle or self.principle, self.limits.name)
        chosen = one_restricting_principle(
            name,
            "a dialogue starts under the principle that its contrast plans must satisfy, one of",
            model_kind(self.model),
        )
        plan_text = self.limits.check("plan", plan_text or "", self.limits.plan)
        plan = Plan.parse(plan_text) if plan_text.strip() else None

        def work(budget: Budget) -> Callable[[], str]:
            dialogue = searching(
                Dialogue.start,
                budget,
                self.model,
                chosen,
                plan,
                self.files,
                **self.options.dialogue(),
            )
            self._prepare(dialogue, budget)

            def commit() -> str:
                session.dialogue = dialogue
                return f"a new dialogue under {chosen}"

            return commit

        what = (
            f"judging the plan under {chosen}"
            if plan is not None
            else f"making a plan under {chosen}"
            if self.model.own_plan() is None
            else f"judging the model's own plan under {chosen}"
        )
        return self.submit(session, "start", what, work)

    def ask(self, session: Session, text: str) -> Job:
        """Ask a question (typed, the grammar of ``ethasp ask``) about the current plan
        (``why step T`` asks for an explanation instead: :meth:`explain`)."""
        self.free(session)
        text = self.limits.check("question", text, self.limits.question)
        if step_question(text) is not None:
            raise InputError(
                f"'{text.strip()}' asks how a step serves the goal, not for a "
                "contrast: the page shows it without a search (GET "
                f"/api/sessions/ID/explain?step={step_question(text)})"
            )
        question = Question.parse(text)
        dialogue = session.require()
        if len(dialogue.steps) >= self.limits.questions:
            raise InputError(
                f"at most {self.limits.questions} questions in one dialogue; "
                "undo some, or save it and start anew"
            )

        def work(budget: Budget) -> Callable[[], str]:
            copy = replace(dialogue, steps=list(dialogue.steps))
            searching(copy.ask, budget, question)
            self._prepare(copy, budget)

            def commit() -> str:
                session.dialogue = copy
                return f"answered: {question}"

            return commit

        return self.submit(session, "ask", f"answering '{question}'", work)

    def undo(self, session: Session) -> Job:
        """Take back the last question."""
        dialogue = self.free(session).require()
        if not dialogue.steps:
            raise InputError("nothing to undo: no question asked yet")

        def work(budget: Budget) -> Callable[[], str]:
            copy = replace(dialogue, steps=list(dialogue.steps))
            step = copy.undo()
            self._prepare(copy, budget)

            def commit() -> str:
                session.dialogue = copy
                return f"took back: {step.question}"

            return commit

        return self.submit(session, "undo", "taking back the last question", work)

    def switch(self, session: Session, principle: str) -> str:
        """The principle later contrast plans must satisfy (no search)."""
        dialogue = self.free(session).require()
        return dialogue.switch_principle(
            self.limits.check("principle", principle, self.limits.name)
        )

    def load(self, session: Session, text: str, name: str = "dialogue.json") -> Job:
        """Load a dialogue saved by the page or by ``ethasp dialogue`` (its
        questions are asked anew, about the served model)."""
        self.free(session)
        name = Path(self.limits.check("file name", name or "dialogue.json", self.limits.name)).name
        text = self.limits.check(name, text, self.limits.dialogue)
        try:
            data = json.loads(text)
        except json.JSONDecodeError as error:
            raise InputError(f"{name}: not a saved dialogue ({error})") from None
        if isinstance(data, dict) and len(data.get("steps") or []) > self.limits.questions:
            raise InputError(f"{name}: more than {self.limits.questions} questions")
        note = ""
        if isinstance(data, dict) and isinstance(data.get("model"), list):
            saved = sorted(Path(str(path)).name for path in data["model"])
            served = sorted(Path(path).name for path in self.files)
            if saved and saved != served:
                note = (
                    f"; it was saved for {', '.join(saved)} and was replayed with the "
                    f"served model {', '.join(served)}"
                )

        def work(budget: Budget) -> Callable[[], str]:
            dialogue = searching(
                Dialogue.from_json, budget, data, self.model, **self.options.dialogue()
            )
            dialogue.model_files = list(self.files)
            self._prepare(dialogue, budget)

            def commit() -> str:
                session.dialogue = dialogue
                return f"loaded {name} ({len(dialogue.steps)} questions){note}"

            return commit

        return self.submit(session, "load", f"loading {name} (asking its questions again)", work)

    def cancel(self, session: Session) -> Job | None:
        job = session.job
        if job is not None:
            job.cancel()
        return job
