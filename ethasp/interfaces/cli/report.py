"""``ethasp report``: the HTML page of a batch's results."""

from __future__ import annotations

import argparse
from pathlib import Path

from ethasp.errors import InputError
from ethasp.interfaces.cli.output import writable


def add_parser(commands) -> None:
    drawing = commands.add_parser(
        "report",
        help="draw the HTML report of a batch's results",
        description="Write one self-contained HTML page about a results file of 'ethasp "
        "batch': verdict counts per principle, the pairwise agreement of the "
        "principles with the cases on which they disagree, the distribution of "
        "times, the slowest and the failed cases, and every case.",
    )
    drawing.add_argument("results", metavar="RESULTS", help="the JSON lines of ethasp batch")
    drawing.add_argument(
        "--output",
        "-o",
        default=None,
        metavar="FILE",
        help="the page (default: RESULTS with the suffix .html)",
    )
    drawing.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """ethasp report: the HTML page of a batch's results."""
    from ethasp.batch.report import write_report

    destination = Path(args.output) if args.output else Path(args.results).with_suffix(".html")
    if destination.resolve() == Path(args.results).resolve():
        raise InputError(f"--output {destination}: would overwrite the results file")
    writable(destination, "--output")
    write_report(args.results, destination)
    print(f"report written to {destination}")
    return 0
