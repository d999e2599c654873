"""Typed clorm predicates for the ASP vocabulary that crosses into Python.

The planning model's own vocabulary (``variable/1`` ... ``utility/3``, see
``encodings/planning/model.lp``) and the atoms that the encodings report
back, one module per concern.  Terms that can be any ground term (action and
variable names) are kept as :class:`clorm.Raw`, so ``push(man)`` stays a
term.

A predicate is imported from here (``from ethasp.vocabulary import
Verdict``); the module that defines it is loaded on first use, so that a
command builds only the predicates it reads (clorm makes each class at some
cost).
"""

from importlib import import_module
from typing import TYPE_CHECKING, Any

# Each predicate and the module of its concern.
_HOMES = {
    "Variable": "model",
    "Action": "model",
    "Init": "model",
    "Goal": "model",
    "Error": "model",
    "Occurs": "trace",
    "Invalid": "trace",
    "Unmet": "trace",
    "Failure": "trace",
    "Final": "trace",
    "UnmetGoal": "trace",
    "IsPlan": "trace",
    "PlanCost": "trace",
    "NoSchemaInstance": "trace",
    "StaticFailure": "trace",
    "Verdict": "judgement",
    "UtilityOfFinal": "judgement",
    "FormulaOf": "judgement",
    "Conj": "judgement",
    "Alternative": "states",
    "UpperBound": "states",
    "BestFact": "states",
    "AtHorizon": "states",
    "ReasonAtom": "reasons",
    "ActualValue": "reasons",
    "Mention": "reasons",
    "ComparisonAtom": "reasons",
    "Conjunct": "reasons",
    "AgentLabel": "reasons",
    "ActionLabel": "reasons",
    "FactLabel": "reasons",
    "PatientLabel": "reasons",
    "Contrast": "questions",
    "Answered": "questions",
    "UnknownAction": "questions",
    "UnknownVariable": "questions",
    "Met": "questions",
    "Weight": "pictures",
    "Initially": "pictures",
    "SetAt": "pictures",
    "Changed": "pictures",
    "Causing": "pictures",
    "Caused": "pictures",
    "EventChanged": "pictures",
    "Happened": "pictures",
    "Link": "links",
    "ServesGoal": "links",
    "Chain": "links",
    "StepUtility": "links",
    "StepCauses": "links",
    "Removable": "links",
    "Demanded": "links",
    "ELink": "links",
    "DLink": "links",
}

if TYPE_CHECKING:  # the same names for type checkers, which do not run __getattr__
    from ethasp.vocabulary.judgement import Conj, FormulaOf, UtilityOfFinal, Verdict
    from ethasp.vocabulary.links import (
        Chain,
        Demanded,
        DLink,
        ELink,
        Link,
        Removable,
        ServesGoal,
        StepCauses,
        StepUtility,
    )
    from ethasp.vocabulary.model import Action, Error, Goal, Init, Variable
    from ethasp.vocabulary.pictures import (
        Caused,
        Causing,
        Changed,
        EventChanged,
        Happened,
        Initially,
        SetAt,
        Weight,
    )
    from ethasp.vocabulary.questions import Answered, Contrast, Met, UnknownAction, UnknownVariable
    from ethasp.vocabulary.reasons import (
        ActionLabel,
        ActualValue,
        AgentLabel,
        ComparisonAtom,
        Conjunct,
        FactLabel,
        Mention,
        PatientLabel,
        ReasonAtom,
    )
    from ethasp.vocabulary.states import Alternative, AtHorizon, BestFact, UpperBound
    from ethasp.vocabulary.trace import (
        Failure,
        Final,
        Invalid,
        IsPlan,
        NoSchemaInstance,
        Occurs,
        PlanCost,
        StaticFailure,
        Unmet,
        UnmetGoal,
    )


def __getattr__(name: str) -> Any:
    if name not in _HOMES:
        raise AttributeError(f"module 'ethasp.vocabulary' has no attribute {name!r}")
    value = getattr(import_module(f"ethasp.vocabulary.{_HOMES[name]}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_HOMES))


__all__ = [
    "Action",
    "ActionLabel",
    "ActualValue",
    "AgentLabel",
    "Alternative",
    "Answered",
    "AtHorizon",
    "BestFact",
    "Caused",
    "Causing",
    "Chain",
    "Changed",
    "ComparisonAtom",
    "Conj",
    "Conjunct",
    "Contrast",
    "DLink",
    "Demanded",
    "ELink",
    "Error",
    "EventChanged",
    "FactLabel",
    "Failure",
    "Final",
    "FormulaOf",
    "Goal",
    "Happened",
    "Init",
    "Initially",
    "Invalid",
    "IsPlan",
    "Link",
    "Mention",
    "Met",
    "NoSchemaInstance",
    "Occurs",
    "PatientLabel",
    "PlanCost",
    "ReasonAtom",
    "Removable",
    "ServesGoal",
    "SetAt",
    "StaticFailure",
    "StepCauses",
    "StepUtility",
    "UnknownAction",
    "UnknownVariable",
    "Unmet",
    "UnmetGoal",
    "UpperBound",
    "UtilityOfFinal",
    "Variable",
    "Verdict",
    "Weight",
]
