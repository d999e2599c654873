"""How a command runs: in a worker process that ends at its limits.

:func:`main` parses the command line (:mod:`ethasp.interfaces.cli.parser`)
and runs the command's ``run`` function.  A command that gives one answer
(``plan``, ``judge``, ``ask``, ...) runs in a worker process
(:mod:`ethasp.execution.worker`) under ``--time-limit`` and
``--memory-limit``: its searches stop a little before the time limit and
answer ``bounded``; where clingo cannot be stopped (a grounding), the worker
is ended at the limit plus a fraction of a second and the command answers
``bounded`` with what it had found (the partial answers the command
reported, see :func:`ethasp.interfaces.cli.output.checkpoint`).  The memory
of this process and the worker's together stays below the memory limit.
The answer is written by this process, whole or not at all; lines on
standard error (warnings, one-line errors) come through as the worker writes
them.

The dialogue, the page and the batch keep this process and run each of their
searches in workers of their own.  Errors become one line on standard error
and an exit code; Ctrl-C ends the worker at once and exits with code 130.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import sys
from collections.abc import Sequence

from ethasp.errors import InputError
from ethasp.execution import context as execution_context
from ethasp.execution.limits import Limits, process_started
from ethasp.execution.worker import CANCELLED, DONE, FAILED, INPUT_ERROR, Worker
from ethasp.interfaces.cli.parser import build_parser
from ethasp.interfaces.progress import ProgressLine


def _command(args: argparse.Namespace) -> int:
    """Run a command; errors become one line on standard error and an exit code."""
    try:
        code = args.run(args)
        sys.stdout.flush()
        return code
    except InputError as error:
        _error(str(error))
        return 2
    except BrokenPipeError:
        # The reader went away (e.g. ethasp ... | head): stop quietly.
        sys.stderr.close()
        return 1
    except OSError as error:
        if error.filename is not None:  # a file named by the user
            _error(f"{error.filename}: {error.strerror or error}")
            return 2
        # Standard output cannot be written (a full disk).
        with contextlib.suppress(OSError):  # nothing more to flush at exit
            sys.stdout = open(os.devnull, "w")  # noqa: SIM115 (until the process ends)
        _error(f"cannot write the answer ({error.strerror or error})")
        return 1
    except RecursionError:
        _error("the input is nested too deeply to read")
        return 2
    except MemoryError:
        running = execution_context.current()
        if running is not None and running.limits.memory is not None:
            raise  # the memory limit: the front end answers bounded
        _error("out of memory: the input is too large")
        return 2


def _error(message: str) -> None:
    print(f"ethasp: error: {' '.join(message.split())}", file=sys.stderr, flush=True)


# -- in the worker -------------------------------------------------------------------


class _Relay(io.TextIOBase):
    """Standard error of a command in a worker: each line to the front end as
    it is written."""

    def __init__(self, running: execution_context.Context):
        self.running = running
        self.pending = ""

    def writable(self) -> bool:
        return True

    def isatty(self) -> bool:
        return False

    def write(self, text: str) -> int:
        self.pending += text
        if "\n" in self.pending:
            complete, _, self.pending = self.pending.rpartition("\n")
            self.running.send(("stderr", complete + "\n"))
        return len(text)

    def flush(self) -> None:
        if self.pending:
            self.running.send(("stderr", self.pending))
            self.pending = ""


def run_in_worker(args: argparse.Namespace) -> tuple[int, str]:
    """A command in a worker: its exit code and what it wrote on standard output."""
    running = execution_context.current()
    out = io.StringIO()
    err = _Relay(running) if running is not None else sys.stderr
    sys.stdout, sys.stderr = out, err
    try:
        code = _command(args)
    finally:
        with contextlib.suppress(OSError, ValueError):
            err.flush()
        sys.stdout, sys.stderr = sys.__stdout__, sys.__stderr__
    return code, out.getvalue()


# -- in this process -------------------------------------------------------------------


def _bounded(args: argparse.Namespace, why: str, partial, progress) -> str:
    """The answer of a command ended at a limit: what it reported so far
    (:func:`~ethasp.interfaces.cli.output.checkpoint`) and which limit was
    reached before what; or, where it reported nothing, that no answer was
    found (and how far its search got, from its last progress record)."""
    if isinstance(partial, dict):
        bounded = f"{why} before {partial['missing']}"
        if getattr(args, "json", False):
            data = {**partial["data"], "bounded": bounded}
            if data.get("status") == "bounded":  # (an answer bounded as a whole says why)
                data.setdefault("proof", bounded)
            return json.dumps(data, indent=2)
        return f"{partial['text']}\nbounded: {bounded}"
    proof = f"{why} before an answer was found"
    if progress:
        proof += f" ({progress[-1].line()})"
    if getattr(args, "json", False):
        return json.dumps({"status": "bounded", "proof": proof}, indent=2)
    return f"bounded: {proof}; nothing was proven"


def _write(text: str, stream=None) -> None:
    stream = stream or sys.stdout
    if text:
        stream.write(text if text.endswith("\n") else text + "\n")
    stream.flush()


def supervised(args: argparse.Namespace, limits: Limits) -> int:
    """Run a command that gives one answer in a worker process (see the module
    docstring); the exit code."""
    progress = ProgressLine(enabled=False if getattr(args, "quiet", False) else None)
    worker = Worker()
    last: list = []  # the last progress record

    def relay(text: str) -> None:
        progress.clear()
        sys.stderr.write(text)
        sys.stderr.flush()

    def record(update) -> None:
        last[:] = [update]
        progress(update)

    try:
        outcome = worker.call(
            run_in_worker, args, limits=limits, on_progress=record, on_stderr=relay
        )
    except KeyboardInterrupt:
        worker.kill()
        progress.clear()
        print("ethasp: interrupted", file=sys.stderr, flush=True)
        return 130
    finally:
        worker.kill()
    progress.clear()
    if outcome.status == DONE:
        code, text = outcome.value
        try:
            # With --svg - the answer went to standard error and the picture here.
            if text:
                sys.stdout.write(text)
            sys.stdout.flush()
        except BrokenPipeError:
            with contextlib.suppress(OSError):
                sys.stderr.close()
            return 1
        return code
    if outcome.status == INPUT_ERROR:
        _error(outcome.message)
        return 2
    if outcome.limited:
        stream = sys.stderr if getattr(args, "svg", None) == "-" else sys.stdout
        _write(_bounded(args, outcome.message, outcome.partial, last), stream)
        return 0
    if outcome.status == CANCELLED:
        print("ethasp: interrupted", file=sys.stderr, flush=True)
        return 130
    detail = outcome.message.strip().splitlines()
    if outcome.status == FAILED and os.environ.get("ETHASP_DEBUG"):
        print(outcome.message, file=sys.stderr, flush=True)
    _error(
        f"internal error: {detail[-1] if detail else outcome.status} (please report it; "
        "ETHASP_DEBUG=1 shows where)"
    )
    return 70


def main(argv: Sequence[str] | None = None, worker: bool | None = None) -> int:
    """The ethasp command line (``argv`` None: the process's arguments).

    A command that gives one answer runs in a worker process under its
    limits (see the module docstring) when ``worker`` is true, which is the
    default for the command line itself (``argv`` None).  Called from Python
    with ``argv``, the command runs in this process by default, under the
    cooperative limits of its searches only (they answer ``bounded`` at the
    time limit, but a grounding is not stopped).
    """
    try:
        arguments = list(sys.argv[1:] if argv is None else argv)
        parser = build_parser(arguments[0] if arguments else None)
        try:
            args = parser.parse_args(arguments)
        except SystemExit as done:  # --help, or a usage error already printed
            return done.code if isinstance(done.code, int) else (0 if done.code is None else 2)
        in_worker = (argv is None) if worker is None else worker
        if args.one_answer and in_worker:
            limits = Limits.of(
                getattr(args, "time_limit", None),
                getattr(args, "memory_limit", None),
                process_started() if argv is None else None,
            )
            return supervised(args, limits)
        try:
            return _command(args)
        except KeyboardInterrupt:
            return _interrupted(args)
        except Exception as error:
            if os.environ.get("ETHASP_DEBUG"):
                raise
            _error(
                f"internal error: {type(error).__name__}: {error} (please report it; "
                "ETHASP_DEBUG=1 shows where)"
            )
            return 70
    except KeyboardInterrupt:
        print("ethasp: interrupted", file=sys.stderr, flush=True)
        return 130


def _interrupted(args: argparse.Namespace) -> int:
    """Ctrl-C: one line (after saving a dialogue), exit code 130."""
    hook = getattr(args, "on_interrupt", None)
    note = ""
    if hook is not None:
        try:
            note = f"; {hook()}"
        except Exception as error:
            note = f"; dialogue not saved: {error}"
    print(f"ethasp: interrupted{note}", file=sys.stderr, flush=True)
    return 130
