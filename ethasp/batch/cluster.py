"""A Dask cluster as a batch's workers (``--scheduler tcp://HOST:PORT``).

Needs Dask's ``distributed`` (``pip install 'ethasp[cluster]'``) here and on
every worker, with ethasp installed there too.  Each case is one Dask task:
the function :func:`ethasp.batch.task.run` with the case's :class:`Work`,
which carries the bytes of the case's files (and of the files they include),
so that workers need no shared file system: a worker writes them to a
private temporary folder, loads the model from there and deletes them.
Messages name the files as the batch's machine knows them, so the lines are
the same as those of the local pool.

Each Dask worker computes its cases in a worker process of its own
(:func:`ethasp.batch.task.run_limited`: the mechanism of the local pool and
of the command line), which holds the case's time and memory limits and is
ended at them.  Dask reschedules the tasks of a worker that is lost (its
machine ends, its process is killed) on the workers left: no case is lost.
A task whose workers die again and again (the scheduler's
``distributed.scheduler.allowed-failures``, 3 by default) becomes an error
line.  Should a case still run past ``2 x time limit + grace`` (a Dask
worker that does not answer), the batch records it as an error line and
goes on without it.
"""

from __future__ import annotations

import contextlib
import time
import uuid
from collections.abc import Iterable, Iterator
from dataclasses import replace

import ethasp.batch.task as task
from ethasp.batch.task import Settings, Work, error_line
from ethasp.errors import InputError

# Seconds past twice the time limit after which a case is given up (its Dask
# worker ends it at the limit; this is for a worker that does not answer).
OVERRUN_GRACE = 10.0
# Seconds to wait for the scheduler when connecting.
CONNECT_TIMEOUT = 20


def _distributed():
    try:
        import distributed
    except ImportError:
        raise InputError(
            "--scheduler needs Dask's distributed: pip install 'ethasp[cluster]'"
        ) from None
    return distributed


class DaskCluster:
    """The workers of a running Dask scheduler (see the module docstring)."""

    def __init__(
        self,
        address: str,
        settings: Settings,
        grace: float = OVERRUN_GRACE,
        memory_limit: float | None = None,
    ):
        distributed = _distributed()
        self.address = address
        self.settings = settings
        self.grace = grace
        self.memory_limit = memory_limit
        try:
            self.client = distributed.Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
        except (OSError, TimeoutError, ValueError) as error:
            detail = " ".join(str(error).split()) or type(error).__name__
            raise InputError(
                f"--scheduler {address}: cannot connect to a Dask scheduler ({detail})"
            ) from None
        with contextlib.suppress(Exception):
            self.client.run(task.warm)

    def workers(self) -> dict:
        """The scheduler's workers now (address -> information)."""
        return self.client.scheduler_info().get("workers", {})

    def close(self) -> None:
        with contextlib.suppress(Exception):
            self.client.close()

    def run(self, works: Iterable[Work]) -> Iterator[tuple[Work, list[dict]]]:
        """Submit every work; yield each with its lines as it finishes."""
        distributed = _distributed()
        from ethasp.batch.cases import read_inputs

        futures = {}
        for work in works:
            inputs = read_inputs(work.case)
            shipped = replace(work, contents={**inputs.files, **inputs.included})
            key = f"ethasp-case-{uuid.uuid4().hex}"
            future = self.client.submit(
                task.run_limited, shipped, self.settings, self.memory_limit, key=key, pure=False
            )
            futures[future] = work
        limit = self.settings.time_limit
        overrun = None if not limit else 2 * limit + self.grace
        pending = set(futures)
        done = distributed.as_completed(
            futures, loop=self.client.loop, with_results=True, raise_errors=False
        )
        looked = time.monotonic()
        try:
            while pending:
                batch = done.next_batch(block=overrun is None)
                if not batch:
                    # A case may be stuck in grounding: look at the running tasks now and then.
                    if time.monotonic() - looked > 1.0:
                        looked = time.monotonic()
                        for future in self._stuck(pending, overrun):
                            pending.discard(future)
                            future.cancel()
                            yield futures[future], [self._stuck_line(futures[future], overrun)]
                    time.sleep(0.02)
                    continue
                for future, result in batch:
                    if future not in pending:
                        continue
                    pending.discard(future)
                    work = futures[future]
                    # (Told by the result, not by the future's status: a worker
                    # lost after its result was gathered makes the status
                    # "lost" while the result is here, whole.)
                    error = task_error(result)
                    if error is None:
                        yield work, result
                    else:
                        yield work, [self._failure(work, error)]
        finally:
            for future in pending:
                future.cancel()

    def _stuck(self, pending, overrun: float) -> list:
        """The futures whose tasks have run longer than ``overrun`` on their worker."""
        try:
            running = self.client.run_on_scheduler(
                _running_seconds, [future.key for future in pending]
            )
        except Exception:
            return []
        return [future for future in pending if running.get(future.key, 0.0) > overrun]

    def _stuck_line(self, work: Work, overrun: float) -> dict:
        line = error_line(
            work.case,
            f"no answer within the time limit of "
            f"{self.settings.time_limit:g} s: still grounding or "
            f"solving after {overrun:g} s (clingo cannot stop "
            "grounding; does the model's grounding end?)",
        )
        line["seconds"] = round(overrun, 6)
        return line

    @staticmethod
    def _failure(work: Work, error) -> dict:
        name = type(error).__name__
        if name == "KilledWorker":
            return error_line(
                work.case,
                "its worker processes ended while computing it, "
                "again and again (out of memory, or a crash)",
            )
        if name == "CancelledError":
            return error_line(work.case, "its task was cancelled on the cluster")
        return error_line(work.case, f"internal error on a worker: {name}: {error}")


def task_error(result) -> BaseException | None:
    """The error a task's result stands for, None for the lines of a case:
    Dask gives a task that raised as its exception, with its type and
    traceback (``(type, exception, traceback)``), a cancelled one as the
    CancelledError."""
    if isinstance(result, BaseException):
        return result
    if isinstance(result, tuple) and len(result) == 3 and isinstance(result[1], BaseException):
        return result[1]
    return None


def _running_seconds(keys, dask_scheduler=None) -> dict:
    """On the scheduler: how long each of the tasks running now has run (as
    their workers last told it)."""
    result = {}
    for key in keys:
        state = dask_scheduler.tasks.get(key)
        worker = getattr(state, "processing_on", None)
        if worker is not None and state in worker.executing:
            result[key] = worker.executing[state]
    return result
