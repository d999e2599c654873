"""Planning tasks in Fast Downward's input: the search model as a SAS+ task.

Planners of the planning community read PDDL and translate it into a task
over finite-domain variables (SAS+, the output of Fast Downward's
translator).  The ground model of a planner is a grounded task already (the
search model of :func:`ethasp.planning.engines.layers.search_model`: usable
actions, the state variables that may change), so it is written here
directly in that form, without PDDL and without grounding it again: each
state variable a variable of two values (0 false, 1 true), each usable
action an operator of cost 1 (so that a cheapest plan is a shortest one),
its preconditions, effects and conditional effects as they are.  When
effects that fire together set one variable both ways, true wins (model.lp):
the operator lists the effects setting false before those setting true on
each variable, and the planner applies them in order.

A goal utility (an HModel's ``goal_utility/1``: the final state is worth at
least B) is no classical goal; it compiles into a counting phase, so that
the plans of the task are the plans of the model followed by exactly
``n + 1`` counting steps:

* a variable ``stage`` (0 while planning, ``i`` while counting the i-th
  valued state variable, ``n + 1`` once counted); every action of the model
  needs stage 0; ``end`` moves to stage 1;
* a counter of the utility gained (0 to what the goal needs, saturated
  there): at stage ``i``, ``take`` adds the gain of the i-th variable if it
  has its better value, ``skip`` adds nothing; both move to stage ``i + 1``;
* the goal: the model's goal, stage ``n + 1`` and the counter full.

Each plan of the model whose final state is worth at least B extends to a
plan of the task with ``n + 1`` more steps, and each plan of the task is
one of them followed by its count, so shortest plans correspond.  The same
compilation without the model's goal asks for a reachable state worth at
least B (:func:`threshold_task`).

Exogenous events and derived variables are not compiled (``FEATURES``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import clingo

from ethasp.planning.engines import CONDITIONAL_EFFECTS, Unhandled, model_features

# The model features this compilation handles (ethasp.planning.engines).
FEATURES = frozenset({CONDITIONAL_EFFECTS})

# Counting operators beyond which a goal utility is not compiled (each
# counter value of each valued variable is an operator).
COUNTING_LIMIT = 200_000


class NotCompiled(Unhandled):
    """The model has something this compilation does not write (a feature, or
    a goal utility whose count would be too large)."""


@dataclass
class Task:
    """A SAS+ task: its text, the model's actions (operator ``aN`` is
    ``actions[N]``; the counting operators have other names), and whether it
    has conditional effects."""

    text: str
    actions: list[clingo.Symbol]
    conditional: bool

    def plan(self, operators: list[str]) -> list[clingo.Symbol]:
        """The model's actions of a plan of the task (operator names: ``aN`` for
        the N-th action), the counting steps left out."""
        return [self.actions[int(name[1:])] for name in operators if name.startswith("a")]


def task(model, goal: bool = True, at_least: int | None = None) -> Task:
    """The SAS+ task of a search model (a :class:`~ethasp.planning.engines.
    reachability.GroundModel`): its goal (``goal``), and a final state worth
    at least its goal utility, or ``at_least`` if given (a search model
    read with the utilities of facts: ``Atoms(planner, weights=True)``).  NotCompiled where
    it has events or derived variables, or a count too large."""
    missing = sorted(model_features(model) - FEATURES)  # read now: tests change FEATURES
    if missing:
        raise NotCompiled(f"Fast Downward's task does not model {' or '.join(missing)}")
    threshold = model.goal_utility if at_least is None else at_least - model.fixed_utility
    counting = _counting(model, threshold) if threshold is not None else None
    wanted = {v for v, _ in model.goal} if goal else set()
    if counting:
        wanted |= {variable for variable, _, _ in counting[0]}
    necessary = _necessary(model, wanted)
    variables = [variable for variable in model.variables if variable in necessary]
    index = {variable: i for i, variable in enumerate(variables)}
    lines = ["begin_version", "3", "end_version", "begin_metric", "0", "end_metric"]
    count = len(variables) + (2 if counting else 0)
    lines.append(str(count))
    for i in range(len(variables)):
        lines += ["begin_variable", f"v{i}", "-1", "2"]
        lines += [f"Atom v{i}(false)", f"Atom v{i}(true)", "end_variable"]
    stage = counter = -1
    if counting:
        stage, counter = len(variables), len(variables) + 1
        items, need = counting
        lines += ["begin_variable", "stage", "-1", str(len(items) + 2)]
        lines += [f"Atom stage({k})" for k in range(len(items) + 2)] + ["end_variable"]
        lines += ["begin_variable", "counter", "-1", str(need + 1)]
        lines += [f"Atom counter({k})" for k in range(need + 1)] + ["end_variable"]
    lines.append("0")  # no mutex groups
    lines.append("begin_state")
    lines += ["1" if variable in model.init else "0" for variable in variables]
    if counting:
        lines += ["0", "0"]
    lines.append("end_state")
    goals = [(index[v], int(b)) for v, b in model.goal] if goal else []
    if counting:
        goals += [(stage, len(counting[0]) + 1), (counter, counting[1])]
    lines += ["begin_goal", str(len(goals))]
    lines += [f"{var} {value}" for var, value in sorted(goals)] + ["end_goal"]
    operators: list[list[str]] = []
    conditional = False
    for number, action in enumerate(model.actions):
        if not any(effect.variable in index for effect in action.effects):
            continue  # it changes nothing that matters (see _necessary)
        operator, has_conditions = _operator(f"a{number}", action, index, stage)
        operators.append(operator)
        conditional = conditional or has_conditions
    if counting:
        operators += _count(counting, index, stage, counter)
    lines.append(str(len(operators)))
    for operator in operators:
        lines += operator
    lines.append("0")  # no axioms
    return Task("\n".join(lines) + "\n", [action.name for action in model.actions], conditional)


def threshold_task(model, at_least: int) -> Task:
    """The task of reaching a state worth at least ``at_least``, goal or not."""
    return task(model, goal=False, at_least=at_least)


def _necessary(model, wanted: set) -> set:
    """The state variables that matter: those ``wanted`` (the goal's, the
    counted ones), and those that a precondition or an effect's condition
    reads of an action that changes one that matters.  An action that
    changes none of them can be left out of every shortest plan, and
    leaving it out makes no plan: the task keeps only the variables that
    matter and the actions that change one (as Fast Downward's translator
    keeps only the necessary variables and operators)."""
    necessary = set(wanted)
    while True:
        more = set()
        for action in model.actions:
            changed = [effect for effect in action.effects if effect.variable in necessary]
            if not changed:
                continue
            more.update(v for v, _ in action.pre)
            for effect in changed:
                more.update(v for v, _ in effect.condition)
        if more <= necessary:
            return necessary
        necessary |= more


def _operator(name: str, action, index: dict, stage: int) -> tuple[list[str], bool]:
    """An action as an operator (its lines; effects on variables left out of
    ``index`` dropped), and whether it has conditional effects."""
    pre = {index[v]: int(b) for v, b in action.pre}
    effects_kept = [effect for effect in action.effects if effect.variable in index]
    touched = {index[effect.variable] for effect in effects_kept}
    prevail = sorted((var, value) for var, value in pre.items() if var not in touched)
    if stage >= 0:
        prevail.append((stage, 0))
    effects = []
    conditional = False
    for effect in effects_kept:  # false before true on each variable (sorted)
        var = index[effect.variable]
        conditions = [(index[v], int(b)) for v, b in effect.condition]
        conditional = conditional or bool(conditions)
        parts = [str(len(conditions))] + [f"{v} {b}" for v, b in conditions]
        parts += [str(var), str(pre.get(var, -1)), str(int(effect.value))]
        effects.append(" ".join(parts))
    lines = ["begin_operator", name, str(len(prevail))]
    lines += [f"{var} {value}" for var, value in prevail]
    lines += [str(len(effects)), *effects, "1", "end_operator"]
    return lines, conditional


def _counting(model, threshold: int) -> tuple[list[tuple[clingo.Symbol, bool, int]], int] | None:
    """The counting phase of a goal utility: the valued state variables (each
    with its better value and the gain of that value over the other, divided
    by their greatest common divisor) and the gain the goal needs; None where
    every state is worth enough."""
    valued: dict = {}
    for (variable, value), utility in model.weights.items():
        valued.setdefault(variable, {True: 0, False: 0})[value] = utility
    base = sum(min(values.values()) for values in valued.values())
    items = []
    for variable in sorted(valued, key=str):
        values = valued[variable]
        gain = abs(values[True] - values[False])
        if gain:
            items.append((variable, values[True] > values[False], gain))
    need = threshold - base
    if need <= 0:
        return None
    divisor = math.gcd(*(gain for _, _, gain in items)) if items else 1
    items = [(variable, better, gain // divisor) for variable, better, gain in items]
    need = -(-need // divisor)
    if need > sum(gain for _, _, gain in items):
        items, need = [], 1  # no state is worth enough: the counter never fills
    if len(items) * (need + 1) > COUNTING_LIMIT:
        raise NotCompiled("Fast Downward's task does not count a goal utility this large")
    return items, need


def _count(counting, index: dict, stage: int, counter: int) -> list[list[str]]:
    """The operators of the counting phase (see the module docstring)."""
    items, need = counting
    operators = [
        ["begin_operator", "end", "0", "1", f"0 {stage} 0 1", "1", "end_operator"],
    ]
    for k, (variable, better, gain) in enumerate(items, start=1):
        move = f"0 {stage} {k} {k + 1}"
        operators.append(["begin_operator", f"skip{k}", "0", "1", move, "1", "end_operator"])
        for value in range(need):
            operators.append(
                [
                    "begin_operator",
                    f"take{k}_{value}",
                    "1",
                    f"{index[variable]} {int(better)}",
                    "2",
                    move,
                    f"0 {counter} {value} {min(need, value + gain)}",
                    "1",
                    "end_operator",
                ]
            )
    return operators
