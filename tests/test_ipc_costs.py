"""Cheapest plans on IPC instances with action costs (tests/data/ipc-costs):
every PDDL file is read, and on the instances ethasp solves within seconds
the cost of its cheapest plan is the least cost Fast Downward's
``astar(lmcut())`` finds (figures of a run of
``benchmarks/costs_vs_fast_downward.py``), the plan valid."""

from __future__ import annotations

from pathlib import Path

import pytest

from ethasp import Model, find_plan, validate

pytestmark = pytest.mark.slow

DATA = Path(__file__).resolve().parent / "data" / "ipc-costs"

# The least cost of a plan, from Fast Downward (astar(lmcut()), cost-optimal).
LEAST_COST = {
    ("elevators", "p1"): 42,
    ("elevators", "p2"): 26,
    ("nomystery", "p1"): 11,
    ("openstacks", "p1"): 2,
    ("openstacks", "p2"): 2,
    ("openstacks", "p3"): 2,
    ("parc-printer", "p1"): 169009,
    ("parc-printer", "p2"): 438047,
    ("parc-printer", "p3"): 807114,
    ("peg-solitaire", "p1"): 2,
    ("peg-solitaire", "p2"): 5,
    ("peg-solitaire", "p3"): 4,
    ("sokoban", "p1"): 11,
    ("sokoban", "p2"): 9,
    ("sokoban", "p3"): 10,
    ("transport", "p1"): 54,
    ("transport", "p2"): 131,
    ("woodworking", "p1"): 170,
    ("woodworking", "p2"): 185,
}


def files(domain: str, problem: str) -> list[Path]:
    folder = DATA / domain
    own = folder / f"domain-{problem}.pddl"
    return [own if own.is_file() else folder / "domain.pddl", folder / f"{problem}.pddl"]


def test_every_instance_is_read():
    for folder in sorted(path for path in DATA.iterdir() if path.is_dir()):
        for problem in sorted(folder.glob("p*.pddl")):
            model = Model.load(files(folder.name, problem.stem))
            assert model.planner.has_costs, problem


@pytest.mark.parametrize("domain,problem", sorted(LEAST_COST))
def test_cheapest_plans_cost_what_fast_downward_proves_least(domain, problem):
    model = Model.load(files(domain, problem))
    result = find_plan(model, time_limit=120)
    assert result.status == "found", result
    assert result.cost == LEAST_COST[(domain, problem)], result
    check = validate(model, result.plan)
    assert check.valid and check.cost == result.cost
