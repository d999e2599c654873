"""The planning model's own vocabulary (``encodings/planning/model.lp``) and its
well-formedness errors (``encodings/planning/check.lp``)."""

from clorm import ConstantStr, Predicate, Raw

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
