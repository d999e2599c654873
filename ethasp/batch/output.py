"""The results file of a batch: JSON lines, each written and flushed at once, and resumed.

Each line has a hash (``hash``) of what it depends on: the case's name, the
bytes of its files (and of the files they include), its plan, the batch's
options (:meth:`ethasp.batch.task.Settings.options`), the principle and the
question.  A batch run again with the same results file reads the lines
there and computes only those whose hash is missing, so that a batch
interrupted by Ctrl-C, a crash or a lost machine ends with every line once.

A last line without its newline (the process ended while writing it) is cut
off and computed again.  While a batch writes the file, it holds a lock on
it, so that two batches cannot write one file at the same time.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Iterator
from pathlib import Path

from ethasp.batch.cases import Case
from ethasp.batch.task import Settings
from ethasp.errors import InputError

# Changes when what a hash covers changes.
HASH_FORMAT = 1


def line_hash(
    case: Case, digest: str, settings: Settings, principle: str | None, question: str | None
) -> str:
    """The hash of one result line (see the module docstring); ``digest`` is
    :meth:`ethasp.batch.cases.Inputs.digest` of the case's files."""
    data = json.dumps(
        [HASH_FORMAT, case.name, digest, case.plan, settings.options(), principle, question],
        sort_keys=True,
    )
    return hashlib.sha256(data.encode()).hexdigest()[:32]


def read_lines(path: Path, repair: bool = False, advice: str = "") -> Iterator[dict]:
    """The results of a JSON lines file, in order.  A last line without its
    newline is left out (and with ``repair`` cut off the file); any other line
    that is not a JSON object is an InputError naming it (and ending with
    ``advice``, if given)."""
    try:
        with open(path, "rb") as stream:
            data = stream.read()
    except FileNotFoundError:
        return
    except OSError as error:
        raise InputError(f"{path}: cannot be read ({error.strerror or error})") from None
    end = data.rfind(b"\n") + 1
    if end < len(data) and repair:
        with open(path, "r+b") as stream:
            stream.truncate(end)
    for number, raw in enumerate(data[:end].split(b"\n")[:-1], start=1):
        if not raw.strip():
            continue
        try:
            line = json.loads(raw)
        except (ValueError, RecursionError):
            line = None
        if not isinstance(line, dict):
            raise InputError(
                f"{path}:{number}: not a line of batch results (a JSON object)"
                + (f"; {advice}" if advice else "")
            )
        yield line


class Output:
    """A results file open for appending: the hashes already there, and a writer."""

    def __init__(self, path: str | os.PathLike, retry_errors: bool = False):
        self.path = Path(path)
        if self.path.is_dir():
            raise InputError(f"--output {self.path}: is a directory, not a file")
        self.stream = None
        try:
            self.stream = open(self.path, "ab")  # noqa: SIM115 (held until close())
        except OSError as error:
            raise InputError(
                f"--output {self.path}: cannot be written ({error.strerror or error})"
            ) from None
        self._lock()
        lines = list(read_lines(self.path, repair=True, advice="give another --output file"))
        if retry_errors and any("error" in line for line in lines):
            lines = [line for line in lines if "error" not in line]
            self._rewrite(lines)
        self.present: dict[str, dict] = {
            line["hash"]: line for line in lines if isinstance(line.get("hash"), str)
        }

    def _lock(self) -> None:
        try:
            import fcntl
        except ImportError:  # no advisory locks here
            return
        try:
            fcntl.flock(self.stream.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            self.stream.close()
            raise InputError(
                f"--output {self.path}: another batch is writing this file "
                "(wait for it, or give another --output file)"
            ) from None

    def _rewrite(self, lines: list[dict]) -> None:
        """Keep only ``lines`` (the file is rewritten in place, under the lock)."""
        text = "".join(json.dumps(line) + "\n" for line in lines).encode()
        self.stream.flush()
        os.ftruncate(self.stream.fileno(), 0)
        self.stream.seek(0)
        self.stream.write(text)
        self.stream.flush()
        os.fsync(self.stream.fileno())

    def write(self, line: dict) -> None:
        """Append one line and flush it to the file at once."""
        self.stream.write((json.dumps(line) + "\n").encode())
        self.stream.flush()

    def close(self) -> None:
        if self.stream is not None and not self.stream.closed:
            self.stream.close()
