"""A batch: many cases, computed by warm workers, results as they finish.

:func:`batch` finds the cases (:mod:`ethasp.batch.cases`), checks the
options, reads the results file of an earlier run if there is one
(:mod:`ethasp.batch.output`), and returns a :class:`Batch`: iterating it
computes the missing lines on the local pool (:mod:`ethasp.batch.pool`) or
on a Dask cluster (:mod:`ethasp.batch.cluster`) and yields each line (a
dict) as its case finishes, after writing it to the results file.
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ethasp.batch.cases import Case, choices, discover, read_inputs
from ethasp.batch.output import Output, line_hash
from ethasp.batch.pool import LocalPool, default_workers
from ethasp.batch.task import ASK, CASE, TASKS, Key, Settings, Work, version
from ethasp.errors import InputError

if TYPE_CHECKING:
    from ethasp.batch.cluster import DaskCluster

# The order of the first fields of a line (the others follow as computed).
FIRST = ("case", "task", "principle", "question", "permissible", "status", "plan", "utility")
LAST = ("seconds", "ethasp_version", "files", "hash")


@dataclass
class _Planned:
    """A case, its lines' hashes by key, and the keys still to compute."""

    case: Case
    hashes: dict[Key, str]
    missing: tuple[Key, ...]
    failed_before: bool


class Batch:
    """The lines of a batch, yielded as they finish (see :func:`batch`).

    Before iterating: ``cases`` (all the batch's cases), ``skipped`` (cases
    whose lines are all in the results file already), ``lines_before`` (their
    number there).  While and after iterating: ``cases_done``,
    ``cases_failed`` (counting earlier runs: a case with an error line),
    ``lines_written``, ``seconds``.
    """

    def __init__(
        self,
        cases: list[Case],
        settings: Settings,
        output: Output | None,
        workers: int,
        scheduler: str | None,
        grace: float | None,
        memory_limit: float | None = None,
    ):
        self.cases = cases
        self.memory_limit = memory_limit
        self.settings = settings
        self.output = output
        self.workers = workers
        self.scheduler = scheduler
        self.grace = grace
        self.backend: LocalPool | DaskCluster | None = None
        self.lines_written = 0
        self.seconds = 0.0
        self._closed = False
        present = output.present if output is not None else {}
        self.planned: list[_Planned] = []
        for given in cases:
            for case in choices(given):  # a causal agency model: each of its actions
                self.planned.append(self._plan(case, present))
        self.skipped = sum(1 for item in self.planned if not item.missing)
        self.lines_before = sum(
            1 for item in self.planned for digest in item.hashes.values() if digest in present
        )
        self.cases_failed = sum(1 for item in self.planned if item.failed_before)
        self.cases_done = self.skipped

    def _plan(self, case: Case, present: dict) -> _Planned:
        from ethasp.principles.principle import select_principles

        digest = read_inputs(case).digest()
        settings = self.settings
        names = case.principles if case.principles is not None else settings.principles
        try:
            principles = [p.name for p in select_principles(names, case.kind)]
        except InputError as error:
            case = Case(
                case.files,
                case.name,
                case.plan,
                (),
                case.questions,
                problem=case.problem or str(error),
            )
            principles = []
        questions = case.questions if case.questions is not None else settings.questions
        asking = settings.task == ASK or (settings.task is None and bool(questions))
        keys = [(p, q) for p in principles for q in (questions if asking and questions else [None])]
        hashes = {key: line_hash(case, digest, settings, *key) for key in [CASE, *keys]}
        failed = hashes[CASE] in present or any(
            "error" in present[hashes[key]] for key in keys if hashes[key] in present
        )
        missing: tuple[Key, ...] = ()
        if hashes[CASE] not in present:
            missing = tuple(key for key in keys if hashes[key] not in present)
            if case.problem is not None and not keys:
                missing = (CASE,)
        return _Planned(case, hashes, missing, failed)

    # -- running ------------------------------------------------------------------

    def _backend(self) -> LocalPool | DaskCluster:
        if self.scheduler is not None:
            from ethasp.batch.cluster import DaskCluster

            if self.grace is None:
                return DaskCluster(self.scheduler, self.settings, memory_limit=self.memory_limit)
            return DaskCluster(self.scheduler, self.settings, self.grace, self.memory_limit)
        if self.grace is None:
            return LocalPool(self.workers, self.settings, memory_limit=self.memory_limit)
        return LocalPool(self.workers, self.settings, self.memory_limit, self.grace)

    def start(self) -> LocalPool | DaskCluster:
        """Connect to the cluster (or prepare the local pool) before iterating;
        a scheduler that cannot be reached is an InputError here."""
        if self.backend is None:
            self.backend = self._backend()
        return self.backend

    def __iter__(self) -> Iterator[dict]:
        started = time.monotonic()
        works = [
            Work(item.case, tuple(k for k in item.missing if k != CASE) or (CASE,))
            for item in self.planned
            if item.missing
        ]
        by_case = {id(item.case): item for item in self.planned}
        try:
            if not works:
                return
            backend = self.start()
            for work, lines in backend.run(works):
                item = by_case[id(work.case)]
                failed = False
                for line in lines:
                    line = self._finish(item, line)
                    failed = failed or "error" in line
                    if self.output is not None:
                        self.output.write(line)
                    self.lines_written += 1
                    yield line
                self.cases_done += 1
                if failed and not item.failed_before:
                    self.cases_failed += 1
                self.seconds = time.monotonic() - started
        finally:
            self.seconds = time.monotonic() - started
            self.close()

    def _finish(self, item: _Planned, line: dict) -> dict:
        key = (line.get("principle"), line.get("question"))
        if "error" in line and key not in item.hashes:
            key = CASE
        line.setdefault("seconds", None)
        line.setdefault("ethasp_version", version())
        line["files"] = list(item.case.files)
        line["hash"] = item.hashes.get(key, item.hashes[CASE])
        ordered = {name: line[name] for name in FIRST if name in line}
        ordered.update(
            (name, value) for name, value in line.items() if name not in FIRST and name not in LAST
        )
        ordered.update((name, line[name]) for name in LAST if name in line)
        return ordered

    def busy_pids(self) -> list[int]:
        """The local workers' process ids that compute a case now (for tests and tools)."""
        return self.backend.busy_pids() if isinstance(self.backend, LocalPool) else []

    def close(self) -> None:
        """End the workers (local) or the connection (cluster), and close the results
        file; callable from another thread (Ctrl-C)."""
        if self._closed:
            return
        self._closed = True
        if self.backend is not None:
            self.backend.close()
        if self.output is not None:
            self.output.close()


def _known(name: str) -> str:
    """A principle or group name known for plans or for causal agency models
    (each case checks it for its own kind); else the InputError for plans."""
    from ethasp.principles.principle import CAM, PLAN, select_principles

    try:
        select_principles([name], PLAN)
    except InputError:
        select_principles([name], CAM)  # defined for causal agency models only
    return name.strip().lower()


def batch(
    cases: Iterable[Case | str | os.PathLike | Sequence[str]],
    principles: Sequence[str] | None = None,
    *,
    task: str | None = None,
    questions: Sequence[str] = (),
    under: str | None = None,
    output: str | os.PathLike | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    time_limit: float | None = None,
    max_horizon: int | None = None,
    reasons_limit: int | None = None,
    satisficing: bool = False,
    allow_scripts: bool = False,
    glob: str | None = None,
    retry_errors: bool = False,
    grace: float | None = None,
    settings: Settings | None = None,
    memory_limit: float | None = None,
) -> Batch:
    """Compute many cases at once; iterate the result to get each line as it finishes.

    ``cases``: model files, folders (searched recursively for file names
    matching ``glob``), CSV or YAML manifests, lists of files (one case) or
    :class:`~ethasp.batch.cases.Case` objects.  ``principles``: names or groups
    (paper, hera, all; default the paper's three).  ``task``: judge, plan or
    ask (default per case: ask when there are questions, judge when the case
    has a plan, else plan).  ``output``: a JSON lines file, appended to and
    resumed (lines already there are not computed again; ``retry_errors``
    computes the error lines again).  ``workers``: local worker processes
    (default: every core); ``scheduler``: the address of a Dask scheduler
    instead.  ``time_limit``: seconds per case (None: none), ``memory_limit``:
    gigabytes per case (None: none), held as by the command line: the
    searches stop at them and answer ``bounded``, and a case stuck where
    clingo cannot be stopped is ended there as an error line
    (:mod:`ethasp.batch.pool`; ``grace``: the seconds past the time limit
    at which a local worker is ended, or past twice the time limit at which
    the cluster gives up a case whose Dask worker does not answer).

    Raises InputError for bad options or inputs (before anything runs).
    """
    if task is not None and task not in TASKS:
        raise InputError(f"unknown task {task!r} (tasks: {', '.join(TASKS)})")
    if workers is not None and workers < 1:
        raise InputError("the number of workers must be at least 1")
    if scheduler is not None and workers is not None:
        raise InputError(
            "--workers is for the local pool: a Dask cluster computes with the "
            "workers started for it"
        )
    if time_limit is not None and not time_limit >= 0:
        raise InputError("the time limit must be 0 seconds or more")
    if reasons_limit is not None and reasons_limit < 0:
        raise InputError("the reasons limit must be at least 0")
    from ethasp.questions.question import Question

    # Names are kept as given: a group (hera) names different principles for
    # plans and for causal agency models, and each case selects its own.
    names = None if principles is None else tuple(_known(name) for name in principles)
    if under is not None:
        under = _known(under)
    for question in questions:
        Question.parse(question)
    if questions and task not in (None, ASK):
        raise InputError(f"questions are asked by the task ask, not {task}")
    if settings is None:
        settings = Settings(
            task,
            names,
            tuple(questions),
            under,
            max_horizon,
            time_limit or None,
            reasons_limit,
            satisficing,
            allow_scripts,
        )
    found = discover(list(cases), glob)
    if not found:
        raise InputError("no case given")
    results = Output(output, retry_errors) if output is not None else None
    try:
        return Batch(
            found,
            settings,
            results,
            workers or default_workers(),
            scheduler,
            grace,
            memory_limit or None,
        )
    except BaseException:
        if results is not None:
            results.close()
        raise
