"""``ethasp serve``: the page on a local web server.

The server binds the loopback address 127.0.0.1; another address only when
it is given explicitly (``--host``), with a warning when it is not loopback.
It prints the page's URL when it starts and can open it in the default
browser.
"""

from __future__ import annotations

import ipaddress
import socket
import sys
import threading
import webbrowser
from typing import TextIO

from werkzeug.serving import make_server

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
    return bool(addresses) and all(ipaddress.ip_address(a.split("%")[0]).is_loopback
                                   for a in addresses)


def page_url(host: str, port: int) -> str:
    shown = host.strip("[]")
    if ":" in shown:
        shown = f"[{shown}]"
    return f"http://{shown}:{port}/"


class Server:
    """A running web server for a workspace (``serve_forever`` / ``shutdown``)."""

    def __init__(self, workspace: Workspace, host: str | None = None, port: int = DEFAULT_PORT):
        """Bind ``host`` (None: 127.0.0.1; an explicit choice otherwise) and ``port``
        (0: any free port)."""
        host = host or DEFAULT_HOST
        self.loopback = loopback = is_loopback(host)
        self.app = create_app(workspace, loopback=loopback)
        try:
            self.httpd = make_server(host.strip("[]"), port, self.app, threaded=True)
        except OSError as error:
            raise InputError(f"cannot serve on {host}:{port} ({error.strerror or error}); "
                             "choose another port with --port") from None
        self.host = host
        self.port = self.httpd.server_port
        self.url = page_url(host, self.port)

    def serve_forever(self) -> None:
        self.httpd.serve_forever()

    def shutdown(self) -> None:
        self.httpd.shutdown()
        self.httpd.server_close()


def serve(workspace: Workspace, host: str | None = None, port: int = DEFAULT_PORT,
          open_browser: bool = False, out: TextIO = sys.stdout) -> int:
    """Serve the page until interrupted (Ctrl-C)."""
    server = Server(workspace, host, port)
    names = " ".join(workspace.files)
    print(f"ethasp: serving {names} at {server.url}", file=out, flush=True)
    if not server.loopback:
        print(f"ethasp: warning: {server.host} is not a loopback address: anyone who can "
              "reach it can use the page", file=out, flush=True)
    print("ethasp: press Ctrl-C to stop", file=out, flush=True)
    if open_browser:
        threading.Timer(0.3, webbrowser.open, [server.url]).start()
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        print("ethasp: stopped", file=out, flush=True)
    finally:
        server.shutdown()
    return 0
