"""What HERA's two kinds of model files share: reading a file (YAML or JSON),
checking its data, HERA's names as ASP terms, and the label keys of ethasp.

HERA (PyPI package ``ethics``) reads situations (:mod:`ethasp.planning.readers.situation`)
and causal agency models (:mod:`ethasp.planning.readers.cam`) from ``.yaml``,
``.yml`` and ``.json`` files; which of the two a file holds is told by its
content (:func:`kind_of`), not by its name.  A reader subclasses
:class:`DataReader`, which collects facts and warnings and raises
:class:`ethasp.errors.InputError` with one line naming the file for data it
cannot map.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NoReturn

import clingo

from ethasp.errors import InputError
from ethasp.planning.terms import INT_MAX, INT_MIN

SUFFIXES = (".yaml", ".yml", ".json")

SITUATION = "situation"
CAM = "cam"

_CONSTANT = re.compile(r"[a-z][A-Za-z0-9_']*")


def is_hera_file(path: Path) -> bool:
    """Is the file one of HERA's (by its suffix): a situation or a causal agency model?"""
    return path.suffix.lower() in SUFFIXES


def name_term(name: str) -> clingo.Symbol:
    """The ASP term of a HERA name: a constant if it is one, else a string."""
    if _CONSTANT.fullmatch(name) and name != "not":
        return clingo.Function(name)
    return clingo.String(name)


def hera_name(term: clingo.Symbol) -> str:
    """The HERA name of a term made by :func:`name_term`."""
    return term.string if term.type == clingo.SymbolType.String else str(term)


def load_data(path: Path, text: str) -> Any:
    """The data of a HERA file: JSON for ``.json``, else YAML (one line for a
    syntax error, with its line)."""
    if path.suffix.lower() == ".json":
        try:
            return json.loads(text)
        except json.JSONDecodeError as error:
            raise InputError(f"{path}:{error.lineno}: not JSON: {error.msg}") from None
        except RecursionError:
            raise InputError(f"{path}: nested too deeply to read") from None
    import yaml

    try:
        return yaml.safe_load(text)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark
        line = f":{mark.line + 1}" if mark is not None else ""
        raise InputError(f"{path}{line}: not YAML: {error.problem}") from None
    except (yaml.YAMLError, RecursionError) as error:
        raise InputError(
            f"{path}: not YAML: {str(error).splitlines()[0] if str(error) else 'nested too deeply'}"
        ) from None


def kind_of(data: Any, where: str) -> str:
    """Which of HERA's models the data is, by its content: a causal agency
    model names its actions by strings (``actions``, or its older layout's
    ``action``) or has ``mechanisms`` or ``consequences``; anything else is
    read as a situation (whose reader says what it lacks)."""
    if not isinstance(data, dict):
        raise InputError(
            f"{where}: the file must be a mapping (a HERA situation or causal agency "
            f"model), not {type(data).__name__ if data is not None else 'empty'}"
        )
    actions = data.get("actions")
    if "initialState" in data or (
        isinstance(actions, list) and any(isinstance(action, dict) for action in actions)
    ):
        return SITUATION
    named = isinstance(actions, list) and bool(actions)
    if "mechanisms" in data or "action" in data or "consequences" in data or named:
        return CAM
    return SITUATION


@dataclass
class DataReader:
    """Checks a HERA file's data and collects the facts of its model."""

    where: str
    facts: list[clingo.Symbol] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    def warn(self, message: str) -> None:
        self.warnings.append(f"{self.where}: warning: {message}")

    def fail(self, message: str) -> NoReturn:
        raise InputError(f"{self.where}: {message}")

    def name(self, value: Any, what: str) -> str:
        if isinstance(value, bool) or not isinstance(value, (str, int)):
            self.fail(f"{what} must be a name, not {value!r}")
        text = str(value)
        if not text or any(ord(char) < 32 or ord(char) == 127 for char in text):
            self.fail(f"{what} must be a non-empty name without control characters: {text!r}")
        return text

    def mapping(self, value: Any, what: str) -> dict:
        if value is None:
            return {}
        if not isinstance(value, dict):
            self.fail(f"{what} must be a mapping, not {type(value).__name__}")
        return value

    def sequence(self, value: Any, what: str) -> list:
        if value is None:
            return []
        if not isinstance(value, list):
            self.fail(f"{what} must be a list, not {type(value).__name__}")
        return value

    def integer(self, value: Any, what: str) -> int:
        if isinstance(value, float) and value.is_integer():
            value = int(value)
        if isinstance(value, bool) or not isinstance(value, int):
            self.fail(f"{what} must be an integer, not {value!r}")
        if not INT_MIN <= value <= INT_MAX:
            self.fail(f"{what} is outside clingo's 32-bit integers: {value}")
        return value

    def add(self, name: str, *arguments) -> None:
        terms = [
            argument
            if isinstance(argument, clingo.Symbol)
            else clingo.Number(argument)
            if isinstance(argument, int) and not isinstance(argument, bool)
            else clingo.Function("true" if argument else "false")
            if isinstance(argument, bool)
            else argument
            for argument in arguments
        ]
        self.facts.append(clingo.Function(name, terms))

    def text(self) -> str:
        """The facts as ASP text."""
        return "".join(f"{fact}.\n" for fact in self.facts)

    # -- ethasp's labels (the key ``labels``, which HERA ignores) -------------------------

    def agent_label(self, labels: dict) -> None:
        if "agent" not in labels:
            return
        agent = labels["agent"]
        if not (
            isinstance(agent, list) and len(agent) == 2 and all(isinstance(p, str) for p in agent)
        ):
            self.fail("labels: agent must be [name, possessive], e.g. [the robot, its]")
        self.add("agent_label", clingo.String(agent[0]), clingo.String(agent[1]))

    def action_labels(self, labels: dict, actions: set[str], of: str) -> dict[str, str]:
        """``action_label/3`` facts; the gerund of each labelled action."""
        gerunds = {}
        for name, words in self.mapping(labels.get("actions"), "labels of actions").items():
            name = self.name(name, "an action in labels")
            if name not in actions:
                self.fail(f"labels: {name} is not an action of the {of}")
            if not (
                isinstance(words, list)
                and len(words) == 2
                and all(isinstance(part, str) for part in words)
            ):
                self.fail(f"labels: action {name} needs [phrase, gerund]")
            self.add(
                "action_label", name_term(name), clingo.String(words[0]), clingo.String(words[1])
            )
            gerunds[name] = words[1]
        return gerunds

    def patient_labels(self, labels: dict, patients: set[str], where: str) -> None:
        for name, phrase in self.mapping(labels.get("patients"), "labels of patients").items():
            name = self.name(name, "a patient in labels")
            if name not in patients:
                self.fail(f"labels: {name} is not a patient of the {where}")
            if not isinstance(phrase, str):
                self.fail(f"labels: patient {name} needs a phrase (a string)")
            self.add("patient_label", name_term(name), clingo.String(phrase))
