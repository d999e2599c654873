"""Pictures of plans: weights, and what changed at each step (``steps.lp``)."""

from clorm import ConstantStr, Predicate, Raw

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
