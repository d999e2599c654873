"""What a batch computes for one case: its result lines, through the Python API.

A worker (a local process or a Dask worker) calls :func:`run` with a
:class:`Work` item and the batch's :class:`Settings`.  The case's model is
loaded from its own files (:meth:`ethasp.planning.model.Model.load`: one
grounding for everything the case asks) and

* ``judge``: its plan (a manifest's, else the model's own) is judged under
  every principle at once (:func:`ethasp.reasons.reasons.judge`);
* ``plan``: a shortest plan permissible under each principle is searched
  (:func:`ethasp.principles.restriction.plan_with_principles`); a principle
  that can only judge (no restriction encoding) judges a shortest plan found
  without it, and its line says so (``"judged": true``);
* ``ask``: each question is asked about the plan under each principle
  (:func:`ethasp.questions.contrast.ask`; without a plan, the plan asked
  about is the one plan search under the principle makes).

Without a task, a case with questions is asked them, a case with a plan is
judged, and a case without is planned for.  One budget (the per-case time
limit) covers the whole case; searches it cuts answer ``bounded``.  Every
line carries ``case``, ``task``, ``principle``, ``permissible``, ``status``,
``plan``, ``utility``, ``seconds`` (the case's whole time in the worker) and
``ethasp_version``.  Bad input becomes a line with ``error`` (the message the
command line prints), for the case or for one principle or question.
"""

from __future__ import annotations

import contextlib
import io
import os
import shutil
import tempfile
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

from ethasp.batch.cases import Case
from ethasp.errors import InputError
from ethasp.execution.limits import Limits
from ethasp.execution.worker import DIED, DONE, Outcome, Worker

JUDGE, PLAN, ASK = "judge", "plan", "ask"
TASKS = (JUDGE, PLAN, ASK)
ERROR = "error"

# The key of a line: (principle, question); CASE = (None, None) for a whole case's error line.
Key = tuple[str | None, str | None]
CASE: Key = (None, None)


@dataclass(frozen=True)
class Settings:
    """The options of a batch that decide its results (all part of each line's hash).

    ``task`` None: per case (see the module docstring).  ``principles`` None:
    the paper's three.  ``reasons_limit`` None: no reasons when judging,
    ``ethasp.reasons.DEFAULT_LIMIT`` when asking (a contrastive answer needs
    them).  ``max_horizon`` None: the searches' default.
    """

    task: str | None = None
    principles: tuple[str, ...] | None = None
    questions: tuple[str, ...] = ()
    under: str | None = None
    max_horizon: int | None = None
    time_limit: float | None = None
    reasons_limit: int | None = None
    satisficing: bool = False
    allow_scripts: bool = False
    # For tests only: a case whose name ends with this text ends its worker
    # process (SIGKILL) on its first ``crash_attempts`` attempts.
    crash_case: str | None = field(default=None, compare=False)
    crash_attempts: int = field(default=0, compare=False)

    def options(self) -> dict:
        """The options as they enter the hash."""
        return {
            "task": self.task,
            "under": self.under,
            "max_horizon": self.max_horizon,
            "time_limit": self.time_limit,
            "reasons_limit": self.reasons_limit,
            "satisficing": self.satisficing,
            "allow_scripts": self.allow_scripts,
        }


@dataclass(frozen=True)
class Work:
    """One case to compute: the lines wanted (keys ``(principle, question)``),
    the attempt (from 1), and, for workers on other machines, the bytes of
    its files (path as named -> content; None: read the files where they are)."""

    case: Case
    keys: tuple[tuple[str | None, str | None], ...]
    attempt: int = 1
    contents: dict[str, bytes] | None = None


_VERSION: list[str] = []


def version() -> str:
    """This worker's ethasp version, as ``ethasp --version`` prints it (read once from
    the package's metadata; ``unknown`` for a checkout that is not installed)."""
    if not _VERSION:
        from importlib.metadata import PackageNotFoundError
        from importlib.metadata import version as installed

        try:
            _VERSION.append(installed("ethasp"))
        except PackageNotFoundError:
            _VERSION.append("unknown")
    return _VERSION[0]


def one_line(message: str) -> str:
    return " ".join(str(message).split())


def error_line(
    case: Case,
    message: str,
    principle: str | None = None,
    question: str | None = None,
    task: str | None = None,
) -> dict:
    line = {
        "case": case.name,
        "principle": principle,
        "permissible": None,
        "status": ERROR,
        "plan": None,
        "utility": None,
        "error": one_line(message),
    }
    if task is not None:
        line["task"] = task
    if question is not None:
        line["question"] = question
    return line


def warm() -> None:
    """Import what every case uses and read the principles' encodings (once per process)."""
    import ethasp.principles.restriction
    import ethasp.questions.contrast
    import ethasp.reasons.reasons  # noqa: F401
    from ethasp.principles.principle import available_principles

    available_principles()
    version()


def case_lines(work: Work, outcome: Outcome) -> list[dict] | None:
    """The lines of a case from how its call in a worker ended: None where it
    should be retried (its worker died on a first attempt)."""
    if outcome.status == DONE:
        return outcome.value
    if outcome.status == DIED and work.attempt < 2:
        return None
    if outcome.status == DIED:
        cause = outcome.message.removeprefix("the worker process ended ").strip("()")
        message = (
            f"its worker process ended while computing it, twice ({cause}): out of "
            "memory, or a crash"
        )
    elif outcome.limited:
        message = (
            f"no answer within the limits: {outcome.message} while clingo was grounding "
            "or solving, where it cannot be stopped (does the model's grounding end?)"
        )
    else:
        message = f"internal error: {outcome.message.strip().splitlines()[-1]} (please report it)"
    line = error_line(work.case, message)
    line["seconds"] = round(outcome.seconds, 6)
    return [line]


_worker: Worker | None = None


def run_limited(work: Work, settings: Settings, memory_limit: float | None = None) -> list[dict]:
    """The lines of one case computed in a worker process of this process
    under the case's limits (how a Dask worker computes a case: the same
    mechanism as the local pool's), retried once on a fresh worker if its
    worker dies."""
    global _worker
    if _worker is None:
        _worker = Worker(warm, "ethasp-batch-worker", own_tree=True)
    while True:
        _worker.ready()  # a case's limits count the case, not the warm-up
        limits = Limits.of(settings.time_limit, memory_limit)
        lines = case_lines(work, _worker.call(run, work, settings, limits=limits))
        if lines is not None:
            return lines
        work = replace(work, attempt=work.attempt + 1)


def run(work: Work, settings: Settings) -> list[dict]:
    """The result lines of one case (never raises for bad input: error lines)."""
    if (
        settings.crash_case is not None
        and work.case.name.endswith(settings.crash_case)
        and work.attempt <= settings.crash_attempts
    ):
        import signal

        os.kill(os.getpid(), signal.SIGKILL)
    started = time.perf_counter()
    folder, renamed = None, {}
    said = io.StringIO()
    try:
        files, folder, renamed = _files(work)
        try:
            with contextlib.redirect_stderr(said):
                lines = _compute(work, settings, files)
        except InputError as error:
            lines = [error_line(work.case, _restore(str(error), renamed))]
        except RecursionError:
            lines = [error_line(work.case, "the input is nested too deeply to read")]
        except MemoryError:
            lines = [error_line(work.case, "out of memory: the input is too large")]
        except Exception as error:
            lines = [
                error_line(
                    work.case,
                    f"internal error: {type(error).__name__}: "
                    f"{_restore(str(error), renamed)} (please report it)",
                )
            ]
        else:
            for line in lines:
                if "error" in line:
                    line["error"] = _restore(line["error"], renamed)
    finally:
        if folder is not None:
            shutil.rmtree(folder, ignore_errors=True)
    seconds = round(time.perf_counter() - started, 6)
    warnings = [_restore(text, renamed) for text in said.getvalue().splitlines() if text.strip()]
    for line in lines:
        if warnings:
            line["warnings"] = warnings
        line["seconds"] = seconds
        line["ethasp_version"] = version()
    return lines


# -- files ----------------------------------------------------------------------------------


def _files(work: Work) -> tuple[list[str], str | None, dict[str, str]]:
    """The paths to load: the case's own, or copies of the bytes sent along
    (in a private folder, laid out as the originals relative to each other;
    ``renamed`` maps each copy back to the name the user gave, for messages)."""
    if work.contents is None:
        return list(work.case.files), None, {}
    folder = tempfile.mkdtemp(prefix="ethasp-case-")
    absolute = {name: os.path.abspath(name) for name in work.contents}
    common = os.path.commonpath([os.path.dirname(path) for path in absolute.values()])
    renamed: dict[str, str] = {}
    copies: dict[str, str] = {}
    for name, content in work.contents.items():
        relative = os.path.relpath(absolute[name], common)
        copy = os.path.join(folder, relative)
        os.makedirs(os.path.dirname(copy), exist_ok=True)
        with open(copy, "wb") as stream:
            stream.write(content)
        copies[name] = copy
        renamed[copy] = name
    # A file that could not be read where the batch started is missing here too.
    paths = [
        copies.get(name, os.path.join(folder, "missing", os.path.basename(name)))
        for name in work.case.files
    ]
    for name, path in zip(work.case.files, paths, strict=True):
        renamed.setdefault(path, name)
    return paths, folder, renamed


def _restore(message: str, renamed: dict[str, str]) -> str:
    for copy in sorted(renamed, key=len, reverse=True):
        message = message.replace(copy, renamed[copy])
    return message


# -- the tasks ------------------------------------------------------------------------------


def _compute(work: Work, settings: Settings, files: list[str]) -> list[dict]:
    from ethasp.planning.budget import Budget
    from ethasp.planning.model import Model
    from ethasp.planning.plan import Plan

    case = work.case
    if case.problem is not None:
        raise InputError(case.problem)
    budget = Budget(settings.time_limit)
    model = Model.load([Path(name) for name in files], allow_scripts=settings.allow_scripts)
    plan = Plan.parse(case.plan) if case.plan is not None else model.own_plan()
    questions = case.questions if case.questions is not None else settings.questions
    task = settings.task or (ASK if questions else JUDGE if plan is not None else PLAN)
    principles = list(dict.fromkeys(principle for principle, _ in work.keys))
    if task == JUDGE:
        if plan is None:
            raise InputError(
                "no plan to judge: the model comes with no plan of its own "
                "(give one in a manifest's column plan, or use --task plan)"
            )
        return _judge(model, case, plan, principles, settings, budget)
    if task == PLAN:
        return _plan(model, case, principles, settings, budget)
    return _ask(model, case, plan, work.keys, settings, budget)


def _max_horizon(settings: Settings, searching: bool = False) -> int:
    """--max-horizon, or its default (as the commands' defaults: larger for the
    plans of an any-plan search)."""
    from ethasp.planning.search import DEFAULT_MAX_HORIZON, DEFAULT_SATISFICING_HORIZON

    if settings.max_horizon is not None:
        return settings.max_horizon
    return (
        DEFAULT_SATISFICING_HORIZON if searching and settings.satisficing else DEFAULT_MAX_HORIZON
    )


def _judge(
    model, case: Case, plan, principles: list[str], settings: Settings, budget
) -> list[dict]:
    from ethasp.reasons.reasons import judge

    report = judge(
        model,
        plan,
        principles,
        _max_horizon(settings),
        reasons_limit=settings.reasons_limit or 0,
        budget=budget,
    )
    lines = []
    for judgement in report.judgements:
        line = {
            "case": case.name,
            "task": JUDGE,
            "principle": judgement.principle,
            "permissible": judgement.permissible,
            "status": judgement.status,
            "plan": report.plan.to_list(),
            "utility": report.utility,
            "proof": judgement.proof,
        }
        if not report.goal_reached:
            line["goal_reached"] = False
        explanation = judgement.explanation
        if explanation is not None:
            line["explanation"] = explanation.text
            line["sufficient_reasons"] = explanation.sufficient_reasons
            line["necessary_reasons"] = explanation.necessary_reasons
        lines.append(line)
    return lines


def _plan(model, case: Case, principles: list[str], settings: Settings, budget) -> list[dict]:
    from ethasp.planning.search import FOUND, NONE
    from ethasp.principles.causal import model_kind
    from ethasp.principles.judgement import final_utility
    from ethasp.principles.principle import select_principles
    from ethasp.principles.restriction import plan_with_principles, restricts

    lines = []
    for principle in principles:
        try:
            if not restricts(select_principles([principle], model_kind(model))[0]):
                lines.append(_judged(model, case, principle, settings, budget))
                continue
            result = plan_with_principles(
                model,
                [principle],
                settings.max_horizon,
                budget=budget,
                satisficing=settings.satisficing,
            )
        except InputError as error:
            lines.append(error_line(case, str(error), principle, task=PLAN))
            continue
        found = result.plan is not None and result.status == FOUND
        line = {
            "case": case.name,
            "task": PLAN,
            "principle": principle,
            "permissible": True if found else False if result.status == NONE else None,
            "status": result.status,
            "plan": result.plan.to_list() if found else None,
            "utility": final_utility(model, result.plan) if found else None,
            "horizon": result.horizon,
            "optimal": result.optimal if found else None,
            "proof": result.proof,
        }
        if result.best is not None:
            line["best_utility"] = result.best.utility
        lines.append(line)
    return lines


def _judged(model, case: Case, principle: str, settings: Settings, budget) -> dict:
    """The plan task's line of a principle that can only judge (it has no
    restriction encoding): a shortest plan, found without it, judged under it
    (``judged``: true).  Permissible, it is a shortest permissible plan;
    impermissible, it says nothing of other plans.  No plan at all: none is
    permissible."""
    from ethasp.planning.search import FOUND, NONE, find_plan
    from ethasp.principles.judgement import final_utility
    from ethasp.reasons.reasons import judge

    result = find_plan(
        model, _max_horizon(settings, True), budget=budget, satisficing=settings.satisficing
    )
    line = {
        "case": case.name,
        "task": PLAN,
        "principle": principle,
        "judged": True,
        "permissible": False if result.status == NONE else None,
        "status": result.status,
        "plan": None,
        "utility": None,
        "horizon": result.horizon,
        "optimal": None,
        "proof": f"{principle} cannot restrict plan search: {result.proof}",
    }
    if result.status != FOUND or result.plan is None:
        return line
    judgement = judge(
        model, result.plan, [principle], _max_horizon(settings), reasons_limit=0, budget=budget
    ).judgements[0]
    shortest = "a shortest plan" if result.optimal else "a plan"
    return line | {
        "permissible": judgement.permissible,
        "status": judgement.status,
        "plan": result.plan.to_list(),
        "utility": final_utility(model, result.plan),
        "optimal": result.optimal,
        "proof": f"{principle} cannot restrict plan search, so {shortest} found without "
        f"it is judged under it: {judgement.proof}",
    }


def _ask(model, case: Case, plan, keys, settings: Settings, budget) -> list[dict]:
    from ethasp.principles.judgement import final_utility
    from ethasp.questions.contrast import ask, original_plan
    from ethasp.reasons.reasons import DEFAULT_LIMIT

    lines = []
    originals: dict[str, object] = {}
    for principle, question in keys:
        if question is None:
            lines.append(
                error_line(
                    case,
                    "no question to ask (give --question, or a manifest's column questions)",
                    principle,
                    task=ASK,
                )
            )
            continue
        try:
            asked = plan
            if asked is None:
                if principle not in originals:
                    try:
                        originals[principle] = original_plan(
                            model,
                            principle,
                            _max_horizon(settings, True),
                            budget=budget,
                            satisficing=settings.satisficing,
                        )
                    except InputError as error:  # searched once, for every question
                        originals[principle] = error
                asked = originals[principle]
                if isinstance(asked, InputError):
                    raise asked
            answer = ask(
                model,
                question,
                asked,
                principle,
                settings.under,
                _max_horizon(settings, True),
                reasons_limit=settings.reasons_limit or DEFAULT_LIMIT,
                budget=budget,
                satisficing=settings.satisficing,
            )
        except InputError as error:
            lines.append(error_line(case, str(error), principle, question, ASK))
            continue
        contrast = answer.contrast
        lines.append(
            {
                "case": case.name,
                "task": ASK,
                "principle": principle,
                "question": question,
                "under": answer.under,
                "permissible": answer.original.judgement.permissible,
                "status": answer.status,
                "plan": asked.to_list(),
                "utility": final_utility(model, asked),
                "contrast_plan": contrast.plan.to_list() if contrast else None,
                "contrast_permissible": contrast.judgement.permissible if contrast else None,
                "contrast_utility": final_utility(model, contrast.plan) if contrast else None,
                "principle_dropped": answer.principle_dropped,
                "conflict": [str(c) for c in answer.conflict],
                "explanation": answer.explanation,
                "proof": answer.proof,
            }
        )
    return lines
