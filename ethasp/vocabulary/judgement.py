"""Judgements and the language L (``encodings/judgement/``)."""

from clorm import ConstantStr, Predicate, Raw

# -- judgements and the language L (language.lp, judge.lp) ----------------------


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
