"""The MODEL arguments: files, names of bundled models, standard input (``-``).

:func:`model_options` is the parent parser of the commands that read a model
(MODEL, ``--json``, ``--allow-scripts``); :func:`load_model` loads what they
name.
"""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Sequence
from pathlib import Path

from ethasp.errors import InputError
from ethasp.planning.model import Model
from ethasp.resources import model_path


def model_paths(names: Sequence[str]) -> list[Path]:
    """Model files: paths as given, or else the bundled models of those names
    (:func:`ethasp.resources.bundled_model` states the naming rule)."""
    return [model_path(name) for name in names]


STDIN = "-"  # as a model file: read the model from standard input
STDIN_NAME = "<stdin>"  # its name in messages


def read_stdin_model() -> str:
    """An ASP model from standard input (one line of error if it is not ASP text)."""
    try:
        data = (
            sys.stdin.buffer.read()
            if hasattr(sys.stdin, "buffer")
            else sys.stdin.read().encode("utf-8", "surrogateescape")
        )
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise InputError(
            f"{STDIN_NAME}: cannot be read (not UTF-8 text: byte {error.start + 1})"
        ) from None
    except (OSError, ValueError) as error:  # closed, or not readable
        raise InputError(
            f"{STDIN_NAME}: cannot be read ({getattr(error, 'strerror', None) or error})"
        ) from None
    head = text.lstrip()
    if head[:1] in ("(", ";") and "(define" in head[:4096].lower():
        raise InputError(
            f"{STDIN_NAME}: this looks like PDDL; standard input takes an ASP "
            "model (give a PDDL domain and problem as files)"
        )
    if re.match(r'\{\s*"|---', head):
        raise InputError(
            f"{STDIN_NAME}: this looks like a HERA situation; standard input "
            "takes an ASP model (give a situation as a .yaml or .json file)"
        )
    return text


def load_model(args: argparse.Namespace, check: bool = True) -> Model:
    """The model of the command's MODEL arguments; ``-`` reads ASP text from
    standard input (at most once); its planning system is ``--planner``'s.
    Without ``check`` the model is read and parsed only, not grounded (a
    worker process checks it: :meth:`Model.check`)."""
    names = list(args.model)
    world = parse_world(getattr(args, "world", None) or [])
    if names.count(STDIN) > 1:
        raise InputError("standard input (-) can be given only once as a model file")
    if STDIN not in names:
        model = Model.load(
            model_paths(names), allow_scripts=args.allow_scripts, check=check, world=world
        )
    else:
        names.remove(STDIN)
        model = Model.load(
            model_paths(names),
            allow_scripts=args.allow_scripts,
            check=check,
            texts=[(STDIN_NAME, read_stdin_model())],
            world=world,
        )
    model.planning_system = getattr(args, "planner", None) or model.planning_system
    return model


def parse_world(items: Sequence[str]) -> dict[str, bool]:
    """The values of ``--world NAME=VALUE,...`` (VALUE true, false, 1 or 0)."""
    world: dict[str, bool] = {}
    for item in items:
        for part in item.split(","):
            if not part.strip():
                continue
            name, equals, value = part.partition("=")
            value = value.strip().lower()
            if not equals or not name.strip() or value not in ("true", "false", "1", "0"):
                raise InputError(
                    f"--world: {part.strip()!r} is not NAME=VALUE with VALUE true or false"
                )
            world[name.strip()] = value in ("true", "1")
    return world


def model_files(args: argparse.Namespace, resolve: bool = False) -> list[str]:
    """The model's files as a dialogue or the page names them (``<stdin>`` for -)."""
    return [
        STDIN_NAME if name == STDIN else str(path.resolve() if resolve else path)
        for name, path in zip(args.model, model_paths(args.model), strict=True)
    ]


MODEL_FILES_HELP = (
    "model files (ASP), or a PDDL domain and problem (.pddl) with ASP "
    "annotation files, or a HERA situation or causal agency model (.yaml, "
    ".json), or the name of a bundled model (trolley, hera/trolley.yaml)"
)
MODEL_HELP = MODEL_FILES_HELP + "; - reads an ASP model from standard input"


def model_options(stdin: bool = True) -> argparse.ArgumentParser:
    """The parent parser of MODEL, ``--json`` and ``--allow-scripts`` (without
    ``stdin``, MODEL cannot be ``-``)."""
    parser = argparse.ArgumentParser(add_help=False)
    parser.add_argument(
        "model", nargs="+", metavar="MODEL", help=MODEL_HELP if stdin else MODEL_FILES_HELP
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument(
        "--allow-scripts",
        action="store_true",
        help="run #script blocks in model files (refused by default)",
    )
    parser.add_argument(
        "--world",
        action="append",
        metavar="NAME=VALUE,...",
        help="the values (true or false) of background variables and events of a "
        "causal agency model, over those of its file (default: false)",
    )
    return parser
