"""Random causal agency models (as the data HERA reads from YAML or JSON), and
HERA's own verdicts on them, for differential tests against the HERA toolbox
(``ethics.cam``, PyPI package ``ethics`` 0.22.3) and for benchmarks.

HERA's release lacks the module ``ethics.argumentation``, which
``ethics.cam.principles`` imports (for its discourse and universality
principles, which judge argumentation dialogues): :func:`hera_principles`
registers an empty stand-in for it in ``sys.modules`` first.

HERA judges a choice when the model's world sets the chosen action true and
the other actions false; the principles that compare are given the worlds of
all actions as alternatives (HERA's list includes the model itself).  It
gives no verdict where it raises an exception (an action without an entry in
``intentions`` or ``goals`` where a principle reads them, a model without
patients under the Kantian principles, a model of one action under Pareto),
or where its evaluation of a formula is ``None`` (an empty conjunction: a
choice without consequences under do-no-harm, ...).
"""

from __future__ import annotations

import json
import random
import sys
import types
from pathlib import Path

from hypothesis import strategies as st

# ethasp's principle -> HERA's class in ethics.cam.principles.
PRINCIPLES = {
    "hera-deontology": "DeontologicalPrinciple",
    "intention-deontology": "IntentionFocusedDeontologicalPrinciple",
    "goal-deontology": "GoalFocusedDeontologicalPrinciple",
    "hera-utilitarianism": "UtilitarianPrinciple",
    "hera-do-no-harm": "DoNoHarmPrinciple",
    "do-no-instrumental-harm": "DoNoInstrumentalHarmPrinciple",
    "do-no-instrumental-harm-without-intentions": "DoNoInstrumentalHarmPrincipleWithoutIntentions",
    "minimize-harm": "MinimizeHarmPrinciple",
    "minimax-harm": "MinimaxHarmPrinciple",
    "double-effect": "DoubleEffectPrinciple",
    "kantian-humanity": "KantianHumanityPrincipleReading1",
    "kantian-humanity-2": "KantianHumanityPrincipleReading2",
    "pareto": "ParetoPrinciple",
    "discourse": "DiscoursePrinciple",
    "universality": "UniversalityPrinciple",
}


def hera_principles():
    """HERA's module ``ethics.cam.principles``, imported with a stand-in for the
    missing ``ethics.argumentation``."""
    if "ethics.argumentation" not in sys.modules:
        stand_in = types.ModuleType("ethics.argumentation")
        for name in ("ArgModel", "ArgGraph", "ArgSolver"):
            setattr(stand_in, name, type(name, (), {}))
        sys.modules["ethics.argumentation"] = stand_in
    import ethics.cam.principles

    return ethics.cam.principles


def literal_text(name: str, value: bool) -> str:
    """A literal as HERA's files write keys and list items: ``x``, ``Not('x')``."""
    return name if value else f"Not('{name}')"


def _quoted(name: str) -> str:
    return "'" + name.replace("\\", "\\\\").replace("'", "\\'") + "'"


class Choices:
    """What the generator draws, from hypothesis (``Choices(draw)``, for
    property tests that shrink) or from a seeded ``random.Random``
    (``Choices(rng=...)``, for benchmarks)."""

    def __init__(self, draw=None, rng: random.Random | None = None):
        self.draw, self.rng = draw, rng

    def integer(self, low: int, high: int) -> int:
        if self.rng is not None:
            return self.rng.randint(low, high)
        return self.draw(st.integers(low, high))

    def boolean(self) -> bool:
        return self.integer(0, 1) == 1 if self.rng is not None else self.draw(st.booleans())

    def pick(self, items):
        items = list(items)
        return (
            items[self.integer(0, len(items) - 1)]
            if self.rng is not None
            else self.draw(st.sampled_from(items))
        )

    def some(self, items, most: int, least: int = 0) -> list:
        """Distinct items, between ``least`` and ``most`` of them."""
        items = list(items)
        if self.rng is not None:
            return self.rng.sample(items, self.rng.randint(least, min(most, len(items))))
        return self.draw(
            st.lists(st.sampled_from(items), unique=True, min_size=least, max_size=most)
        )


def formula(choices: Choices, names: list[str], depth: int = 0) -> str:
    """A HERA formula string over the names."""
    if depth >= 2 or choices.integer(0, 9) < 4:
        name = choices.pick(names)
        return _quoted(name) if choices.boolean() else f"Not({_quoted(name)})"
    connective = choices.pick(["And", "Or", "Not", "Impl", "BiImpl"])
    if connective == "Not":
        return f"Not({formula(choices, names, depth + 1)})"
    first, second = formula(choices, names, depth + 1), formula(choices, names, depth + 1)
    return f"{connective}({first}, {second})"


def cam(
    choices: Choices,
    actions: int,
    background: int,
    events: int,
    consequences: int,
    spaces: bool = True,
    utilities: int = 8,
) -> tuple[dict, dict]:
    """A causal agency model with these numbers of variables, and its world:
    ``(data, world)``, the world giving the values of the background variables
    and events; at most ``utilities`` facts have a utility."""
    acts = [f"a{i}" for i in range(actions)]
    given = [f"b{i}" for i in range(background)]
    happenings = [f"e{i}" for i in range(events)]
    effects = [f"c {i}" if spaces and i == 1 else f"c{i}" for i in range(consequences)]
    exogenous = acts + given + happenings
    mechanisms = {
        c: formula(choices, exogenous + effects[:index]) for index, c in enumerate(effects)
    }
    literals = [literal_text(v, b) for v in exogenous + effects for b in (True, False)]
    data = {
        "description": "a random model",
        "actions": acts,
        "background": given,
        "events": happenings,
        "consequences": effects,
        "mechanisms": mechanisms,
        "utilities": {key: choices.integer(-3, 3) for key in choices.some(literals, utilities)},
    }
    for key, most in (("intentions", 3), ("goals", 2)):
        if choices.integer(0, 9) > 0:  # else HERA has none, and fails where it reads them
            data[key] = {
                action: choices.some(literals, most) for action in acts if choices.integer(0, 9) > 0
            }
    patients = [f"p{i}" for i in range(choices.integer(0, 2))]
    data["patients"] = patients
    if patients:
        data["affects"] = {
            key: [
                [choices.pick(patients), choices.pick("+-")] for _ in range(choices.integer(1, 2))
            ]
            for key in choices.some(literals, 5)
        }
    world = {name: choices.boolean() for name in given + happenings}
    return data, world


@st.composite
def cams(draw, max_actions: int = 3, max_consequences: int = 4, spaces: bool = True):
    """A causal agency model and its world (:func:`cam`) of random size."""
    choices = Choices(draw)
    actions, background, events = (
        choices.integer(1, max_actions),
        choices.integer(0, 2),
        choices.integer(0, 1),
    )
    consequences = choices.integer(0 if choices.integer(0, 9) == 0 else 1, max_consequences)
    return cam(choices, actions, background, events, consequences, spaces)


def write(data: dict, path: Path, world: dict | None = None) -> Path:
    """The model as a JSON file (with ethasp's key ``world``, which HERA ignores)."""
    content = dict(data, world=world) if world else data
    path.write_text(json.dumps(content))
    return path


def hera_verdicts(path: Path, data: dict, world: dict) -> dict[tuple[str, str], bool | None]:
    """HERA's verdict on every choice (action) under every principle it has:
    (action, ethasp's name) -> True, False, or None where HERA gives none."""
    principles = hera_principles()
    from ethics.cam.semantics import CausalModel

    def model(action: str):
        values = {a: int(a == action) for a in data["actions"]}
        for name in (data.get("background") or []) + (data.get("events") or []):
            values[name] = int(bool(world.get(name, False)))
        return CausalModel(str(path), values)

    verdicts: dict[tuple[str, str], bool | None] = {}
    for action in data["actions"]:
        for name, cls in PRINCIPLES.items():
            chosen = model(action)
            chosen.alternatives = [chosen] + [model(b) for b in data["actions"] if b != action]
            try:
                principle = getattr(principles, cls)(chosen)
                verdict = principle.permissible()
                if any(result is None for result in principle.result):
                    verdict = None
            except Exception:  # HERA fails on this input
                verdict = None
            verdicts[(action, name)] = verdict if isinstance(verdict, bool) else None
    return verdicts


# -- reasons: HERA's literals and ethasp's, as comparable keys ---------------------


def _hera_fact(formula) -> tuple[str, bool]:
    """A fact of HERA's (``Atom('x')``, ``Not('x')``, ``Not(Not('x'))``) as (x, value)."""
    from ethics.language import Not

    value = True
    while isinstance(formula, Not):
        formula, value = formula.f1, not value
    return str(formula), value


def _hera_facts(formula) -> frozenset:
    from ethics.language import And

    if isinstance(formula, And):
        return _hera_facts(formula.f1) | _hera_facts(formula.f2)
    if isinstance(formula, bool) or formula is None:
        return frozenset()
    return frozenset([_hera_fact(formula)])


def _hera_term(term):
    from ethics.language import U

    if isinstance(term, U):
        return ("u", _hera_facts(term.t1))
    return ("num", term)


def hera_literal_key(literal) -> tuple:
    """A literal of HERA's reasons as a key comparable with :func:`ethasp_literal_key`."""
    from ethics import language as L

    if isinstance(literal, L.Not) and not isinstance(literal.f1, (L.Atom, L.Not)):
        return ("not", hera_literal_key(literal.f1))
    names = {L.Good: "good", L.Bad: "bad", L.Neutral: "neutral", L.Caused: "caused"}
    names |= {L.I: "intended", L.Goal: "goal_fact", L.Instrumental: "instrumental"}
    for kind, name in names.items():
        if type(literal) is kind:
            return (name, _hera_fact(literal.f1))
    for kind, name in ((L.Means, "means"), (L.Means2, "means2"), (L.End, "end")):
        if type(literal) is kind:
            return (name, str(literal.f1))
    if isinstance(literal, L.Causes):
        return ("causes", _hera_fact(literal.f1), _hera_fact(literal.f2))
    if isinstance(literal, L.Intervention):  # HERA's do(): the last value of a variable wins
        setting = dict(_hera_fact(part) for part in literal.f1.getConj())
        return ("do", frozenset(setting.items()), _hera_fact(literal.f2))
    if isinstance(literal, L.GEq):
        first, second = _hera_term(literal.f1), _hera_term(literal.f2)
        if first[0] == second[0] == "u":
            return ("geq", first[1], second[1])
        return ("ucompare", "geq", first, second)
    if isinstance(literal, L.Gt):
        return ("ucompare", "gt", _hera_term(literal.f1), _hera_term(literal.f2))
    raise ValueError(f"a literal of HERA's not mapped: {literal!r}")


def hera_reason_keys(reasons, conjunctive: bool) -> set[frozenset]:
    """HERA's reasons (conjunctions for sufficient ones, disjunctions else) as
    sets of literal keys."""
    keys = set()
    for reason in reasons:
        parts = reason.getConj() if conjunctive else reason.getClause()
        keys.add(frozenset(hera_literal_key(part) for part in parts))
    return keys


def ethasp_literal_key(text: str, elements) -> tuple:
    """A literal of ethasp's reasons (text of L) as a key."""
    import clingo

    from ethasp.principles.formula import parse_formula

    parsed = parse_formula(text, elements)

    def fact(term) -> tuple[str, bool]:
        name = term.arguments[0]
        shown = name.string if name.type == clingo.SymbolType.String else str(name)
        return shown, term.arguments[1].name == "true"

    def utility(term):
        if term.name == "u":
            return ("u", frozenset(conj[term.arguments[0]]))
        return ("num", term.arguments[0].number)

    def key(term) -> tuple:
        name, args = term.name, term.arguments
        if name == "neg":
            return ("not", key(args[0]))
        if name in ("good", "bad", "neutral"):
            return (name, fact(args[0]))
        if name in ("caused", "intended", "goal_fact", "instrumental"):
            return (name, fact(term))
        if name in ("means", "means2", "end"):
            return (name, _shown(args[0]))
        if name == "causes":
            return ("causes", fact(args[0]), fact(args[1]))
        if name == "do":
            return ("do", frozenset(conj[args[0]]), fact(args[1]))
        if name == "geq":
            return ("geq", *(frozenset(conj[a]) for a in args))
        if name == "ucompare":
            return ("ucompare", args[0].name, utility(args[1]), utility(args[2]))
        raise ValueError(f"a literal of ethasp's not mapped: {text}")

    def _shown(symbol) -> str:
        return symbol.string if symbol.type == clingo.SymbolType.String else str(symbol)

    conj = {
        name: [(_shown(v), b == "true") for v, b in members]
        for name, members in parsed.conjunctions.items()
    }
    return key(parsed.term)


def ethasp_reason_keys(reasons, elements) -> set[frozenset]:
    return {frozenset(ethasp_literal_key(text, elements) for text in reason) for reason in reasons}
