"""Typed clorm predicates for the ASP vocabulary that crosses into Python.

The planning model's own vocabulary (``variable/1`` ... ``utility/3``, see
``encodings/planning/model.lp``) and the atoms that the encodings report back.  Terms
that can be any ground term (action and variable names) are kept as
:class:`clorm.Raw`, so ``push(man)`` stays a term.
"""

from clorm import ConstantStr, Predicate, Raw, StringField

# -- the planning model -------------------------------------------------------


class Variable(Predicate, name="variable"):
    name: Raw


class Action(Predicate, name="action"):
    name: Raw


class Init(Predicate, name="init"):
    variable: Raw


class Goal(Predicate, name="goal"):
    variable: Raw
    value: ConstantStr


# -- well-formedness (check.lp) -----------------------------------------------


class Error(Predicate, name="error"):
    problem: Raw


# -- plans and traces (transition.lp, trace.lp) -------------------------------


class Occurs(Predicate, name="occurs"):
    action: Raw
    step: int


class Invalid(Predicate, name="invalid"):
    problem: Raw


class Unmet(Predicate, name="unmet"):
    step: int
    action: Raw
    variable: Raw
    value: ConstantStr


class Failure(Predicate, name="failure"):
    step: int


class Final(Predicate, name="final"):
    variable: Raw
    value: ConstantStr


class UnmetGoal(Predicate, name="unmet_goal"):
    variable: Raw
    value: ConstantStr


class IsPlan(Predicate, name="plan"):
    pass


# -- terms of a plan that are no action of a PDDL task (static.lp) --------------------


class NoSchemaInstance(Predicate, name="no_schema_instance"):
    action: Raw


class StaticFailure(Predicate, name="pddl_static_failure"):
    action: Raw
    variable: Raw
    value: ConstantStr


# -- judgements and the language L (language.lp, judge.lp, judgement/best.lp) ----


class Verdict(Predicate, name="verdict"):
    name: Raw
    value: ConstantStr


class UtilityOfFinal(Predicate, name="utility_of_final"):
    utility: int


class FormulaOf(Predicate, name="formula"):
    name: Raw
    formula: Raw


class Conj(Predicate, name="conj"):
    name: Raw
    variable: Raw
    value: ConstantStr


class Alternative(Predicate, name="alternative"):
    name: Raw


class UpperBound(Predicate, name="upper_bound"):
    bound: int


class BestFact(Predicate, name="best_fact"):
    variable: Raw
    value: ConstantStr


class AtHorizon(Predicate, name="at_horizon"):
    variable: Raw
    value: ConstantStr
    time: int


# -- reasons and their words (encodings/reasons/) --------------------------------


class ReasonAtom(Predicate, name="reason"):
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


# -- contrastive questions (questions.lp) -----------------------------------------


class Contrast(Predicate, name="contrast"):
    question: Raw
    constraint: Raw


class Answered(Predicate, name="answered"):
    question: Raw
    time: int


class UnknownAction(Predicate, name="unknown_action"):
    question: Raw
    action: Raw


class UnknownVariable(Predicate, name="unknown_variable"):
    question: Raw
    variable: Raw


class Met(Predicate, name="met"):
    question: Raw
    constraint: Raw
    time: int


# -- pictures of plans (model.lp's weights, steps.lp) ------------------------------


class Weight(Predicate, name="weight"):
    element: Raw
    utility: int


class Initially(Predicate, name="initially"):
    variable: Raw
    value: ConstantStr


class SetAt(Predicate, name="set"):
    step: int
    variable: Raw
    value: ConstantStr


class Changed(Predicate, name="changed"):
    step: int
    variable: Raw
    value: ConstantStr


class Causing(Predicate, name="causing"):
    step: int
    variable: Raw
    value: ConstantStr


class Caused(Predicate, name="caused"):
    variable: Raw
    value: ConstantStr


class EventChanged(Predicate, name="event_changed"):
    step: int
    variable: Raw
    value: ConstantStr


class Happened(Predicate, name="happened"):
    step: int
    event: Raw


# -- causal links of a plan (questions/links.lp, removable.lp) ------------------------


class Link(Predicate, name="link"):
    provider: Raw
    consumer: Raw
    variable: Raw
    value: ConstantStr
    kind: Raw
    via: Raw


class ServesGoal(Predicate, name="serves_goal"):
    node: Raw


class Chain(Predicate, name="goal_chain"):
    step: int
    index: int
    node: Raw


class StepUtility(Predicate, name="step_utility"):
    step: int
    utility: int


class StepCauses(Predicate, name="step_causes"):
    step: int
    variable: Raw
    value: ConstantStr
    utility: int


class Removable(Predicate, name="removable"):
    step: int
