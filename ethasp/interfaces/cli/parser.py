"""The parser of the ethasp command line: the commands, each from its own module."""

from __future__ import annotations

import argparse

import ethasp.interfaces.cli.ask as ask
import ethasp.interfaces.cli.batch as batch
import ethasp.interfaces.cli.completion as completion
import ethasp.interfaces.cli.dialogue as dialogue
import ethasp.interfaces.cli.explain as explain
import ethasp.interfaces.cli.judge as judge
import ethasp.interfaces.cli.plan as plan
import ethasp.interfaces.cli.query as query
import ethasp.interfaces.cli.repair as repair
import ethasp.interfaces.cli.report as report
import ethasp.interfaces.cli.serve as serve
import ethasp.interfaces.cli.validate as validate
from ethasp.interfaces.version import package_version

# The commands in the order --help lists them.
COMMANDS = (
    plan,
    repair,
    validate,
    judge,
    query,
    ask,
    explain,
    dialogue,
    serve,
    completion,
    batch,
    report,
)

DESCRIPTION = """\
Ethical plan explanation with Answer Set Programming (clingo), after Krarup,
Lindner, Krivic and Long, "Understanding a Robot's Guiding Ethical Principles
via Automatically Generated Explanations" (IEEE CASE 2021).

MODEL is one or more ASP files in the vocabulary variable/1, action/1, pre/3,
eff/3, ceff/4, cpre/4, init/1, goal/2, utility/2, utility/3 (derived variables:
derived/1, axiom/2, axiom_pre/4; events: event/1, event_at/2, ...), or a PDDL
domain and problem (STRIPS, ADL, derived predicates) with ASP annotation files,
or a HERA situation (.yaml, .json); the name of a bundled model also works (its
path in the bundled folder asp/, the .lp left out: trolley, hera/trolley.yaml),
and - reads an ASP model from standard input.  A model that comes
with a plan (a situation's) is judged on it when --plan is not given.  Bad
input gets one line on standard error and exit code 2; Ctrl-C one line and exit
code 130."""


def build_parser(command_name: str | None = None) -> argparse.ArgumentParser:
    """The command line's parser; with ``command_name`` (the first argument,
    where it names a command), only that command's parser is built (each
    command's options take a few milliseconds to build)."""
    parser = _Parser(
        prog="ethasp", description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.set_defaults(one_answer=True)
    parser.add_argument(
        "-V",
        "--version",
        action=_Version,
        nargs=0,
        help="show the program's version number and exit",
    )
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    names = {command.__name__.rsplit(".", 1)[-1]: command for command in COMMANDS}
    chosen = [names[command_name]] if command_name in names else COMMANDS
    for command in chosen:
        command.add_parser(commands)
    if "completion" in commands.choices:
        # The completion script is made from the whole parser.
        commands.choices["completion"].set_defaults(build_parser=build_parser)
    return parser


class _Version(argparse.Action):
    """--version, read from the package's metadata only when asked for."""

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"ethasp {package_version()}")
        parser.exit()


class _Parser(argparse.ArgumentParser):
    """Usage errors in one line, like every other error."""

    def error(self, message: str):
        command = self.prog if self.prog.startswith("ethasp ") else "ethasp"
        self.exit(2, f"ethasp: error: {' '.join(message.split())} (see {command} --help)\n")
