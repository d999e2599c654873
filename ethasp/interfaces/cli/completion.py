"""``ethasp completion``: the shell completion script for bash or zsh."""

from __future__ import annotations

import argparse
import sys


def add_parser(commands) -> None:
    shells = commands.add_parser(
        "completion",
        help="print a shell completion script (bash, zsh)",
        description="Print a script that completes ethasp's commands, options, principle "
        "names, bundled models and file names in bash or zsh. Install: "
        "'ethasp completion bash > ~/.local/share/bash-completion/completions/"
        "ethasp', or 'ethasp completion zsh > ~/.zfunc/_ethasp' with "
        "fpath+=(~/.zfunc) before compinit in ~/.zshrc (see docs/cli.md).",
    )
    shells.add_argument("shell", choices=("bash", "zsh"), help="the shell: bash or zsh")
    shells.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """ethasp completion bash|zsh: the completion script (ethasp/interfaces/completion.py)."""
    from ethasp.interfaces.completion import script

    sys.stdout.write(script(args.shell, args.build_parser()))
    return 0
