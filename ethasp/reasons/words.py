"""English words for explanations, from the model's labels.

The label vocabulary is documented in ``encodings/reasons/labels.lp``:
``agent_label(Name,Possessive)``, ``action_label(A,Phrase,Gerund)`` and
``fact_label(V,B,Phrase)``.  Whatever has no label is named by its term
("the agent", "its", the action's name, "the fact v" / "the fact not v").

This module only renders: which reason an explanation uses, and which facts
the words of a comparison mention, are chosen in ASP
(``encodings/reasons/relevance.lp`` and ``comparison.lp``).  The building
blocks are separate functions, so that other texts (for instance contrastive
explanations: "The man could refrain from action. This would be permissible
under the do-no-harm principle because this way the death of the five persons
is not caused by his action.") can be assembled from them.

Templates, by literal (``X`` a gerund or fact phrase, ``P`` a possessive):

* ``Bad(a)`` / ``not Bad(a)``: "X is inherently bad" / "X is not inherently bad"
  (``Good``: "inherently good", ``Neutral``: "morally neutral"); for facts
  without "inherently": "X is bad";
* ``Caused(p)`` / ``not Caused(p)``: "this way X is caused by P action" /
  "this way X is not caused by P action" ("actions" for plans of several
  steps);
* ``GEq(c,d)``: "X is better than Y" (or "is as good as"), ``not GEq(c,d)``:
  "X is worse than Y", where X and Y name the facts mentioned for each side;
* HERA's operators: ``Goal(p)`` "X is (not) one of P goals", ``Finally(p)``
  "X holds (does not hold) in the end", ``ButFor(p)`` "but for P action, X
  would not come about" / "X would come about even without P action",
  ``Instrumental(p)``
  "X is (not) a means to P goal", ``Avoidable(p)`` "X could (not) be
  avoided", ``Means(x)`` "x is (not) used as a means", ``Means2(x)`` "x is
  (not) affected by P action", ``End(x)`` "x is (not) treated as an end",
  and comparisons "the utility of the final state is (not) greater than 0".

A reason of several literals joins their clauses with "and"; literals of one
kind share a clause: "neither X nor Y is inherently bad", "X and Y are
inherently bad", "this way neither X nor Y is caused by P actions", and for
every action of a plan of more than three, "none of P N actions is inherently
bad".  Actions and facts without labels are named by their terms, or in PDDL
form for PDDL models (``action (move kitchen hall)``, ``the fact (not
(robot-at hall))``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import clingo

from ethasp.planning.plan import Plan
from ethasp.reasons.explanation import Comparison, Explanation, Labels, Literal

# The members of conjunctions by name: (variable, value) pairs.
Conjunctions = Mapping[clingo.Symbol, Sequence[tuple[clingo.Symbol, object]]]

DEFAULT_AGENT = "the agent"
DEFAULT_POSSESSIVE = "its"
EMPTY_PLAN = "do nothing"

VALUATIONS = {"good": "good", "bad": "bad", "neutral": "morally neutral"}


def capitalize(text: str) -> str:
    """The text with its first letter in upper case."""
    return text[:1].upper() + text[1:]


def join(parts: Sequence[str], word: str = "and") -> str:
    """ "a", "a and b", "a, b and c"."""
    parts = list(parts)
    if len(parts) <= 1:
        return "".join(parts)
    return f"{', '.join(parts[:-1])} {word} {parts[-1]}"


# -- names ------------------------------------------------------------------------


def agent(labels: Labels) -> str:
    """The agent as a noun phrase, e.g. "the man"."""
    return labels.agent or DEFAULT_AGENT


def possessive(labels: Labels, pronoun: bool = False) -> str:
    """The agent's possessive: "the man's", or with ``pronoun`` "his"."""
    if pronoun:
        return labels.possessive or DEFAULT_POSSESSIVE
    return f"{agent(labels)}'s"


def _term_words(term: clingo.Symbol, labels: Labels | None = None) -> str:
    """A term without a label: an ASP constant as words (``do_nothing``: "do
    nothing"), another ASP term as it is, or in PDDL form for a PDDL model."""
    if labels is not None and labels.naming.pddl:
        return labels.naming.name(term)
    if term.type == clingo.SymbolType.Function and not term.arguments:
        return term.name.replace("_", " ")
    return str(term)


def _action_name(labels: Labels, action: clingo.Symbol) -> str:
    """An action without a label: its term in words, or its PDDL form ``(move a b)``."""
    return labels.naming.action(action) if labels.naming.pddl else _compound_words(action)


def _compound_words(term: clingo.Symbol) -> str:
    """An ASP term in words: its name with spaces for underscores and its
    arguments after it (``put_down(p2,r2)``: "put down (p2, r2)")."""
    if term.type != clingo.SymbolType.Function or not term.name:
        return str(term)
    name = term.name.replace("_", " ")
    if not term.arguments:
        return name
    return f"{name} ({', '.join(str(argument) for argument in term.arguments)})"


def term_words(term: clingo.Symbol) -> str:
    """A term in words: a constant with spaces for underscores, else the term."""
    return _term_words(term)


def action_phrase(labels: Labels, action: clingo.Symbol) -> str:
    """An action as a verb phrase, e.g. "pull the lever"."""
    label = labels.actions.get(action)
    if label:
        return label[0]
    return _action_name(labels, action)


def gerund(labels: Labels, action: clingo.Symbol) -> str:
    """An action as a gerund phrase, e.g. "pulling a lever"."""
    label = labels.actions.get(action)
    return label[1] if label else f"action {_action_name(labels, action)}"


def plan_phrase(labels: Labels, plan: Plan) -> str:
    """A plan as a verb phrase: "pull the lever", "scout, then steal, then ..."."""
    if not len(plan):
        return EMPTY_PLAN
    return ", then ".join(action_phrase(labels, action) for action in plan)


def fact_phrase(labels: Labels, variable: clingo.Symbol, value: bool) -> str:
    """A fact as a noun phrase, e.g. "the death of the one person"."""
    label = labels.facts.get((variable, value))
    if label:
        return label
    if labels.naming.pddl:
        return f"the fact {labels.naming.fact_of(variable, value)}"
    return f"the fact {variable}" if value else f"the fact not {variable}"


def principle_phrase(principle: str) -> str:
    """A principle as a noun phrase, e.g. "the do-no-harm principle"."""
    return f"the {principle.replace('_', '-')} principle"


def verdict_word(permissible: bool) -> str:
    return "permissible" if permissible else "impermissible"


# -- reasons ----------------------------------------------------------------------


def _element_phrase(labels: Labels, element: clingo.Symbol) -> tuple[str, bool]:
    """The phrase of an element of L and whether it is an action."""
    if element.name == "action":
        return gerund(labels, element.arguments[0]), True
    variable, value = element.arguments
    return fact_phrase(labels, variable, value.name == "true"), False


def _facts_words(labels: Labels, term: clingo.Symbol, conjunctions: Conjunctions) -> str:
    """A fact, or facts joined (``all_facts/1``: "and", ``any_facts/1``: "or")."""
    if term.name == "fact":
        return fact_phrase(labels, term.arguments[0], term.arguments[1].name == "true")
    members = conjunctions.get(term.arguments[0], [])
    phrases = [fact_phrase(labels, v, _true(b)) for v, b in members]
    return join(phrases, "and" if term.name == "all_facts" else "or") or "nothing"


def _true(value) -> bool:
    return value is True or str(value) == "true"


def _intervention_words(labels: Labels, name: clingo.Symbol, conjunctions: Conjunctions) -> str:
    """The condition of an intervention: "if the man chose to pull the lever"
    (a choice of a causal agency model: ``choose(b)``), else "with X brought about"."""
    if name.name == "choose" and len(name.arguments) == 1:
        return f"if {agent(labels)} chose to {action_phrase(labels, name.arguments[0])}"
    members = conjunctions.get(name, [])
    facts = join([fact_phrase(labels, v, _true(b)) for v, b in members]) or "nothing"
    return f"with {facts} brought about"


def literal_clause(
    literal: Literal,
    labels: Labels,
    comparisons: dict[clingo.Symbol, Comparison] | None = None,
    pronoun: bool = False,
    actions: int = 1,
    conjunctions: Conjunctions | None = None,
) -> str:
    """The words of one literal, e.g. "pulling a lever is not inherently bad".

    ``pronoun`` uses the possessive pronoun ("his action") instead of the
    agent's name ("the man's action"); ``actions`` is the plan's length
    ("action" or "actions"); ``conjunctions`` the members of the conjunctions
    that Causes and Do atoms name.
    """
    atom, value = literal.atom, literal.value
    negation = "" if value else "not "
    conjunctions = conjunctions or {}
    if atom.name == "intended":
        fact = fact_phrase(labels, atom.arguments[0], atom.arguments[1].name == "true")
        return f"{fact} is {negation}one of {possessive(labels, pronoun)} intentions"
    if atom.name in ("affects_pos", "affects_neg"):
        fact = fact_phrase(labels, atom.arguments[0], atom.arguments[1].name == "true")
        patient = labels.patients.get(atom.arguments[2]) or _term_words(atom.arguments[2], labels)
        verb = "affects" if value else "does not affect"
        way = "positively" if atom.name == "affects_pos" else "negatively"
        return f"{fact} {verb} {patient} {way}"
    if atom.name == "causes":
        cause = _facts_words(labels, atom.arguments[0], conjunctions)
        effect = _facts_words(labels, atom.arguments[1], conjunctions)
        return f"{cause} {'causes' if value else 'does not cause'} {effect}"
    if atom.name == "do":
        effect = _facts_words(labels, atom.arguments[1], conjunctions)
        condition = _intervention_words(labels, atom.arguments[0], conjunctions)
        would = "would" if value else "would not"
        if condition.startswith("if "):
            return f"{effect} {would} hold {condition}"
        return f"{condition}, {effect} {would} hold"
    if atom.name in VALUATIONS:
        subject, is_action = _element_phrase(labels, atom.arguments[0])
        degree = "inherently " if is_action and atom.name != "neutral" else ""
        return f"{subject} is {negation}{degree}{VALUATIONS[atom.name]}"
    if atom.name == "caused":
        variable, truth = atom.arguments
        fact = fact_phrase(labels, variable, truth.name == "true")
        noun = "action" if actions <= 1 else "actions"
        return f"this way {fact} is {negation}caused by {possessive(labels, pronoun)} {noun}"
    if atom.name in _HERA_FACTS:
        variable, truth = atom.arguments
        fact = fact_phrase(labels, variable, truth.name == "true")
        noun = "action" if actions <= 1 else "actions"
        return _HERA_FACTS[atom.name](fact, possessive(labels, pronoun), noun, value)
    if atom.name in _HERA_PATIENTS:
        patient = labels.patients.get(atom.arguments[0]) or _term_words(atom.arguments[0], labels)
        noun = "action" if actions <= 1 else "actions"
        return _HERA_PATIENTS[atom.name](patient, possessive(labels, pronoun), noun, value)
    if atom.name == "ucompare":
        operator, left, right = atom.arguments
        relation = _RELATIONS[operator.name][0 if value else 1]
        left_words = _utility_words(left, labels, conjunctions)
        return f"{left_words} {relation} {_utility_words(right, labels, conjunctions)}"
    if atom.name == "geq":
        comparison = (comparisons or {}).get(atom)
        if comparison is None:
            return f"{atom} is {negation}true"
        left = join([fact_phrase(labels, v, b) for v, b in comparison.left]) or "nothing"
        right = join([fact_phrase(labels, v, b) for v, b in comparison.right]) or "nothing"
        verb = "are" if len(comparison.left) > 1 else "is"  # several facts: "X and Y are"
        if not value:
            relation = f"{verb} worse than"
        elif comparison.relation == "equal":
            relation = f"{verb} as good as"
        else:
            relation = f"{verb} better than"
        return f"{left} {relation} {right}"
    return f"{atom} is {negation}true"


_HERA_FACTS = {
    "goal_fact": lambda fact, poss, noun, value: (
        f"{fact} is {'' if value else 'not '}one of {poss} goals"
    ),
    "finally": lambda fact, poss, noun, value: (
        f"{fact} {'holds' if value else 'does not hold'} in the end"
    ),
    "but_for": lambda fact, poss, noun, value: (
        f"but for {poss} {noun}, {fact} would not come about"
        if value
        else f"{fact} would come about even without {poss} {noun}"
    ),
    "instrumental": lambda fact, poss, noun, value: (
        f"{fact} is {'' if value else 'not '}a means to {poss} goal"
    ),
    "avoidable": lambda fact, poss, noun, value: (
        f"{fact} could {'' if value else 'not '}be avoided"
    ),
}
_HERA_PATIENTS = {
    "means": lambda patient, poss, noun, value: (
        f"{patient} is {'' if value else 'not '}used as a means"
    ),
    "means2": lambda patient, poss, noun, value: (
        f"{patient} is {'' if value else 'not '}affected by {poss} {noun}"
    ),
    "end": lambda patient, poss, noun, value: (
        f"{patient} is {'' if value else 'not '}treated as an end"
    ),
}
_RELATIONS = {
    "gt": ("is greater than", "is not greater than"),
    "geq": ("is at least", "is less than"),
    "eq": ("equals", "does not equal"),
}


def _utility_words(
    term: clingo.Symbol, labels: Labels, conjunctions: Conjunctions | None = None
) -> str:
    """A utility term in words (no recursion: the left spine is walked)."""
    parts: list[str] = []
    while term.name in ("add", "sub") and len(term.arguments) == 2:
        word = "plus" if term.name == "add" else "minus"
        parts.append(f"{word} {_utility_primary_words(term.arguments[1], labels, conjunctions)}")
        term = term.arguments[0]
    first = _utility_primary_words(term, labels, conjunctions)
    return " ".join([first, *list(reversed(parts))])


def _utility_primary_words(
    term: clingo.Symbol, labels: Labels, conjunctions: Conjunctions | None = None
) -> str:
    signs = 0
    while term.name == "minus" and len(term.arguments) == 1:
        signs += 1
        term = term.arguments[0]
    if term.name == "num":
        text = str(term.arguments[0])
    else:
        name = term.arguments[0] if term.arguments else term
        if name.name == "final" and not name.arguments:
            text = "the utility of the final state"
        elif name.name == "alternative_final" and len(name.arguments) == 1:
            text = f"the utility of alternative {name.arguments[0]}'s final state"
        elif name.name == "consequences":
            text = "the utility of the consequences"
        elif conjunctions and name in conjunctions:
            facts = [fact_phrase(labels, v, _true(b)) for v, b in conjunctions[name]]
            text = f"the utility of {join(facts) or 'nothing'}"
        else:
            text = f"the utility of {name}"
    return "minus " * signs + text


def _group(literal: Literal) -> tuple | None:
    """Literals that one clause can say together: Good/Bad/Neutral of actions,
    or of facts, with one value; Caused with one value.  None: said alone."""
    atom = literal.atom
    if atom.name in VALUATIONS:
        return atom.name, literal.value, atom.arguments[0].name
    if atom.name == "caused":
        return atom.name, literal.value
    return None


def _none_of(subjects: list[str]) -> str:
    """ "neither a nor b", "none of a, b and c"."""
    if len(subjects) == 2:
        return f"neither {subjects[0]} nor {subjects[1]}"
    return f"none of {join(subjects)}"


def _group_clause(
    key: tuple,
    literals: list[Literal],
    labels: Labels,
    pronoun: bool,
    actions: int,
    plan: Plan | None,
) -> str:
    """The words of several literals of one group (see :func:`_group`), e.g.
    "none of his 8 actions is inherently bad"."""
    whose = possessive(labels, pronoun)
    if key[0] == "caused":
        facts = [
            fact_phrase(labels, lit.atom.arguments[0], lit.atom.arguments[1].name == "true")
            for lit in literals
        ]
        noun = "action" if actions <= 1 else "actions"
        if key[1]:
            return f"this way {join(facts)} are caused by {whose} {noun}"
        return f"this way {_none_of(facts)} is caused by {whose} {noun}"
    name, value, element = key
    degree = "inherently " if element == "action" and name != "neutral" else ""
    subjects = [_element_phrase(labels, lit.atom.arguments[0])[0] for lit in literals]
    if value:
        return f"{join(subjects)} are {degree}{VALUATIONS[name]}"
    elements = {lit.atom.arguments[0].arguments[0] for lit in literals}
    if element == "action" and plan is not None and len(elements) > 3 and elements == set(plan):
        return f"none of {whose} {len(plan)} actions is {degree}{VALUATIONS[name]}"
    return f"{_none_of(subjects)} is {degree}{VALUATIONS[name]}"


def reason_clause(
    literals: Sequence[Literal],
    labels: Labels,
    comparisons: dict[clingo.Symbol, Comparison] | None = None,
    pronoun: bool = False,
    actions: int = 1,
    plan: Plan | None = None,
    conjunctions: Conjunctions | None = None,
) -> str:
    """The words of a reason: its literals' clauses joined by "and"; literals
    of one group share a clause ("neither pulling a lever nor pushing a man is
    inherently bad", or with the ``plan`` whose every action they name, "none
    of the man's 5 actions is inherently bad")."""
    groups: dict[tuple, list[Literal]] = {}
    order: list[tuple | Literal] = []
    for literal in literals:
        key = _group(literal)
        if key is None:
            order.append(literal)
        elif key in groups:
            groups[key].append(literal)
        else:
            groups[key] = [literal]
            order.append(key)
    clauses = []
    for item in order:
        if isinstance(item, Literal):
            clauses.append(
                literal_clause(item, labels, comparisons, pronoun, actions, conjunctions)
            )
        elif len(groups[item]) == 1:
            clauses.append(
                literal_clause(groups[item][0], labels, comparisons, pronoun, actions, conjunctions)
            )
        else:
            clauses.append(_group_clause(item, groups[item], labels, pronoun, actions, plan))
    return join(clauses)


def explanation_clause(explanation: Explanation, pronoun: bool = False) -> str:
    """The chosen reason of an explanation in words ("because ..." follows)."""
    return reason_clause(
        explanation.literals,
        explanation.labels,
        explanation.comparisons,
        pronoun,
        len(explanation.plan),
        explanation.plan,
        explanation.conjunctions,
    )


# -- sentences --------------------------------------------------------------------


def option_sentence(labels: Labels, plan: Plan, modal: str = "can") -> str:
    """ "The man can pull the lever." (``modal`` "could" for alternatives)."""
    return f"{capitalize(agent(labels))} {modal} {plan_phrase(labels, plan)}."


def verdict_sentence(
    explanation: Explanation,
    opening: str = "Doing so is",
    principle: bool = False,
    pronoun: bool = False,
) -> str:
    """ "Doing so is permissible because ..." (``opening`` e.g. "This would be";
    ``principle`` adds "under the ... principle")."""
    words = f"{opening} {verdict_word(explanation.permissible)}"
    if principle:
        words += f" under {principle_phrase(explanation.principle)}"
    if not explanation.literals:
        if explanation.cut:
            return f"{words} (its reasons were cut short: {explanation.cut})."
        return f"{words} in any case."
    return f"{words} because {explanation_clause(explanation, pronoun)}."


def non_contrastive(explanation: Explanation) -> str:
    """The non-contrastive explanation: the plan and why it is (im)permissible."""
    return (
        f"{option_sentence(explanation.labels, explanation.plan)} {verdict_sentence(explanation)}"
    )


# -- questions ------------------------------------------------------------------


def _steps_words(count: int) -> str:
    return f"{count} step" if count == 1 else f"{count} steps"


def constraint_phrase(labels: Labels, term: clingo.Symbol) -> str:
    """A question's constraint (a term of ``contrast(Q,C)``, questions.lp) as
    what a plan does, a verb phrase: "include pulling a lever at step 2", "end
    with the door open", "take at most 3 steps"."""
    name, arguments = term.name, term.arguments

    def doing(index: int = 0) -> str:
        return gerund(labels, arguments[index])

    def fact(index: int = 0) -> str:
        variable, value = arguments[index], arguments[index + 1]
        return fact_phrase(labels, variable, value.name == "true")

    if name == "used":
        return f"include {doing()}"
    if name == "unused":
        return f"avoid {doing()}"
    if name == "before":
        if arguments[0] == arguments[1]:
            return f"include {doing(0)}"
        return f"include {doing(0)}, and {doing(1)} only after it"
    if name == "at":
        return f"include {doing()} at step {arguments[1]}"
    if name == "not_at":
        return f"avoid {doing()} at step {arguments[1]}"
    if name == "within":
        return f"include {doing()} at some step from {arguments[1]} to {arguments[2]}"
    if name == "not_within":
        return f"avoid {doing()} from step {arguments[1]} to {arguments[2]}"
    if name == "ends":
        return f"end with {fact()}"
    if name == "fact_at":
        return f"have {fact()} after step {arguments[2]}"
    if name == "at_most":
        return f"take at most {_steps_words(arguments[0].number)}"
    if name == "cheaper_than":
        return f"cost less than {arguments[0]}"
    return f"meet {term}"
