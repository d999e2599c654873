"""Child processes for the engines, started safely from a process with threads.

The engines that run beside a search (exact layers, greedy search:
:mod:`ethasp.planning.engines`) work in a child process of their own, which
the search ends when it ends.  The process that starts them has threads by
then (clingo's solver and grounding, listeners), and a plain ``fork()`` of a
process with threads copies locks that no thread will release.  So children
are forked by a *spawner*, a small process forked early, while its parent
still had one thread (:func:`start`, called by every worker process when it
starts): it only ever forks, on request, and hands the new child's pipe back
over a Unix socket.  A process that has no spawner of its own (a program
that uses the Python API from a thread) starts them as new Python processes
instead (fork and exec at once, safe with threads; slower to start).

A child runs ``target(*args, out)``: it writes lines to ``out``, a text
stream, and ends.  Each child is killed when its parent (the spawner, or the
parent) ends, and the spawner when the process that started it ends.
"""

from __future__ import annotations

import contextlib
import gc
import os
import pickle
import signal
import socket
import struct
import subprocess
import sys
import threading
from collections.abc import Callable, Iterator
from typing import Any

from ethasp.execution import symbols  # noqa: F401 (symbols pickle as text)
from ethasp.execution.limits import limit_data


def end_with_parent() -> None:
    """Linux: this process is killed when the thread that started it ends (the
    main thread of a single-threaded process, or the spawner)."""
    if not sys.platform.startswith("linux"):
        return
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def threads() -> int:
    """The threads of this process, clingo's native ones included (Linux);
    Python's count elsewhere."""
    try:
        return len(os.listdir("/proc/self/task"))
    except OSError:
        return threading.active_count()


class Child:
    """A child process started by a spawner: its lines, and an end."""

    def __init__(self, pid: int, lines: Iterator[str], end: Callable[[], None]):
        self.pid = pid
        self._lines = lines
        self._end = end

    def lines(self) -> Iterator[str]:
        """The lines the child writes, until it ends."""
        return self._lines

    def kill(self) -> None:
        self._end()


def _send(sock: socket.socket, data: bytes, fds: list[int] = ()) -> None:
    header = struct.pack("!Q", len(data))
    if fds:
        socket.send_fds(sock, [header], list(fds))
    else:
        sock.sendall(header)
    sock.sendall(data)


def _receive(sock: socket.socket, with_fd: bool = False) -> tuple[bytes, list[int]]:
    if with_fd:
        header, fds, _, _ = socket.recv_fds(sock, 8, 1)
    else:
        header, fds = sock.recv(8, socket.MSG_WAITALL), []
    if len(header) < 8:
        raise EOFError
    (size,) = struct.unpack("!Q", header)
    data = b""
    while len(data) < size:
        chunk = sock.recv(size - len(data))
        if not chunk:
            raise EOFError
        data += chunk
    return data, list(fds)


def _run(target: Callable, args: tuple, out, memory: int | None) -> int:
    """In a child: run the target, writing to ``out``; the exit code."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent ends it
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    limit_data(memory)
    try:
        target(*args, out)
        return 0
    except BaseException:
        return 1


class Spawner:
    """A process forked while its parent had one thread, that forks children on
    request (see the module docstring)."""

    def __init__(self):
        mine, theirs = socket.socketpair()
        pid = os.fork()
        if pid == 0:  # the spawner
            code = 0
            try:
                mine.close()
                self._serve(theirs)
            except BaseException:
                code = 1
            finally:
                os._exit(code)
        theirs.close()
        self.pid = pid
        self._socket = mine
        self._lock = threading.Lock()
        self._owner = os.getpid()

    @staticmethod
    def _serve(sock: socket.socket) -> None:
        # Nothing inherited is ever collected here: it may hold descriptors
        # closed below.
        gc.disable()
        gc.freeze()
        end_with_parent()
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGCHLD, signal.SIG_IGN)  # children are reaped at once
        # Only the socket to the parent stays open (a worker's pipes must close
        # when the worker ends, not when its spawner does).
        os.closerange(3, sock.fileno())
        os.closerange(sock.fileno() + 1, 65536)
        while True:
            try:
                data, _ = _receive(sock)
            except (EOFError, OSError):
                return
            try:
                target, args, memory = pickle.loads(data)
            except Exception as error:  # e.g. a target this process cannot import
                _send(sock, pickle.dumps(f"{type(error).__name__}: {error}"))
                continue
            read, write = os.pipe()
            child = os.fork()
            if child == 0:
                code = 1
                try:
                    sock.close()
                    os.close(read)
                    end_with_parent()
                    signal.signal(signal.SIGCHLD, signal.SIG_DFL)
                    with os.fdopen(write, "w", buffering=1) as out:
                        code = _run(target, args, out, memory)
                finally:
                    os._exit(code)
            os.close(write)
            try:
                _send(sock, pickle.dumps(child), [read])
            finally:
                os.close(read)

    def spawn(self, target: Callable, args: tuple, memory: int | None = None) -> Child:
        data = pickle.dumps((target, args, memory))
        with self._lock:
            _send(self._socket, data)
            answer, fds = _receive(self._socket, with_fd=True)
        pid = pickle.loads(answer)
        if not isinstance(pid, int):
            raise RuntimeError(f"the spawner could not start a child process: {pid}")
        stream = os.fdopen(fds[0], "r")

        def lines() -> Iterator[str]:
            with stream:
                yield from stream

        def end() -> None:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.kill(pid, signal.SIGKILL)

        return Child(pid, lines(), end)


def child_main() -> None:
    """A child started by :class:`SubprocessSpawner`: its target from standard
    input, its lines to standard output; it ends when standard input closes
    (its parent ended, or ended it)."""
    source = sys.stdin.buffer
    (size,) = struct.unpack("!Q", source.read(8))
    target, args, memory = pickle.loads(source.read(size))
    # The parent's pipe, watched on a descriptor of its own: a target may put
    # something else on standard input (a planner reads its task there), and
    # the watch must not take the end of that for the end of its parent.
    parent = os.fdopen(os.dup(source.fileno()), "rb", buffering=0)

    def watch() -> None:
        parent.read()  # until the parent closes it
        os._exit(0)

    threading.Thread(target=watch, name="ethasp-parent-watch", daemon=True).start()
    out = sys.stdout
    code = _run(target, args, out, memory)
    out.flush()
    os._exit(code)


class SubprocessSpawner:
    """Children as new Python processes (fork and exec at once: safe from a
    process with threads), for a process without a spawner of its own."""

    def spawn(self, target: Callable, args: tuple, memory: int | None = None) -> Child:
        data = pickle.dumps((target, args, memory))
        process = subprocess.Popen(
            [sys.executable, "-c", "from ethasp.execution.spawner import child_main; child_main()"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=False,
            # The child imports the target as this process would.
            env={**os.environ, "PYTHONPATH": os.pathsep.join(p for p in sys.path if p)},
        )
        process.stdin.write(struct.pack("!Q", len(data)) + data)
        process.stdin.flush()

        def lines() -> Iterator[str]:
            try:
                for line in process.stdout:
                    yield line.decode()
            finally:
                process.stdout.close()
                end()

        def end() -> None:
            with contextlib.suppress(OSError, ValueError):
                process.kill()
            with contextlib.suppress(OSError, ValueError):
                process.stdin.close()
            with contextlib.suppress(OSError, subprocess.TimeoutExpired):
                process.wait(1.0)

        return Child(process.pid, lines(), end)


_spawner: Spawner | SubprocessSpawner | None = None
_lock = threading.Lock()


def start() -> None:
    """Start this process's spawner now, if it has none and has one thread
    (workers call this first thing)."""
    global _spawner
    with _lock:
        if isinstance(_spawner, Spawner) and _spawner._owner == os.getpid():
            return
        if hasattr(os, "fork") and sys.platform.startswith("linux") and threads() == 1:
            _spawner = Spawner()


def get() -> Spawner | SubprocessSpawner:
    """This process's spawner (new Python processes where it has none)."""
    global _spawner
    with _lock:
        owned = _spawner is not None and (
            not isinstance(_spawner, Spawner) or _spawner._owner == os.getpid()
        )
        if not owned:
            _spawner = None
    if _spawner is None:
        start()
    with _lock:
        if _spawner is None:
            _spawner = SubprocessSpawner()
        return _spawner


def spawn(target: Callable[..., Any], args: tuple, memory: int | None = None) -> Child:
    """A child process running ``target(*args, out)`` (see the module docstring)."""
    return get().spawn(target, args, memory)
