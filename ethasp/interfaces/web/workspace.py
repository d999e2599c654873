"""What a server holds: one model (named on its command line), its dialogues
(one per page session) and the jobs that change them.

The server keeps each dialogue as data, with what the page shows of it
(:class:`~ethasp.interfaces.web.moves.Shown`).  Every move that needs clingo
(start a dialogue, ask, undo, load) runs as a job
(:mod:`ethasp.interfaces.web.jobs`) in one of the server's worker processes
(:mod:`ethasp.interfaces.web.workers`), on a copy of the session's dialogue
sent to it; what the worker sends back replaces the dialogue only when the
job ends without being cancelled.  The server itself never grounds the
model, so its requests for the state and the pictures are answered at once.
A session runs one job at a time, and the server as many as it has workers
(:attr:`Limits.running`).
"""

from __future__ import annotations

import json
import secrets
import threading
import weakref
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ethasp.errors import InputError
from ethasp.execution import limits as execution_limits
from ethasp.execution import worker as execution
from ethasp.interfaces.pictures import Pictures
from ethasp.interfaces.web import jobs, moves
from ethasp.interfaces.web.jobs import Job
from ethasp.interfaces.web.moves import Glance, Settings, Shown
from ethasp.interfaces.web.workers import Workers
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.planning.search import DEFAULT_MAX_HORIZON
from ethasp.principles.causal import model_kind
from ethasp.principles.restriction import one_restricting_principle
from ethasp.questions.dialogue import Dialogue
from ethasp.questions.question import Question, step_question
from ethasp.reasons.reasons import DEFAULT_LIMIT

# Seconds a cancel waits for the job's worker to be ended.
CANCEL_WAIT = 5.0


class Refused(Exception):
    """A request the server will not carry out: an HTTP status and one line."""

    def __init__(self, status: int, message: str):
        super().__init__(message)
        self.status = status


@dataclass(frozen=True)
class Options:
    """The search options of every dialogue and the limits of every job (the
    command line's): seconds and gigabytes, None for no limit.  The memory
    limit holds for the whole server: its process and every worker."""

    max_horizon: int = DEFAULT_MAX_HORIZON
    time_limit: float | None = None
    reasons_limit: int = DEFAULT_LIMIT
    memory_limit: float | None = None

    def settings(self) -> Settings:
        return Settings(self.max_horizon, self.time_limit, self.reasons_limit)

    def limits(self) -> execution_limits.Limits:
        """The limits of a job starting now."""
        return execution_limits.Limits.of(self.time_limit, self.memory_limit)


@dataclass(frozen=True)
class Limits:
    """Limits on what the page may send and keep."""

    question: int = 500  # characters of a typed question
    plan: int = 10_000  # characters of a typed plan
    name: int = 100  # characters of a principle name or file name
    dialogue: int = 1_000_000  # characters of a saved dialogue to load
    questions: int = 100  # questions in one dialogue
    sessions: int = 32  # dialogues kept (the least recently used idle one goes)
    running: int = 2  # moves running at once: the server's worker processes

    def check(self, what: str, text: object, limit: int) -> str:
        if not isinstance(text, str):
            raise InputError(f"{what}: expected text")
        if len(text) > limit:
            raise InputError(f"{what}: too long ({len(text)} characters; at most {limit})")
        return text


@dataclass
class Session:
    """One page's dialogue, what the page shows of it, and its current (or
    last) job."""

    id: str
    shown: Shown | None = None
    job: Job | None = None

    @property
    def busy(self) -> bool:
        return self.job is not None and self.job.running

    @property
    def dialogue(self) -> Dialogue | None:
        return self.shown.dialogue if self.shown is not None else None

    def require(self) -> Dialogue:
        if self.shown is None:
            raise InputError("no dialogue yet: start one")
        return self.shown.dialogue

    def have(self) -> frozenset[moves.PlanKey]:
        """The plans whose timelines the session keeps."""
        return frozenset(self.shown.timelines) if self.shown is not None else frozenset()

    def install(self, shown: Shown) -> str:
        """A move's result replaces the dialogue; the timelines kept before
        are kept where the dialogue still draws their plans.  Its note."""
        timelines = {**(self.shown.timelines if self.shown else {}), **shown.timelines}
        needed = {moves.plan_key(plan) for plan in moves.drawn_plans(shown.dialogue, shown.report)}
        shown.timelines = {key: timelines[key] for key in timelines if key in needed}
        self.shown = shown
        return shown.note


class Workspace:
    """The served model, its dialogues, and the worker processes that make
    their moves.

    The model is checked by a worker when the workspace is made (InputError
    in one line if it describes no planning task); :meth:`close` ends the
    workers (they end with this process too).
    """

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
        self._sessions: OrderedDict[str, Session] = OrderedDict()
        self._lock = threading.Lock()
        job_limits = options.limits()
        self.workers = Workers(model, limits.running, job_limits.memory)
        self._closing = weakref.finalize(self, self.workers.close)
        try:
            self.glance: Glance = self._now(moves.glance, model)
        except BaseException:
            self.close()
            raise
        self.pictures = Pictures(model, self.glance.valuation, {})

    def close(self) -> None:
        """End the worker processes."""
        self._closing()

    def _now(self, move: Callable[..., Any], *args: Any) -> Any:
        """Make a move in a worker and wait for it (when the server starts)."""
        worker = self.workers.take()
        if worker is None:
            raise RuntimeError("no worker process is free")
        try:
            outcome = worker.call(move, *args, limits=self.options.limits())
        finally:
            self.workers.give_back(worker)
        if outcome.status == execution.DONE:
            return outcome.value
        if outcome.status == execution.INPUT_ERROR:
            raise InputError(outcome.message)
        if outcome.limited:
            raise InputError(
                f"{outcome.message} while the model was grounded and checked "
                "(see --time-limit and --memory-limit)"
            )
        raise RuntimeError(f"the worker process failed: {outcome.message}")

    def pictures_of(self, shown: Shown) -> Pictures:
        """Pictures of a dialogue's plans, drawn from the timelines kept with it."""
        return Pictures(self.model, self.glance.valuation, shown.timelines)

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
        """Moves running now."""
        return self.workers.busy()

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
        move: Callable[..., Shown],
        *args: Any,
    ) -> Job:
        """Start a job for the session (one at a time; as many in the server
        as it has workers)."""
        self.free(session)
        worker = self.workers.take()
        if worker is None:
            raise Refused(
                503,
                f"busy: {self.limits.running} searches are running; try again shortly "
                "(or cancel one)",
            )
        job = Job(secrets.token_hex(8), kind, description, self.options.limits())
        session.job = job
        return jobs.start(job, worker, self.workers.give_back, move, args, session.install)

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
        what = (
            f"judging the plan under {chosen}"
            if plan is not None
            else f"making a plan under {chosen}"
            if self.glance.own_plan is None
            else f"judging the model's own plan under {chosen}"
        )
        return self.submit(
            session,
            "start",
            what,
            moves.start,
            self.model,
            chosen,
            plan,
            self.files,
            self.options.settings(),
        )

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
        return self.submit(
            session, "ask", f"answering '{question}'", moves.ask, dialogue, question, session.have()
        )

    def undo(self, session: Session) -> Job:
        """Take back the last question."""
        dialogue = self.free(session).require()
        if not dialogue.steps:
            raise InputError("nothing to undo: no question asked yet")
        return self.submit(
            session, "undo", "taking back the last question", moves.undo, dialogue, session.have()
        )

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
        return self.submit(
            session,
            "load",
            f"loading {name} (asking its questions again)",
            moves.load,
            data,
            self.model,
            self.files,
            self.options.settings(),
            name,
            note,
        )

    def cancel(self, session: Session) -> Job | None:
        """Cancel the session's job: its worker process is ended (this waits
        for that, a moment), and a new worker started in its place."""
        job = session.job
        if job is not None and job.cancel():
            job.wait(CANCEL_WAIT)
        return job
