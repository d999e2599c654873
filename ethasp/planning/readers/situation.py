"""HERA situations (``.yaml``, ``.json``) as planning models.

A situation of the HERA toolbox (PyPI package ``ethics``, module
``ethics.plans``) describes actions with intrinsic values, preconditions and
conditional effects; exogenous events at time points; utilities of facts;
moral patients affected by facts; a goal, a plan and an initial state.  This
module translates one into ASP facts of the model vocabulary
(``encodings/planning/model.lp``); the encodings give them HERA's meaning.

The mapping (names: a HERA name that is an ASP constant, such as
``frank_healthy``, stays one; any other, such as ``4alive`` or
``in_rob-a_kitchen``, becomes the string ``"4alive"``):

============================== ==================================================
HERA                           ASP
============================== ==================================================
``initialState: {v: b}``       ``variable(v).``, and ``init(v).`` when b is true
action ``a``                   ``action(a).``
``intrinsicvalue`` good, bad   ``utility(a,1).``, ``utility(a,-1).`` (neutral or
                               missing: utility 0)
``preconditions: P``,          for each effect i and variable v of it:
``effects: [{condition: C_i,   ``ceff(a,K,v,b).`` with ``cpre(a,K,w,c).`` for every
effect: E_i}, ...]``           w: c of P and C_i (P becomes a condition of every
                               effect: an action whose precondition fails does
                               nothing, as in HERA, where it is not an error)
event ``e``, ``timepoints``    ``event(e).``, ``event_at(e,t+1).`` for each time
                               point t >= 0 (HERA's time t is the t-th action;
                               ethasp's steps count from 1)
event ``preconditions``        ``event_pre(e,v,b).``
event ``effects``              ``event_effect(e,K,v,b).``,
                               ``event_condition(e,K,w,c).``; K numbers the effects
                               of all events in file order
``utilities``                  ``utility(v,b,u).``
``affects: {p: {pos: [..],     ``patient(p).``, ``affects(p,v,b,pos).``,
neg: [..]}}``                  ``affects(p,v,b,neg).``
``goal: {v: b}``               ``goal(v,b).`` (no goal: the empty goal)
``plan: [a1, ...]``            ``plan_length(n).``, ``plan_step(1,a1).``, ...
``alternatives: [[..], ..]``   ``alternative_plan(k,n).``, ``alternative_step(k,t,a).``
(an ethasp extension: the      (HERA's utilitarianism compares the plan with
plans of ``alethicAlternatives``) the final states of these plans)
``labels`` (an extension)      ``agent_label/2``, ``action_label/3``, ``fact_label/3``,
                               ``patient_label/2``
``changes`` (an extension):    what a repair may change (``ethasp repair``), each
``initialState: {v: C}``       ``changeable(v,C).``
``actions: [{name: a, ...,     ``creative(a,C).`` and the action's facts as above
cost: C}]``                    (HERA's creative alternatives, as actions)
``events: {e: C}``             ``preventable(e,C).``
``goal: {v: C}``               ``goal_cost(v,b,C).`` (``fixed``: ``goal_fixed(v,b).``)
============================== ==================================================

HERA applies an action's effects (and the events of one time point) one after
the other, so the last effect that sets a variable wins.  Events keep that
order through their keys K (the greatest key wins).  An action's conditional
effects follow ethasp's rule instead (when firing effects conflict, true
wins), so an effect i that sets v to true, followed in the list by effects j
that set v to false, gets conditions that at least one literal of each such
j's condition fails (one copy of the effect per choice), marked with
``override/4``: deleting v = false from the action (HERA's instrumentality
test) lifts them.  An effect that a later one always overrides is kept with
an impossible override condition (a literal contradicting its condition, or
v and not v).

A variable that ``initialState`` leaves out (HERA's states may lack one: then
neither of its values holds until an effect sets it) is read as false until
an effect sets it, with a warning on standard error.  The reading gives
HERA's answers wherever the situation never reads the fact "v is false" (no
precondition, condition, goal, utility or patient's fact names it), as then
"v is false" and "v is undefined" are told apart by nothing but the final
state that ``validate`` prints; the warning names the places otherwise, where
HERA's answers may differ (a condition "v is false" holds here, and fails in
HERA, before an effect sets v).

What cannot be mapped gets one line (exit code 2): a truth value that is not
a Boolean, an intrinsic value other than good, bad or neutral, a utility that
is not an integer, a fact of several variables in ``affects``, two actions
or two events of one name, an event without its ``name``,
``preconditions``, ``effects`` or ``timepoints`` (HERA would then ignore
every event of the situation), and an alternative plan naming an unknown
action.  What HERA ignores is ignored with a warning on standard error: a
utility of a fact of several variables (HERA never matches one), a second
utility of a fact (HERA uses the first), and an action of the situation's
plan that is not an action of the situation (HERA drops it from the plan).
"""

from __future__ import annotations

import itertools
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import clingo

from ethasp.planning.readers.hera_data import (
    SUFFIXES,
    DataReader,
    hera_name,
    load_data,
    name_term,
)
from ethasp.planning.terms import read_text

__all__ = ["SUFFIXES", "hera_name", "name_term", "translate", "translate_data"]

# Copies of one conditional effect that override conditions may need; beyond,
# the situation is refused.
MAX_COPIES = 10_000
# The largest cost of a change (encodings/planning/check.lp).
MAX_COST = 1_000_000

Literal = tuple[str, bool]


@dataclass
class _Reader(DataReader):
    """Checks a situation's data and collects the facts of its model."""

    variables: dict[str, bool] = field(default_factory=dict)
    patients: set[str] = field(default_factory=set)
    # Variables that initialState leaves out: where each is first named, and
    # where the fact "v is false" is read (see the module docstring).
    undefined: dict[str, str] = field(default_factory=dict)
    read_false: dict[str, list[str]] = field(default_factory=dict)

    # -- checking -------------------------------------------------------------------

    def partial(
        self, value: Any, what: str, known: bool = True, reads: bool = True
    ) -> list[Literal]:
        """A partial state {v: b}: its literals.  A variable that initialState
        leaves out (``known``) is declared here, false initially; ``reads``
        says whether the literals are read (conditions, goals, utilities,
        patients' facts) rather than set (effects)."""
        literals = []
        for key, truth in self.mapping(value, what).items():
            variable = self.name(key, f"a variable in {what}")
            if not isinstance(truth, bool):
                self.fail(f"{what}: the value of {variable} must be true or false, not {truth!r}")
            if known and variable not in self.variables:
                self.variables[variable] = False
                self.undefined[variable] = what
                self.add("variable", name_term(variable))
            if reads and not truth and variable in self.undefined:
                self.read_false.setdefault(variable, []).append(what)
            literals.append((variable, truth))
        return literals

    def warn_undefined(self) -> None:
        """One warning per variable that initialState leaves out."""
        for variable, first in self.undefined.items():
            places = self.read_false.get(variable)
            differ = (
                f"; HERA's answers may differ, as the situation reads "
                f"'{variable} is false' ({', '.join(dict.fromkeys(places))}), which "
                "holds here and fails in HERA before an effect sets it"
                if places
                else ""
            )
            self.warn(
                f"variable {variable} (in {first}) has no value in initialState: read "
                f"as false until an effect sets it (in HERA neither value holds until "
                f"then){differ}"
            )

    def fact(self, value: Any, what: str) -> Literal:
        literals = self.partial(value, what)
        if len(literals) != 1:
            self.fail(
                f"{what} must be a fact of one variable, such as {{v: true}} (HERA "
                f"matches facts of one variable only), not {value!r}"
            )
        return literals[0]

    # -- the parts of a situation -------------------------------------------------------

    def read(self, data: Any) -> None:
        data = self.mapping(data, "the situation")
        if "initialState" not in data:
            self.fail("the situation has no initialState")
        for variable, value in self.partial(data["initialState"], "initialState", known=False):
            self.variables[variable] = value
            self.add("variable", name_term(variable))
            if value:
                self.add("init", name_term(variable))
        actions = self.actions(data.get("actions"))
        changes = self.mapping(data.get("changes"), "changes")
        creative = self.actions(changes.get("actions"), actions, creative=True)
        events = self.events(data.get("events"))
        self.utilities(data.get("utilities"))
        self.affects(data.get("affects"))
        for variable, value in self.partial(data.get("goal"), "goal"):
            self.add("goal", name_term(variable), value)
        if data.get("plan") is not None:
            self.plan(data["plan"], actions, "plan")
        for number, plan in enumerate(self.sequence(data.get("alternatives"), "alternatives"), 1):
            self.plan(plan, actions, f"alternative {number}", number)
        self.changes(changes, data.get("goal"), events)
        self.labels(data.get("labels"), actions | creative)
        self.warn_undefined()

    def actions(
        self, value: Any, taken: set[str] = frozenset(), creative: bool = False
    ) -> set[str]:
        """The actions (with ``creative``: the creative alternatives of
        ``changes``, each with a cost, named unlike the ``taken`` actions)."""
        names: set[str] = set()
        where = "the creative alternatives of changes" if creative else "actions"
        for index, action in enumerate(self.sequence(value, where), 1):
            kind = "creative alternative" if creative else "action"
            action = self.mapping(action, f"{kind} {index}")
            name = self.name(action.get("name"), f"the name of {kind} {index}")
            what = f"{kind} {name}"
            if name in names or name in taken:
                self.fail(f"two actions are named {name}")
            names.add(name)
            term = name_term(name)
            if creative:
                self.add("creative", term, self.cost(action.get("cost", 1), what))
            else:
                self.add("action", term)
            value = action.get("intrinsicvalue", "neutral")
            if value not in ("good", "bad", "neutral"):
                self.fail(f"{what}: the intrinsicvalue must be good, bad or neutral, not {value!r}")
            if value != "neutral":
                self.add("utility", term, 1 if value == "good" else -1)
            pre = self.partial(action.get("preconditions"), f"the preconditions of {what}")
            effects = self.effects(action.get("effects"), what)
            self.compile_action(term, pre, effects)
        return names

    def cost(self, value: Any, what: str) -> int:
        cost = self.integer(value, f"the cost of {what}")
        if not 1 <= cost <= MAX_COST:
            self.fail(f"the cost of {what} must be from 1 to {MAX_COST}, not {cost}")
        return cost

    def changes(self, changes: dict, goal: Any, events: set[str]) -> None:
        """What a repair may change besides creative alternatives: initial
        values, events, and the costs of goal facts (or ``fixed``)."""
        for key, cost in self.mapping(changes.get("initialState"), "changes: initialState").items():
            variable = self.name(key, "a variable in changes: initialState")
            if variable not in self.variables:
                self.fail(f"changes: initialState: {variable} is not a variable of initialState")
            self.add("changeable", name_term(variable), self.cost(cost, f"changing {variable}"))
        for key, cost in self.mapping(changes.get("events"), "changes: events").items():
            event = self.name(key, "an event in changes: events")
            if event not in events:
                self.fail(f"changes: events: {event} is not an event of the situation")
            self.add("preventable", name_term(event), self.cost(cost, f"preventing {event}"))
        goals = dict(self.partial(goal, "goal", known=False, reads=False))
        for key, cost in self.mapping(changes.get("goal"), "changes: goal").items():
            variable = self.name(key, "a variable in changes: goal")
            if variable not in goals:
                self.fail(f"changes: goal: {variable} is not a variable of the goal")
            if cost == "fixed":
                self.add("goal_fixed", name_term(variable), goals[variable])
            else:
                cost = self.cost(cost, f"dropping the goal {variable}")
                self.add("goal_cost", name_term(variable), goals[variable], cost)

    def effects(self, value: Any, what: str) -> list[tuple[list[Literal], list[Literal]]]:
        result = []
        for index, effect in enumerate(self.sequence(value, f"the effects of {what}"), 1):
            effect = self.mapping(effect, f"effect {index} of {what}")
            condition = self.partial(
                effect.get("condition"), f"the condition of effect {index} of {what}"
            )
            sets = self.partial(effect.get("effect"), f"effect {index} of {what}", reads=False)
            result.append((condition, sets))
        return result

    def compile_action(
        self,
        action: clingo.Symbol,
        pre: list[Literal],
        effects: list[tuple[list[Literal], list[Literal]]],
    ) -> None:
        """ceff/cpre facts for HERA's effects in order (see the module docstring)."""
        conditions: list[dict[str, bool] | None] = []
        for condition, _ in effects:
            full = dict(pre)
            consistent = True
            for variable, value in condition:
                if full.get(variable, value) != value:
                    consistent = False
                full[variable] = value
            conditions.append(full if consistent else None)
        for i, (_, sets) in enumerate(effects):
            full = conditions[i]
            if full is None:
                continue  # the precondition and the condition exclude each other
            for variable, value in sets:
                overriders = []
                if value:
                    for j in range(i + 1, len(effects)):
                        later = conditions[j]
                        if later is None or dict(effects[j][1]).get(variable) is not False:
                            continue
                        if any(full.get(w, c) != c for w, c in later.items()):
                            continue  # never fires together with effect i
                        overriders.append([(w, not c) for w, c in later.items() if w not in full])
                self.emit_effect(action, i + 1, variable, value, full, overriders)

    def emit_effect(
        self,
        action: clingo.Symbol,
        index: int,
        variable: str,
        value: bool,
        condition: dict[str, bool],
        overriders: list[list[Literal]],
    ) -> None:
        term = name_term(variable)
        # The impossible override condition of an effect that a later one always
        # overrides: a literal contradicting its condition (or, without one, both
        # values of its variable); never one of its genuine conditions.
        dormant = [(w, not c) for w, c in sorted(condition.items())][:1] or [
            (variable, True),
            (variable, False),
        ]
        if not overriders:
            copies: list[list[Literal]] = [[]]
        elif any(not choices for choices in overriders):
            # A later effect always fires with this one and overrides it.
            copies = [dormant]
        else:
            count = 1
            for choices in overriders:
                count *= len(choices)
            if count > MAX_COPIES:
                self.fail(
                    f"action {hera_name(action)}: effect {index} is overridden by "
                    f"later effects in too many ways to map ({count} cases)"
                )
            copies = []
            for choice in itertools.product(*overriders):
                guard = dict(choice)
                if len(guard) == len(set(choice)) and sorted(set(choice)) not in copies:
                    copies.append(sorted(set(choice)))
            if not copies:
                copies = [dormant]
        for number, guard in enumerate(copies, 1):
            key = clingo.Tuple_([clingo.Number(index), term, clingo.Number(number)])
            self.add("ceff", action, key, term, value)
            for w, c in condition.items():
                self.add("cpre", action, key, name_term(w), c)
            for w, c in guard:
                self.add("cpre", action, key, name_term(w), c)
                self.add("override", action, key, name_term(w), c)

    def events(self, value: Any) -> set[str]:
        names: set[str] = set()
        key = 0
        for index, event in enumerate(self.sequence(value, "events"), 1):
            event = self.mapping(event, f"event {index}")
            name = self.name(event.get("name"), f"the name of event {index}")
            what = f"event {name}"
            for part in ("preconditions", "effects", "timepoints"):
                if part not in event:
                    self.fail(
                        f"{what} has no {part} (HERA would then ignore every event of the "
                        f"situation; write {part}: {'{}' if part == 'preconditions' else '[]'})"
                    )
            if name in names:
                self.fail(f"two events are named {name}")
            names.add(name)
            term = name_term(name)
            self.add("event", term)
            for time in self.sequence(event.get("timepoints"), f"the timepoints of {what}"):
                time = self.integer(time, f"a time point of {what}")
                if time >= 0:  # HERA's time points count from 0; earlier ones never come
                    if time >= 1_000_000:
                        self.fail(f"{what}: time point {time} is beyond 999999")
                    self.add("event_at", term, time + 1)
            for variable, truth in self.partial(
                event.get("preconditions"), f"the preconditions of {what}"
            ):
                self.add("event_pre", term, name_term(variable), truth)
            for condition, sets in self.effects(event.get("effects"), what):
                if not sets:
                    continue  # an effect that sets nothing
                key += 1
                for variable, truth in sets:
                    self.add("event_effect", term, key, name_term(variable), truth)
                for variable, truth in condition:
                    self.add("event_condition", term, key, name_term(variable), truth)
        return names

    def utilities(self, value: Any) -> None:
        seen: dict[Literal, int] = {}
        for index, entry in enumerate(self.sequence(value, "utilities"), 1):
            entry = self.mapping(entry, f"utility {index}")
            literals = self.partial(entry.get("fact"), f"the fact of utility {index}")
            utility = self.integer(entry.get("utility"), f"utility {index}")
            if len(literals) != 1:
                self.warn(
                    f"utility {index} is of a fact of {len(literals)} variables, which HERA "
                    "never matches: ignored"
                )
                continue
            fact = literals[0]
            if fact in seen:
                if seen[fact] != utility:
                    self.warn(
                        f"utility {index} is a second utility for the fact "
                        f"{{{fact[0]}: {str(fact[1]).lower()}}}: ignored (HERA uses the "
                        "first)"
                    )
                continue
            seen[fact] = utility
            self.add("utility", name_term(fact[0]), fact[1], utility)

    def affects(self, value: Any) -> None:
        for patient, sides in self.mapping(value, "affects").items():
            name = self.name(patient, "a patient in affects")
            self.patients.add(name)
            term = name_term(name)
            self.add("patient", term)
            sides = self.mapping(sides, f"affects of {name}")
            for sign in ("pos", "neg"):
                for fact in self.sequence(sides.get(sign), f"affects of {name} ({sign})"):
                    variable, truth = self.fact(fact, f"a fact affecting {name} ({sign})")
                    self.add("affects", term, name_term(variable), truth, clingo.Function(sign))

    def plan(self, value: Any, actions: set[str], what: str, number: int | None = None) -> None:
        steps = []
        for step in self.sequence(value, what):
            name = self.name(step, f"an action of the {what}")
            if name not in actions:
                if number is None:
                    self.warn(
                        f"the {what} names {name}, which is not an action of the "
                        "situation: dropped from the plan (as HERA does)"
                    )
                    continue
                self.fail(f"the {what} names {name}, which is not an action of the situation")
            steps.append(name_term(name))
        if number is None:
            self.add("plan_length", len(steps))
            for index, term in enumerate(steps, 1):
                self.add("plan_step", index, term)
        else:
            self.add("alternative_plan", number, len(steps))
            for index, term in enumerate(steps, 1):
                self.add("alternative_step", number, index, term)

    def labels(self, value: Any, actions: set[str]) -> None:
        labels = self.mapping(value, "labels")
        self.agent_label(labels)
        self.action_labels(labels, actions, "situation")
        for index, entry in enumerate(self.sequence(labels.get("facts"), "labels of facts"), 1):
            entry = self.mapping(entry, f"fact label {index}")
            variable, truth = self.fact(entry.get("fact"), f"fact label {index}")
            if not isinstance(entry.get("label"), str):
                self.fail(f"fact label {index} needs a label (a string)")
            self.add("fact_label", name_term(variable), truth, clingo.String(entry["label"]))
        self.patient_labels(labels, self.patients, "situation (in affects)")


def translate(path: Path) -> str:
    """The ASP facts of a situation file (one line with the problem if it cannot be mapped)."""
    text = read_text(path)
    reader = _Reader(str(path))
    reader.read(load_data(path, text))
    for line in reader.warnings:
        print(line, file=sys.stderr)
    return "".join(f"{fact}.\n" for fact in reader.facts)


def read_situation(data: Any, where: str) -> tuple[str, list[str]]:
    """The ASP facts of a situation given as data, and its warnings."""
    reader = _Reader(where)
    reader.read(data)
    return reader.text(), reader.warnings


def translate_data(data: Any, where: str = "<situation>") -> str:
    """The ASP facts of a situation given as Python data (dicts and lists, as
    HERA reads them)."""
    reader = _Reader(where)
    reader.read(data)
    return "".join(f"{fact}.\n" for fact in reader.facts)
