"""Contrastive questions (``encodings/questions/questions.lp``)."""

from clorm import Predicate, Raw

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
