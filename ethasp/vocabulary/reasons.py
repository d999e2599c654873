"""Reasons and the labels that put them into words (``encodings/reasons/``)."""

from clorm import ConstantStr, Predicate, Raw, StringField

# -- reasons and their words (encodings/reasons/) --------------------------------


class ReasonAtom(Predicate, name="reason"):
    atom: Raw
    value: ConstantStr


class ActualValue(Predicate, name="actual_value"):
    """An atom of the explained formula and its truth value for the plan
    (``reasons/literals.lp``)."""

    atom: Raw
    value: ConstantStr


class Mention(Predicate, name="mention"):
    atom: Raw
    side: ConstantStr
    variable: Raw
    value: ConstantStr


class ComparisonAtom(Predicate, name="comparison"):
    atom: Raw
    relation: ConstantStr


class Conjunct(Predicate, name="conjunct"):
    name: Raw
    variable: Raw
    value: ConstantStr


class AgentLabel(Predicate, name="agent_label"):
    name: str = StringField
    possessive: str = StringField


class ActionLabel(Predicate, name="action_label"):
    action: Raw
    phrase: str = StringField
    gerund: str = StringField


class FactLabel(Predicate, name="fact_label"):
    variable: Raw
    value: ConstantStr
    phrase: str = StringField


class PatientLabel(Predicate, name="patient_label"):
    patient: Raw
    phrase: str = StringField
