"""Brute-force reference for reasons: prime implicants by enumeration.

Formulas of L are nested tuples over atom strings (ASP terms of
``encodings/judgement/language.lp``): ``("neg", F)``, ``("and", F, G)``, ``("or", F, G)``,
``("imp", F, G)``, ``("all", [F, ...])``, ``("any", [F, ...])``, or an atom.
Every assignment of the atoms is enumerated; the background theory is written
here again from its description in ``encodings/reasons/theory.lp``.  Used
only by tests, as an oracle.
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Iterable

Formula = object
Literal = tuple[str, bool]


def atoms_of(formula: Formula) -> list[str]:
    found: list[str] = []

    def walk(node):
        if isinstance(node, str):
            if node not in found:
                found.append(node)
        elif node[0] in ("all", "any"):
            for child in node[1]:
                walk(child)
        else:
            for child in node[1:]:
                walk(child)

    walk(formula)
    return found


def evaluate(formula: Formula, assignment: dict[str, bool]) -> bool:
    if isinstance(formula, str):
        return assignment[formula]
    kind = formula[0]
    if kind == "neg":
        return not evaluate(formula[1], assignment)
    if kind == "and":
        return evaluate(formula[1], assignment) and evaluate(formula[2], assignment)
    if kind == "or":
        return evaluate(formula[1], assignment) or evaluate(formula[2], assignment)
    if kind == "imp":
        return (not evaluate(formula[1], assignment)) or evaluate(formula[2], assignment)
    if kind == "all":
        return all(evaluate(child, assignment) for child in formula[1])
    if kind == "any":
        return any(evaluate(child, assignment) for child in formula[1])
    raise ValueError(formula)


# -- the background theory ---------------------------------------------------------

_VALUATION = re.compile(r"^(good|bad|neutral)\((.*)\)$")
_CAUSED = re.compile(r"^caused\((.*),(true|false)\)$")
_GEQ = re.compile(r"^geq\((\w+),(\w+)\)$")
_INTENDED = re.compile(r"^intended\((.*),(true|false)\)$")
_CAUSES = re.compile(r"^causes\(fact\((\w+),(true|false)\),fact\((\w+),(true|false)\)\)$")
_COMPARE = re.compile(r"^ucompare\((gt|geq|eq),(num\(-?\d+\)|u\(\w+\)),(num\(-?\d+\)|u\(\w+\))\)$")
_OTHER = {"true": "false", "false": "true"}


def _compare_consistent(compare: dict[tuple[str, str, str], bool]) -> bool:
    """HERA's theory of comparisons: X > X fails, X >= X and X = X hold, and
    X > Y excludes Y > X, Y >= X, X = Y and Y = X."""
    for (op, x, y), value in compare.items():
        if x == y and value == (op == "gt"):
            return False
        if op == "gt" and value:
            against = [("gt", y, x), ("geq", y, x), ("eq", x, y), ("eq", y, x)]
            if any(compare.get(key) and key != (op, x, y) for key in against):
                return False
    return True


def _causes_consistent(causes: dict[tuple[tuple, tuple], bool]) -> bool:
    """HERA's theory of Causes between facts p, q (-p the other fact of p's
    variable): not Causes(p,-p); not both Causes(p,q) and Causes(q,p) (p !=
    q), Causes(p,q) and Causes(p,-q), Causes(p,q) and Causes(-p,q)."""
    for (p, q), value in causes.items():
        if not value:
            continue
        other_p, other_q = (p[0], _OTHER[p[1]]), (q[0], _OTHER[q[1]])
        if q == other_p:
            return False
        if p != q and causes.get((q, p)):
            return False
        if causes.get((p, other_q)) or causes.get((other_p, q)):
            return False
    return True


def consistent(assignment: dict[str, bool]) -> bool:
    """Does the assignment respect the background theory?"""
    valuations: dict[str, dict[str, bool]] = {}
    caused: dict[str, dict[str, bool]] = {}
    geq: dict[tuple[str, str], bool] = {}
    intended: dict[str, dict[str, bool]] = {}
    causes: dict[tuple[tuple, tuple], bool] = {}
    compare: dict[tuple[str, str, str], bool] = {}
    for atom, value in assignment.items():
        if match := _INTENDED.match(atom):
            intended.setdefault(match.group(1), {})[match.group(2)] = value
        elif match := _CAUSES.match(atom):
            p, q = (match.group(1), match.group(2)), (match.group(3), match.group(4))
            causes[(p, q)] = value
        elif match := _COMPARE.match(atom):
            compare[(match.group(1), match.group(2), match.group(3))] = value
        elif match := _VALUATION.match(atom):
            valuations.setdefault(match.group(2), {})[match.group(1)] = value
        elif match := _CAUSED.match(atom):
            caused.setdefault(match.group(1), {})[match.group(2)] = value
        elif match := _GEQ.match(atom):
            geq[(match.group(1), match.group(2))] = value
    for kinds in valuations.values():
        if sum(kinds.values()) > 1:
            return False
        if len(kinds) == 3 and not any(kinds.values()):
            return False
    for values in [*caused.values(), *intended.values()]:
        if values.get("true") and values.get("false"):
            return False
    if not (_compare_consistent(compare) and _causes_consistent(causes)):
        return False
    for (c, d), value in geq.items():
        if c == d and not value:
            return False
        if c < d and (d, c) in geq and not value and not geq[(d, c)]:
            return False
    for (c, d), (d2, e) in itertools.product(geq, geq):
        chained = d == d2 and len({c, d, e}) == 3 and (c, e) in geq
        if chained and geq[(c, d)] and geq[(d, e)] and not geq[(c, e)]:
            return False
    return True


def assignments(atoms: list[str]) -> list[dict[str, bool]]:
    """Every assignment of the atoms that respects the theory."""
    result = []
    for values in itertools.product([False, True], repeat=len(atoms)):
        assignment = dict(zip(atoms, values, strict=True))
        if consistent(assignment):
            result.append(assignment)
    return result


# -- reasons --------------------------------------------------------------------------


def _minimal(sets: Iterable[frozenset]) -> set[frozenset]:
    sets = set(sets)
    return {s for s in sets if not any(other < s for other in sets)}


def sufficient_reasons(formula: Formula, actual: dict[str, bool]) -> set[frozenset]:
    """Subset-minimal sets of actual literals entailing the actual value."""
    atoms = atoms_of(formula)
    target = evaluate(formula, actual)
    models = assignments(atoms)
    literals = [(atom, actual[atom]) for atom in atoms]
    entailing = []
    for size in range(len(literals) + 1):
        for subset in itertools.combinations(literals, size):
            agreeing = [m for m in models if all(m[a] == v for a, v in subset)]
            if all(evaluate(formula, m) == target for m in agreeing):
                entailing.append(frozenset(subset))
    return _minimal(entailing)


def necessary_reasons(formula: Formula, actual: dict[str, bool]) -> set[frozenset]:
    """Minimal hitting sets of the sufficient reasons (from the definition)."""
    reasons = sufficient_reasons(formula, actual)
    literals = [(atom, actual[atom]) for atom in atoms_of(formula)]
    hitting = []
    for size in range(len(literals) + 1):
        for subset in itertools.combinations(literals, size):
            chosen = frozenset(subset)
            if all(chosen & reason for reason in reasons):
                hitting.append(chosen)
    return _minimal(hitting) if reasons else set()


def inus_reasons(formula: Formula, actual: dict[str, bool]) -> set[frozenset]:
    """HERA's INUS reasons (ethics.explanations.generate_inus_reasons): its
    necessary reasons, the actual literals C cap A of each prime implicate C
    of the actual value (the literals that a prime implicant of the other
    value flips), that are part of a sufficient reason."""
    atoms = atoms_of(formula)
    target = evaluate(formula, actual)
    models = assignments(atoms)
    flipping = []
    for values in itertools.product([None, False, True], repeat=len(atoms)):
        term = {a: v for a, v in zip(atoms, values, strict=True) if v is not None}
        agreeing = [m for m in models if all(m[a] == v for a, v in term.items())]
        if agreeing and all(evaluate(formula, m) != target for m in agreeing):
            flipping.append(frozenset(term.items()))
    primes = _minimal(flipping)
    necessary = {frozenset((a, actual[a]) for a, v in prime if v != actual[a]) for prime in primes}
    sufficient = sufficient_reasons(formula, actual)
    return {n for n in necessary if any(n <= s for s in sufficient)}


# -- ASP facts ----------------------------------------------------------------------


def to_asp(formula: Formula, name: str = "q") -> str:
    """``formula(name,F)`` and ``member/2`` facts for a formula."""
    members: list[str] = []
    counter = itertools.count()

    def term(node) -> str:
        if isinstance(node, str):
            return node
        kind = node[0]
        if kind in ("all", "any"):
            index = f"i{next(counter)}"
            for child in node[1]:
                members.append(f"member({index},{term(child)}).")
            return f"{kind}({index})"
        return f"{kind}({','.join(term(child) for child in node[1:])})"

    top = term(formula)
    return f"formula({name},{top}).\n" + "\n".join(members)
