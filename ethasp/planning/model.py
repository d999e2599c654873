"""Planning models: ASP files or text in the vocabulary of encodings/planning/model.lp.

A model sent to another process (pickled) travels as a reference: its
:attr:`~Model.key` with its sources.  The receiving process resolves it to
the model it keeps under that key, with that model's grounding and the
results kept for it (a warm worker, :mod:`ethasp.execution.worker`), or
else makes one from the sources and keeps it (:func:`kept`).  So a dialogue
sent to a worker is answered from the worker's grounding, and sent back it
refers again to the model of the process that sent it.
"""

from __future__ import annotations

import hashlib
import threading
from collections import OrderedDict
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import clingo
import clingo.script
from clingo import ast

from ethasp.errors import InputError
from ethasp.planning.driver.namespace import NamespaceCheck, misused_vocabulary
from ethasp.planning.messages import Messages
from ethasp.planning.naming import Naming, PddlNaming
from ethasp.planning.terms import read_text, scan_file, scan_program
from ethasp.resources import encoding, model_path

if TYPE_CHECKING:
    from ethasp.planning.driver.planner import Planner


@dataclass(frozen=True)
class Source:
    """One piece of a model: a file, or text with a name for messages."""

    name: str
    text: str
    path: Path | None = None
    generated: bool = False  # written by ethasp (a translation), not by a user
    kind: str = "asp"  # asp, pddl (a PDDL translation), situation (a HERA
    # situation), cam (a HERA causal agency model) or hmodel (a restriction's,
    # of facts)
    facts: tuple[clingo.Symbol, ...] = ()  # ground facts, added without parsing


def _describe(problem: clingo.Symbol) -> str:
    """One sentence for an error/1 atom of check.lp."""
    name, args = problem.name, problem.arguments
    if name == "undeclared_variable":
        return f"unknown variable {args[0]} in {args[1]} (declare it with variable({args[0]}))"
    if name == "undeclared_action":
        return f"unknown action {args[0]} in {args[1]} (declare it with action({args[0]}))"
    if name == "bad_value":
        return f"truth value must be true or false in {args[0]}"
    if name == "not_integer":
        return f"utility must be an integer in {args[0]}"
    if name == "ambiguous_utility":
        return f"two different utilities for one element, one of them {args[0]}"
    if name == "bad_cost":
        return f"a cost must be an integer from 0 to 1000000 in {args[0]}"
    if name == "ambiguous_cost":
        return f"two different costs for one action, one of them {args[0]}"
    if name == "contradicting_effects":
        return f"action {args[0]} sets variable {args[1]} both to true and to false"
    if name == "condition_without_effect":
        return f"{args[0]} is a condition of a conditional effect that no ceff/4 has"
    if name == "derived_misuse":
        return (
            f"derived variable {args[0]} in {args[1]} (a derived variable is computed "
            "from the state: no effect sets it, no initial value, no utility)"
        )
    if name == "derived_and_variable":
        return f"{args[0]} is declared both a variable and a derived variable"
    if name == "undeclared_derived":
        return f"{args[1]} defines {args[0]}, which is not declared by derived({args[0]})"
    if name == "condition_without_axiom":
        return f"{args[0]} is a condition of an axiom that no axiom/2 has"
    if name == "unstratified":
        return (
            f"derived variable {args[0]} depends on the negation of {args[1]}, which "
            f"depends on {args[0]} (derived variables must be stratified)"
        )
    if name == "too_large":
        return (
            f"{args[0]}: the utility is too large: with {args[2]} morally valued elements, "
            f"|utility| must be at most {args[1]} (= (2^31 - 1) / {args[2]}), so that every "
            "sum of utilities stays within clingo's 32-bit integers"
        )
    if name == "empty":
        return "the model is empty: it declares no variable and no action"
    if name == "undeclared_event":
        return f"unknown event {args[0]} in {args[1]} (declare it with event({args[0]}))"
    if name == "bad_time":
        return f"an event's step must be an integer from 1 to 10000 in {args[0]}"
    if name == "derived_in_event":
        return f"derived variable {args[0]} in {args[1]} (events read and set state variables only)"
    if name == "contradicting_event_effect":
        return (
            f"effect {args[1]} of event {args[0]} sets variable {args[2]} both to true and to false"
        )
    if name == "undeclared_patient":
        return f"unknown moral patient {args[0]} in {args[1]} (declare it with patient({args[0]}))"
    if name == "bad_sign":
        return f"the sign must be pos or neg in {args[0]}"
    if name == "bad_plan":
        return (
            f"{args[0]} does not describe a plan (one length N >= 0, one action at each step 1..N)"
        )
    if name == "static_written":
        return (
            f"{args[1]} changes {args[0]}, which no action of the PDDL domain changes: the "
            "translation keeps only the action instances whose preconditions on such "
            "atoms hold initially (give the effect in the domain instead)"
        )
    if name == "reserved_name":
        return (
            f"{args[0]} in {args[1]}: names of the form ethasp(...) are reserved for the "
            "state variables that restrictions add to a model"
        )
    if name == "creative_and_action":
        return (
            f"{args[0]} is declared both an action and a creative alternative (a creative "
            "alternative exists only where a repair adds it: declare it with creative/1 only)"
        )
    if name == "unknown_creative":
        return (
            f"creative alternative {args[0]} is no instance of an action of the PDDL domain "
            "(its parameters' types, or a static precondition, rule it out)"
        )
    if name == "not_a_goal":
        return f"{args[0]} names a fact that is no goal fact"
    if name == "bad_change_cost":
        return f"the cost must be an integer from 1 to 1000000, one per change, in {args[0]}"
    if name == "override_without_condition":
        return f"{args[0]} names a condition that no cpre/4 has"
    return str(problem)


def _renamed(logger, placeholder: str, name: str):
    """A clingo logger that names a text source ``name`` where clingo writes
    ``placeholder`` (``<string>`` when parsing text, ``<block>`` when grounding it)."""

    def log(code: clingo.MessageCode, message: str) -> None:
        logger(code, message.replace(f"{placeholder}:", f"{name}:"))

    return log


@dataclass
class Model:
    """A planning model made of ASP sources (files or text).

    Build one with :meth:`load` (files) or :meth:`from_string`; both check that
    the sources parse, refuse ``#script`` blocks unless ``allow_scripts``, and
    check the model with ``encodings/planning/check.lp`` (``checked`` says
    that :meth:`check` passed in this process).
    """

    sources: list[Source] = field(default_factory=list)
    allow_scripts: bool = False
    naming: Naming = field(default_factory=Naming)
    # Which planning system searches its plans (ethasp.planning.systems).
    planning_system: str = "auto"
    _planner: Planner | None = field(default=None, repr=False, compare=False)
    _key: str | None = field(default=None, repr=False, compare=False)
    checked: bool = field(default=False, repr=False, compare=False)

    # -- construction ---------------------------------------------------------

    @classmethod
    def load(
        cls,
        paths: Iterable[str | Path],
        allow_scripts: bool = False,
        check: bool = True,
        texts: Sequence[tuple[str, str]] = (),
        world: Mapping[str, bool] | None = None,
    ) -> Model:
        """Load a model from ASP files, or a PDDL domain and problem plus ASP files.

        Files ending in ``.pddl`` are translated into rules (see
        :mod:`ethasp.planning.readers.pddl`); the model then shows actions in PDDL form.
        HERA's files (``.yaml``, ``.yml``, ``.json``) are situations or causal
        agency models, told apart by their content, and translated into facts
        (see :mod:`ethasp.planning.readers.situation` and
        :mod:`ethasp.planning.readers.cam`).  ``texts`` are more ASP
        sources given as (name, text), e.g. ``("<stdin>", text)`` read from
        standard input; messages name them by that name.  A path that does not
        exist names a bundled model (``"trolley"``, ``"hera/trolley.yaml"``; the
        naming rule: :func:`ethasp.resources.bundled_model`).
        """
        from ethasp.planning.readers.hera_data import is_hera_file

        sources, naming = [], Naming()
        resolved = [model_path(path) for path in paths]
        files = [path for path in resolved if not is_hera_file(path)]
        situations = [path for path in resolved if is_hera_file(path)]
        if situations:  # (the readers of HERA's files imported only for them)
            from ethasp.planning.readers.hera import translate_file

            for path in situations:
                kind, text = translate_file(path, world)
                sources.append(Source(str(path), text, generated=True, kind=kind))
        if world and not any(source.kind == "cam" for source in sources):
            raise InputError(
                "a world (--world) gives the background variables and events of a causal "
                "agency model, and the model is none"
            )
        if any(path.suffix.lower() == ".pddl" for path in files):
            from ethasp.planning.readers.pddl import split_paths, translate_files

            pddl_paths, files = split_paths(files)
            try:
                program, name = translate_files(pddl_paths)
            except RecursionError:
                raise InputError(
                    f"{', '.join(map(str, pddl_paths))}: expressions nested too deeply to read"
                ) from None
            sources.append(
                Source(
                    name,
                    encoding("planning/pddl.lp").read_text() + program,
                    generated=True,
                    kind="pddl",
                )
            )
            naming = PddlNaming()
        for path in files:
            if path.suffix.lower() == ".hera":
                raise InputError(
                    f"{path}: HERA's text format (.hera) is not read; give the situation "
                    "or causal agency model as YAML or JSON, as HERA's examples are"
                )
            text = read_text(path)
            scan_file(path, text)
            sources.append(Source(str(path), text, path))
        for name, text in texts:
            scan_program(text, name)
            sources.append(Source(name, text))
        if not sources:
            raise InputError("no model file given")
        model = cls._build(sources, allow_scripts, check)
        model.naming = naming
        return model

    @classmethod
    def from_string(
        cls, text: str, name: str = "<model>", allow_scripts: bool = False, check: bool = True
    ) -> Model:
        """A model from ASP text."""
        scan_program(text, name)
        return cls._build([Source(name, text)], allow_scripts, check)

    @classmethod
    def _build(cls, sources: list[Source], allow_scripts: bool, check: bool) -> Model:
        model = cls(sources, allow_scripts)
        for source in sources:
            model._parse(source)
        if check:
            model.check()
        return model

    @property
    def is_pddl(self) -> bool:
        """Is this a PDDL task (a translation plus annotation files)?"""
        return any(source.kind == "pddl" for source in self.sources)

    @property
    def is_situation(self) -> bool:
        """Is this a HERA situation (a translation, perhaps with ASP files)?
        Its plans are judged even where they miss the goal, as HERA does."""
        return any(source.kind == "situation" for source in self.sources)

    @property
    def is_cam(self) -> bool:
        """Is this a causal agency model (HERA's CAM, perhaps with ASP files)?
        Its choices are its actions, one at a time (a plan of one step), judged
        by the encodings of ``encodings/cam/`` (:mod:`ethasp.principles.causal`)."""
        return any(source.kind == "cam" for source in self.sources)

    def require_planning(self, what: str) -> None:
        """Raise InputError if the model is a causal agency model: ``what``
        (plan search, validation, ...) applies to planning models."""
        if self.is_cam:
            names = ", ".join(source.name for source in self.sources if source.kind == "cam")
            raise InputError(
                f"{names} is a causal agency model: its choices are its actions, one at a "
                f"time (ethasp judge, query, ask); {what} applies to planning models"
            )

    def _parse(self, source: Source) -> None:
        """Parse a source: syntax, #script blocks, and the model's namespace
        (:mod:`ethasp.planning.driver.namespace`) for the files users write."""
        messages = Messages()
        scripts: list[str] = []
        namespace = None if source.generated else NamespaceCheck(pddl=self.is_pddl)

        def visit(statement):
            if statement.ast_type == ast.ASTType.Script:
                begin = statement.location.begin
                scripts.append(f"{begin.filename}:{begin.line}")
            elif namespace is not None:
                namespace(statement)

        try:
            if source.path is not None:
                ast.parse_files([str(source.path)], visit, logger=messages)
            else:
                ast.parse_string(
                    source.text, visit, logger=_renamed(messages, "<string>", source.name)
                )
        except RuntimeError:
            messages.raise_first(f"{source.name}: syntax error")
        if scripts and not self.allow_scripts:
            raise InputError(
                f"{scripts[0]}: the model contains a #script block, which would run code; "
                "it is refused (pass --allow-scripts to run it)"
            )

    # -- in other processes -------------------------------------------------------

    @property
    def key(self) -> str:
        """A fingerprint of the model's content (its sources, whether scripts
        run, its naming): the same in every process."""
        if self._key is None:
            digest = hashlib.sha256()
            digest.update(f"{self.allow_scripts} {type(self.naming).__name__}".encode())
            for source in self.sources:
                for part in (
                    source.name,
                    source.text,
                    str(source.path),
                    str(source.generated),
                    source.kind,
                    " ".join(map(str, source.facts)),
                ):
                    digest.update(len(part).to_bytes(8, "big"))
                    digest.update(part.encode("utf-8", "surrogateescape"))
            self._key = digest.hexdigest()
        return self._key

    def __reduce__(self):
        # A reference: resolved to the model the receiving process keeps (see
        # the module docstring).  This process keeps this one for the answer.
        _keep(self)
        return (_resolve, (self.key, tuple(self.sources), self.allow_scripts, self.naming))

    def grounded(self) -> bool:
        """Has this model been grounded in this process (a planner made)?"""
        return self._planner is not None

    # -- use --------------------------------------------------------------------

    def control(
        self, arguments: Sequence[str] = (), messages: Messages | None = None
    ) -> clingo.Control:
        """A fresh clingo control object holding the model (not yet grounded)."""
        if self.allow_scripts:
            clingo.script.enable_python()
        logger = messages or Messages()
        written = [
            source for source in self.sources if source.path is None and not source.generated
        ]
        if len(written) == 1:  # clingo calls a text source <block>
            logger = _renamed(logger, "<block>", written[0].name)
        ctl = clingo.Control(list(arguments), logger=logger, message_limit=20)
        for source in self.sources:
            if source.path is not None and _unchanged(source):
                ctl.load(str(source.path))
            elif source.text:  # (a file changed since it was read: the text read)
                ctl.add("base", [], source.text)
            if source.facts:
                with ctl.backend() as backend:
                    for fact in source.facts:
                        backend.add_rule([backend.add_atom(fact)])
        return ctl

    @classmethod
    def of_facts(
        cls, name: str, facts: Sequence[clingo.Symbol], naming: Naming, kind: str = "hmodel"
    ) -> Model:
        """A model made of ground facts that ethasp itself computed (an HModel):
        not parsed and not checked, as its facts come from a checked model."""
        return cls([Source(name, "", generated=True, kind=kind, facts=tuple(facts))], naming=naming)

    @property
    def planner(self) -> Planner:
        """The model's one grounding (:class:`ethasp.planning.driver.planner.Planner`),
        made on first use."""
        if self._planner is None:
            from ethasp.planning.driver.planner import Planner

            self._planner = Planner(self)
        return self._planner

    def check(self) -> None:
        """Raise InputError naming the first defect found by check.lp, or if the
        model's rules have no answer set or more than one (a model describes one
        planning task: a choice, a disjunction or a constraint in it would let the
        model vary with the searches of the encodings).  The model's planner
        grounds it once for this and for everything after."""
        planner = self.planner
        names = ", ".join(
            source.name for source in self.sources if not source.generated
        ) or ", ".join(source.name for source in self.sources)
        answers = planner.base_answers()
        for symbols in answers[:1]:
            if not symbols:
                break  # check.lp shows error/1 only: no defect
            from clorm import unify

            from ethasp.vocabulary import Error

            errors = sorted(
                error.problem.symbol for error in unify([Error], symbols).query(Error).all()
            )
            if errors:
                raise InputError(f"{names}: {_describe(errors[0])}")
        misspelt = misused_vocabulary(planner.signatures())
        if misspelt:
            raise InputError(f"{names}: {misspelt}")
        if not answers:
            raise InputError(
                f"{names}: the model's rules have no answer set (a constraint or "
                "a contradiction rules every one out), so it describes no "
                "planning task"
            )
        if len(answers) > 1:
            raise InputError(
                f"{names}: the model's rules have more than one answer set (a "
                "choice, a disjunction or a loop through negation); a model must "
                "describe one planning task"
            )
        self.checked = True

    def own_plan(self):
        """The plan the model comes with (``plan_length/1``, ``plan_step/2``: a
        HERA situation's), or None."""
        from ethasp.planning.plan import Plan

        if not self.planner.get("plan_length", 1):
            return None
        steps = sorted(
            (atom.arguments[0].number, atom.arguments[1])
            for atom in self.planner.get("plan_step", 2)
        )
        return Plan(tuple(action for _, action in steps))

    def facts(self, predicates):
        """The model's atoms of the given clorm predicates (its rules grounded
        once, by its planner), as a clorm FactBase."""
        return self.planner.facts(predicates)


def _unchanged(source: Source) -> bool:
    """Does the file of a source still hold the text read from it?  (A model
    is the text read when it was loaded, in every process that grounds it.)"""
    try:
        return source.path is not None and source.path.read_text(encoding="utf-8") == source.text
    except (OSError, UnicodeDecodeError, ValueError):
        return False


# The models this process keeps by key, the most recently used last (a warm
# worker keeps its model here between calls; a process that sends a model
# keeps that one, so that it comes back as itself).
KEPT = 4
_kept: OrderedDict[str, Model] = OrderedDict()
_kept_lock = threading.Lock()


def kept(model: Model) -> Model:
    """The model this process keeps for ``model``'s key: the one kept before,
    or else ``model`` itself, kept from now on (at most :data:`KEPT` models
    are kept, the least recently used goes)."""
    key = model.key
    with _kept_lock:
        known = _kept.get(key)
        if known is None:
            _kept[key] = known = model
            while len(_kept) > KEPT:
                _kept.popitem(last=False)
        _kept.move_to_end(key)
        return known


def _keep(model: Model) -> None:
    """Keep this model for its key (in place of one kept before)."""
    key = model.key
    with _kept_lock:
        _kept[key] = model
        _kept.move_to_end(key)
        while len(_kept) > KEPT:
            _kept.popitem(last=False)


def _resolve(key: str, sources: tuple[Source, ...], allow_scripts: bool, naming: Naming) -> Model:
    """A model that arrived from another process (see :meth:`Model.__reduce__`)."""
    with _kept_lock:
        known = _kept.get(key)
    if known is not None:
        return kept(known)
    return kept(Model(list(sources), allow_scripts, naming, _key=key))
