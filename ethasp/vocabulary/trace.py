"""Plans and their traces (``encodings/planning/transition.lp``, ``trace.lp``), and
the terms of a plan that are no action of a PDDL task (``static.lp``)."""

from clorm import ConstantStr, Predicate, Raw

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


class PlanCost(Predicate, name="plan_cost"):
    cost: int


# -- terms of a plan that are no action of a PDDL task (static.lp) --------------------


class NoSchemaInstance(Predicate, name="no_schema_instance"):
    action: Raw


class StaticFailure(Predicate, name="pddl_static_failure"):
    action: Raw
    variable: Raw
    value: ConstantStr
