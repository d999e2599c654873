"""``ethasp serve`` as a user starts it: a port in use (a real listening
socket) and other addresses that cannot be served are one line and exit code
2; the request log is off by default, on with --log-requests, and nothing of
werkzeug's under --quiet; --open without a browser says so; a model from
standard input is served."""

from __future__ import annotations

import json
import os
import re
import signal
import socket
import subprocess
import sys
import urllib.request

import pytest
from conftest import MODELS, ROOT

WAIT = 120  # seconds a server may take to start on a busy machine


def serve(*args: str, env: dict | None = None, stdin: str | None = None) -> subprocess.Popen:
    environment = {**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}
    return subprocess.Popen(
        [sys.executable, "-m", "ethasp.interfaces.cli", "serve", *args],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=ROOT,
        env=environment,
    )


def started(process: subprocess.Popen, stdin: str | None = None) -> str:
    """The page's URL, once the server prints it."""
    if stdin is not None:
        process.stdin.write(stdin)
    process.stdin.close()
    line = process.stdout.readline()
    match = re.search(r" at (http://\S+/)$", line.strip())
    assert match, line + process.stderr.read()
    return match.group(1)


def stopped(process: subprocess.Popen) -> tuple[str, str]:
    """Ctrl-C, then what the server wrote."""
    process.send_signal(signal.SIGINT)
    process.wait(timeout=WAIT)
    return process.stdout.read(), process.stderr.read()


def fetch(url: str) -> bytes:
    with urllib.request.urlopen(url, timeout=WAIT) as reply:
        return reply.read()


def test_a_port_in_use_is_one_line_and_exit_code_2():
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        run = subprocess.run(
            [
                sys.executable,
                "-m",
                "ethasp.interfaces.cli",
                "serve",
                "trolley",
                "--port",
                str(port),
            ],
            capture_output=True,
            text=True,
            cwd=ROOT,
            env={**os.environ, "PYTHONPATH": str(ROOT)},
            timeout=WAIT,
        )
    assert run.returncode == 2, run.stderr
    assert run.stderr == (
        f"ethasp: error: port {port} on 127.0.0.1 is in use (by another "
        "program, or another ethasp serve); choose another port with --port N, "
        "or --port 0 for a free one\n"
    )
    assert run.stdout == ""


def test_a_second_server_on_the_same_port():
    first = serve("trolley", "--port", "0")
    try:
        url = started(first)
        port = url.rsplit(":", 1)[1].strip("/")
        second = subprocess.run(
            [sys.executable, "-m", "ethasp.interfaces.cli", "serve", "trolley", "--port", port],
            capture_output=True,
            text=True,
            cwd=ROOT,
            env={**os.environ, "PYTHONPATH": str(ROOT)},
            timeout=WAIT,
        )
        assert second.returncode == 2 and "is in use" in second.stderr
        assert second.stderr.count("\n") == 1
        assert json.loads(fetch(url + "api/model"))["name"] == "trolley.lp"  # still serving
    finally:
        stopped(first)


def test_addresses_that_cannot_be_served_are_one_line():
    # (a name that fails before any lookup: the tests run offline)
    for host, words in (
        ("bad..host", "unknown host name"),
        ("192.0.2.1", "not an address of this machine"),
    ):
        run = subprocess.run(
            [
                sys.executable,
                "-m",
                "ethasp.interfaces.cli",
                "serve",
                "trolley",
                "--host",
                host,
                "--port",
                "0",
            ],
            capture_output=True,
            text=True,
            cwd=ROOT,
            env={**os.environ, "PYTHONPATH": str(ROOT)},
            timeout=WAIT,
        )
        assert run.returncode == 2 and words in run.stderr, run.stderr
        assert run.stderr.count("\n") == 1 and run.stderr.startswith("ethasp: error: ")


@pytest.mark.parametrize(
    "options, logged", [((), False), (("--log-requests",), True), (("--quiet",), False)]
)
def test_the_request_log(options, logged):
    process = serve("trolley", "--port", "0", *options)
    try:
        url = started(process)
        fetch(url)
        fetch(url + "api/model")
    finally:
        out, err = stopped(process)
    assert ('"GET /api/model HTTP/1.1" 200' in err) == logged, err
    lines = [line for line in err.splitlines() if line != "ethasp: interrupted"]  # Ctrl-C
    assert (lines != []) == logged, err
    assert out == "ethasp: press Ctrl-C to stop\n"  # after the line with the URL


def test_log_requests_cannot_go_with_quiet():
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "ethasp.interfaces.cli",
            "serve",
            "trolley",
            "--quiet",
            "--log-requests",
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
        timeout=WAIT,
    )
    assert (
        run.returncode == 2
        and run.stderr == "ethasp: error: --log-requests cannot go with --quiet\n"
    )


def test_open_without_a_browser_says_so(tmp_path):
    # No display, no browser on the PATH, none named by $BROWSER.
    env = {"PATH": str(tmp_path), "DISPLAY": "", "WAYLAND_DISPLAY": "", "BROWSER": ""}
    process = serve("trolley", "--port", "0", "--open", env=dict(env.items()))
    try:
        url = started(process)
        line = process.stderr.readline()
    finally:
        stopped(process)
    assert line.startswith("ethasp: --open: no ")
    assert line.endswith(f"; open {url} in a browser yourself\n")


def test_a_model_from_standard_input_is_served():
    process = serve("-", "--port", "0")
    try:
        url = started(process, stdin=(MODELS / "trolley.lp").read_text())
        glance = json.loads(fetch(url + "api/model"))
        assert glance["name"] == "<stdin>"
        assert [action["term"] for action in glance["model"]["actions"]] == ["pull", "refrain"]
    finally:
        stopped(process)


def test_a_hera_situation_is_served():
    process = serve("robot-and-frank.yaml", "--port", "0")
    try:
        url = started(process)
        assert json.loads(fetch(url + "api/model"))["name"] == "robot-and-frank.yaml"
    finally:
        stopped(process)
