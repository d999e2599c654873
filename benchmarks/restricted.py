"""Plans under principles and answers to questions against plain plan search.

For every domain folder (a ``domain.pddl`` and problem files) under the folder
given (default ``../shared/ipc`` beside the repository) that has an annotation
file ``benchmarks/annotations/DOMAIN.lp`` (moral utilities over the domain's
actions and facts; each file's header says what it makes bad, harmful and
good), and for the problems chosen (default the first four), these whole
processes are timed from outside, each with ``--time-limit`` (default 60 s)
and ``--json``:

* ``plain``: ``ethasp plan DOMAIN PROBLEM ANNOTATION`` (a shortest plan);
* one search per principle: ``ethasp plan ... --principle P`` for the three
  principles of the paper and HERA's restricting ones;
* one search per question form about the plain plan: ``ethasp ask ...
  --plan "<the plain plan>" --question Q`` (under deontology, ask's default),
  with Q ``why A`` (A the plan's first action), ``why not B`` (B an action
  outside the plan that changes the first state of the plan where such an
  action is applicable, chosen by a random generator seeded with the
  instance's name), ``why A rather than B``,
  ``why A before C`` (C the plan's last action); forms that ``ethasp ask
  --help`` lists beyond these (``why A at T``, ``why F``, ``why not in N
  steps``) are asked too (see ``FORMS``);
* ``ask``: ``ethasp ask ... --question "why A"`` without ``--plan`` (ask
  first makes the plan under deontology; A is the first action of the plan
  that ``plan --principle deontology`` found, else of the plain plan).

Each process gets ``--time-limit`` seconds and is killed at that limit plus
``--grace`` (default 15 s): a killed process, or an answer ``bounded``,
counts as unanswered.  The peak memory of each process is the largest
resident set of it and of its child processes (``os.wait4``).

Printed per instance and search: the status (``found``, ``none``,
``bounded``, ``killed``, ``error N``; a ``*`` marks a status without a proof:
``bounded``, a plan not proven shortest, or a question whose principle was
dropped without a proof), the seconds, the ratio to plain search's seconds
and the peak memory.  Then a summary against the targets: every restricted
search answered with a proof where plain search proves; restricted/plain
time at most 1.5x as a geometric mean and at most 3x on every search; under
1 GB; ``ask`` without ``--plan`` about one plain search plus one contrast
(the ``why A`` question with ``--plan``).

Usage: python benchmarks/restricted.py [FOLDER] [--problems 1-4] [--time-limit S]
           [--principles P,...] [--questions why,why-not,...] [--no-ask]
           [--repeat N] [--only TEXT] [--json FILE] [--annotations DIR]
       python benchmarks/restricted.py --summary FILE   (the summary of a --json file)
"""

from __future__ import annotations

import argparse
import compileall
import contextlib
import io
import json
import math
import os
import random
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import asdict, dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_FOLDER = ROOT.parent / "shared" / "ipc"
if not DEFAULT_FOLDER.is_dir():
    DEFAULT_FOLDER = Path("/work/shared/ipc")
ANNOTATIONS = Path(__file__).resolve().parent / "annotations"

PRINCIPLES = (
    "deontology",
    "utilitarianism",
    "do-no-harm",
    "hera-deontology",
    "goal-deontology",
    "avoid-any-harm",
    "avoid-avoidable-harm",
    "hera-utilitarianism",
)

# Question forms: a template over the instance's choices (A the plain plan's
# first action, B an action outside it, C its last action, T a step, F a fact
# the plan makes true that the goal does not ask for, N one step less than the
# plan) and, for forms that not every version of ethasp has, a pattern that
# `ethasp ask --help` shows when it has them.  A new form is one line here.
FORMS: dict[str, tuple[str, str | None]] = {
    "why": ("why {A}", None),
    "why-not": ("why not {B}", None),
    "rather-than": ("why {A} rather than {B}", None),
    "before": ("why {A} before {C}", None),
    "at": ("why {A} at {T}", r"why A at T"),
    "fact": ("why {F}", r"why F\b"),
    "steps": ("why not in {N} steps", r"in N steps"),
}

# Targets (benchmark figures, not tests).
TARGET_GMEAN = 1.5
TARGET_MAX = 3.0
TARGET_MEMORY_MB = 1024.0


# -- instances ------------------------------------------------------------------


@dataclass
class Instance:
    domain_name: str
    name: str
    domain: Path
    problem: Path
    annotation: Path

    @property
    def label(self) -> str:
        return f"{self.domain_name}/{self.name}"

    def model(self) -> list[str]:
        return [str(self.domain), str(self.problem), str(self.annotation)]


def _natural(path: Path):
    return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", path.name)]


def _problem_numbers(text: str) -> set[int]:
    """``1-4`` or ``1,3,5-8``: the positions (from 1) of the problems chosen."""
    chosen = set()
    for part in text.split(","):
        if "-" in part:
            low, high = part.split("-", 1)
            chosen.update(range(int(low), int(high) + 1))
        elif part.strip():
            chosen.add(int(part))
    return chosen


def instances(
    folder: Path, annotations: Path, problems: set[int], only: str | None
) -> tuple[list[Instance], list[str]]:
    """The chosen problems of every domain folder that has an annotation file
    (the problems in natural order: p2 before p10), and the domains skipped."""
    result, skipped = [], []
    for domain in sorted(folder.glob("*/domain.pddl")):
        annotation = annotations / f"{domain.parent.name}.lp"
        if not annotation.is_file():
            skipped.append(domain.parent.name)
            continue
        files = sorted(
            (path for path in domain.parent.glob("*.pddl") if path.name != "domain.pddl"),
            key=_natural,
        )
        for position, problem in enumerate(files, start=1):
            if position not in problems:
                continue
            instance = Instance(domain.parent.name, problem.stem, domain, problem, annotation)
            if only is None or only in instance.label:
                result.append(instance)
    return result, skipped


# -- whole processes ---------------------------------------------------------------


@dataclass
class Run:
    """One whole process: its outcome as read from its JSON, its seconds and its
    peak memory (MB, the largest resident set of it and its children)."""

    search: str
    command: list[str]
    status: str
    seconds: float
    memory_mb: float
    cpu: float = 0.0
    proven: bool = False
    plan: list[str] | None = None
    note: str = ""
    ratio: float | None = None


def _run_process(
    command: list[str], cap: float
) -> tuple[int | None, str, str, float, float, float]:
    """Run a command in a session of its own, killed (with its children) after
    ``cap`` seconds; its exit code (None when killed), standard output and
    error, seconds, peak memory in MB and processor seconds (user and system,
    of it and its reaped children: less sensitive to a busy machine than the
    seconds, but the search's engines may use more than one core)."""
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        start = time.perf_counter()
        process = subprocess.Popen(
            command, stdout=out, stderr=err, text=True, cwd=ROOT, start_new_session=True
        )
        result: dict = {}

        def reap():
            # wait4 gives this child's own resource use, its reaped children's
            # included (ru_maxrss: the largest of them).
            _, status, usage = os.wait4(process.pid, 0)
            result["end"] = time.perf_counter()
            result["status"], result["usage"] = status, usage

        waiter = threading.Thread(target=reap, daemon=True)
        waiter.start()
        waiter.join(cap)
        killed = waiter.is_alive()
        if killed:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(process.pid, signal.SIGKILL)
            waiter.join()
        process.returncode = -1  # reaped here, not by Popen
        seconds = cap if killed else result["end"] - start
        usage = result["usage"]
        memory = usage.ru_maxrss / 1024.0  # kB on Linux
        code = None if killed else os.waitstatus_to_exitcode(result["status"])
        out.seek(0)
        err.seek(0)
        return code, out.read(), err.read(), seconds, memory, usage.ru_utime + usage.ru_stime


def ethasp_command(*arguments: str) -> list[str]:
    return [sys.executable, "-m", "ethasp.interfaces.cli", *arguments]


_UNPROVEN_DROP = re.compile(r"\bfound: ")
# ask without --plan when no plan under the principle exists or was found.
_NOTHING_TO_ASK = re.compile(r"no plan to ask about: (.*)")


def read_outcome(search: str, stdout: str) -> tuple[str, bool, list[str] | None, str]:
    """Status, whether it is proven, the plan (of ``plan``) and a note, from a
    JSON answer of ``ethasp plan`` or ``ethasp ask``."""
    data = json.loads(stdout)
    status = data.get("status", "?")
    note = ""
    if search.startswith("ask"):
        plan = (data.get("contrast") or {}).get("plan")
        proven = status in ("found", "none") and data.get("optimal") is not False
        because = data.get("principle_dropped_because") or ""
        if data.get("principle_dropped") and _UNPROVEN_DROP.search(because):
            # The search under the principle ended without a proof (bounded),
            # and the contrast was searched without the principle.
            proven = False
            note = "principle dropped unproven"
        elif data.get("principle_dropped"):
            note = "principle dropped"
        return status, proven, plan, note
    plan = data.get("plan")
    proven = status in ("found", "none") and data.get("optimal") is not False
    if status == "bounded" and plan is not None:
        note = "plan, best not proven"
    return status, proven, plan, note


def _reread(fields: dict) -> Run:
    """A row of a --json file as a run (an ask without --plan that ended with
    nothing to ask about read as its answer, as :func:`run` does now)."""
    result = Run(**fields)
    asked = _NOTHING_TO_ASK.search(result.note)
    if result.status == "error 2" and asked:
        result.proven = not _UNPROVEN_DROP.search(asked.group(1))
        result.status = "none" if result.proven else "bounded"
    return result


def run(search: str, command: list[str], limit: float, grace: float, repeat: int) -> Run:
    """The fastest of ``repeat`` runs (an answered run beats one that was not);
    memory the largest seen."""
    runs = []
    for _ in range(max(1, repeat)):
        code, stdout, stderr, seconds, memory, cpu = _run_process(command, limit + grace)
        if code is None:
            runs.append(Run(search, command, "killed", seconds, memory, cpu))
            continue
        if code != 0:
            last = (stderr.strip().splitlines() or [""])[-1]
            asked = _NOTHING_TO_ASK.search(last)
            if code == 2 and asked:
                # ask without --plan, when the plan search under the principle
                # has no plan: an answer, proven or bounded as its words say.
                proven = not _UNPROVEN_DROP.search(asked.group(1))
                runs.append(
                    Run(
                        search,
                        command,
                        "none" if proven else "bounded",
                        seconds,
                        memory,
                        cpu,
                        proven,
                        note=asked.group(1)[:200],
                    )
                )
                continue
            runs.append(
                Run(search, command, f"error {code}", seconds, memory, cpu, note=last[:200])
            )
            continue
        try:
            status, proven, plan, note = read_outcome(search, stdout)
        except (json.JSONDecodeError, AttributeError) as error:
            runs.append(Run(search, command, "unreadable", seconds, memory, cpu, note=str(error)))
            continue
        runs.append(Run(search, command, status, seconds, memory, cpu, proven, plan, note))
    best = min(runs, key=lambda r: (not r.proven, r.seconds))
    best.memory_mb = max(r.memory_mb for r in runs)
    return best


# -- what the questions name ------------------------------------------------------


@dataclass
class Choices:
    """The actions and facts the questions about one plan name."""

    A: str | None = None
    B: str | None = None
    C: str | None = None
    T: int | None = None
    F: str | None = None
    N: int | None = None


def _applicable(preconditions: dict, state: set, action) -> bool:
    return all(
        (value == "true") == (variable in state)
        for variable, value in preconditions.get(action, ())
    )


def choose(instance: Instance, plan: list[str]) -> Choices:
    """A (first action), C (last action, another than A), B (an action outside the
    plan that changes the first state the plan passes where such an action is
    applicable; chosen by a generator seeded with the instance's name), T = 1,
    N one less than the plan's length, F a fact true after the plan that the
    goal does not ask for and the initial state does not have (else a goal
    fact).  The ground model is read in this process (not timed)."""
    from ethasp.planning.model import Model

    choices = Choices()
    if not plan:
        return choices
    with contextlib.redirect_stderr(io.StringIO()):  # the translation's warnings
        planner = Model.load(instance.model()).planner
    actions = sorted(planner.get("action", 1), key=str)
    preconditions: dict = {}
    for atom in planner.get("pre", 3):
        action, variable, value = atom.arguments
        preconditions.setdefault(action, []).append((variable, str(value)))
    initial = {atom.arguments[0] for atom in planner.get("init", 1)}
    goal = {
        atom.arguments[0] for atom in planner.get("goal", 2) if str(atom.arguments[1]) == "true"
    }
    by_text = {str(action.arguments[0]): action.arguments[0] for action in actions}
    effects: dict = {}
    for atom in planner.get("eff", 3):
        action, variable, value = atom.arguments
        effects.setdefault(str(action), []).append((variable, str(value) == "true"))
    used = set(plan)
    outside = [text for text in by_text if text not in used]
    # The states the plan passes (unconditional effects; enough to choose by).
    states, state = [set(initial)], set(initial)
    for step in plan:
        adds = {variable for variable, value in effects.get(step, ()) if value}
        state = (
            state - {variable for variable, value in effects.get(step, ()) if not value}
        ) | adds
        states.append(state)
    # B: an action that changes the first state of the plan where such an
    # action outside the plan is applicable (else any action outside it).
    pool = []
    for before in states:
        pool = [
            text
            for text in outside
            if _applicable(preconditions, before, by_text[text])
            and any(value != (variable in before) for variable, value in effects.get(text, ()))
        ]
        if pool:
            break
    generator = random.Random(instance.label)
    pool = pool or outside
    choices.A = plan[0]
    choices.B = generator.choice(pool) if pool else None
    later = [action for action in plan[1:] if action != plan[0]]
    choices.C = later[-1] if later else None
    choices.T = 1
    choices.N = len(plan) - 1
    variables = {atom.arguments[0] for atom in planner.get("variable", 1)}
    made = sorted(str(v) for v in state & variables if v not in goal and v not in initial)
    choices.F = generator.choice(made) if made else (sorted(map(str, goal))[0] if goal else None)
    return choices


def question(form: str, choices: Choices) -> str | None:
    """The question of a form, or None where the plan lacks what it names."""
    template = FORMS[form][0]
    names = re.findall(r"{(\w)}", template)
    if any(getattr(choices, name) is None for name in names):
        return None
    return template.format(**{name: getattr(choices, name) for name in names})


def available_forms() -> list[str]:
    """The question forms this version of ethasp answers (its ``ask --help``)."""
    done = subprocess.run(ethasp_command("ask", "--help"), capture_output=True, text=True, cwd=ROOT)
    text = " ".join(done.stdout.split())
    return [
        form for form, (_, marker) in FORMS.items() if marker is None or re.search(marker, text)
    ]


# -- figures ------------------------------------------------------------------------


def cell(run_: Run) -> str:
    mark = "" if run_.proven else "*"
    ratio = f"{run_.ratio:.2f}" if run_.ratio is not None else "-"
    return (
        f"{run_.status + mark:12} {run_.seconds:7.2f} {ratio:>6} "
        f"{run_.memory_mb:7.0f} {run_.cpu:7.2f}"
    )


def gmean(values: list[float]) -> float:
    return math.exp(sum(math.log(v) for v in values) / len(values)) if values else float("nan")


def summary(rows: list[dict], limit: float) -> list[str]:
    lines = []
    proved = [row for row in rows if row["plain"].proven]
    restricted = [(row, r) for row in proved for r in row["searches"] if r.search != "ask"]
    answered = sum(1 for _, r in restricted if r.proven)
    lines.append(
        f"plain search proved on {len(proved)} of {len(rows)} instances (time limit {limit:g} s)"
    )
    lines.append(
        f"restricted searches answered with a proof where plain proved: "
        f"{answered} of {len(restricted)}   (target: all)"
    )
    ratios = [r.seconds / row["plain"].seconds for row, r in restricted]
    if ratios:
        worst_row, worst = max(
            restricted, key=lambda pair: pair[1].seconds / pair[0]["plain"].seconds
        )
        lines.append(
            f"restricted/plain time: geometric mean {gmean(ratios):.2f}x "
            f"(target <= {TARGET_GMEAN}x), max {max(ratios):.1f}x "
            f"({worst_row['instance']} {worst.search}; target <= {TARGET_MAX}x each); "
            f"over {TARGET_MAX}x: {sum(r > TARGET_MAX for r in ratios)} of {len(ratios)}"
            " (unanswered searches count with the seconds they took)"
        )
        proven_ratios = [r.seconds / row["plain"].seconds for row, r in restricted if r.proven]
        if proven_ratios:
            lines.append(
                f"  of those answered with a proof: geometric mean "
                f"{gmean(proven_ratios):.2f}x, max {max(proven_ratios):.1f}x"
            )
        kinds: dict[str, list] = {}
        for row, r in restricted:
            kinds.setdefault(r.search, []).append((row, r))
        lines.append(f"  {'search':24} {'proven':>7} {'gmean':>6} {'max':>6}")
        for kind, pairs in kinds.items():
            values = [r.seconds / row["plain"].seconds for row, r in pairs]
            lines.append(
                f"  {kind:24} {sum(r.proven for _, r in pairs):3} of {len(pairs):<2} "
                f"{gmean(values):6.2f} {max(values):6.1f}"
            )
    everything = [r for row in rows for r in [row["plain"], *row["searches"]]]
    if everything:
        top = max(everything, key=lambda r: r.memory_mb)
        top_row = next(row for row in rows if top is row["plain"] or top in row["searches"])
        lines.append(
            f"peak memory: {top.memory_mb:.0f} MB ({top_row['instance']} {top.search}; "
            f"target < {TARGET_MEMORY_MB:.0f} MB)"
        )
    asks = [(row, r) for row in rows for r in row["searches"] if r.search == "ask"]
    if asks:
        lines.append(
            f"ask without --plan: answered with a proof on "
            f"{sum(r.proven for _, r in asks)} of {len(asks)} instances"
        )
    reference = []
    for row, r in asks:
        contrast = next((s for s in row["searches"] if s.search == "ask why"), None)
        if contrast is None or not row["plain"].proven or not contrast.proven:
            continue
        reference.append(r.seconds / (row["plain"].seconds + contrast.seconds))
    if reference:
        lines.append(
            f"ask without --plan / (plain + 'why A' with --plan): geometric mean "
            f"{gmean(reference):.2f}x, max {max(reference):.1f}x over {len(reference)} "
            "instances (target: about 1x)"
        )
    return lines


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "folder",
        type=Path,
        nargs="?",
        default=DEFAULT_FOLDER,
        help=f"a folder of domain folders (default {DEFAULT_FOLDER})",
    )
    parser.add_argument(
        "--annotations",
        type=Path,
        default=ANNOTATIONS,
        help="the folder of annotation files DOMAIN.lp (default benchmarks/annotations)",
    )
    parser.add_argument(
        "--problems",
        default="1-4",
        help="positions of the problems of each domain, natural order "
        "(default 1-4; e.g. 1-8 or 1,3)",
    )
    parser.add_argument(
        "--time-limit",
        type=float,
        default=60.0,
        help="ethasp's --time-limit per process (default 60)",
    )
    parser.add_argument(
        "--grace",
        type=float,
        default=15.0,
        help="seconds past the time limit before a process is killed (default 15)",
    )
    parser.add_argument(
        "--principles",
        default=",".join(PRINCIPLES),
        help="comma-separated principles (default all eight; '' for none)",
    )
    parser.add_argument(
        "--questions",
        default=None,
        help=f"comma-separated question forms of {','.join(FORMS)} "
        "(default: every form that 'ethasp ask --help' lists)",
    )
    parser.add_argument("--no-ask", action="store_true", help="no 'ask' without --plan")
    parser.add_argument(
        "--reasons-limit",
        type=int,
        metavar="N",
        help="pass --reasons-limit N to 'plan --principle' (0: the search and the verdict "
        "without reasons) and, when N >= 1, to 'ask' (default: ethasp's own, 10)",
    )
    parser.add_argument(
        "--repeat", type=int, default=1, help="runs per process, the fastest kept (default 1)"
    )
    parser.add_argument("--only", help="instances whose DOMAIN/PROBLEM contains this text")
    parser.add_argument(
        "--planner",
        default="auto",
        help="ethasp's --planner for every command, plain search included (default auto)",
    )
    parser.add_argument("--json", type=Path, help="also write every row to this JSON file")
    parser.add_argument(
        "--summary",
        type=Path,
        metavar="JSON",
        help="print the summary of an earlier run's --json file and stop",
    )
    args = parser.parse_args()
    if args.summary is not None:
        data = json.loads(args.summary.read_text())
        rows = [
            {
                "instance": row["instance"],
                "plain": _reread(row["plain"]),
                "searches": [_reread(r) for r in row["searches"]],
            }
            for row in data["rows"]
        ]
        reasons = data.get("reasons_limit")
        print(
            f"{data['started']}; time limit {data['time_limit']:g} s; "
            f"question forms: {', '.join(data['forms'])}"
            + (f"; --reasons-limit {reasons}" if reasons is not None else "")
        )
        for line in summary(rows, data["time_limit"]):
            print(line)
        return 0

    principles = [p for p in args.principles.split(",") if p]
    unknown = set(principles) - set(PRINCIPLES)
    if unknown:
        parser.error(f"unknown principles: {', '.join(sorted(unknown))}")
    forms = (
        available_forms()
        if args.questions is None
        else [form for form in args.questions.split(",") if form]
    )
    unknown = set(forms) - set(FORMS)
    if unknown:
        parser.error(f"unknown question forms: {', '.join(sorted(unknown))}")
    chosen, skipped = instances(
        args.folder, args.annotations, _problem_numbers(args.problems), args.only
    )
    if skipped:
        print(f"skipped (no annotation file in {args.annotations}): {', '.join(skipped)}")
    if not chosen:
        print(f"no instances in {args.folder} with annotation files")
        return 1
    compileall.compile_dir(ROOT / "ethasp", quiet=1)
    started = time.strftime("%Y-%m-%d %H:%M")
    load = os.getloadavg()
    print(
        f"{started}; load average at start: {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}; "
        f"{os.cpu_count()} cores; time limit {args.time_limit:g} s (+{args.grace:g} s grace)"
    )
    print(f"question forms: {', '.join(forms)}")
    print(
        "* no proof: bounded, killed, error, a plan not proven shortest or a principle dropped "
        "without proof"
    )
    print(f"{'instance / search':44} {'status':12} {'s':>7} {'ratio':>6} {'MB':>7} {'cpu s':>7}")
    limit = ["--time-limit", f"{args.time_limit:g}", "--json", "--planner", args.planner]
    print(f"--planner {args.planner} (every command)")
    reasons = [] if args.reasons_limit is None else ["--reasons-limit", str(args.reasons_limit)]
    asked = reasons if args.reasons_limit is not None and args.reasons_limit >= 1 else []
    if reasons:
        print(f"--reasons-limit {args.reasons_limit} (plan --principle{', ask' if asked else ''})")
    rows = []
    for instance in chosen:
        model = instance.model()
        plain = run(
            "plain",
            ethasp_command("plan", *model, *limit),
            args.time_limit,
            args.grace,
            args.repeat,
        )
        print(f"{instance.label:44} {cell(plain)}", flush=True)
        searches: list[Run] = []

        def record(
            result: Run, text: str = "", plain: Run = plain, searches: list[Run] = searches
        ) -> None:
            if plain.seconds > 0:
                result.ratio = result.seconds / plain.seconds
            searches.append(result)
            detail = f"  {text}" if text else ""
            note = f"  ({result.note})" if result.note else ""
            print(f"  {result.search[:42]:42} {cell(result)}{note}{detail}", flush=True)

        for principle in principles:
            record(
                run(
                    principle,
                    ethasp_command("plan", *model, "--principle", principle, *limit, *reasons),
                    args.time_limit,
                    args.grace,
                    args.repeat,
                )
            )
        plan = plain.plan if plain.status == "found" else None
        if plan is None and (forms or not args.no_ask):
            print("  (no plain plan: no questions)")
            rows.append({"instance": instance.label, "plain": plain, "searches": searches})
            continue
        choices = choose(instance, plan) if forms or not args.no_ask else Choices()
        for form in forms:
            text = question(form, choices)
            if text is None:
                continue
            record(
                run(
                    f"ask {form}",
                    ethasp_command(
                        "ask",
                        *model,
                        "--plan",
                        " ".join(plan),
                        "--question",
                        text,
                        *limit,
                        *asked,
                    ),
                    args.time_limit,
                    args.grace,
                    args.repeat,
                ),
                text,
            )
        if not args.no_ask:
            deontic = next((r for r in searches if r.search == "deontology"), None)
            first = deontic.plan[0] if deontic is not None and deontic.plan else choices.A
            text = f"why {first}"
            record(
                run(
                    "ask",
                    ethasp_command("ask", *model, "--question", text, *limit, *asked),
                    args.time_limit,
                    args.grace,
                    args.repeat,
                ),
                text + " (no --plan)",
            )
        rows.append({"instance": instance.label, "plain": plain, "searches": searches})
    print()
    for line in summary(rows, args.time_limit):
        print(line)
    load = os.getloadavg()
    print(f"load average at end: {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    if args.json:
        args.json.write_text(
            json.dumps(
                {
                    "started": started,
                    "time_limit": args.time_limit,
                    "reasons_limit": args.reasons_limit,
                    "forms": forms,
                    "rows": [
                        {
                            "instance": row["instance"],
                            "plain": asdict(row["plain"]),
                            "searches": [asdict(r) for r in row["searches"]],
                        }
                        for row in rows
                    ],
                },
                indent=1,
            )
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
