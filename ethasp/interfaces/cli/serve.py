"""``ethasp serve``: the dialogue on a local web page."""

from __future__ import annotations

import argparse

from ethasp.errors import InputError
from ethasp.interfaces.cli.models import MODEL_HELP, load_model, model_files
from ethasp.interfaces.cli.options import (
    default_reasons_limit,
    inherit,
    max_horizon,
    port,
    reasons_option,
    search_options,
)


def add_parser(commands) -> None:
    web = commands.add_parser(
        "serve",
        help="explore the dialogue on a local web page",
        description="Serve the dialogue as a web page on this machine: the model at a glance, "
        "the current plan judged under every principle with its reasons, "
        "questions typed or clicked, contrast plans side by side with pictures, "
        "history, undo, save and load. Only the model given here is served. "
        "The server binds 127.0.0.1 unless --host is given, and prints the "
        "page's URL.",
    )
    web.add_argument("model", nargs="+", metavar="MODEL", help=MODEL_HELP)
    web.add_argument(
        "--allow-scripts",
        action="store_true",
        help="run #script blocks in model files (refused by default)",
    )
    web.add_argument(
        "--principle",
        default="deontology",
        metavar="P",
        help="the principle the first plan is made and judged under (default deontology)",
    )
    web.add_argument(
        "--port",
        type=port,
        default=8765,
        metavar="N",
        help="the port (default 8765; 0: any free port)",
    )
    web.add_argument(
        "--host",
        default=None,
        metavar="H",
        help="the address to bind (default 127.0.0.1; an address beyond "
        "loopback serves the page to other machines)",
    )
    web.add_argument(
        "--open",
        action="store_true",
        help="open the page in the default web browser (one line on standard "
        "error if none can be started)",
    )
    inherit(
        web,
        search_options(
            quiet="no log lines from the web server on standard error "
            "(the page's URL is still printed)"
        ),
    )
    web.add_argument(
        "--log-requests",
        action="store_true",
        help="print a line per HTTP request on standard error (off by default)",
    )
    inherit(web, reasons_option(answers=True))
    web.set_defaults(run=run, one_answer=False)


def run(args: argparse.Namespace) -> int:
    """ethasp serve: the dialogue as a local web page (ethasp/interfaces/web/)."""
    try:
        from ethasp.interfaces.web.server import serve
        from ethasp.interfaces.web.workspace import Options, Workspace
    except ImportError as error:  # a broken installation without Flask
        raise InputError(
            f"ethasp serve needs the package {error.name} (pip install flask)"
        ) from None

    default_reasons_limit(args)
    model = load_model(args)
    files = model_files(args)
    workspace = Workspace(
        model,
        files,
        args.principle,
        Options(max_horizon(args), args.time_limit, args.reasons_limit),
    )
    if args.quiet and args.log_requests:
        raise InputError("--log-requests cannot go with --quiet")
    return serve(
        workspace, args.host, args.port, args.open, log_requests=args.log_requests, quiet=args.quiet
    )
