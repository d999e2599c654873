"""Benchmark: the utilitarian HModel against plain plan search and Algorithm 1.

Model family (``rescue_model``): a rescue robot walks a one-way corridor of
rooms 0..R to the exit in room R (the goal).  N people wait in rooms 1..R,
person P with utility u(saved(P)) = P, so there are N morally weighted
variables.  The robot carries only K oxygen masks and each rescue uses one,
so at most K people can be saved: every state with more than K people saved
(most of the 2^N candidate states, and all of the best ones) is unreachable,
although relaxed reachability cannot tell.  R = N/2 and K = N/4.

Three searches on the same model, in one run:

* plain: a shortest plan (``ethasp.find_plan``), ignoring ethics;
* HModel: a shortest utilitarian HPlan (``ethasp.principles.restriction``): the best
  reachable utility by optimisation, then plan search for a goal state that
  attains it;
* Algorithm 1 of the paper: candidate states of the weighted variables in
  decreasing utility, enumerated lazily, one plan-existence call each with
  this project's planner (the candidate as goal); for a reachable candidate
  a second call adds the original goal.  A level of equal utility succeeds
  if any of its candidates is reachable with the goal (the paper's max
  prefers goal states among ties), and yields "impermissible" if one is
  reachable only without it.  It stops at a time cap, which then makes its
  time, and the speed-up of the HModel, lower bounds.

Usage::

    python benchmarks/utilitarian_hmodel.py [--people 4 8 12 16] [--cap SECONDS]
                                            [--no-processes]

Timings are in-process (models built beforehand), plain and HModel the best
of ``--repeat`` runs; whole-process timings of plain and HModel runs (a fresh
Python process each: start-up, model loading, search) are printed beneath
them unless ``--no-processes``.
"""

from __future__ import annotations

import argparse
import heapq
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from ethasp import Model, find_plan  # noqa: E402
from ethasp.principles.restriction import plan_with_principles  # noqa: E402

MAX_HORIZON = 64


# -- the model family -----------------------------------------------------------

def rescue_model(people: int, goal: bool = True) -> str:
    """The rescue model with ``people`` weighted variables (ASP text)."""
    rooms, masks = max(1, people // 2), max(1, people // 4)
    text = f"""\
room(0..{rooms}). mask(1..{masks}). person(1..{people}).
variable(at(I)) :- room(I).
variable(masks(K)) :- K = 0..{masks}.
variable(saved(P)) :- person(P).
init(at(0)). init(masks({masks})).
action(move(I)) :- room(I), room(I+1).
pre(move(I),at(I),true) :- action(move(I)).
eff(move(I),at(I),false) :- action(move(I)).
eff(move(I),at(I+1),true) :- action(move(I)).
in(P,1+(P-1)\\{rooms}) :- person(P).
action(rescue(P,K)) :- person(P), mask(K).
pre(rescue(P,K),at(I),true) :- action(rescue(P,K)), in(P,I).
pre(rescue(P,K),saved(P),false) :- action(rescue(P,K)).
pre(rescue(P,K),masks(K),true) :- action(rescue(P,K)).
eff(rescue(P,K),saved(P),true) :- action(rescue(P,K)).
eff(rescue(P,K),masks(K),false) :- action(rescue(P,K)).
eff(rescue(P,K),masks(K-1),true) :- action(rescue(P,K)).
utility(saved(P),true,P) :- person(P).
"""
    return text + (f"goal(at({rooms}),true).\n" if goal else "")


def weights(people: int) -> dict[str, tuple[int, int]]:
    """Utilities (of true, of false) of the weighted variables of ``rescue_model``."""
    return {f"saved({p})": (p, 0) for p in range(1, people + 1)}


def goal_facts(people: int) -> str:
    return f"goal(at({max(1, people // 2)}),true).\n"


# -- Algorithm 1 ----------------------------------------------------------------

def candidates(utilities: dict[str, tuple[int, int]]) -> Iterator[tuple[int, dict[str, bool]]]:
    """Every assignment to the weighted variables, by decreasing utility, lazily.

    The best assignment gives each variable its better value; every other one
    flips a set of variables, losing the sum of their differences.  Sets are
    enumerated by increasing loss with a heap: from a set whose largest index
    is i, extend it by i+1, or replace i by i+1 (each set is reached once).
    """
    names = sorted(utilities, key=lambda v: abs(utilities[v][0] - utilities[v][1]))
    loss = [abs(utilities[v][0] - utilities[v][1]) for v in names]
    best = {v: utilities[v][0] >= utilities[v][1] for v in names}
    top = sum(max(utilities[v]) for v in names)

    def assignment(flipped: tuple[int, ...]) -> dict[str, bool]:
        result = dict(best)
        for index in flipped:
            result[names[index]] = not result[names[index]]
        return result

    yield top, assignment(())
    heap: list[tuple[int, tuple[int, ...]]] = [(loss[0], (0,))] if names else []
    while heap:
        lost, flipped = heapq.heappop(heap)
        yield top - lost, assignment(flipped)
        last = flipped[-1]
        if last + 1 < len(names):
            heapq.heappush(heap, (lost + loss[last + 1], flipped + (last + 1,)))
            heapq.heappush(heap, (lost - loss[last] + loss[last + 1], flipped[:-1] + (last + 1,)))


@dataclass
class Algorithm1Result:
    outcome: str            # "permissible", "impermissible", "cut" (time cap)
    utility: int | None     # the utility of the level it stopped at
    plan_length: int | None
    calls: int
    candidates: int
    seconds: float
    undecided: int = 0      # planner calls that ended bounded, not proven


def algorithm1(people: int, cap: float) -> Algorithm1Result:
    """Algorithm 1 on the rescue model, one planner call per candidate goal."""
    start = time.perf_counter()
    base = rescue_model(people, goal=False)
    calls = count = undecided = 0

    def plan(goal: dict[str, bool], with_goal: bool):
        nonlocal calls, undecided
        calls += 1
        text = base + "".join(f"goal({v},{str(b).lower()}).\n" for v, b in goal.items())
        if with_goal:
            text += goal_facts(people)
        result = find_plan(Model.from_string(text, check=False), MAX_HORIZON)
        undecided += result.status == "bounded"
        return result

    level: int | None = None
    reachable_without_goal = False
    for utility, candidate in candidates(weights(people)):
        if level is not None and utility != level and reachable_without_goal:
            break                      # the best level has no goal state
        level = utility
        if time.perf_counter() - start > cap:
            return Algorithm1Result("cut", utility, None, calls, count,
                                    time.perf_counter() - start, undecided)
        count += 1
        if plan(candidate, with_goal=False).status != "found":
            continue
        with_goal = plan(candidate, with_goal=True)
        if with_goal.status == "found":
            return Algorithm1Result("permissible", utility, len(with_goal.plan), calls, count,
                                    time.perf_counter() - start, undecided)
        reachable_without_goal = True
    return Algorithm1Result("impermissible", level, None, calls, count,
                            time.perf_counter() - start, undecided)


def states_above(people: int, utility: int) -> int:
    """How many candidate states have utility above ``utility`` (counting subsets)."""
    counts = {0: 1}
    for p in range(1, people + 1):
        nxt = dict(counts)
        for total, n in counts.items():
            nxt[total + p] = nxt.get(total + p, 0) + n
        counts = nxt
    return sum(n for total, n in counts.items() if total > utility)


# -- timing -----------------------------------------------------------------------

def timed(repeat: int, function, *args):
    """The result of a call and its best time over ``repeat`` calls."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        result = function(*args)
        best = min(best, time.perf_counter() - start)
    return result, best


def run_one(kind: str, people: int) -> None:
    """One search in this process (for whole-process timing)."""
    model = Model.from_string(rescue_model(people))
    if kind == "plain":
        print(find_plan(model, MAX_HORIZON).status)
    else:
        print(plan_with_principles(model, ["utilitarianism"], MAX_HORIZON).status)


def process_seconds(kind: str, people: int, repeat: int) -> float:
    """The best time of ``repeat`` fresh processes running one search."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run([sys.executable, __file__, "--only", kind, "--people", str(people)],
                       check=True, capture_output=True)
        best = min(best, time.perf_counter() - start)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--people", type=int, nargs="+", default=[4, 8, 12, 16],
                        help="numbers of morally weighted variables (default 4 8 12 16)")
    parser.add_argument("--cap", type=float, default=120.0,
                        help="time cap of Algorithm 1 per model, seconds (default 120)")
    parser.add_argument("--repeat", type=int, default=3,
                        help="time plain and HModel searches as the best of this many runs")
    parser.add_argument("--no-processes", action="store_true",
                        help="skip the whole-process timings")
    parser.add_argument("--only", choices=["plain", "hmodel"], help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.only:
        run_one(args.only, args.people[0])
        return

    header = (f"{'N':>3} {'plain s':>8} {'HModel s':>9} {'HM/plain':>9} {'Alg.1 s':>10} "
              f"{'calls':>6} {'Alg.1/HM':>9} {'lengths p/HM/A1':>16} {'best':>5}  Alg.1 outcome")
    print(header)
    for people in args.people:
        model = Model.from_string(rescue_model(people))
        plain, plain_s = timed(args.repeat, find_plan, model, MAX_HORIZON)
        hmodel, hmodel_s = timed(args.repeat, plan_with_principles, model, ["utilitarianism"],
                                 MAX_HORIZON)
        alg = algorithm1(people, args.cap)
        bound = ">=" if alg.outcome == "cut" else ""
        lengths = (f"{len(plain.plan)}/{len(hmodel.plan) if hmodel.plan else '-'}/"
                   f"{alg.plan_length if alg.plan_length is not None else '-'}")
        note = alg.outcome
        if alg.outcome == "cut":
            note += (f" after {alg.candidates} of the {states_above(people, hmodel.best.utility)}"
                     f" candidates better than the best reachable utility")
        elif alg.utility != hmodel.best.utility:
            note += f" (utility {alg.utility} differs from the HModel's!)"
        if alg.undecided:
            note += f", {alg.undecided} planner calls bounded"
        print(f"{people:>3} {plain_s:>8.3f} {hmodel_s:>9.3f} {hmodel_s / plain_s:>8.1f}x "
              f"{bound:>2}{alg.seconds:>8.2f} {alg.calls:>6} {bound:>2}{alg.seconds / hmodel_s:>6.0f}x "
              f"{lengths:>16} {hmodel.best.utility:>5}  {note}")
        if not args.no_processes:
            plain_p = process_seconds("plain", people, args.repeat)
            hmodel_p = process_seconds("hmodel", people, args.repeat)
            print(f"    whole process: plain {plain_p:.3f} s, HModel {hmodel_p:.3f} s, "
                  f"HModel/plain {hmodel_p / plain_p:.1f}x, Alg.1 (in-process) / HModel "
                  f"{bound}{alg.seconds / hmodel_p:.0f}x")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
