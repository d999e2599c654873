"""Brute-force semantics of small PDDL tasks, written from the PDDL definitions.

A random task is generated as Python data (types, objects, predicates,
derived predicates, actions with ADL preconditions and effects, init, goal)
and printed as a PDDL domain and problem.  Its semantics are computed here
directly: explicit grounding of actions over typed objects, formulas evaluated
in explicit states (quantifiers over the objects of their types), derived
predicates as the least fixpoint of their definitions, stratum by stratum,
effects whose conditions are evaluated in the state before the action
(deletes applied before adds), and breadth-first search.  Used only by tests,
as an oracle for the translation into ASP (ethasp/planning/readers/pddl.py) and the
encodings.

Formulas are tuples: ("atom", p, terms), ("=", t1, t2), ("not", f),
("and", [f...]), ("or", [f...]), ("imply", f, g), ("exists", params, f),
("forall", params, f); effects: ("lit", p, terms, positive),
("and", [e...]), ("forall", params, e), ("when", f, e).  A term is a
variable "?x" or an object; params are [(variable, types)], where types ()
means object and several types mean (either ...).
"""

from __future__ import annotations

import itertools
import random
from collections import deque
from dataclasses import dataclass, field


def _type_text(types: tuple[str, ...]) -> str:
    if not types:
        return "object"
    return types[0] if len(types) == 1 else f"(either {' '.join(types)})"


def _params_text(params) -> str:
    return " ".join(f"{var} - {_type_text(types)}" for var, types in params)


def formula_text(f) -> str:
    kind = f[0]
    if kind == "atom":
        return f"({' '.join([f[1], *f[2]])})"
    if kind == "=":
        return f"(= {f[1]} {f[2]})"
    if kind == "not":
        return f"(not {formula_text(f[1])})"
    if kind in ("and", "or"):
        return f"({kind} {' '.join(formula_text(g) for g in f[1])})"
    if kind == "imply":
        return f"(imply {formula_text(f[1])} {formula_text(f[2])})"
    if kind in ("exists", "forall"):
        return f"({kind} ({_params_text(f[1])}) {formula_text(f[2])})"
    raise ValueError(f)


def effect_text(e) -> str:
    kind = e[0]
    if kind == "lit":
        atom = f"({' '.join([e[1], *e[2]])})"
        return atom if e[3] else f"(not {atom})"
    if kind == "and":
        return f"(and {' '.join(effect_text(g) for g in e[1])})"
    if kind == "forall":
        return f"(forall ({_params_text(e[1])}) {effect_text(e[2])})"
    if kind == "when":
        return f"(when {formula_text(e[1])} {effect_text(e[2])})"
    raise ValueError(e)


@dataclass
class PddlTask:
    types: dict[str, str]  # type -> parent type
    objects: dict[str, tuple[str, ...]]  # object -> declared types
    constants: list[str]  # objects declared in the domain
    predicates: dict[str, tuple]  # predicate -> argument types
    derived: list[tuple[str, list, tuple]]  # (predicate, params, body), in strata order
    actions: list[tuple[str, list, tuple, tuple]]  # (name, params, precondition, effect)
    init: frozenset  # ground atoms (p, (o, ...))
    goal: tuple
    requirements: str = ":adl :derived-predicates"
    _ground: list | None = field(default=None, repr=False)

    # -- PDDL text ----------------------------------------------------------------

    def domain_text(self) -> str:
        types = " ".join(f"{t} - {parent}" for t, parent in self.types.items())
        constants = " ".join(f"{o} - {_type_text(self.objects[o])}" for o in self.constants)
        predicates = " ".join(
            f"({p} {' '.join(f'?a{i} - {_type_text(t)}' for i, t in enumerate(args))})"
            for p, args in self.predicates.items()
        )
        parts = [
            "(define (domain random)",
            f"  (:requirements {self.requirements})" if self.requirements else "",
            f"  (:types {types})",
            f"  (:constants {constants})" if constants else "",
            f"  (:predicates {predicates})",
        ]
        for name, params, body in self.derived:
            head = " ".join([name] + [f"{v} - {_type_text(t)}" for v, t in params])
            parts.append(f"  (:derived ({head}) {formula_text(body)})")
        for name, params, pre, effect in self.actions:
            parts.append(
                f"  (:action {name} :parameters ({_params_text(params)})\n"
                f"    :precondition {formula_text(pre)}\n"
                f"    :effect {effect_text(effect)})"
            )
        return "\n".join(part for part in parts if part) + ")\n"

    def problem_text(self) -> str:
        objects = " ".join(
            f"{o} - {_type_text(t)}" for o, t in self.objects.items() if o not in self.constants
        )
        init = " ".join(f"({' '.join([p, *args])})" for p, args in sorted(self.init))
        return (
            f"(define (problem random-problem) (:domain random)\n"
            f"  (:objects {objects})\n  (:init {init})\n"
            f"  (:goal {formula_text(self.goal)}))\n"
        )

    # -- typing --------------------------------------------------------------------

    def type_closure(self, name: str) -> set[str]:
        result = {"object"}
        todo = [name]
        while todo:
            current = todo.pop()
            if current not in result:
                result.add(current)
                if current in self.types:
                    todo.append(self.types[current])
        return result

    def objects_of(self, types: tuple[str, ...]) -> list[str]:
        if not types:
            return sorted(self.objects)
        return sorted(
            o
            for o, declared in self.objects.items()
            if any(t in self.type_closure(d) for d in declared for t in types)
        )

    def bindings(self, params, binding: dict) -> list[dict]:
        domains = [self.objects_of(types) for _, types in params]
        return [
            {**binding, **{var: value for (var, _), value in zip(params, values, strict=True)}}
            for values in itertools.product(*domains)
        ]

    # -- formulas -------------------------------------------------------------------

    @staticmethod
    def ground_terms(terms, binding: dict) -> tuple[str, ...]:
        return tuple(binding[t] if t.startswith("?") else t for t in terms)

    def holds(self, f, state: frozenset | set, binding: dict) -> bool:
        kind = f[0]
        if kind == "atom":
            return (f[1], self.ground_terms(f[2], binding)) in state
        if kind == "=":
            left, right = self.ground_terms((f[1], f[2]), binding)
            return left == right
        if kind == "not":
            return not self.holds(f[1], state, binding)
        if kind == "and":
            return all(self.holds(g, state, binding) for g in f[1])
        if kind == "or":
            return any(self.holds(g, state, binding) for g in f[1])
        if kind == "imply":
            return not self.holds(f[1], state, binding) or self.holds(f[2], state, binding)
        if kind == "exists":
            return any(self.holds(f[2], state, b) for b in self.bindings(f[1], binding))
        if kind == "forall":
            return all(self.holds(f[2], state, b) for b in self.bindings(f[1], binding))
        raise ValueError(f)

    def closure(self, state: frozenset) -> frozenset:
        """The state with its derived atoms: the least fixpoint of each derived
        predicate's definition, in the order of the strata."""
        full = set(state)
        for name, params, body in self.derived:
            changed = True
            while changed:
                changed = False
                for binding in self.bindings(params, {}):
                    atom = (name, tuple(binding[var] for var, _ in params))
                    if atom not in full and self.holds(body, full, binding):
                        full.add(atom)
                        changed = True
        return frozenset(full)

    # -- actions ----------------------------------------------------------------------

    def ground_actions(self) -> list[tuple[str, tuple, dict]]:
        """Every action with every typed assignment: (ASP name, precondition, binding)."""
        if self._ground is None:
            self._ground = []
            for name, params, pre, effect in self.actions:
                for binding in self.bindings(params, {}):
                    args = [binding[var] for var, _ in params]
                    term = f"{name}({','.join(args)})" if args else name
                    self._ground.append((term, (pre, effect), binding))
        return self._ground

    def effects(self, e, full: frozenset, binding: dict, out: list) -> None:
        kind = e[0]
        if kind == "lit":
            out.append(((e[1], self.ground_terms(e[2], binding)), e[3]))
        elif kind == "and":
            for g in e[1]:
                self.effects(g, full, binding, out)
        elif kind == "forall":
            for b in self.bindings(e[1], binding):
                self.effects(e[2], full, b, out)
        elif kind == "when":
            if self.holds(e[1], full, binding):
                self.effects(e[2], full, binding, out)
        else:
            raise ValueError(e)

    def successors(self, state: frozenset):
        full = self.closure(state)
        for term, (pre, effect), binding in self.ground_actions():
            if self.holds(pre, full, binding):
                yield term, self.apply_with(state, full, effect, binding)

    def apply_with(self, state, full, effect, binding) -> frozenset:
        out: list = []
        self.effects(effect, full, binding, out)
        deletes = {atom for atom, positive in out if not positive}
        adds = {atom for atom, positive in out if positive}
        return frozenset((set(state) - deletes) | adds)

    def step(self, state: frozenset, term: str) -> frozenset | None:
        """The state after an action (by its ASP name), None if it is inapplicable."""
        full = self.closure(state)
        for name, (pre, effect), binding in self.ground_actions():
            if name == term:
                if not self.holds(pre, full, binding):
                    return None
                return self.apply_with(state, full, effect, binding)
        raise KeyError(term)

    def is_goal(self, state: frozenset) -> bool:
        return self.holds(self.goal, self.closure(state), {})

    def distances(self) -> dict[frozenset, int]:
        dist = {self.init: 0}
        queue = deque([self.init])
        while queue:
            state = queue.popleft()
            for _, succ in self.successors(state):
                if succ not in dist:
                    dist[succ] = dist[state] + 1
                    queue.append(succ)
        return dist

    def shortest_plan_length(self, dist: dict | None = None) -> int | None:
        dist = self.distances() if dist is None else dist
        goals = [d for s, d in dist.items() if self.is_goal(s)]
        return min(goals) if goals else None


def asp_atom(atom) -> str:
    predicate, args = atom
    return f"{predicate}({','.join(args)})" if args else predicate


# -- random tasks -----------------------------------------------------------------------


class _Generator:
    def __init__(self, rng: random.Random):
        self.rng = rng
        self.fresh = 0

    def type_spec(self, types: list[str]) -> tuple[str, ...]:
        r = self.rng.random()
        if r < 0.25:
            return ()
        if r < 0.4 and len(types) > 1:
            return tuple(sorted(self.rng.sample(types, 2)))
        return (self.rng.choice(types),)

    def term(self, variables: list[str], objects: list[str]) -> str:
        if variables and self.rng.random() < 0.75:
            return self.rng.choice(variables)
        return self.rng.choice(objects)

    def atom(self, predicates: dict, variables, objects):
        name = self.rng.choice(sorted(predicates))
        return ("atom", name, tuple(self.term(variables, objects) for _ in predicates[name]))

    def formula(self, predicates: dict, variables: list[str], objects, types, depth: int):
        rng = self.rng
        if depth == 0 or rng.random() < 0.45:
            if rng.random() < 0.12:
                return ("=", self.term(variables, objects), self.term(variables, objects))
            atom = self.atom(predicates, variables, objects)
            return ("not", atom) if rng.random() < 0.3 else atom
        kind = rng.choice(["not", "and", "or", "imply", "exists", "forall"])
        if kind == "not":
            return ("not", self.formula(predicates, variables, objects, types, depth - 1))
        if kind in ("and", "or"):
            return (
                kind,
                [
                    self.formula(predicates, variables, objects, types, depth - 1)
                    for _ in range(rng.randint(0 if rng.random() < 0.1 else 1, 3))
                ],
            )
        if kind == "imply":
            return (
                "imply",
                self.formula(predicates, variables, objects, types, depth - 1),
                self.formula(predicates, variables, objects, types, depth - 1),
            )
        self.fresh += 1
        var = f"?q{self.fresh}"
        body = self.formula(predicates, [*variables, var], objects, types, depth - 1)
        return (kind, [(var, self.type_spec(types))], body)

    def literal(self, basic: dict, variables, objects):
        name = self.rng.choice(sorted(basic))
        terms = tuple(self.term(variables, objects) for _ in basic[name])
        return ("lit", name, terms, self.rng.random() < 0.65)

    def effect(self, basic: dict, readable: dict, variables, objects, types):
        """A literal (half of the time), a conditional or a universal effect."""
        rng = self.rng
        r = rng.random()
        if r < 0.5:
            return self.literal(basic, variables, objects)
        if r < 0.75:
            condition = self.formula(readable, variables, objects, types, rng.randint(0, 1))
            inner = [self.literal(basic, variables, objects) for _ in range(rng.randint(1, 2))]
            return ("when", condition, inner[0] if len(inner) == 1 else ("and", inner))
        self.fresh += 1
        var = f"?e{self.fresh}"
        inner = self.literal(basic, [*variables, var], objects)
        if rng.random() < 0.6:
            condition = self.formula(readable, [*variables, var], objects, types, rng.randint(0, 1))
            inner = ("when", condition, inner)
        return ("forall", [(var, self.type_spec(types))], inner)


def random_task(seed: int) -> PddlTask:
    """A small random ADL task with derived predicates (2 or 3 objects) and,
    mostly, static predicates (of arity 2, sometimes also 1) that preconditions
    use as plain conjuncts, positive and negative, as well as anywhere else."""
    rng = random.Random(seed)
    gen = _Generator(rng)
    types = {"t0": "object", "t1": "t0"} if rng.random() < 0.5 else {"t0": "object", "t1": "object"}
    type_names = sorted(types)
    objects = {
        f"o{i}": (
            tuple(sorted(rng.sample(type_names, 2)))
            if rng.random() < 0.15
            else (rng.choice(type_names),)
        )
        for i in range(rng.randint(2, 3))
    }
    names = sorted(objects)
    constants = [names[0]] if rng.random() < 0.5 else []
    basic = {
        f"p{i}": tuple(gen.type_spec(type_names) for _ in range(rng.randint(0, 2)))
        for i in range(rng.randint(2, 3))
    }
    if all(args for args in basic.values()) and rng.random() < 0.5:
        basic["p9"] = ()
    # static predicates: no effect changes them (the translation prunes actions by them)
    static = {}
    if rng.random() < 0.7:
        static["s0"] = (gen.type_spec(type_names), gen.type_spec(type_names))
        if rng.random() < 0.4:
            static["s1"] = (gen.type_spec(type_names),)
    predicates = {**basic, **static}
    derived = []
    readable = {**basic, **static}
    for i in range(rng.choice([0, 1, 1, 2])):
        name = f"d{i}"
        params = [(f"?h{j}", gen.type_spec(type_names)) for j in range(rng.randint(0, 1))]
        variables = [var for var, _ in params]
        body = gen.formula(readable, variables, names, type_names, 2)
        binary = [p for p, args in basic.items() if len(args) == 2]
        if params and binary and rng.random() < 0.5:
            # a recursive disjunct (transitive closure), positive only
            gen.fresh += 1
            other = f"?r{gen.fresh}"
            step = (
                "and",
                [("atom", name, (other,)), ("atom", rng.choice(binary), (other, variables[0]))],
            )
            body = ("or", [body, ("exists", [(other, params[0][1])], step)])
        derived.append((name, params, body))
        predicates[name] = tuple(types for _, types in params)
        readable[name] = predicates[name]
    actions = []
    for i in range(rng.randint(2, 4)):
        params = [(f"?x{j}", gen.type_spec(type_names)) for j in range(rng.randint(0, 2))]
        variables = [var for var, _ in params]
        pre = (
            ("and", [])
            if rng.random() < 0.4
            else gen.formula(readable, variables, names, type_names, rng.randint(0, 2))
        )
        if static and variables and rng.random() < 0.6:
            # plain conjuncts on static predicates, positive and negative
            literals = []
            for _ in range(rng.randint(1, 2)):
                name = rng.choice(sorted(static))
                atom = ("atom", name, tuple(gen.term(variables, names) for _ in static[name]))
                literals.append(("not", atom) if rng.random() < 0.4 else atom)
            pre = ("and", [pre, *literals])
        effect = (
            "and",
            [
                gen.effect(basic, readable, variables, names, type_names)
                for _ in range(rng.randint(1, 4))
            ],
        )
        actions.append((f"a{i}", params, pre, effect))
    task = PddlTask(
        types, objects, constants, predicates, derived, actions, frozenset(), ("and", [])
    )
    ground = [
        (p, args)
        for p, arg_types in basic.items()
        for args in itertools.product(*[task.objects_of(t) for t in arg_types])
    ]
    fixed = [
        (p, args)
        for p, arg_types in static.items()
        for args in itertools.product(*[task.objects_of(t) for t in arg_types])
    ]
    task.init = frozenset(
        [
            *(atom for atom in ground if rng.random() < 0.4),
            *(atom for atom in fixed if rng.random() < 0.5),
        ]
    )
    # Mostly a goal that a far reachable state meets (some of its literals),
    # sometimes with a random formula (then often unreachable).
    distances = task.distances()
    far = max(distances.values())
    target = rng.choice(sorted((s for s, d in distances.items() if d >= far - 1), key=sorted))
    literals = [
        ("atom", p, args) if (p, args) in target else ("not", ("atom", p, args))
        for p, args in ground
        if ((p, args) in target) != ((p, args) in task.init)
    ]
    goal = rng.sample(literals, min(len(literals), rng.randint(1, 3)))
    if rng.random() < 0.4 or not goal:
        goal.append(gen.formula(readable, [], names, type_names, rng.randint(0, 2)))
    task.goal = goal[0] if len(goal) == 1 else ("and", goal)
    task._ground = None
    if rng.random() < 0.2:
        task.requirements = ""
    return task
