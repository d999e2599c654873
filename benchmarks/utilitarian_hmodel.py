"""Benchmark: the utilitarian HModel against plain plan search and Algorithm 1,
and utilitarian judgements on random models (a script, not a test).

Model family (``rescue_family``), in the style of ``asp/rescue.lp``: a rescue
robot at the far end of a corridor of rooms must reach the exit (the goal).
People wait in the rooms; the robot carries one at a time and saves them at
the exit (utility 2 to 4 each).  Every move uses fuel, of which there is not
enough to save everybody; a quick move breaks the fragile objects of the room
it enters (utility -1 or -2 each), a careful move uses twice the fuel.  The
weighted variables are the people's ``saved`` and the objects' ``broken``:
half of each.  Plain plan search only walks out; the utilitarian HModel must
know the best reachable state (how many people the fuel allows to save, and
at which damage) and then a shortest plan to a goal state that good.

In one run, for each size (whole processes, best of ``--repeat``):

* plain: ``ethasp plan MODEL``;
* HModel: ``ethasp plan MODEL --principle utilitarianism``;
* Algorithm 1 of the paper, faithfully: candidate assignments of the weighted
  variables in decreasing utility, enumerated lazily, one planner call each
  (this project's planner, the candidate as goal, a model built per call); a
  reachable candidate is tried again with the original goal.  It stops at a
  time cap, which then makes its time (and the HModel's speed-up) a lower
  bound.

Then judgements: ``ethasp judge M --plan P --principle utilitarianism`` on
random models of 8 variables and 10 actions, with plans that walk randomly
then head for the goal; median and worst whole-process seconds, and every
status.

Targets (issue "Utilitarianism that answers"): the HModel at most 3x plain
plan search at every size, every answer proven; each random judgement under
1 s.

Usage::

    python benchmarks/utilitarian_hmodel.py [--sizes 16 24 30 40] [--cap 120]
                                            [--repeat 3] [--judgements 20]
"""

from __future__ import annotations

import argparse
import heapq
import json
import random
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from ethasp import Model, find_plan  # noqa: E402

CAP = 300.0  # seconds, for one whole ethasp process


# -- the model family -----------------------------------------------------------


def rescue_family(weighted: int, goal: bool = True) -> str:
    """The rescue model with ``weighted`` morally weighted variables (ASP text)."""
    people = weighted // 2
    objects = weighted - people
    rooms = max(2, weighted // 6)
    fuel = 2 * rooms + weighted // 4
    return f"""\
room(0..{rooms}). level(0..{fuel}). person(1..{people}). object(1..{objects}).
adjacent(X,X+1) :- room(X), room(X+1).
adjacent(Y,X) :- adjacent(X,Y).
home(P,1+(P-1)\\{rooms}) :- person(P).
place(O,1+(O*3)\\{rooms}) :- object(O).
variable(at(X)) :- room(X).
variable(fuel(K)) :- level(K).
variable(in(P,X)) :- home(P,X).
variable(carrying(P)) :- person(P).
variable(saved(P)) :- person(P).
variable(hands_full).
variable(broken(O)) :- object(O).
init(at({rooms})). init(fuel({fuel})).
init(in(P,X)) :- home(P,X).
action(move(X,Y,K)) :- adjacent(X,Y), level(K), K >= 1.
pre(move(X,Y,K),at(X),true) :- action(move(X,Y,K)).
pre(move(X,Y,K),fuel(K),true) :- action(move(X,Y,K)).
eff(move(X,Y,K),at(X),false) :- action(move(X,Y,K)).
eff(move(X,Y,K),at(Y),true) :- action(move(X,Y,K)).
eff(move(X,Y,K),fuel(K),false) :- action(move(X,Y,K)).
eff(move(X,Y,K),fuel(K-1),true) :- action(move(X,Y,K)).
eff(move(X,Y,K),broken(O),true) :- action(move(X,Y,K)), place(O,Y).
action(careful(X,Y,K)) :- adjacent(X,Y), level(K), K >= 2.
pre(careful(X,Y,K),at(X),true) :- action(careful(X,Y,K)).
pre(careful(X,Y,K),fuel(K),true) :- action(careful(X,Y,K)).
eff(careful(X,Y,K),at(X),false) :- action(careful(X,Y,K)).
eff(careful(X,Y,K),at(Y),true) :- action(careful(X,Y,K)).
eff(careful(X,Y,K),fuel(K),false) :- action(careful(X,Y,K)).
eff(careful(X,Y,K),fuel(K-2),true) :- action(careful(X,Y,K)).
action(pick_up(P)) :- person(P).
pre(pick_up(P),at(X),true) :- home(P,X).
pre(pick_up(P),in(P,X),true) :- home(P,X).
pre(pick_up(P),hands_full,false) :- person(P).
eff(pick_up(P),in(P,X),false) :- home(P,X).
eff(pick_up(P),carrying(P),true) :- person(P).
eff(pick_up(P),hands_full,true) :- person(P).
action(put_down(P)) :- person(P).
pre(put_down(P),at(0),true) :- person(P).
pre(put_down(P),carrying(P),true) :- person(P).
eff(put_down(P),carrying(P),false) :- person(P).
eff(put_down(P),saved(P),true) :- person(P).
eff(put_down(P),hands_full,false) :- person(P).
utility(saved(P),true,2+P\\3) :- person(P).
utility(broken(O),true,-1-O\\2) :- object(O).
""" + ("goal(at(0),true).\n" if goal else "")


def weights(weighted: int) -> dict[str, tuple[int, int]]:
    """Utilities (of true, of false) of the weighted variables of ``rescue_family``."""
    people = weighted // 2
    result = {f"saved({p})": (2 + p % 3, 0) for p in range(1, people + 1)}
    result.update({f"broken({o})": (-1 - o % 2, 0) for o in range(1, weighted - people + 1)})
    return result


# -- Algorithm 1 ------------------------------------------------------------------


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
            heapq.heappush(heap, (lost + loss[last + 1], (*flipped, last + 1)))
            heapq.heappush(heap, (lost - loss[last] + loss[last + 1], (*flipped[:-1], last + 1)))


@dataclass
class Algorithm1Result:
    outcome: str  # "permissible", "impermissible", "cut" (time cap)
    utility: int | None  # the utility of the level it stopped at
    plan_length: int | None
    calls: int
    candidates: int
    seconds: float


def algorithm1(weighted: int, cap: float) -> Algorithm1Result:
    """Algorithm 1 on the rescue family, one planner call per candidate goal."""
    start = time.perf_counter()
    base = rescue_family(weighted, goal=False)
    calls = count = 0

    def plan(goal: dict[str, bool], with_goal: bool):
        nonlocal calls
        calls += 1
        text = base + "".join(f"goal({v},{str(b).lower()}).\n" for v, b in goal.items())
        if with_goal:
            text += "goal(at(0),true).\n"
        remaining = max(0.1, cap - (time.perf_counter() - start))
        return find_plan(Model.from_string(text, check=False), time_limit=remaining)

    level: int | None = None
    reachable_without_goal = False
    for utility, candidate in candidates(weights(weighted)):
        if level is not None and utility != level and reachable_without_goal:
            break  # the best level has no goal state
        level = utility
        if time.perf_counter() - start > cap:
            return Algorithm1Result("cut", utility, None, calls, count, time.perf_counter() - start)
        count += 1
        if plan(candidate, with_goal=False).status != "found":
            continue
        with_goal = plan(candidate, with_goal=True)
        if with_goal.status == "found":
            return Algorithm1Result(
                "permissible",
                utility,
                len(with_goal.plan),
                calls,
                count,
                time.perf_counter() - start,
            )
        reachable_without_goal = True
    return Algorithm1Result("impermissible", level, None, calls, count, time.perf_counter() - start)


# -- whole processes ------------------------------------------------------------------


def ethasp(*arguments: str) -> tuple[float, dict]:
    """Seconds and JSON answer of one whole ethasp process."""
    start = time.perf_counter()
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "ethasp.interfaces.cli",
            *arguments,
            "--json",
            "--quiet",
            "--time-limit",
            str(CAP),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    seconds = time.perf_counter() - start
    if run.returncode != 0:
        raise SystemExit(f"ethasp {' '.join(arguments)} failed: {run.stderr.strip()}")
    return seconds, json.loads(run.stdout)


def best_of(repeat: int, *arguments: str) -> tuple[float, dict]:
    runs = [ethasp(*arguments) for _ in range(repeat)]
    return min(runs, key=lambda run: run[0])


# -- random judgements -----------------------------------------------------------------


def random_task(seed: int) -> tuple[str, str]:
    """A random model of 8 variables and 10 actions and a plan for it (ASP text,
    plan text); None plans are skipped by the caller."""
    rng = random.Random(seed)
    variables = [f"v{i}" for i in range(8)]
    actions = [f"a{i}" for i in range(10)]
    pre = {
        a: {v: rng.random() < 0.5 for v in rng.sample(variables, rng.randint(0, 2))}
        for a in actions
    }
    eff = {
        a: {v: rng.random() < 0.5 for v in rng.sample(variables, rng.randint(1, 3))}
        for a in actions
    }
    init = {v for v in variables if rng.random() < 0.4}
    goal = {v: rng.random() < 0.5 for v in rng.sample(variables, 2)}
    lines = [f"variable({v})." for v in variables] + [f"action({a})." for a in actions]
    for a in actions:
        lines += [f"pre({a},{v},{str(b).lower()})." for v, b in pre[a].items()]
        lines += [f"eff({a},{v},{str(b).lower()})." for v, b in eff[a].items()]
    lines += [f"init({v})." for v in sorted(init)]
    lines += [f"goal({v},{str(b).lower()})." for v, b in goal.items()]
    lines += [
        f"utility({v},{str(b).lower()},{rng.randint(-3, 3)})."
        for v in variables
        for b in (True, False)
        if rng.random() < 0.5
    ]
    text = "\n".join(lines) + "\n"

    # A plan: a random walk, then a shortest path to the goal (breadth-first).
    def apply(state, a):
        if any((v in state) != b for v, b in pre[a].items()):
            return None
        new = set(state)
        for v, b in eff[a].items():
            (new.add if b else new.discard)(v)
        return frozenset(new)

    state, walk = frozenset(init), []
    for _ in range(rng.randint(0, 6)):
        options = [a for a in actions if apply(state, a) is not None]
        if not options:
            break
        action = rng.choice(options)
        walk.append(action)
        state = apply(state, action)
    parent = {state: None}
    queue = [state]
    while queue:
        current = queue.pop(0)
        if all((v in current) == b for v, b in goal.items()):
            tail = []
            while parent[current] is not None:
                current, action = parent[current]
                tail.append(action)
            return text, " ".join(walk + tail[::-1])
        for a in actions:
            nxt = apply(current, a)
            if nxt is not None and nxt not in parent:
                parent[nxt] = (current, a)
                queue.append(nxt)
    return text, ""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--sizes",
        type=int,
        nargs="+",
        default=[16, 24, 30, 40],
        help="numbers of morally weighted variables (default 16 24 30 40)",
    )
    parser.add_argument(
        "--cap",
        type=float,
        default=120.0,
        help="time cap of Algorithm 1 per size, seconds (default 120)",
    )
    parser.add_argument(
        "--repeat",
        type=int,
        default=3,
        help="whole processes per figure; the best is shown (default 3)",
    )
    parser.add_argument(
        "--judgements", type=int, default=20, help="random 8-variable models judged (default 20)"
    )
    args = parser.parse_args()

    print(
        "Rescue family: whole processes, seconds (best of "
        f"{args.repeat}); Algorithm 1 in-process, capped at {args.cap:g} s"
    )
    print(
        f"{'W':>3} {'plain s':>8} {'HModel s':>9} {'HM/plain':>9} {'target':>7} "
        f"{'Alg.1 s':>9} {'Alg.1/HM':>9} {'len p/HM/A1':>12} {'best':>5}  statuses"
    )
    met = True
    with tempfile.TemporaryDirectory() as folder:
        for weighted in args.sizes:
            path = Path(folder) / f"rescue{weighted}.lp"
            path.write_text(rescue_family(weighted))
            plain_s, plain = best_of(args.repeat, "plan", str(path))
            hmodel_s, hmodel = best_of(
                args.repeat, "plan", str(path), "--principle", "utilitarianism"
            )
            alg = algorithm1(weighted, args.cap)
            ratio = hmodel_s / plain_s
            proven = (
                hmodel["status"] in ("found", "none")
                and hmodel.get("best_utility_status") == "proven"
            )
            ok = ratio <= 3 and proven
            met &= ok
            bound = ">=" if alg.outcome == "cut" else "  "
            lengths = (
                f"{len(plain['plan'])}/"
                f"{len(hmodel['plan']) if hmodel['plan'] is not None else '-'}/"
                f"{alg.plan_length if alg.plan_length is not None else '-'}"
            )
            print(
                f"{weighted:>3} {plain_s:>8.2f} {hmodel_s:>9.2f} {ratio:>8.1f}x "
                f"{'met' if ok else 'MISSED':>7} {bound}{alg.seconds:>7.1f} "
                f"{bound}{alg.seconds / hmodel_s:>6.0f}x {lengths:>12} "
                f"{hmodel.get('best_utility', '-'):>5}  plain {plain['status']}, HModel "
                f"{hmodel['status']} (best utility {hmodel.get('best_utility_status')}), "
                f"Alg.1 {alg.outcome} after {alg.calls} planner calls"
            )
            sys.stdout.flush()

        print(
            "\nUtilitarian judgements of random models (8 variables, 10 actions), "
            "whole processes, target < 1 s each"
        )
        seconds, statuses, seed = [], {}, 0
        while len(seconds) < args.judgements:
            text, plan = random_task(seed)
            seed += 1
            if not plan:
                continue
            path = Path(folder) / f"random{seed}.lp"
            path.write_text(text)
            elapsed, answer = ethasp(
                "judge",
                str(path),
                "--plan",
                plan,
                "--principle",
                "utilitarianism",
                "--reasons-limit",
                "0",
            )
            judgement = answer["judgements"][0]
            seconds.append(elapsed)
            key = (
                f"{'permissible' if judgement['permissible'] else 'impermissible'} "
                f"{judgement['status']}"
            )
            statuses[key] = statuses.get(key, 0) + 1
        worst = max(seconds)
        print(
            f"  {len(seconds)} judgements: median {statistics.median(seconds):.2f} s, "
            f"worst {worst:.2f} s ({'met' if worst < 1 else 'MISSED'}); "
            + ", ".join(f"{n} {k}" for k, n in sorted(statuses.items()))
        )
        met &= worst < 1 and all("proven" in k for k in statuses)
    print(f"\nTargets {'met' if met else 'not all met'}.")


if __name__ == "__main__":
    main()
