"""Explanations as data: literals of L, comparisons, labels, and the
explanation of one judgement (read from answer sets by
:mod:`ethasp.reasons.reasons`, put into words by :mod:`ethasp.reasons.words`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import clingo

from ethasp.planning.naming import Naming
from ethasp.planning.plan import Plan


@dataclass(frozen=True)
class Literal:
    """A literal of L: an atom (``caused(V,B)``, ``good(E)``, ``bad(E)``,
    ``neutral(E)``, ``geq(C,D)``, as terms of ``language.lp``) and its value."""

    atom: clingo.Symbol
    value: bool

    def term(self) -> clingo.Symbol:
        return self.atom if self.value else clingo.Function("neg", [self.atom])


@dataclass
class Comparison:
    """What the words of a GEq atom mention: the facts of each side (variable,
    value) and how the left side actually compares (better, equal, worse)."""

    left: list[tuple[clingo.Symbol, bool]]
    right: list[tuple[clingo.Symbol, bool]]
    relation: str


@dataclass
class Labels:
    """The model's label facts (``encodings/reasons/labels.lp``), and how the
    model names what has no label (``naming``: ASP terms, or PDDL form)."""

    agent: str | None = None
    possessive: str | None = None
    actions: dict[clingo.Symbol, tuple[str, str]] = field(default_factory=dict)
    facts: dict[tuple[clingo.Symbol, bool], str] = field(default_factory=dict)
    patients: dict[clingo.Symbol, str] = field(default_factory=dict)
    naming: Naming = field(default_factory=Naming)


@dataclass
class Explanation:
    """Why a plan is (im)permissible under one principle.

    ``sufficient_reasons``, ``necessary_reasons`` and ``inus_reasons`` are
    lists of reasons, each a list of literals in the formula syntax
    (``Bad(a2)``, ``not Caused(five_will_die)``); at most ``limit`` of each
    are computed, and ``truncated`` says that the limit cut an enumeration
    short (more reasons may exist; ``necessary_truncated``,
    ``sufficient_truncated`` and ``inus_truncated`` say it per kind: INUS
    reasons are those of the sufficient reasons enumerated).
    ``chosen_reason`` is the most relevant necessary reason (empty when the
    verdict holds whatever the atoms' values), ``text`` its words.
    ``alternative`` is the state compared with (utilitarianism), as literals
    ``v`` / ``-v``.  ``literals`` holds what the words say as :class:`Literal`
    objects, with ``comparisons`` and ``labels``, for building other texts
    (see :mod:`ethasp.reasons.words`): the chosen reason, or the only
    sufficient reason when its literals are all of one kind (a permissible
    plan of several actions under deontology: none of them is bad), and
    ``spoken_reason`` their texts; ``cut`` says why a limit cut the reasons
    short, where one did (the lists are then truncated).  ``actual`` holds every atom of the
    principle's formula with its value for the plan (what the plan makes
    true or false of it), for telling which of a reason's literals another
    plan shares; ``conjunctions`` the members of the conjunctions its
    literals name.
    """

    principle: str
    plan: Plan
    permissible: bool
    sufficient_reasons: list[list[str]]
    necessary_reasons: list[list[str]]
    chosen_reason: list[str]
    text: str
    truncated: bool
    alternative: list[str] | None = None
    necessary_truncated: bool = False
    sufficient_truncated: bool = False
    inus_reasons: list[list[str]] = field(default_factory=list)
    inus_truncated: bool = False
    literals: list[Literal] = field(default_factory=list)
    spoken_reason: list[str] = field(default_factory=list)
    actual: frozenset[Literal] = frozenset()
    comparisons: dict[clingo.Symbol, Comparison] = field(default_factory=dict)
    labels: Labels = field(default_factory=Labels)
    conjunctions: dict[clingo.Symbol, list[tuple[clingo.Symbol, str]]] = field(default_factory=dict)
    cut: str = ""  # why a limit cut the reasons short (the budget ran out), if it did

    def to_json(self) -> dict:
        data = {
            "sufficient_reasons": self.sufficient_reasons,
            "necessary_reasons": self.necessary_reasons,
            "chosen_reason": self.chosen_reason,
            "explanation": self.text,
            "inus_reasons": self.inus_reasons,
            "reasons_truncated": self.truncated,
            "necessary_reasons_truncated": self.necessary_truncated,
            "sufficient_reasons_truncated": self.sufficient_truncated,
            "inus_reasons_truncated": self.inus_truncated,
        }
        if self.alternative is not None:
            data["compared_state"] = self.alternative
        return data
