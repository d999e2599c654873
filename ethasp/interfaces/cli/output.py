"""What commands write: the answer (text or ``--json``), ``--svg`` pictures, files.

:func:`svg_option` is the parent parser of ``--svg``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

from ethasp.errors import InputError
from ethasp.interfaces.cli.models import STDIN
from ethasp.planning.model import Model


def emit(args: argparse.Namespace, data: dict, text: str) -> None:
    """Print the answer (text, or JSON with --json) on standard output, or on
    standard error when the picture goes to standard output (--svg -)."""
    progress = getattr(args, "progress", None)
    if progress is not None:
        progress.clear()
    out = sys.stderr if getattr(args, "svg", None) == STDIN else sys.stdout
    print(json.dumps(data, indent=2) if args.json else text, file=out, flush=True)


def svg_option(what: str) -> argparse.ArgumentParser:
    """``--svg FILE``: also draw ``what`` (:func:`write_picture` writes it)."""
    parser = argparse.ArgumentParser(add_help=False)
    parser.add_argument(
        "--svg",
        metavar="FILE",
        help=f"also draw {what} as an SVG picture in FILE (- for standard "
        "output; the answer then goes to standard error)",
    )
    return parser


def write_picture(args: argparse.Namespace, model: Model, draw) -> None:
    """--svg FILE: write the picture that ``draw(Pictures)`` makes
    (ethasp/interfaces/pictures.py); --svg -: to standard output."""
    if args.svg is not None:
        from ethasp.interfaces.pictures import Pictures, write

        svg = draw(Pictures(model))
        if args.svg == STDIN:
            sys.stdout.write(svg)
            sys.stdout.flush()
        else:
            write(args.svg, svg)


def no_picture(args: argparse.Namespace) -> None:
    if args.svg is not None:
        where = "standard output" if args.svg == STDIN else args.svg
        print(f"ethasp: no plan found, so no picture was written to {where}", file=sys.stderr)


def writable(path: Path, what: str) -> None:
    """Refuse a file that cannot be written before any work is done."""
    try:
        if path.is_dir():
            raise InputError(f"{what} {path}: is a directory, not a file")
        parent = path.parent if str(path.parent) else Path(".")
        if not parent.is_dir():
            raise InputError(f"{what} {path}: cannot be written (no directory {parent})")
        if not os.access(parent, os.W_OK) or (path.exists() and not os.access(path, os.W_OK)):
            raise InputError(f"{what} {path}: cannot be written (permission denied)")
        if len(path.name.encode()) > os.pathconf(parent, "PC_NAME_MAX"):
            raise InputError(f"{what} {path}: cannot be written (file name too long)")
    except (OSError, ValueError) as error:
        reason = getattr(error, "strerror", None) or str(error)
        raise InputError(f"{what} {path}: cannot be written ({reason})") from None
