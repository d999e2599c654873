"""HERA's causal agency models (CAMs, ``.yaml``, ``.json``) as facts.

A causal agency model of the HERA toolbox (PyPI package ``ethics``, module
``ethics.cam``, version 0.22.3) describes one choice: the agent performs one
of its actions; Boolean structural equations (``mechanisms``) say which
consequences follow; the file also gives what the agent intends and aims at
with each action, the utilities of facts, and who is affected by them.  This
module checks such a file and translates it into the facts that
``encodings/cam/model.lp`` documents; the encodings give them HERA's meaning.

============================== ==================================================
HERA                           ASP
============================== ==================================================
``actions: [a, ...]``          ``cam_action(a,N).`` (N-th action), ``variable(a).``
``background: [b, ...]``       ``cam_background(b).``, ``variable(b).``
``events: [e, ...]``           ``cam_event(e).``, ``variable(e).``
``consequences: [c, ...]``     ``cam_consequence(c,N).``, ``variable(c).``
``mechanisms: {c: F}``         ``cam_mechanism(c,F).``, F a term of ``var/1``,
                               ``neg/1``, ``and/2``, ``or/2``, ``imp/2``,
                               ``iff/2``, ``top``, ``bottom``
``utilities: {x: u}``          ``utility(x,true,u).``; a key ``Not('x')``:
                               ``utility(x,false,u).``
``intentions: {a: [x, ...]}``  ``cam_intention(a,x,B).`` (B false for ``Not('x')``)
``goals: {a: [x, ...]}``       ``cam_goal(a,x,B).``
``patients: [p, ...]``         ``patient(p).``
``affects: {x: [[p, s]]}``     ``affects(p,x,B,pos).`` for s ``+``, ``neg`` for ``-``
``description``                ``cam_description("...").``
``world: {b: true}`` (ethasp)  ``init(b).``: a background variable or event that
                               is true (HERA's default: all false)
``labels`` (ethasp)            ``agent_label/2``, ``action_label/3``,
                               ``fact_label/3``, ``patient_label/2``
============================== ==================================================

Names become ASP terms as in situations
(:func:`ethasp.planning.readers.hera_data.name_term`): ``frank_healthy``
stays a constant, ``shoot the airplane`` becomes a string.  Formulas are
read by :mod:`ethasp.planning.readers.hera_formulas`, never evaluated.

HERA's older layout, in some files of its repository, is read where its
meaning is clear: a single ``action: a`` is ``actions: [a]``; ``consequences``
as a mapping from a cause to its effects makes each effect a consequence
that holds when one of its causes holds (the disjunction of the causes that
list it); ``intended: [x, ...]`` are the intentions of the single action.

What cannot be mapped gets one line naming the file and the field (exit
code 2): a CAM without actions, a name used twice, a formula that does not
parse, an unknown variable in a mechanism, a consequence without mechanism,
a cycle among mechanisms, a utility that is not an integer, a sign of
``affects`` other than ``+`` and ``-``, and a ``world`` value for something
that is not a background variable or an event.  What HERA ignores is
ignored with a warning on standard error: a mechanism of a variable that is
not a consequence, a utility or ``affects`` key that names no variable or
that is no literal, intentions and goals of something that is not an
action, an intention or goal that is no literal of a known variable, a
patient in ``affects`` that ``patients`` does not list, and a key that HERA
does not read.  A key ``Not("x")`` (HERA matches only the spelling
``Not('x')``) is read as the negation of x, with a warning.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import clingo

from ethasp.planning.readers.hera_data import DataReader, load_data, name_term
from ethasp.planning.readers.hera_formulas import (
    FormulaError,
    Parsed,
    hera_literal_text,
    literal_of,
    parse_hera_formula,
    variables_of,
)
from ethasp.planning.terms import read_text

Literal = tuple[str, bool]

# The keys of a CAM file: HERA's, its older layout's, and ethasp's own.
KEYS = (
    "description",
    "actions",
    "background",
    "events",
    "consequences",
    "mechanisms",
    "utilities",
    "intentions",
    "goals",
    "patients",
    "affects",
)
OLD_KEYS = ("action", "intended")
ETHASP_KEYS = ("world", "labels")

_KINDS = {"action": "an action", "background": "a background variable"}
_KINDS |= {"event": "an event", "consequence": "a consequence"}


def formula_term(parsed: Parsed) -> clingo.Symbol:
    """The ASP term of a parsed formula (``var/1``, ``neg/1``, ``and/2``, ...)."""
    kind = parsed[0]
    if kind == "var":
        return clingo.Function("var", [name_term(parsed[1])])
    if kind == "const":
        return clingo.Function("top" if parsed[1] else "bottom")
    if kind == "not":
        return clingo.Function("neg", [formula_term(parsed[1])])
    if kind in ("and", "or"):
        terms = [formula_term(part) for part in parsed[1]]
        term = terms[0]
        for other in terms[1:]:
            term = clingo.Function(kind, [term, other])
        return term
    return clingo.Function(kind, [formula_term(parsed[1]), formula_term(parsed[2])])


@dataclass
class _CamReader(DataReader):
    """Checks a CAM's data and collects its facts."""

    kinds: dict[str, str] = field(default_factory=dict)  # variable: its kind
    actions: list[str] = field(default_factory=list)
    patients: list[str] = field(default_factory=list)

    def read(self, data: Any) -> None:
        data = self.mapping(data, "the causal agency model")
        for key in data:
            if key not in KEYS + OLD_KEYS + ETHASP_KEYS:
                self.warn(f"{key!r} is not a key of HERA's causal agency models: ignored")
        if isinstance(data.get("description"), str):
            self.add("cam_description", clingo.String(data["description"]))
        self.read_actions(data)
        for kind, key in (("background", "background"), ("event", "events")):
            for name in self.names(data.get(key), key):
                self.declare(name, kind, key)
                self.add(f"cam_{kind}", name_term(name))
        mechanisms = self.read_consequences(data)
        self.read_mechanisms(mechanisms)
        self.read_utilities(data.get("utilities"))
        intentions = data.get("intentions")
        if data.get("intended") is not None:
            if intentions is not None or len(self.actions) != 1:
                self.fail(
                    "intended (HERA's older layout: the intentions of the single action) "
                    "needs one action and no intentions"
                )
            intentions = {self.actions[0]: data["intended"]}
        self.read_aims(intentions, "intentions", "cam_intention")
        self.read_aims(data.get("goals"), "goals", "cam_goal")
        for name in self.names(data.get("patients"), "patients"):
            if name in self.patients:
                self.fail(f"patients: {name} is listed twice")
            self.patients.append(name)
            self.add("patient", name_term(name))
        self.read_affects(data.get("affects"))
        self.read_world(data.get("world"))
        self.read_labels(data.get("labels"))

    # -- names and literals ------------------------------------------------------------

    def names(self, value: Any, what: str) -> list[str]:
        return [self.name(item, f"an entry of {what}") for item in self.sequence(value, what)]

    def declare(self, name: str, kind: str, what: str) -> None:
        if name in self.kinds:
            self.fail(f"{what}: {name} is already {_KINDS[self.kinds[name]]}")
        self.kinds[name] = kind
        self.add("variable", name_term(name))

    def literal(self, value: Any, what: str, key: bool = False) -> Literal | None:
        """A literal written as HERA writes one (``x``, ``'x'``, ``Not('x')``);
        None, with a warning, for another formula or an unknown variable."""
        try:
            parsed = parse_hera_formula(value)
        except FormulaError as error:
            self.fail(f"{what}: cannot read {value!r}: {error}")
        literal = literal_of(parsed)
        if literal is None:
            self.warn(f"{what}: {value!r} is not a variable or its negation: ignored")
            return None
        if literal[0] not in self.kinds:
            self.warn(f"{what}: {literal[0]!r} is not a variable of the model: ignored")
            return None
        if key and str(value) != hera_literal_text(*literal) and not literal[1]:
            self.warn(
                f"{what}: {value!r} is read as the negation of {literal[0]} (HERA matches "
                f"only the spelling {hera_literal_text(*literal)})"
            )
        return literal

    # -- the parts ------------------------------------------------------------------

    def read_actions(self, data: dict) -> None:
        if "action" in data:
            if "actions" in data:
                self.fail("both action (HERA's older layout) and actions are given")
            names = [self.name(data["action"], "action")]
        else:
            names = self.names(data.get("actions"), "actions")
        if not names:
            self.fail("actions: a causal agency model needs at least one action")
        for number, name in enumerate(names, 1):
            self.declare(name, "action", "actions")
            self.actions.append(name)
            self.add("cam_action", name_term(name), number)

    def read_consequences(self, data: dict) -> dict[str, Any]:
        """Declare the consequences; their mechanisms as given (formula strings)."""
        value = data.get("consequences")
        if isinstance(value, dict):  # HERA's older layout: cause -> [effects]
            if data.get("mechanisms") is not None:
                self.fail(
                    "consequences is a mapping from causes to effects (HERA's older "
                    "layout), which cannot be combined with mechanisms"
                )
            causes: dict[str, list[str]] = {}
            for cause, effects in value.items():
                cause = self.name(cause, "a cause in consequences")
                for effect in self.names(effects, f"the effects of {cause} in consequences"):
                    causes.setdefault(effect, [])
                    if cause not in causes[effect]:
                        causes[effect].append(cause)
            for number, effect in enumerate(causes, 1):
                self.declare(effect, "consequence", "consequences")
                self.add("cam_consequence", name_term(effect), number)
            mechanisms: dict[str, Any] = {}
            for effect, its in causes.items():
                for cause in its:
                    if cause not in self.kinds:
                        self.fail(
                            f"consequences: {cause} (a cause of {effect}) is not an action, "
                            "background variable, event or consequence"
                        )
                mechanisms[effect] = (
                    ("or", [("var", c) for c in its]) if len(its) > 1 else ("var", its[0])
                )
            return mechanisms
        for number, name in enumerate(self.names(value, "consequences"), 1):
            self.declare(name, "consequence", "consequences")
            self.add("cam_consequence", name_term(name), number)
        return self.mapping(data.get("mechanisms"), "mechanisms")

    def read_mechanisms(self, mechanisms: dict[str, Any]) -> None:
        parents: dict[str, list[str]] = {}
        for key, value in mechanisms.items():
            name = self.name(key, "a key of mechanisms")
            if self.kinds.get(name) != "consequence":
                what = _KINDS[self.kinds[name]] if name in self.kinds else "no variable"
                self.warn(
                    f"mechanisms: {name} is {what}, not a consequence: its mechanism is "
                    "ignored (as HERA does)"
                )
                continue
            if isinstance(value, tuple):  # made from the older layout
                parsed = value
            else:
                try:
                    parsed = parse_hera_formula(value)
                except FormulaError as error:
                    self.fail(f"mechanisms: {name}: cannot read the formula {value!r}: {error}")
            for variable in variables_of(parsed):
                if variable not in self.kinds:
                    self.fail(
                        f"mechanisms: {name}: unknown variable {variable!r} (not an action, "
                        "background variable, event or consequence)"
                    )
            parents[name] = [v for v in variables_of(parsed) if self.kinds[v] == "consequence"]
            self.add("cam_mechanism", name_term(name), formula_term(parsed))
        for name, kind in self.kinds.items():
            if kind == "consequence" and name not in parents:
                self.fail(f"mechanisms: consequence {name} has no mechanism")
        cycle = _cycle(parents)
        if cycle:
            self.fail(f"mechanisms: a cycle among mechanisms: {' -> '.join(cycle)}")

    def read_utilities(self, value: Any) -> None:
        seen: dict[Literal, int] = {}
        for key, utility in self.mapping(value, "utilities").items():
            literal = self.literal(key, "utilities", key=True)
            number = self.integer(utility, f"utilities: the utility of {key}")
            if literal is None:
                continue
            if literal in seen:
                self.warn(f"utilities: a second utility of {key!r}: ignored (HERA uses the first)")
                continue
            seen[literal] = number
            self.add("utility", name_term(literal[0]), literal[1], number)

    def read_aims(self, value: Any, what: str, predicate: str) -> None:
        for key, items in self.mapping(value, what).items():
            action = self.name(key, f"a key of {what}")
            if self.kinds.get(action) != "action":
                self.warn(f"{what}: {action} is not an action: ignored (as HERA does)")
                continue
            for item in self.sequence(items, f"the {what} of {action}"):
                literal = self.literal(item, f"the {what} of {action}")
                if literal is not None:
                    self.add(predicate, name_term(action), name_term(literal[0]), literal[1])

    def read_affects(self, value: Any) -> None:
        for key, pairs in self.mapping(value, "affects").items():
            literal = self.literal(key, "affects", key=True)
            pairs = self.sequence(pairs, f"affects of {key}")
            if literal is None:
                continue
            for pair in pairs:
                if not (isinstance(pair, list) and len(pair) == 2):
                    self.fail(f"affects of {key}: each entry must be [patient, + or -]")
                patient = self.name(pair[0], f"a patient in affects of {key}")
                if pair[1] not in ("+", "-"):
                    self.fail(f"affects of {key}: the sign must be + or -, not {pair[1]!r}")
                if patient not in self.patients:
                    self.warn(
                        f"affects of {key}: {patient} is not listed in patients: ignored "
                        "(HERA's principles consider the patients listed)"
                    )
                    continue
                sign = clingo.Function("pos" if pair[1] == "+" else "neg")
                self.add("affects", name_term(patient), name_term(literal[0]), literal[1], sign)

    def read_world(self, value: Any) -> None:
        for key, truth in self.mapping(value, "world").items():
            name = self.name(key, "a key of world")
            kind = self.kinds.get(name)
            if kind not in ("background", "event"):
                what = _KINDS[kind] if kind else "no variable of the model"
                self.fail(
                    f"world: {name} is {what}; the world gives background variables "
                    "and events (the action is chosen)"
                )
            if truth in (0, 1) and not isinstance(truth, bool):
                truth = bool(truth)
            if not isinstance(truth, bool):
                self.fail(f"world: the value of {name} must be true or false, not {truth!r}")
            if truth:
                self.add("init", name_term(name))

    def read_labels(self, value: Any) -> None:
        labels = self.mapping(value, "labels")
        self.agent_label(labels)
        self.action_labels(labels, set(self.actions), "causal agency model")
        for key, phrase in self.mapping(labels.get("facts"), "labels of facts").items():
            literal = self.literal(key, "labels of facts", key=True)
            if not isinstance(phrase, str):
                self.fail(f"labels of facts: {key} needs a phrase (a string)")
            if literal is not None:
                self.add("fact_label", name_term(literal[0]), literal[1], clingo.String(phrase))
        self.patient_labels(labels, set(self.patients), "causal agency model")


def _cycle(parents: dict[str, list[str]]) -> list[str]:
    """A cycle of the graph (each node to its parents), as a path, or []."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    for start in parents:
        if state.get(start):
            continue
        path = [start]
        state[start] = 1
        iterators = [iter(parents.get(start, []))]
        while iterators:
            step = next(iterators[-1], None)
            if step is None:
                state[path.pop()] = 2
                iterators.pop()
                continue
            if state.get(step) == 1:
                return [*path[path.index(step) :], step]
            if not state.get(step):
                state[step] = 1
                path.append(step)
                iterators.append(iter(parents.get(step, [])))
    return []


def translate_data(data: Any, where: str = "<causal agency model>") -> tuple[str, list[str]]:
    """The ASP facts of a CAM given as Python data (as HERA reads it), and the
    warnings (lines naming ``where``)."""
    reader = _CamReader(where)
    reader.read(data)
    return reader.text(), reader.warnings


def translate(path: Path) -> str:
    """The ASP facts of a CAM file; its warnings go to standard error."""
    text, warnings = translate_data(load_data(path, read_text(path)), str(path))
    for line in warnings:
        print(line, file=sys.stderr)
    return text
