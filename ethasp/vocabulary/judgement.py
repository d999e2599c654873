"""Judgements, the language L and best reachable states (``encodings/judgement/``)."""

from clorm import ConstantStr, Predicate, Raw

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
