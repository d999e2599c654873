"""Time and memory limits of work, and the memory of process trees.

A :class:`Limits` is what a front end promises its user: the work ends by
``time`` seconds after it began (plus :data:`GRACE`), and the resident
memory of every process it runs, together with the front end's own, stays
below ``memory`` bytes.  The work itself stops cooperatively a little
earlier (:meth:`Limits.soft_deadline`, :data:`SOFT_MEMORY`) and answers
``bounded`` with what it found; the front end ends its process at the hard
limits (:mod:`ethasp.execution.worker`).

Resident memory is read from ``/proc`` (Linux); where it cannot be read it
counts as 0 and only the address-space limit set in the child holds.
"""

from __future__ import annotations

import contextlib
import os
import resource
import time
from dataclasses import dataclass

# Seconds after the time limit at which a front end ends work that is still
# running (where clingo cannot be interrupted: a grounding).  The promise to
# users is the time limit plus one second, process teardown included.
GRACE = 0.3
# Seconds before the time limit at which the work's own budget expires, so
# that it can still put what it found into words: a part of the limit, at
# most this much.
RESERVE = 0.4
RESERVE_SHARE = 0.1
# Fractions of the memory limit: beyond SOFT the work is asked to stop and
# answer bounded; beyond HARD its processes are ended.
SOFT_MEMORY = 0.7
HARD_MEMORY = 0.9
# How often a front end reads the memory of the processes it watches.
POLL = 0.02

GB = 2**30
PAGE = os.sysconf("SC_PAGE_SIZE") if hasattr(os, "sysconf") else 4096


@dataclass(frozen=True)
class Limits:
    """A time limit (seconds) and a memory limit (bytes) of some work, measured
    from ``started`` (a :func:`time.monotonic` reading, shared by every
    process of this machine); None: no limit.  The work's processes are
    ended ``grace`` seconds after the time limit."""

    time: float | None = None
    memory: int | None = None
    started: float = 0.0
    grace: float = GRACE

    @classmethod
    def of(
        cls,
        seconds: float | None,
        gigabytes: float | None,
        started: float | None = None,
        grace: float = GRACE,
    ) -> Limits:
        """Limits from the command line's units, starting at ``started`` (a
        :func:`time.monotonic` reading; None: now)."""
        return cls(
            seconds if seconds else None,
            int(gigabytes * GB) if gigabytes else None,
            time.monotonic() if started is None else started,
            grace,
        )

    def restarted(self) -> Limits:
        """The same limits, from now."""
        return Limits(self.time, self.memory, time.monotonic(), self.grace)

    def deadline(self) -> float | None:
        """When the work must have ended (before the grace)."""
        return None if self.time is None else self.started + self.time

    def soft_deadline(self) -> float | None:
        """When the work's own budget expires: a little before the deadline,
        to put what it found into words."""
        if self.time is None:
            return None
        return self.started + self.time - min(RESERVE, RESERVE_SHARE * self.time)

    def hard_deadline(self) -> float | None:
        """When a front end ends the work's processes."""
        return None if self.time is None else self.started + self.time + self.grace

    def remaining(self) -> float | None:
        """Seconds to the soft deadline (None: no limit; never below 0)."""
        deadline = self.soft_deadline()
        return None if deadline is None else max(0.0, deadline - time.monotonic())

    def gigabytes(self) -> float | None:
        return None if self.memory is None else self.memory / GB

    def time_words(self) -> str:
        return f"the time limit of {self.time:g} s was reached"

    def memory_words(self) -> str:
        return f"the memory limit of {self.memory / GB:g} GB was reached"


def process_started() -> float:
    """When this process started, as a :func:`time.monotonic` reading (now,
    where that cannot be read): a command's limits count its start-up too."""
    now = time.monotonic()
    try:
        with open("/proc/self/stat") as stat:
            text = stat.read()
        ticks = int(text[text.rfind(")") + 2 :].split()[19])
        age = time.clock_gettime(time.CLOCK_BOOTTIME) - ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError, AttributeError):
        return now
    return now - age if 0 <= age < 60 else now


def resident(pid: int) -> int:
    """The resident memory of one process in bytes (0 where it cannot be read)."""
    try:
        with open(f"/proc/{pid}/statm") as statm:
            return int(statm.read().split()[1]) * PAGE
    except (OSError, ValueError, IndexError):
        return 0


def data_size(pid: int) -> int:
    """The private writable memory of a process in bytes (``VmData``: what
    ``RLIMIT_DATA`` limits); 0 where it cannot be read."""
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmData:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return 0


def _parents() -> dict[int, int]:
    """Every process of this machine and its parent (empty where /proc is not)."""
    parents: dict[int, int] = {}
    try:
        names = os.listdir("/proc")
    except OSError:
        return parents
    for name in names:
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/stat") as stat:
                text = stat.read()
        except OSError:
            continue
        # pid (comm) state ppid ...: comm may hold spaces and parentheses.
        fields = text[text.rfind(")") + 2 :].split()
        if len(fields) > 1:
            parents[int(name)] = int(fields[1])
    return parents


# Does the kernel list each thread's children in /proc (CONFIG_PROC_CHILDREN)?
_CHILDREN_FILES = os.path.exists(f"/proc/self/task/{os.getpid()}/children")


def _children(pid: int) -> list[int]:
    """The children of a process, from its threads' ``children`` files in
    /proc: a few small files, where the scan of every process reads hundreds
    (none for a process that ended)."""
    try:
        threads = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return []
    found: list[int] = []
    for thread in threads:
        try:
            with open(f"/proc/{pid}/task/{thread}/children") as children:
                found += [int(child) for child in children.read().split()]
        except OSError:
            continue  # the thread ended
    return found


def descendants(root: int) -> list[int]:
    """The processes below ``root`` (children, their children, ...)."""
    if not _CHILDREN_FILES:
        return _descendants_by_scan(root)
    found: list[int] = []
    stack = [root]
    while stack:
        below = _children(stack.pop())
        found += below
        stack += below
    return found


def _descendants_by_scan(root: int) -> list[int]:
    """:func:`descendants` from the parent of every process of the machine."""
    children: dict[int, list[int]] = {}
    for pid, parent in _parents().items():
        children.setdefault(parent, []).append(pid)
    found, stack = [], [root]
    while stack:
        for child in children.get(stack.pop(), ()):
            found.append(child)
            stack.append(child)
    return found


def tree_resident(root: int) -> int:
    """The resident memory of ``root`` and every process below it, in bytes."""
    return resident(root) + sum(resident(pid) for pid in descendants(root))


def limit_data(size: int | None) -> tuple[int, int] | None:
    """In a child process: no more than ``size`` bytes of private writable
    memory (``RLIMIT_DATA``: the heap and anonymous mappings, where clingo and
    Python keep what they build).  An allocation beyond fails (MemoryError,
    or clingo's ``std::bad_alloc``), which the work reports as the memory
    limit; processes it starts inherit the limit.  The limit before (for
    :func:`restore_data`), None where nothing was set."""
    if size is None or not hasattr(resource, "RLIMIT_DATA"):
        return None
    try:
        before = resource.getrlimit(resource.RLIMIT_DATA)
        hard = before[1]
        if hard != resource.RLIM_INFINITY:
            size = min(size, hard)
        resource.setrlimit(resource.RLIMIT_DATA, (size, hard))
        return before
    except (OSError, ValueError):
        return None


def restore_data(before: tuple[int, int] | None) -> None:
    """Undo :func:`limit_data`."""
    if before is not None:
        with contextlib.suppress(OSError, ValueError):
            resource.setrlimit(resource.RLIMIT_DATA, before)
