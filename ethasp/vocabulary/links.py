"""Causal links of a plan (``encodings/questions/links.lp``, ``removable.lp``), and
its E-links and D-links (``producers.lp``, ``demands.lp``)."""

from clorm import ConstantStr, Predicate, Raw

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


# -- E-links and D-links (questions/demands.lp, producers.lp) ---------------------------


class Demanded(Predicate, name="demanded"):
    step: int
    variable: Raw
    value: ConstantStr


class ELink(Predicate, name="e_link"):
    producer: Raw
    consumer: Raw
    variable: Raw
    value: ConstantStr


class DLink(Predicate, name="d_link"):
    producer: Raw
    step: int
    variable: Raw
    value: ConstantStr
