"""Fast Downward as an engine: a planner of the planning community, run as a process.

Fast Downward (the PyPI package ``up-fast-downward``, installed with the
``planners`` extra: ``pip install 'ethasp[planners]'``) searches the task of
:mod:`ethasp.planning.engines.sas`, written from the ground model: no PDDL
and no translation, the model's one grounding.  Its search component runs
as a child process of this one (started by :mod:`ethasp.execution.spawner`,
which then executes the planner in its place: it dies with its parent, its
memory counts in the process tree the front end watches, and it inherits
the worker's memory limit); the search kills it when its budget ends, and
in any case when it returns.

One configuration per kind of search, single-threaded and deterministic (the
same plan on every run):

* shortest plans: ``astar(lmcut())``, A* with the admissible LM-cut
  heuristic; with conditional effects, which LM-cut does not handle,
  ``astar(hmax())``.  A plan found is a cheapest one, and every operator
  costs 1: a shortest plan (proven);
* any plan: ``lazy_greedy([ff()], preferred=[ff()])``, lazy greedy search
  with the FF heuristic and its helpful actions: a plan fast, not proven
  shortest;
* whether a plan exists, where a proof that none does is as likely an
  answer (the sets of a goal's items in its conflicts):
  ``eager_greedy([ff()])``, which evaluates each state once as it reaches
  it, so that exhausting the states costs less than with the others.

Each proves that there is no plan when they explore every state not
recognised as a dead end (one from which the goal is unreachable even
ignoring delete effects): the planner then says the task is provably
unsolvable.  Anything else (an error, a configuration that refuses the
task, a process that ends without a word) is a failure, which the search
reports in one line of warning before it searches with clingo instead.

Like every engine's, a plan it returns is checked by its trace
(``encodings/planning/trace.lp``) before it is reported.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import os
import shutil
import tempfile
import threading
from dataclasses import dataclass, field
from pathlib import Path

from ethasp.execution import spawner
from ethasp.planning.budget import Budget
from ethasp.planning.engines import model_features, sas

# The model features this engine handles (ethasp.planning.engines).
FEATURES = sas.FEATURES

OPTIMAL = "astar(lmcut())"
OPTIMAL_CONDITIONAL = "astar(hmax())"
SATISFICING = "lazy_greedy([ff()], preferred=[ff()])"
DECIDING = "eager_greedy([ff()])"

# What the planner says at the end of a search (its standard output).
SOLVED = "Solution found."
UNSOLVABLE = "Task is provably unsolvable."

PLAN, NO_PLAN, STOPPED, FAILED = "plan", "unsolvable", "stopped", "failed"


def compiled(model, goal: bool = True, at_least: int | None = None) -> sas.Task:
    """The task this engine searches for a search model (see :func:`ethasp.
    planning.engines.sas.task`); :class:`~ethasp.planning.engines.sas.
    NotCompiled` (an :class:`~ethasp.planning.engines.Unhandled`) where the
    model has a feature the engine does not handle (``FEATURES``)."""
    missing = sorted(model_features(model) - FEATURES)
    if missing:
        raise sas.NotCompiled(f"Fast Downward's task does not model {' or '.join(missing)}")
    return sas.task(model, goal, at_least)


def executable() -> Path | None:
    """The search component of Fast Downward, if the package is installed."""
    spec = importlib.util.find_spec("up_fast_downward")
    if spec is None or not spec.submodule_search_locations:
        return None
    for location in spec.submodule_search_locations:
        binary = Path(location) / "downward" / "builds" / "release" / "bin" / "downward"
        if binary.is_file() and os.access(binary, os.X_OK):
            return binary
    return None


def configuration(task: sas.Task, optimal: bool, deciding: bool = False) -> str:
    """The search configuration for a task (see the module docstring);
    ``deciding``: any plan, where none may well exist."""
    if not optimal:
        return DECIDING if deciding else SATISFICING
    return OPTIMAL_CONDITIONAL if task.conditional else OPTIMAL


@dataclass
class Outcome:
    """What the planner answered: ``status`` ``plan`` (``operators``, the names
    of a plan's operators), ``unsolvable`` (proven), ``stopped`` (the budget
    ended it) or ``failed`` (``why``)."""

    status: str
    configuration: str
    operators: list[str] = field(default_factory=list)
    why: str = ""


# The answers of the searches done in this process (a plan, or a proof that
# there is none) by their task's text and configuration: the planner searches
# deterministically, so a task searched again (utilitarianism asks for the
# nearest goal state as good as the best one, and then its HModel's plan
# search writes the same task) is answered from here.  Bounded.
_ANSWERS: dict[tuple[str, str], Outcome] = {}
_ANSWERS_LOCK = threading.Lock()
ANSWERS_KEPT = 64


def solve(task: sas.Task, budget: Budget, optimal: bool = True, deciding: bool = False) -> Outcome:
    """Search the task with Fast Downward, under the budget (``deciding``:
    see :func:`configuration`)."""
    config = configuration(task, optimal, deciding)
    binary = executable()
    if binary is None:
        return Outcome(FAILED, config, why="Fast Downward is not installed")
    key = (hashlib.sha256(task.text.encode()).hexdigest(), config)
    with _ANSWERS_LOCK:
        if key in _ANSWERS:
            return _ANSWERS[key]
    outcome = _search(task, budget, config, binary)
    if outcome.status in (PLAN, NO_PLAN):
        with _ANSWERS_LOCK:
            if len(_ANSWERS) >= ANSWERS_KEPT:
                del _ANSWERS[next(iter(_ANSWERS))]
            _ANSWERS[key] = outcome
    return outcome


def _search(task: sas.Task, budget: Budget, config: str, binary: Path) -> Outcome:
    """One run of the planner on the task (see :func:`solve`)."""
    if budget.expired():
        return Outcome(STOPPED, config)
    folder = tempfile.mkdtemp(prefix="ethasp-downward-")
    child = None
    try:
        task_file = Path(folder) / "task.sas"
        task_file.write_text(task.text)
        plan_file = Path(folder) / "plan"
        argv = [str(binary), "--search", config, "--internal-plan-file", str(plan_file)]
        child = spawner.spawn(_execute, (argv, str(task_file), folder))
        lines: list[str] = []
        ended = threading.Event()

        def read() -> None:
            try:
                for line in child.lines():
                    lines.append(line.rstrip("\n"))
            finally:
                ended.set()

        threading.Thread(target=read, name="ethasp-downward", daemon=True).start()
        if not budget.wait_event(ended):
            return Outcome(STOPPED, config)
        said = {line.strip() for line in lines}
        if SOLVED in said and plan_file.is_file():
            return Outcome(PLAN, config, operators=_operators(plan_file.read_text()))
        if UNSOLVABLE in said:
            return Outcome(NO_PLAN, config)
        last = next((line.strip() for line in reversed(lines) if line.strip()), "")
        return Outcome(FAILED, config, why=last or "it ended without an answer")
    finally:
        if child is not None:
            child.kill()
        shutil.rmtree(folder, ignore_errors=True)


def _operators(text: str) -> list[str]:
    """The operator names of a plan file: ``(name)`` a line, comments left out."""
    return [
        line.strip()[1:-1].split()[0]
        for line in text.splitlines()
        if line.strip().startswith("(") and line.strip().endswith(")")
    ]


def _execute(argv: list[str], task_file: str, folder: str, out) -> None:
    """In a child process: become the planner, reading the task on standard
    input and writing to ``out`` (standard output and error both)."""
    spawner.end_with_parent()  # killed with its parent (kept across exec)
    with contextlib.suppress(OSError):
        os.setpgid(0, 0)  # a process group of its own (a terminal's Ctrl-C is not its)
    task = os.open(task_file, os.O_RDONLY)
    os.dup2(task, 0)
    os.dup2(out.fileno(), 1)
    os.dup2(out.fileno(), 2)
    os.chdir(folder)
    os.execv(argv[0], argv)
