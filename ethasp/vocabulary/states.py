"""Best reachable states: the states compared with (``judgement/best.lp``)
and the bounds of relaxed reachability (``planning/relaxed.lp``)."""

from clorm import ConstantStr, Predicate, Raw


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
