"""Planning tasks in Fast Downward's input: the search model as a SAS+ task.

Planners of the planning community read PDDL and translate it into a task
over finite-domain variables (SAS+, the output of Fast Downward's
translator).  The ground model of a planner is a grounded task already (the
search model of :func:`ethasp.planning.engines.layers.search_model`: usable
actions, the state variables that may change), so it is written here
directly in that form, without PDDL and without grounding it again: each
state variable a variable of two values (0 false, 1 true), or with the
others of its mutex group one variable (:mod:`ethasp.planning.engines.groups`,
:class:`_Layout`), each usable action an operator of cost 1 (so that a
cheapest plan is a shortest one), its preconditions, effects and conditional
effects as they are.  When
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

A valued variable whose better value every state worth B has (without its
gain, all the others together fall short) is not counted: its better value
is a goal fact.  At the greatest B (every valued variable at its better
value) no count is left, and the task has a classical goal, which
heuristics such as LM-cut see whole (a count hides it from them).

Exogenous events and derived variables are not compiled (``FEATURES``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

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


def task(model, goal: bool = True, at_least: int | None = None, grouped: bool = True) -> Task:
    """The SAS+ task of a search model (a :class:`~ethasp.planning.engines.
    reachability.GroundModel`): its goal (``goal``), and a final state worth
    at least its goal utility, or ``at_least`` if given (a search model
    read with the utilities of facts: ``Atoms(planner, weights=True)``).  With
    ``grouped``, each proven mutex group of :mod:`~ethasp.planning.engines.groups`
    that the task can write is one variable (see :class:`_Layout`).  NotCompiled
    where it has events or derived variables, or a count too large."""
    missing = sorted(model_features(model) - FEATURES)  # read now: tests change FEATURES
    if missing:
        raise NotCompiled(f"Fast Downward's task does not model {' or '.join(missing)}")
    threshold = model.goal_utility if at_least is None else at_least - model.fixed_utility
    counting = _counting(model, threshold) if threshold is not None else None
    names = model.variables
    model = _numbered(model)
    if counting:
        number = {name: i for i, name in enumerate(names)}
        counting = ([(number[v], better, gain) for v, better, gain in counting[0]], counting[1])
        forced, left = _forced(counting)
        kept = list(model.goal) if goal else []
        if forced and not any((v, not better) in kept for v, better in forced):
            # Facts every state worth enough has: goal facts, not counted.  (A
            # goal that refutes one keeps the whole count: no plan is found.)
            model = replace(model, goal=kept + [fact for fact in forced if fact not in kept])
            goal, counting = True, left
    if counting and len(counting[0]) * (counting[1] + 1) > COUNTING_LIMIT:
        raise NotCompiled("Fast Downward's task does not count a goal utility this large")
    wanted = {v for v, _ in model.goal} if goal else set()
    if counting:
        wanted |= {variable for variable, _, _ in counting[0]}
    necessary = _necessary(model, wanted)
    variables = [variable for variable in model.variables if variable in necessary]
    layout = _Layout(model, variables, goal, counting, grouped, names)
    lines = ["begin_version", "3", "end_version", "begin_metric", "0", "end_metric"]
    # Fast Downward refuses a task without a goal: where nothing is asked, a
    # variable of its own that holds from the start (every state is a goal).
    unasked = not (goal and model.goal) and not counting
    count = len(layout.domains) + (2 if counting else 0) + (1 if unasked else 0)
    lines.append(str(count))
    for i, values in enumerate(layout.domains):
        lines += ["begin_variable", f"v{i}", "-1", str(len(values))]
        lines += [f"Atom v{i}({value})" for value in values] + ["end_variable"]
    stage = counter = -1
    if counting:
        stage, counter = len(layout.domains), len(layout.domains) + 1
        items, need = counting
        lines += ["begin_variable", "stage", "-1", str(len(items) + 2)]
        lines += [f"Atom stage({k})" for k in range(len(items) + 2)] + ["end_variable"]
        lines += ["begin_variable", "counter", "-1", str(need + 1)]
        lines += [f"Atom counter({k})" for k in range(need + 1)] + ["end_variable"]
    if unasked:
        lines += ["begin_variable", "unasked", "-1", "2", "Atom unasked()"]
        lines += ["NegatedAtom unasked()", "end_variable"]
    lines.append("0")  # no mutex groups
    lines.append("begin_state")
    lines += [str(value) for value in layout.initial(model.init)]
    if counting:
        lines += ["0", "0"]
    if unasked:
        lines.append("0")
    lines.append("end_state")
    goals = [layout.fact[literal] for literal in model.goal] if goal else []
    if unasked:
        goals.append((len(layout.domains), 0))
    if counting:
        goals += [(stage, len(counting[0]) + 1), (counter, counting[1])]
    lines += ["begin_goal", str(len(goals))]
    lines += [f"{var} {value}" for var, value in sorted(goals)] + ["end_goal"]
    operators: list[list[str]] = []
    conditional = False
    for number, action in enumerate(model.actions):
        if not any(effect.variable in layout.where for effect in action.effects):
            continue  # it changes nothing that matters (see _necessary)
        written = _operator(f"a{number}", action, layout, stage)
        if written is None:
            continue  # never applicable (it needs two variables of a group), or no change
        operator, has_conditions = written
        operators.append(operator)
        conditional = conditional or has_conditions
    if counting:
        operators += _count(counting, layout, stage, counter)
    lines.append(str(len(operators)))
    for operator in operators:
        lines += operator
    lines.append("0")  # no axioms
    return Task("\n".join(lines) + "\n", [action.name for action in model.actions], conditional)


def _numbered(model):
    """The search model over its variables' numbers (positions in
    ``model.variables``): what the task is written from, without hashing
    clingo's symbols (slow) at every read."""
    from ethasp.planning.engines.reachability import Effect, GroundAction

    number = {variable: i for i, variable in enumerate(model.variables)}

    def literals(items) -> tuple:
        return tuple((number[v], b) for v, b in items)

    actions = [
        GroundAction(
            action.name,
            literals(action.pre),
            tuple(
                Effect(number[e.variable], e.value, literals(e.condition)) for e in action.effects
            ),
        )
        for action in model.actions
    ]
    return replace(
        model,
        variables=list(range(len(model.variables))),
        actions=actions,
        init=frozenset(number[v] for v in model.init if v in number),
        goal=list(literals(model.goal)),
        weights={(number[v], b): u for (v, b), u in model.weights.items() if v in number},
    )


class _Layout:
    """The task's variables: a variable of two values (0 false, 1 true) for
    each state variable, except the members of a group: one variable for
    the group, with a value for each member (that member true, the others
    false) and a last one for none of them.

    A proven group (at most one member true in every reachable state)
    compiles where each action reads and writes it as a value: a member is
    read true only (not false, not in an effect's condition, not set by a
    conditional effect, not false in the goal or the better value of a
    count; not two members true in the goal), and an action that makes a
    member false without making another true needs a member true (the group
    becomes "none" where it needed that member, and stays otherwise: the
    member was false).  Members that break this leave their group (a part
    of a proven group is one), until every group compiles; an action that
    needs two members true is never applicable and is left out."""

    def __init__(self, model, variables: list, goal: bool, counting, grouped: bool, names):
        members = _compiled_groups(model, variables, goal, counting, names) if grouped else []
        grouped_variables = {v for group in members for v in group}
        # In the model's order, a group where its first member is (the order
        # changes no plan or proof, but heuristics break ties by it: LM-cut's
        # cuts, and so its estimates and the states it expands).
        position = {variable: i for i, variable in enumerate(variables)}
        units = [[v] for v in variables if v not in grouped_variables] + members
        units.sort(key=lambda unit: min(position[v] for v in unit))
        self.domains: list[list[str]] = []
        self.where: dict = {}  # state variable -> (task variable, its value when true)
        self.groups: dict[int, list] = {}  # task variable -> its members
        for unit in units:
            number = len(self.domains)
            if unit[0] not in grouped_variables:
                self.where[unit[0]] = (number, None)
                self.domains.append(["false", "true"])
                continue
            self.groups[number] = unit
            for value, variable in enumerate(unit):
                self.where[variable] = (number, value)
            self.domains.append([*(f"m{k}" for k in range(len(unit))), "none"])
        self.fact = _Facts(self)

    def none(self, var: int) -> int:
        return len(self.groups[var])

    def initial(self, init) -> list[int]:
        values = []
        for var in range(len(self.domains)):
            if var in self.groups:
                true = [i for i, v in enumerate(self.groups[var]) if v in init]
                values.append(true[0] if true else self.none(var))
            else:
                values.append(0)
        for variable, (var, value) in self.where.items():
            if value is None and variable in init:
                values[var] = 1
        return values


class _Facts:
    """``layout.fact[(variable, value)]``: the (task variable, value) of a literal."""

    def __init__(self, layout: _Layout):
        self.layout = layout

    def __getitem__(self, literal) -> tuple[int, int]:
        variable, truth = literal
        var, value = self.layout.where[variable]
        return (var, int(truth)) if value is None else (var, value)


def _compiled_groups(model, variables: list, goal: bool, counting, names) -> list[list]:
    """The proven groups over ``variables`` that the task writes as
    variables (see :class:`_Layout`)."""
    from ethasp.planning.engines.groups import groups

    kept = set(variables)
    found = [[v for v in group if v in kept] for group in groups(model, names)]
    group_of = {v: i for i, group in enumerate(found) for v in group}
    left: set = set()  # members that leave their group

    def read_false(variable) -> None:
        if variable in group_of:
            left.add(variable)

    for action in model.actions:
        for variable, value in action.pre:
            if not value:
                read_false(variable)
        for effect in action.effects:
            if effect.condition:
                read_false(effect.variable)
                for variable, _ in effect.condition:
                    read_false(variable)
    if goal:
        true_goals: dict[int, list] = {}
        for variable, value in model.goal:
            if not value:
                read_false(variable)
            elif variable in group_of:
                true_goals.setdefault(group_of[variable], []).append(variable)
        for members in true_goals.values():
            if len(members) > 1:
                left.update(members)
    if counting:
        for variable, better, _ in counting[0]:
            if not better:
                read_false(variable)
    while True:
        more = set()
        for action in model.actions:
            needs = {v for v, b in action.pre if b}
            adds = {e.variable for e in action.effects if e.value and not e.condition}
            for effect in action.effects:
                variable = effect.variable
                if effect.value or effect.condition or variable in adds or variable in left:
                    continue
                if variable not in group_of:
                    continue
                group = group_of[variable]
                siblings = [v for v in found[group] if v not in left]
                if not any(v in needs for v in siblings) and not any(v in adds for v in siblings):
                    more.add(variable)
        if not more - left:
            break
        left |= more
    compiled = [[v for v in group if v not in left] for group in found]
    return [group for group in compiled if len(group) > 1]


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


def _operator(name: str, action, layout: _Layout, stage: int) -> tuple[list[str], bool] | None:
    """An action as an operator (its lines; effects on variables left out of
    the task dropped), and whether it has conditional effects; None where it
    needs two members of a group true (it is never applicable), or where it
    changes nothing (the members of a group it makes false are false wherever
    it applies: Fast Downward refuses an operator without effects)."""
    where, fact = layout.where, layout.fact
    pre: dict[int, int] = {}
    for literal in action.pre:
        if literal[0] not in where:
            continue
        var, value = fact[literal]
        if var in layout.groups and pre.get(var, value) != value:
            return None
        pre[var] = value
    effects_kept = [effect for effect in action.effects if effect.variable in where]
    # A variable an effect without condition makes true is true after the
    # action (true wins): effects making it false are left out, and one
    # effect says so once (LM-cut refuses an operator with two effects on a
    # variable, and a condition that is always true is no condition).
    always = {e.variable for e in effects_kept if e.value and not e.condition}
    lines_of_effects = []
    touched = set()
    conditional = False
    added: dict[int, int] = {}
    deleted: dict[int, list[int]] = {}
    for effect in effects_kept:  # false before true on each variable (sorted)
        var, value = fact[(effect.variable, effect.value)]
        if var in layout.groups:
            if effect.value:
                added[var] = value
            else:
                deleted.setdefault(var, []).append(where[effect.variable][1])
            continue
        if effect.variable in always and (not effect.value or effect.condition):
            continue
        conditions = [fact[literal] for literal in effect.condition]
        conditional = conditional or bool(conditions)
        parts = [str(len(conditions))] + [f"{v} {b}" for v, b in conditions]
        parts += [str(var), str(pre.get(var, -1)), str(int(effect.value))]
        line = " ".join(parts)
        if line not in lines_of_effects:
            lines_of_effects.append(line)
        touched.add(var)
    for var in sorted(set(added) | set(deleted)):
        if var in added:
            post = added[var]
        elif pre.get(var) in deleted[var]:
            post = layout.none(var)  # the member it needs becomes false
        else:
            continue  # the members it makes false are false already
        if pre.get(var) == post:
            continue  # it stays (a prevail condition)
        lines_of_effects.append(f"0 {var} {pre.get(var, -1)} {post}")
        touched.add(var)
    if not lines_of_effects:
        return None
    prevail = sorted((var, value) for var, value in pre.items() if var not in touched)
    if stage >= 0:
        prevail.append((stage, 0))
    lines = ["begin_operator", name, str(len(prevail))]
    lines += [f"{var} {value}" for var, value in prevail]
    lines += [str(len(lines_of_effects)), *lines_of_effects, "1", "end_operator"]
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
    return items, need


def _forced(counting) -> tuple[list[tuple[int, bool]], tuple | None]:
    """The valued variables whose better value every state worth enough has
    (without the gain of one, the others together cannot fill the counter),
    as facts; and the count of the others (None where nothing is left to
    count).  At the greatest threshold every valued variable is forced:
    the goal utility is a conjunction of facts, a classical goal."""
    items, need = counting
    total = sum(gain for _, _, gain in items)
    forced = [(v, better, gain) for v, better, gain in items if total - gain < need]
    if not forced or not items:
        return [], counting
    rest = [item for item in items if item not in forced]
    need -= sum(gain for _, _, gain in forced)
    left = (rest, need) if need > 0 else None
    return [(v, better) for v, better, _ in forced], left


def _count(counting, layout: _Layout, stage: int, counter: int) -> list[list[str]]:
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
                    "{} {}".format(*layout.fact[(variable, better)]),
                    "2",
                    move,
                    f"0 {counter} {value} {min(need, value + gain)}",
                    "1",
                    "end_operator",
                ]
            )
    return operators
