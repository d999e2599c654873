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


@st.composite
def formulas(draw, names: list[str], depth: int = 0):
    """A HERA formula string over the names."""
    if depth >= 2 or draw(st.integers(0, 9)) < 4:
        name = draw(st.sampled_from(names))
        return _quoted(name) if draw(st.booleans()) else f"Not({_quoted(name)})"
    connective = draw(st.sampled_from(["And", "Or", "Not", "Impl", "BiImpl"]))
    if connective == "Not":
        return f"Not({draw(formulas(names, depth + 1))})"
    first, second = draw(formulas(names, depth + 1)), draw(formulas(names, depth + 1))
    return f"{connective}({first}, {second})"


@st.composite
def cams(draw, max_actions: int = 3, max_consequences: int = 4, spaces: bool = True):
    """A causal agency model and its world: ``(data, world)``, the world
    giving the values of the background variables and events."""
    actions = [f"a{i}" for i in range(draw(st.integers(1, max_actions)))]
    background = [f"b{i}" for i in range(draw(st.integers(0, 2)))]
    events = [f"e{i}" for i in range(draw(st.integers(0, 1)))]
    count = draw(st.integers(0 if draw(st.integers(0, 9)) == 0 else 1, max_consequences))
    consequences = [f"c {i}" if spaces and i == 1 else f"c{i}" for i in range(count)]
    exogenous = actions + background + events
    mechanisms = {
        c: draw(formulas(exogenous + consequences[:index])) for index, c in enumerate(consequences)
    }
    variables = exogenous + consequences
    literals = [literal_text(v, b) for v in variables for b in (True, False)]
    utilities = {
        key: draw(st.integers(-3, 3))
        for key in draw(st.lists(st.sampled_from(literals), unique=True, max_size=8))
    }
    data = {
        "description": "a random model",
        "actions": actions,
        "background": background,
        "events": events,
        "consequences": consequences,
        "mechanisms": mechanisms,
        "utilities": utilities,
    }
    for key, most in (("intentions", 3), ("goals", 2)):
        if draw(st.integers(0, 9)) > 0:  # else HERA has none, and fails where it reads them
            data[key] = {
                action: draw(st.lists(st.sampled_from(literals), unique=True, max_size=most))
                for action in actions
                if draw(st.integers(0, 9)) > 0
            }
    patients = [f"p{i}" for i in range(draw(st.integers(0, 2)))]
    data["patients"] = patients
    if patients:
        affected = draw(st.lists(st.sampled_from(literals), unique=True, max_size=5))
        data["affects"] = {
            key: draw(
                st.lists(
                    st.tuples(st.sampled_from(patients), st.sampled_from("+-")).map(list),
                    min_size=1,
                    max_size=2,
                )
            )
            for key in affected
        }
    world = {name: draw(st.booleans()) for name in background + events}
    return data, world


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
