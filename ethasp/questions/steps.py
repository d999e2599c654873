"""Step-by-step causal explanations of a plan: which later steps, events and
goal facts each step serves (causal links), which steps are not needed
(removable), each step's moral side, and the E-links and D-links of Lindner
and Olz ("Step-by-Step Task Plan Explanations Beyond Causal Links", RO-MAN
2022): what enables each step, and what requires it.

The semantics are the encodings': ``encodings/questions/links.lp`` (causal
links, chains to the goal, utilities and the valued facts each step causes)
and ``encodings/questions/removable.lp`` (the plan without a step), run on
the plan's trace (``planning/trace.lp``, ``trace_events.lp``, ``steps.lp``).
In short: step i links variable V with value B to step j (or to the goal)
when step i sets V to B, step j's precondition (or the goal) needs V = B, and
no step or event between them sets V.  A conditional effect counts where it
fires; a value an event sets is linked from that event; a need on a derived
variable is a need on the state variables that give it its value (the link
says through which derived variable).

E-links and D-links (``encodings/questions/producers.lp``, with the
demanded literals of ``encodings/questions/demands.lp``, one solve for its
brave consequences): a *producer* of literal l for step t (or the goal) is
every earlier step (or event) that sets l with nothing setting the opposite
in between, and ``init`` if l holds initially and nothing before t sets the
opposite; l is *demanded* at step t when it holds before t and, had it not
held, some subsequence of the later steps would reach the goal.  A D-link
(p, l, t): l is demanded at t and p produces it; an E-link (p, l, t): step t
(or the goal) needs l, p produces it, and it is no D-link.

This module reads the atoms back and puts them into words
(:mod:`ethasp.reasons.words` building blocks).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import clingo
from clorm import unify

from ethasp.errors import InputError
from ethasp.planning.driver.planner import TRACE_EVENTS, occurrences, solve_configuration
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.planning.validation import literal, plan_atoms
from ethasp.reasons import words
from ethasp.reasons.explanation import Labels
from ethasp.reasons.reasons import model_labels
from ethasp.vocabulary import (
    Chain,
    DLink,
    ELink,
    Link,
    PlanCost,
    Removable,
    ServesGoal,
    StepCauses,
    StepUtility,
    UnmetGoal,
)

ENCODINGS = (
    "planning/model.lp",
    "planning/trace.lp",
    TRACE_EVENTS,
    "planning/steps.lp",
    "questions/links.lp",
    "questions/removable.lp",
    "questions/producers.lp",
)
# The demanded literals, a program of their own (solved for its brave consequences).
DEMAND_ENCODINGS = (
    "planning/model.lp",
    "planning/trace.lp",
    TRACE_EVENTS,
    "planning/steps.lp",
    "questions/demands.lp",
)

# Removable steps are found by tracing the plan once without each step: the
# work grows with the square of the length, so longer plans are refused.
MAX_STEPS = 400


@dataclass(frozen=True)
class Node:
    """Where a link starts or ends: the action of a step (``step``), an event
    of a step (``event``), the goal (``goal``, step 0), or the initial state
    (``init``, step 0: where an E-link or D-link may start)."""

    kind: str
    step: int = 0
    event: clingo.Symbol | None = None

    @classmethod
    def of(cls, term: clingo.Symbol) -> Node:
        if term.name == "step":
            return cls("step", term.arguments[0].number)
        if term.name == "event":
            return cls("event", term.arguments[0].number, term.arguments[1])
        if term.name == "init":
            return cls("init")
        return cls("goal")

    def to_json(self):
        """A step number, ``"goal"``, ``"init"``, or ``{"event": E, "step": T}``."""
        if self.kind == "step":
            return self.step
        if self.kind in ("goal", "init"):
            return self.kind
        return {"event": str(self.event), "step": self.step}


@dataclass(frozen=True)
class CausalLink:
    """A causal link: ``provider`` sets ``variable`` to ``value``, which
    ``consumer`` needs (``kind``: precondition, condition (of the
    conditional effect ``effect``), event or goal), and nothing sets the
    variable between them; ``via``: the derived variable that the consumer
    needs, which has its value because of this one."""

    provider: Node
    consumer: Node
    variable: clingo.Symbol
    value: bool
    kind: str
    effect: clingo.Symbol | None = None
    via: clingo.Symbol | None = None

    def literal(self) -> str:
        return str(self.variable) if self.value else f"-{self.variable}"

    def to_json(self, naming=None) -> dict:
        data = {
            "variable": str(self.variable),
            "value": self.value,
            "to": self.consumer.step if self.consumer.kind != "goal" else "goal",
            "kind": self.kind,
        }
        if naming is not None:
            data["shown"] = naming.fact(self.literal())
        if self.consumer.kind == "event":
            data["event"] = str(self.consumer.event)
        if self.effect is not None:
            data["effect"] = str(self.effect)
        if self.via is not None:
            data["via"] = str(self.via)
        return data


@dataclass(frozen=True)
class ProducerLink:
    """An E-link (``demand`` False) or a D-link (``demand`` True): ``producer``
    (``init``, a step or an event) produces ``variable`` = ``value``, which
    enables (E-link) or requires (D-link) ``consumer`` (a step, or the goal
    for E-links)."""

    producer: Node
    consumer: Node
    variable: clingo.Symbol
    value: bool
    demand: bool

    def literal(self) -> str:
        return str(self.variable) if self.value else f"-{self.variable}"

    def to_json(self) -> dict:
        """``{"from": step number, "init" or {"event", "step"}, "variable",
        "value", "to": step number or "goal"}``."""
        return {
            "from": self.producer.to_json(),
            "variable": str(self.variable),
            "value": self.value,
            "to": self.consumer.to_json(),
        }


@dataclass
class StepExplanation:
    """One step: its links, whether the plan without it is still a plan, its
    utility, the valued facts it causes (variable, value, utility), and a
    chain of links from it to the goal (empty if it serves no goal fact)."""

    step: int
    action: clingo.Symbol
    links: list[CausalLink]
    removable: bool
    utility: int
    causes: list[tuple[clingo.Symbol, bool, int]]
    chain: list[Node]

    @property
    def bad(self) -> bool:
        """Bad under deontology: the action's utility is negative."""
        return self.utility < 0

    @property
    def serves_goal(self) -> bool:
        return bool(self.chain)

    def to_json(self, naming=None) -> dict:
        def facts(sign: int) -> list[dict]:
            return [
                {"variable": str(v), "value": b, "utility": u}
                for v, b, u in self.causes
                if (u < 0) == (sign < 0)
            ]

        data = {"step": self.step, "action": str(self.action)}
        if naming is not None:
            data["shown"] = naming.action(self.action)
        data.update(
            {
                "links": [link.to_json(naming) for link in self.links],
                "removable": self.removable,
                "utility": self.utility,
                "bad": self.bad,
                "harms": facts(-1),
                "goods": facts(1),
                "serves_goal": self.serves_goal,
                "chain": [node.to_json() for node in self.chain],
            }
        )
        return data


@dataclass
class EventExplanation:
    """An event that happened at a step and the links from what it set."""

    step: int
    event: clingo.Symbol
    links: list[CausalLink]

    def to_json(self, naming=None) -> dict:
        return {
            "step": self.step,
            "event": str(self.event),
            "links": [link.to_json(naming) for link in self.links],
        }


@dataclass
class StepsExplanation:
    """A plan explained step by step (see the module docstring)."""

    plan: Plan
    steps: list[StepExplanation]
    events: list[EventExplanation]
    labels: Labels = field(default_factory=Labels)
    text: str = ""
    e_links: list[ProducerLink] = field(default_factory=list)
    d_links: list[ProducerLink] = field(default_factory=list)
    cost: int | None = None  # the plan's cost, in a model with action costs
    # The goal facts (variable, value) the plan misses: only a HERA situation's
    # plan may miss its goal, and its steps are explained against the goal
    # facts it reaches.
    unmet_goal: list[tuple[clingo.Symbol, bool]] = field(default_factory=list)

    def to_json(self, naming=None) -> dict:
        missed = {}
        if self.unmet_goal:
            missed = {
                "goal_reached": False,
                "unmet_goal": [literal(v, "true" if b else "false") for v, b in self.unmet_goal],
            }
        return {
            "plan": self.plan.to_list(),
            **({"cost": self.cost} if self.cost is not None else {}),
            **missed,
            "steps": [step.to_json(naming) for step in self.steps],
            "events": [event.to_json(naming) for event in self.events if event.links],
            "e_links": [link.to_json() for link in self.e_links],
            "d_links": [link.to_json() for link in self.d_links],
            "explanation": self.text,
        }

    def lines(self) -> list[str]:
        """The explanation in words, one sentence per step (and per event
        with links, in its place)."""
        return plan_lines(self.labels, self.plan, self.steps, self.events, self.unmet_goal)

    def link_lines(self) -> list[str]:
        """The E-links and D-links in words, a sentence per step (see
        :func:`producer_lines`)."""
        return producer_lines(self.labels, self.plan, self.e_links, self.d_links)

    @property
    def links(self) -> list[CausalLink]:
        """Every link, from steps and events, in the order of the plan."""
        found = [link for step in self.steps for link in step.links]
        found += [link for event in self.events for link in event.links]
        return sorted(found, key=_link_order)

    def step_text(self, step: int, model: Model | None = None) -> str:
        """``why step T``: the step's links, its chain to the goal, whether it
        is needed and its moral side, in words."""
        if not 1 <= step <= len(self.steps):
            raise InputError(
                f"why step {step}: the plan has "
                f"{'no steps' if not self.steps else f'steps 1 to {len(self.steps)}'}"
            )
        explained = self.steps[step - 1]
        text = step_sentence(self.labels, self.plan, explained, bool(self.unmet_goal))
        if explained.chain:
            middle = [node for node in explained.chain[1:] if node.kind != "goal"]
            if middle:
                text += (
                    " It serves the goal through "
                    f"{words.join([_node_words(self.labels, self.plan, n) for n in middle])}."
                )
            else:
                text += " It serves the goal directly."
        else:
            text += " It serves no goal fact, directly or through later steps."
        links = producer_sentence(self.labels, self.plan, step, self.e_links, self.d_links)
        return f"{text} {links.split(': ', 1)[1][0].upper()}{links.split(': ', 1)[1][1:]}"


def _node_order(node: Node) -> int:
    if node.kind == "goal":
        return 1 << 40
    return 2 * node.step + (1 if node.kind == "event" else 0)


def _link_order(link: CausalLink):
    return (_node_order(link.provider), _node_order(link.consumer), str(link.variable))


def _producer_order(link: ProducerLink):
    """As plan-explainer lists them: by consumer, then producer (init first)."""
    return (
        _node_order(link.consumer),
        _node_order(link.producer) if link.producer.kind != "init" else -1,
        str(link.producer.event),
        str(link.variable),
        link.value,
    )


# -- words ---------------------------------------------------------------------------


def _node_words(labels: Labels, plan: Plan, node: Node) -> str:
    if node.kind == "goal":
        return "the goal"
    if node.kind == "event" and node.event is not None:
        return f"the event {words.term_words(node.event)} of step {node.step}"
    return f"step {node.step}"


def _fact_words(labels: Labels, link: CausalLink) -> str:
    fact = words.fact_phrase(labels, link.variable, link.value)
    if link.via is not None:
        return f"{fact}, for {words.term_words(link.via)}"
    return fact


def _clause(labels: Labels, plan: Plan, consumer: Node, links: list[CausalLink]) -> str:
    """What the links to one consumer let happen, e.g. "lets step 4 unlock
    the door (the fact holding_key)"."""
    facts = f" ({words.join(sorted({_fact_words(labels, link) for link in links}))})"
    if consumer.kind == "goal":
        return f"brings about the goal{facts}"
    if consumer.kind == "event":
        return f"lets {_node_words(labels, plan, consumer)} happen{facts}"
    phrase = words.action_phrase(labels, plan.actions[consumer.step - 1])
    kinds = {link.kind for link in links}
    if kinds == {"condition"}:
        effects = words.join(sorted({str(link.effect) for link in links}))
        return (
            f"makes the conditional effect {effects} of step {consumer.step} ({phrase}) fire{facts}"
        )
    return f"lets step {consumer.step} {phrase}{facts}"


def _moral_words(labels: Labels, explained: StepExplanation) -> str:
    parts = []
    if explained.utility != 0:
        quality = "inherently bad" if explained.utility < 0 else "inherently good"
        parts.append(
            f"{words.gerund(labels, explained.action)} is {quality} (utility {explained.utility})"
        )
    for variable, value, utility in explained.causes:
        verb = "causes" if utility < 0 else "brings about"
        parts.append(f"it {verb} {words.fact_phrase(labels, variable, value)} (utility {utility})")
    return words.capitalize("; ".join(parts)) + "." if parts else ""


def step_sentence(
    labels: Labels, plan: Plan, explained: StepExplanation, missed: bool = False
) -> str:
    """One step in words: what it lets later steps, events and the goal do,
    whether it is needed, and its moral side (``missed``: the plan misses
    part of its goal, and needed means needed for the part it reaches)."""
    head = f"Step {explained.step}, {words.action_phrase(labels, explained.action)},"
    still = (
        "without it, the plan still reaches every goal fact it reaches"
        if missed
        else "the plan without it is still a plan"
    )
    without = (
        "without it, some step would not be applicable or the plan would reach less of its goal"
        if missed
        else "the plan without it is no plan"
    )
    consumers: dict[Node, list[CausalLink]] = {}
    for link in explained.links:
        consumers.setdefault(link.consumer, []).append(link)
    if consumers:
        clauses = [
            _clause(labels, plan, consumer, links)
            for consumer, links in sorted(consumers.items(), key=lambda item: _node_order(item[0]))
        ]
        text = f"{head} {words.join(clauses)}."
        if explained.removable:
            text += f" It is not needed, though: {still}."
    elif explained.removable:
        text = f"{head} is not needed: {still}."
    else:
        text = (
            f"{head} is needed ({without}), though no later step, "
            "event or goal fact needs a value it sets."
        )
    moral = _moral_words(labels, explained)
    return f"{text} {moral}" if moral else text


def _step_ref(labels: Labels, plan: Plan, step: int) -> str:
    return f"step {step} ({words.action_phrase(labels, plan.actions[step - 1])})"


def _producer_words(labels: Labels, plan: Plan, node: Node) -> str:
    if node.kind == "step":
        return _step_ref(labels, plan, node.step)
    return _node_words(labels, plan, node)


def _facts_words(labels: Labels, links: list[ProducerLink]) -> str:
    return words.join([words.fact_phrase(labels, link.variable, link.value) for link in links])


def _initially(labels: Labels, links: list[ProducerLink], verb: str) -> str:
    """ "X holds initially and <verb>s ...", or "X and Y hold initially and <verb> ..."."""
    if len(links) > 1:
        return f"{_facts_words(labels, links)} hold initially and {verb}"
    return f"{_facts_words(labels, links)} holds initially and {verb}s"


def _grouped(links: list[ProducerLink], key) -> list[list[ProducerLink]]:
    """Links grouped by a key, in the order of their first link."""
    groups: dict = {}
    for link in links:
        groups.setdefault(key(link), []).append(link)
    return list(groups.values())


def _results(labels: Labels, plan: Plan, subject: str, links: list[ProducerLink]) -> list[str]:
    """ "<subject> results in X, which enables step 3 (...) and fulfils the
    goal": the E-links from one producer, the consumers of equal facts joined."""
    by_facts: dict[tuple, list[Node]] = {}
    for group in _grouped(links, lambda e: e.consumer):
        key = tuple((e.variable, e.value) for e in group)
        by_facts.setdefault(key, []).append(group[0].consumer)
    clauses = []
    for key, consumers in by_facts.items():
        facts = words.join([words.fact_phrase(labels, v, b) for v, b in key])
        steps = [_step_ref(labels, plan, c.step) for c in consumers if c.kind == "step"]
        which = [f"enables {words.join(steps)}"] if steps else []
        if any(c.kind == "goal" for c in consumers):
            which.append("fulfils the goal")
        clauses.append(f"{subject} results in {facts}, which {' and '.join(which)}")
    return clauses


def producer_sentence(
    labels: Labels, plan: Plan, step: int, e_links: list[ProducerLink], d_links: list[ProducerLink]
) -> str:
    """What requires step ``step`` (its D-links), what enables it and what it
    enables (its E-links), in plan-explainer's words: "X holds initially and
    requires it", "step 1 (...) results in X, which requires it", "X holds
    initially and enables it", "it results in X, which enables step 3 (...)"
    or "..., which fulfils the goal"."""
    clauses = []
    for group in _grouped([d for d in d_links if d.consumer.step == step], lambda d: d.producer):
        producer = group[0].producer
        if producer.kind == "init":
            clauses.append(f"{_initially(labels, group, 'require')} it")
        else:
            clauses.append(
                f"{_producer_words(labels, plan, producer)} results in "
                f"{_facts_words(labels, group)}, which requires it"
            )
    into = [e for e in e_links if e.consumer == Node("step", step) and e.producer.kind == "init"]
    if into:
        clauses.append(f"{_initially(labels, into, 'enable')} it")
    clauses += _results(
        labels, plan, "it", [e for e in e_links if e.producer == Node("step", step)]
    )
    head = f"Step {step}, {words.action_phrase(labels, plan.actions[step - 1])}:"
    if not clauses:
        return f"{head} no E-link or D-link leads to it or from it."
    return f"{head} {'; '.join(clauses)}."


def producer_lines(
    labels: Labels, plan: Plan, e_links: list[ProducerLink], d_links: list[ProducerLink]
) -> list[str]:
    """The E-links and D-links of a plan in words: a sentence per step
    (:func:`producer_sentence`), then the events' E-links and the goal
    literals that hold initially."""
    lines = [producer_sentence(labels, plan, t, e_links, d_links) for t in range(1, len(plan) + 1)]
    from_events = [e for e in e_links if e.producer.kind == "event"]
    for group in _grouped(from_events, lambda e: e.producer):
        subject = _node_words(labels, plan, group[0].producer)
        lines.append(words.capitalize("; ".join(_results(labels, plan, subject, group))) + ".")
    initial = [e for e in e_links if e.producer.kind == "init" and e.consumer.kind == "goal"]
    if initial:
        lines.append(words.capitalize(f"{_initially(labels, initial, 'fulfil')} the goal."))
    return lines


def event_sentence(labels: Labels, plan: Plan, event: EventExplanation) -> str:
    consumers: dict[Node, list[CausalLink]] = {}
    for link in event.links:
        consumers.setdefault(link.consumer, []).append(link)
    clauses = [
        _clause(labels, plan, consumer, links)
        for consumer, links in sorted(consumers.items(), key=lambda item: _node_order(item[0]))
    ]
    return f"The event {words.term_words(event.event)} of step {event.step} {words.join(clauses)}."


def plan_text(
    labels: Labels,
    plan: Plan,
    steps: list[StepExplanation],
    events: list[EventExplanation],
    unmet_goal: Sequence[tuple[clingo.Symbol, bool]] = (),
) -> str:
    """The whole plan in words, step by step (events with links in their place)."""
    return " ".join(plan_lines(labels, plan, steps, events, unmet_goal))


def missed_sentence(labels: Labels, unmet_goal: Sequence[tuple[clingo.Symbol, bool]]) -> str:
    """Words for a plan that misses goal facts (a HERA situation's may)."""
    facts = words.join([words.fact_phrase(labels, v, b) for v, b in unmet_goal])
    verb = "does" if len(unmet_goal) == 1 else "do"
    return (
        f"The plan does not reach its goal: {facts} {verb} not hold at the end; its "
        "steps are explained against the goal facts it reaches."
    )


def plan_lines(
    labels: Labels,
    plan: Plan,
    steps: list[StepExplanation],
    events: list[EventExplanation],
    unmet_goal: Sequence[tuple[clingo.Symbol, bool]] = (),
) -> list[str]:
    """The sentences of :func:`plan_text`."""
    opening = [missed_sentence(labels, list(unmet_goal))] if unmet_goal else []
    if not steps and not any(event.links for event in events):
        if unmet_goal:
            return [*opening, "The plan has no steps."]
        return ["The plan has no steps: the goal holds without any action."]
    sentences = [*opening] if steps else [*opening, "The plan has no steps."]
    by_step: dict[int, list[EventExplanation]] = {}
    for event in events:
        if event.links:
            by_step.setdefault(event.step, []).append(event)
    last = max([len(steps), *list(by_step)])  # events after the plan's end come last
    for number in range(1, last + 1):
        if number <= len(steps):
            sentences.append(step_sentence(labels, plan, steps[number - 1], bool(unmet_goal)))
        sentences += [event_sentence(labels, plan, event) for event in by_step.get(number, [])]
    return sentences


# -- the API -------------------------------------------------------------------------


def explain_steps(
    model: Model, plan: Plan, allow_missed_goal: bool | None = None
) -> StepsExplanation:
    """The causal explanation of a plan, step by step (one clingo call on its
    trace); InputError if it is not a plan or has more than
    :data:`MAX_STEPS` steps.  With ``allow_missed_goal`` (by default for a
    HERA situation's plan, which judge takes too:
    :func:`ethasp.principles.judgement.require_plan`), an executable sequence
    that misses goal facts is explained against the goal facts it reaches
    (exactly as the plan it is of the goal made of those), and the
    explanation says which it misses."""
    model.require_planning("explaining a plan step by step")
    if len(plan) > MAX_STEPS:
        raise InputError(
            f"the plan has {len(plan)} steps; step-by-step explanations are made "
            f"for plans of at most {MAX_STEPS} steps"
        )
    symbols = plan_atoms(
        model,
        plan,
        ENCODINGS,
        demanded(model, plan),
        reach_goal=not (model.is_situation if allow_missed_goal is None else allow_missed_goal),
    )
    atoms = unify(
        [Link, ServesGoal, Chain, StepUtility, StepCauses, Removable, ELink, DLink, UnmetGoal],
        symbols,
    )
    unmet_goal = sorted(
        ((atom.variable.symbol, atom.value == "true") for atom in atoms.query(UnmetGoal).all()),
        key=lambda fact: (str(fact[0]), fact[1]),
    )
    by_provider: dict[Node, list[CausalLink]] = {}
    for atom in atoms.query(Link).all():
        kind = atom.kind.symbol
        link = CausalLink(
            Node.of(atom.provider.symbol),
            Node.of(atom.consumer.symbol),
            atom.variable.symbol,
            atom.value == "true",
            "condition" if kind.name == "condition" else kind.name,
            kind.arguments[0] if kind.name == "condition" else None,
            None if atom.via.symbol.name == "none" else atom.via.symbol,
        )
        by_provider.setdefault(link.provider, []).append(link)
    chains: dict[int, list[tuple[int, Node]]] = {}
    for chain in atoms.query(Chain).all():
        chains.setdefault(chain.step, []).append((chain.index, Node.of(chain.node.symbol)))
    utilities = {u.step: u.utility for u in atoms.query(StepUtility).all()}
    causes: dict[int, list[tuple[clingo.Symbol, bool, int]]] = {}
    for cause in atoms.query(StepCauses).all():
        causes.setdefault(cause.step, []).append(
            (cause.variable.symbol, cause.value == "true", cause.utility)
        )
    removable = {r.step for r in atoms.query(Removable).all()}
    steps = []
    for number, action in enumerate(plan, start=1):
        node = Node("step", number)
        steps.append(
            StepExplanation(
                number,
                action,
                sorted(by_provider.get(node, []), key=_link_order),
                number in removable,
                utilities.get(number, 0),
                sorted(causes.get(number, []), key=lambda c: (str(c[0]), c[1])),
                [n for _, n in sorted(chains.get(number, []), key=lambda item: item[0])],
            )
        )
    events = [
        EventExplanation(node.step, node.event, sorted(links, key=_link_order))
        for node, links in sorted(by_provider.items(), key=lambda i: _node_order(i[0]))
        if node.kind == "event" and node.event is not None
    ]
    e_links = sorted(
        (
            ProducerLink(
                Node.of(atom.producer.symbol),
                Node.of(atom.consumer.symbol),
                atom.variable.symbol,
                atom.value == "true",
                False,
            )
            for atom in atoms.query(ELink).all()
        ),
        key=_producer_order,
    )
    d_links = sorted(
        (
            ProducerLink(
                Node.of(atom.producer.symbol),
                Node("step", atom.step),
                atom.variable.symbol,
                atom.value == "true",
                True,
            )
            for atom in atoms.query(DLink).all()
        ),
        key=_producer_order,
    )
    labels = model_labels(model)
    costs = [atom.cost for atom in unify([PlanCost], symbols).query(PlanCost).all()]
    return StepsExplanation(
        plan,
        steps,
        events,
        labels,
        plan_text(labels, plan, steps, events, unmet_goal),
        e_links,
        d_links,
        costs[0] if costs and model.planner.has_costs else None,
        unmet_goal,
    )


def demanded(model: Model, plan: Plan) -> list[clingo.Symbol]:
    """The ``demanded(T,V,B)`` atoms of a plan: the brave consequences of
    ``encodings/questions/demands.lp`` (one solve, which tries every step and
    variable and finds a subsequence of the later steps for each that has
    one)."""
    ctl = model.planner.program(DEMAND_ENCODINGS, symbols=occurrences(plan))
    config = solve_configuration(ctl)
    config.enum_mode = "brave"
    config.models = "0"
    found: list[clingo.Symbol] = []

    def on_model(answer: clingo.Model) -> None:
        found[:] = [s for s in answer.symbols(shown=True) if s.name == "demanded"]

    ctl.solve(on_model=on_model)
    return sorted(found)
