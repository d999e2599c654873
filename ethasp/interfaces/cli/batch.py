"""``ethasp batch``: many cases at once, on local workers or a Dask cluster."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ethasp.interfaces.cli.models import model_paths
from ethasp.interfaces.cli.options import horizon, reasons_number, seconds, whole_number
from ethasp.interfaces.cli.output import writable
from ethasp.planning.budget import DEFAULT_TIME_LIMIT
from ethasp.planning.search import DEFAULT_MAX_HORIZON, DEFAULT_SATISFICING_HORIZON


def add_parser(commands) -> None:
    many = commands.add_parser(
        "batch",
        help="judge, plan or ask about many cases at once, on all cores or a cluster",
        description="Compute many cases at once on warm worker processes (all local cores "
        "by default, or the workers of a Dask cluster with --scheduler) and "
        "append one JSON line per case and principle (and question) to --output "
        "as each case finishes. Running the same command again skips the lines "
        "already there and computes only the missing ones. Task (default per "
        "case): ask the questions when there are any, judge the case's own plan "
        "when it has one, else plan under each principle. A bad case gets a line "
        "with its error and the batch goes on. Exit code 0 when every case "
        "succeeded, 1 when some case has an error line, 2 for bad options, "
        "130 on Ctrl-C. See docs/batch.md.",
    )
    many.add_argument(
        "cases",
        nargs="+",
        metavar="CASE",
        help="a model file (.lp, HERA .yaml/.json; a PDDL domain and problem "
        "side by side, with their .lp annotation files after them), a "
        "bundled model's name, a folder (searched recursively), or a "
        "manifest (.csv, or .yaml with a list 'cases') listing cases with "
        "their own files, plans, principles and questions",
    )
    many.add_argument(
        "--output",
        "-o",
        required=True,
        metavar="FILE",
        help="the JSON lines file the results are appended to (and resumed from)",
    )
    many.add_argument(
        "--principle",
        action="append",
        metavar="NAME",
        help="a principle or group as for 'ethasp judge' (repeatable; default "
        "the paper's three; groups: paper, hera, all)",
    )
    many.add_argument(
        "--task",
        choices=["judge", "plan", "ask"],
        default=None,
        help="judge: the case's plan under each principle; plan: a shortest "
        "plan permissible under each principle; ask: each question about "
        "the case's plan (default: per case, see above)",
    )
    many.add_argument(
        "--question",
        action="append",
        metavar='"why ..."',
        help="a contrastive question for every case (repeatable: one line per "
        "case, principle and question)",
    )
    many.add_argument(
        "--under",
        default=None,
        metavar="Q",
        help="with questions: the principle the contrast plan must satisfy "
        "(default: the principle of the line)",
    )
    many.add_argument(
        "--glob",
        default=None,
        metavar="PATTERN",
        help="in folders, only file names matching PATTERN, e.g. 'case-*.lp' "
        "(default: every .lp, .pddl, .yaml, .yml and .json file)",
    )
    many.add_argument(
        "--workers",
        type=whole_number("number of workers", 4096),
        default=None,
        metavar="N",
        help="local worker processes (default: one per core)",
    )
    many.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="compute on a Dask cluster, e.g. tcp://10.0.0.5:8786 (needs "
        "pip install 'ethasp[cluster]' here and on the workers)",
    )
    many.add_argument(
        "--time-limit",
        type=seconds,
        default=DEFAULT_TIME_LIMIT,
        metavar="SECONDS",
        help="per case: searches stop after SECONDS and answer 'bounded' "
        f"(default {DEFAULT_TIME_LIMIT:g}; 0 for no limit); a case still "
        "running at twice the limit plus 10 s is stuck in grounding: its "
        "worker is ended and the case gets an error line",
    )
    many.add_argument(
        "--max-horizon",
        type=horizon,
        default=None,
        metavar="N",
        help=f"search plans and states of at most N steps (default "
        f"{DEFAULT_MAX_HORIZON}; {DEFAULT_SATISFICING_HORIZON} for plans "
        "with --satisficing)",
    )
    many.add_argument(
        "--reasons-limit",
        type=reasons_number,
        default=None,
        metavar="N",
        help="judge: add the explanation and at most N reasons of each kind to "
        "each line (default 0: verdicts only); ask: at most N reasons "
        "per judgement (default: ethasp.reasons.DEFAULT_LIMIT)",
    )
    many.add_argument(
        "--satisficing",
        action="store_true",
        help="plans searched are found fast, not proven shortest",
    )
    many.add_argument(
        "--allow-scripts",
        action="store_true",
        help="run #script blocks in model files (refused by default: such a "
        "case gets an error line)",
    )
    many.add_argument(
        "--retry-errors",
        action="store_true",
        help="compute the lines with an error again (they are removed from --output first)",
    )
    many.add_argument(
        "--report", metavar="FILE", help="also write the HTML report of --output to FILE at the end"
    )
    many.add_argument(
        "--quiet", action="store_true", help="no progress bar or summary on standard error"
    )
    many.set_defaults(run=run, one_answer=False)  # each case has its own limit


def run(args: argparse.Namespace) -> int:
    """ethasp batch: many cases on warm local workers or a Dask cluster (ethasp/batch/)."""
    from ethasp.batch.progress import BatchProgress
    from ethasp.batch.report import write_report
    from ethasp.batch.run import batch

    writable(Path(args.output), "--output")
    if args.report is not None:
        writable(Path(args.report), "--report")
    run = batch(
        [str(path) for path in model_paths(args.cases)],
        args.principle,
        task=args.task,
        questions=args.question or (),
        under=args.under,
        output=args.output,
        workers=args.workers,
        scheduler=args.scheduler,
        time_limit=args.time_limit,
        max_horizon=args.max_horizon,
        reasons_limit=args.reasons_limit,
        satisficing=args.satisficing,
        allow_scripts=args.allow_scripts,
        glob=args.glob,
        retry_errors=args.retry_errors,
    )
    progress = BatchProgress(len(run.cases), run.skipped, run.cases_failed, enabled=not args.quiet)

    def interrupted() -> str:
        run.close()
        return (
            f"{run.lines_written} new lines written to {args.output}; run the same "
            "command again to compute the rest"
        )

    args.on_interrupt = interrupted
    run.start()
    for _ in run:
        progress.update(run.cases_done, run.cases_failed)
    computed = run.cases_done - run.skipped
    before = f", {run.skipped} done before" if run.skipped else ""
    progress.finish(
        f"ethasp batch: {len(run.cases)} cases ({computed} computed now{before}), "
        f"{run.cases_failed} failed; {run.lines_written} new lines in "
        f"{args.output} ({run.seconds:.1f} s)"
    )
    if args.report is not None:
        write_report(args.output, args.report)
        if not args.quiet:
            print(f"ethasp batch: report written to {args.report}", file=sys.stderr)
    return 1 if run.cases_failed else 0
