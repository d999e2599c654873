"""How a command runs: in a worker thread, watched for its memory and time limits.

:func:`main` parses the command line (:mod:`ethasp.interfaces.cli.parser`),
runs the command's ``run`` function, turns errors into one line on standard
error and an exit code, and handles Ctrl-C.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import threading
import time
from collections.abc import Sequence

from ethasp.errors import InputError
from ethasp.interfaces.cli.options import MEMORY_HARD
from ethasp.interfaces.cli.parser import build_parser


def _memory() -> int:
    """This process's resident memory in bytes (0 where it cannot be read)."""
    try:
        with open("/proc/self/statm") as statm:
            return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


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
        _error("out of memory: the input is too large")
        return 2


def _error(message: str) -> None:
    print(f"ethasp: error: {' '.join(message.split())}", file=sys.stderr, flush=True)


# A command that has not answered this long after its time limit is stuck where
# clingo cannot be stopped (the searches' groundings stop at the limit, but
# not a model's own grounding, nor a program over one plan): seconds = limit + this.
# Only commands that give one answer are watched (``one_answer``): the dialogue
# and the web page run jobs, each under the time limit of its own budget, and
# stay up however long they are used.
OVERRUN_GRACE = 10.0


def _end(code: int, end_process: bool) -> int:
    """Leave with ``code`` while the command's thread may still be inside clingo
    (or reading input): the process ends at once when it is the command line's."""
    if end_process:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(OSError, ValueError):
                stream.flush()
        os._exit(code)
    return code


def _interrupted(args: argparse.Namespace, done: threading.Event, end_process: bool) -> int:
    """Ctrl-C: one line (after saving a dialogue), exit code 130."""
    hook = getattr(args, "on_interrupt", None)
    note = ""
    if hook is not None:
        try:
            note = f"; {hook()}"
        except Exception as error:
            note = f"; dialogue not saved: {error}"
    print(f"ethasp: interrupted{note}", file=sys.stderr, flush=True)
    return 130 if done.is_set() else _end(130, end_process)


def main(argv: Sequence[str] | None = None) -> int:
    """The ethasp command line (``argv`` None: the process's arguments).

    The command runs in a worker thread, so that Ctrl-C is handled at once even
    while clingo grounds or solves, and so that a command still running long
    after its time limit (clingo cannot interrupt grounding) is ended with an
    error.  Called with ``argv`` from Python, main returns in these cases and
    leaves the worker behind; as the command line, it ends the process.
    """
    end_process = argv is None
    args = None
    try:
        parser = build_parser()
        try:
            args = parser.parse_args(argv)
        except SystemExit as done:  # --help, or a usage error already printed
            return done.code if isinstance(done.code, int) else (0 if done.code is None else 2)
        outcome: dict = {}
        done = threading.Event()

        def work() -> None:
            try:
                outcome["code"] = _command(args)
            except BaseException as error:
                outcome["error"] = error
            finally:
                done.set()

        limit = getattr(args, "time_limit", None)
        overrun = limit + OVERRUN_GRACE if limit and args.one_answer else None
        started = time.monotonic()
        # (An Event, not Thread.join: an interrupted join can mark a running
        # thread as stopped.)
        threading.Thread(target=work, name="ethasp-command", daemon=True).start()
        memory = getattr(args, "memory_limit", None)
        memory = memory * 2**30 if memory else None
        try:
            while not done.wait(0.5):
                if memory is not None and args.one_answer:
                    used = _memory()
                    limits = getattr(args, "limits", None)
                    if used > memory and limits is not None and not limits.cancelled:
                        limits.cancel(f"the memory limit of {args.memory_limit:g} GB was reached")
                    if used > MEMORY_HARD * memory:
                        _error(
                            f"out of memory: {used / 2**30:.1f} GB in use, more than "
                            f"{MEMORY_HARD:g} times the memory limit of "
                            f"{args.memory_limit:g} GB, where clingo cannot be stopped "
                            "(--memory-limit GB raises it)"
                        )
                        return _end(2, end_process)
                if overrun is not None and time.monotonic() - started > overrun:
                    _error(
                        f"no answer within the time limit of {limit:g} s: still working "
                        f"after {overrun:g} s, where clingo cannot be stopped (the model's "
                        "own grounding, or a program over one plan; does it end?)"
                    )
                    return _end(2, end_process)
        except KeyboardInterrupt:
            return _interrupted(args, done, end_process)
        if "error" in outcome:
            error = outcome["error"]
            if isinstance(error, KeyboardInterrupt):
                return _interrupted(args, done, end_process)
            if os.environ.get("ETHASP_DEBUG"):
                raise error
            _error(
                f"internal error: {type(error).__name__}: {error} (please report it; "
                "ETHASP_DEBUG=1 shows where)"
            )
            return 70
        # The command is done and its output written: the process ends at
        # once, without tearing down clingo's grounding (tens of milliseconds).
        return _end(outcome["code"], end_process)
    except KeyboardInterrupt:
        print("ethasp: interrupted", file=sys.stderr, flush=True)
        return 130
