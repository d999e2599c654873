"""``ethasp serve``: the page on a local web server.

The server binds the loopback address 127.0.0.1; another address only when
it is given explicitly (``--host``), with a warning when it is not loopback.
It prints the page's URL when it starts and can open it in the default
browser (or says in one line why it could not).  A port in use, an address
of another machine or a port that needs privileges is one line (an
:class:`InputError`), not werkzeug's message and exit.  HTTP requests are
not logged unless asked for (``log_requests``); ``quiet`` silences
werkzeug's log altogether (the application's own errors are still shown).
"""

from __future__ import annotations

import errno
import ipaddress
import os
import socket
import sys
import threading
import webbrowser
from typing import TextIO

from werkzeug.serving import WSGIRequestHandler, get_sockaddr, make_server, select_address_family

from ethasp.errors import InputError
from ethasp.interfaces.web.app import create_app
from ethasp.interfaces.web.workspace import Workspace

DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8765


def is_loopback(host: str) -> bool:
    """Does the host name or address resolve to loopback addresses only?"""
    if host.strip("[]").lower() == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        pass
    try:
        addresses = {info[4][0] for info in socket.getaddrinfo(host, None)}
    except (socket.gaierror, UnicodeError):
        return False
    return bool(addresses) and all(
        ipaddress.ip_address(a.split("%")[0]).is_loopback for a in addresses
    )


def page_url(host: str, port: int) -> str:
    shown = host.strip("[]")
    if ":" in shown:
        shown = f"[{shown}]"
    return f"http://{shown}:{port}/"


def _handler(log_requests: bool, quiet: bool) -> type[WSGIRequestHandler]:
    """werkzeug's request handler, logging requests only when asked to, and
    nothing at all when ``quiet``."""

    class Handler(WSGIRequestHandler):
        def log_request(self, code="-", size="-") -> None:
            if log_requests and not quiet:
                super().log_request(code, size)

        def log(self, type: str, message: str, *args) -> None:
            if not quiet:
                super().log(type, message, *args)

    return Handler


def listen(host: str, port: int) -> socket.socket:
    """A socket bound to ``host`` and ``port`` (0: any free port) and listening;
    InputError in one line if that cannot be done (a port in use, ...)."""
    shown = host.strip("[]")
    where = f"port {port} on {shown}"
    try:
        family = select_address_family(shown, port)
        address = get_sockaddr(shown, port, family)
        sock = socket.socket(family, socket.SOCK_STREAM)
    except (OSError, UnicodeError, ValueError) as error:
        reason = getattr(error, "strerror", None) or str(error)
        raise InputError(
            f"cannot serve on {shown}: unknown host name or address ({reason}); "
            "--host takes a name or address of this machine"
        ) from None
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as werkzeug does
        sock.bind(address)
        sock.listen(64)
    except OSError as error:
        sock.close()
        if isinstance(error, socket.gaierror):
            raise InputError(
                f"cannot serve on {shown}: unknown host name "
                f"({error.strerror or error}); --host takes a name or address "
                "of this machine"
            ) from None
        if error.errno == errno.EADDRINUSE:
            raise InputError(
                f"{where} is in use (by another program, or another ethasp "
                "serve); choose another port with --port N, or --port 0 for a "
                "free one"
            ) from None
        if error.errno == errno.EACCES:
            raise InputError(
                f"cannot serve on {where}: permission denied (ports below 1024 "
                "need privileges); choose another port with --port N, or "
                "--port 0 for a free one"
            ) from None
        if error.errno == errno.EADDRNOTAVAIL:
            raise InputError(
                f"cannot serve on {shown}: not an address of this machine (see --host)"
            ) from None
        raise InputError(f"cannot serve on {where} ({error.strerror or error})") from None
    return sock


class Server:
    """A running web server for a workspace (``serve_forever`` / ``shutdown``)."""

    def __init__(
        self,
        workspace: Workspace,
        host: str | None = None,
        port: int = DEFAULT_PORT,
        log_requests: bool = False,
        quiet: bool = False,
    ):
        """Bind ``host`` (None: 127.0.0.1; an explicit choice otherwise) and ``port``
        (0: any free port); InputError in one line if that cannot be done.
        ``log_requests``: a line per HTTP request on standard error (werkzeug's);
        ``quiet``: none of werkzeug's lines at all."""
        host = host or DEFAULT_HOST
        self.workspace = workspace
        self.loopback = loopback = is_loopback(host)
        self.app = create_app(workspace, loopback=loopback)
        sock = listen(host, port)
        try:
            # werkzeug serves a duplicate of the bound socket (its own binding
            # would print a message and exit when the port is in use).
            self.httpd = make_server(
                host.strip("[]"),
                port,
                self.app,
                threaded=True,
                request_handler=_handler(log_requests, quiet),
                fd=sock.fileno(),
            )
        finally:
            sock.close()
        self.host = host
        self.port = self.httpd.port
        self.url = page_url(host, self.port)

    def serve_forever(self) -> None:
        self.httpd.serve_forever()

    def shutdown(self) -> None:
        """Stop serving, and end the workspace's worker processes."""
        self.httpd.shutdown()
        self.httpd.server_close()
        self.workspace.close()


def browser_problem() -> str | None:
    """Why no web browser can open the page here (None: one can).

    Without a display, Python's :mod:`webbrowser` would run a text-mode
    browser in this terminal, or finds none; a browser named by ``$BROWSER``
    is used as given.
    """
    try:
        browser = webbrowser.get()
    except webbrowser.Error:
        return "no web browser found"
    graphical = (
        sys.platform in ("darwin", "win32")
        or os.environ.get("DISPLAY")
        or os.environ.get("WAYLAND_DISPLAY")
        or os.environ.get("BROWSER")
    )
    if not graphical and not isinstance(browser, webbrowser.BackgroundBrowser):
        return "no display for a web browser"
    return None


def open_page(url: str, err: TextIO = sys.stderr) -> threading.Thread | None:
    """Open the page in the default web browser (in a thread: a browser may take
    a while to start); one line on ``err`` when that cannot be done."""
    problem = browser_problem()
    if problem is not None:
        print(f"ethasp: --open: {problem}; open {url} in a browser yourself", file=err, flush=True)
        return None

    def run() -> None:
        try:
            opened = webbrowser.open(url)
        except Exception as error:
            opened, problem = False, f" ({error})"
        else:
            problem = ""
        if not opened:
            print(
                f"ethasp: --open: the web browser did not start{problem}; open {url} in "
                "a browser yourself",
                file=err,
                flush=True,
            )

    thread = threading.Thread(target=run, name="ethasp-browser", daemon=True)
    thread.start()
    return thread


def serve(
    workspace: Workspace,
    host: str | None = None,
    port: int = DEFAULT_PORT,
    open_browser: bool = False,
    out: TextIO = sys.stdout,
    log_requests: bool = False,
    quiet: bool = False,
) -> int:
    """Serve the page until interrupted (Ctrl-C); see :class:`Server`."""
    server = Server(workspace, host, port, log_requests=log_requests, quiet=quiet)
    names = " ".join(workspace.files)
    print(f"ethasp: serving {names} at {server.url}", file=out, flush=True)
    if not server.loopback:
        print(
            f"ethasp: warning: {server.host} is not a loopback address: anyone who can "
            "reach it can use the page",
            file=out,
            flush=True,
        )
    print("ethasp: press Ctrl-C to stop", file=out, flush=True)
    if open_browser:
        open_page(server.url)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        print("ethasp: stopped", file=out, flush=True)
    finally:
        server.shutdown()
    return 0
