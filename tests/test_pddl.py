"""PDDL input: names, translation into lifted rules, refused features, commands."""

from __future__ import annotations

import itertools
import json
import os
import re
import subprocess
import sys

import clingo
import pytest
from conftest import ENCODINGS, MODELS, ROOT
from hypothesis import given
from hypothesis import strategies as st

from ethasp import InputError, Model, Plan, find_plan, validate
from ethasp.planning.naming import (
    ASP_NAME,
    PddlNaming,
    asp_name_to_pddl,
    pddl_atom_to_term,
    pddl_name_to_asp,
    term_to_pddl,
)
from ethasp.planning.readers.pddl import PddlFile, translate

PDDL = MODELS / "pddl"
TROLLEY_PDDL = [
    str(PDDL / "trolley-domain.pddl"),
    str(PDDL / "trolley-problem.pddl"),
    str(PDDL / "trolley-utility.lp"),
]
VOCABULARY = ("variable", "action", "pre", "eff", "init", "goal", "utility")


def ethasp(*args: str, cwd=ROOT) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
    )


def translated(domain: str, problem: str) -> str:
    return translate(PddlFile("d.pddl", domain.lower()), PddlFile("p.pddl", problem.lower()))


def ground_model(program: str) -> dict[str, set[str]]:
    """The atoms of the model vocabulary after grounding pddl.lp + model.lp + program."""
    ctl = clingo.Control(logger=lambda code, message: None)
    ctl.load(str(ENCODINGS / "planning/pddl.lp"))
    ctl.load(str(ENCODINGS / "planning/model.lp"))
    ctl.add("base", [], program)
    ctl.ground([("base", [])])
    atoms: dict[str, set[str]] = {name: set() for name in (*VOCABULARY, "has_type")}
    for atom in ctl.symbolic_atoms:
        assert atom.is_fact, atom.symbol
        if atom.symbol.name in atoms:
            atoms[atom.symbol.name].add(str(atom.symbol))
    return atoms


def model_atoms(model: Model) -> dict[str, set[str]]:
    ctl = model.control()
    ctl.load(str(ENCODINGS / "planning/model.lp"))
    ctl.ground([("base", [])])
    atoms: dict[str, set[str]] = {name: set() for name in VOCABULARY}
    for atom in ctl.symbolic_atoms:
        if atom.symbol.name in atoms:
            atoms[atom.symbol.name].add(str(atom.symbol))
    return atoms


# -- names ------------------------------------------------------------------------


@pytest.mark.slow
@given(st.from_regex(r"[A-Za-z][-_A-Za-z0-9]{0,12}", fullmatch=True))
def test_name_rule_round_trip(name):
    asp = pddl_name_to_asp(name)
    assert ASP_NAME.fullmatch(asp)
    assert clingo.parse_term(asp) == clingo.Function(asp)
    assert asp_name_to_pddl(asp) == name.lower()
    assert pddl_name_to_asp(asp_name_to_pddl(asp)) == asp


def test_name_rule_examples():
    assert pddl_name_to_asp("Five-Will-Die") == "five_will_die"
    assert pddl_name_to_asp("pick_up") == "pick'up"
    assert pddl_name_to_asp("a-_b") != pddl_name_to_asp("a_-b")
    assert asp_name_to_pddl("room_1") == "room-1"
    for bad in ("1st", "-a", "a b", ""):
        with pytest.raises(InputError):
            pddl_name_to_asp(bad)


def test_atoms_and_terms():
    term = pddl_atom_to_term("(Push Man Foot-Bridge)")
    assert term == clingo.parse_term("push(man,foot_bridge)")
    assert term_to_pddl(term) == "(push man foot-bridge)"
    assert pddl_atom_to_term("(refrain)") == clingo.Function("refrain")
    naming = PddlNaming()
    assert naming.fact("-five_will_die") == "(not (five-will-die))"
    assert naming.actions(Plan.parse("(pull) go(a,room_2)")) == "(pull) (go a room-2)"
    for bad in ("(push", "()", "(a (b))"):
        with pytest.raises(InputError):
            Plan.parse(bad)


# -- translation (encoding level) -------------------------------------------------

ROOMS_DOMAIN = """
(define (domain Rooms)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types room agent - object robot - agent)
  (:constants Hall - room)
  (:predicates (at ?a - agent ?r - room) (Lights-On) (link ?x ?y - room) (visited ?x))
  (:action Go
    :parameters (?a - robot ?from ?to - room)
    :precondition (and (at ?a ?from) (link ?from ?to) (not (= ?from ?to)) (not (lights-on)))
    :effect (and (not (at ?a ?from)) (at ?a ?to) (visited ?to)))
  (:action stay
    :parameters (?a - agent ?r - room)
    :precondition (and (= ?r hall) (at ?a ?r))
    :effect (and (not (at ?a ?r)) (at ?a ?r)))
  (:action switch :parameters () :effect (lights-on)))
"""

ROOMS_PROBLEM = """
(define (problem two) (:domain rooms)
  (:objects kitchen - room r2-d2 - robot ann - agent)
  (:init (at r2-d2 hall) (link hall kitchen) (link kitchen hall))
  (:goal (and (at r2-d2 kitchen) (not (lights-on)))))
"""


def test_translation_is_lifted():
    program = translated(ROOMS_DOMAIN, ROOMS_PROBLEM)
    assert (
        "pddl_action(go(A,From,To)) :- has_type(A,robot), has_type(From,room), "
        "has_type(To,room), From != To, init(link(From,To))." in program
    )
    assert "pre(go(A,From,To),at(A,From),true) :- pddl_action(go(A,From,To))." in program
    assert "variable(at(A,R)) :- has_type(A,agent), has_type(R,room)." in program
    # no action instance is written out: clingo grounds the rules
    assert not re.search(r"action\(go\([a-z]", program)


def test_translation_grounds_to_the_model():
    atoms = ground_model(translated(ROOMS_DOMAIN, ROOMS_PROBLEM))
    assert {
        "has_type(r2_d2,robot)",
        "has_type(r2_d2,agent)",
        "has_type(r2_d2,object)",
        "has_type(hall,room)",
        "has_type(ann,agent)",
    } <= atoms["has_type"]
    assert "has_type(ann,robot)" not in atoms["has_type"]
    agents, rooms = ["ann", "r2_d2"], ["hall", "kitchen"]
    # link/2 is static: its atoms are variables where the task uses them (the
    # initial state here; no action exists whose link precondition fails).
    assert atoms["variable"] == (
        {f"variable(at({a},{r}))" for a in agents for r in rooms}
        | {"variable(link(hall,kitchen))", "variable(link(kitchen,hall))"}
        | {f"variable(visited({x}))" for x in agents + rooms}
        | {"variable(lights_on)"}
    )
    assert atoms["action"] == {
        "action(go(r2_d2,hall,kitchen))",
        "action(go(r2_d2,kitchen,hall))",
        "action(stay(ann,hall))",
        "action(stay(r2_d2,hall))",
        "action(switch)",
    }
    assert {
        "pre(go(r2_d2,hall,kitchen),at(r2_d2,hall),true)",
        "pre(go(r2_d2,hall,kitchen),link(hall,kitchen),true)",
        "pre(go(r2_d2,hall,kitchen),lights_on,false)",
    } <= atoms["pre"]
    assert len(atoms["pre"]) == 2 * 3 + 2
    assert {
        "eff(go(r2_d2,hall,kitchen),at(r2_d2,hall),false)",
        "eff(go(r2_d2,hall,kitchen),at(r2_d2,kitchen),true)",
        "eff(go(r2_d2,hall,kitchen),visited(kitchen),true)",
        "eff(switch,lights_on,true)",
    } <= atoms["eff"]
    # an atom both deleted and added is added, as in PDDL
    assert "eff(stay(ann,hall),at(ann,hall),true)" in atoms["eff"]
    assert "eff(stay(ann,hall),at(ann,hall),false)" not in atoms["eff"]
    assert atoms["init"] == {
        "init(at(r2_d2,hall))",
        "init(link(hall,kitchen))",
        "init(link(kitchen,hall))",
    }
    assert atoms["goal"] == {"goal(at(r2_d2,kitchen),true)", "goal(lights_on,false)"}


def test_translated_model_passes_the_check_and_plans():
    model = Model.from_string(
        (ENCODINGS / "planning/pddl.lp").read_text() + translated(ROOMS_DOMAIN, ROOMS_PROBLEM)
    )
    result = find_plan(model)
    assert result.status == "found" and str(result.plan) == "go(r2_d2,hall,kitchen)"


def test_bundled_blocksworld_action_count():
    model = Model.load([PDDL / "blocksworld-domain.pddl", PDDL / "blocksworld-problem.pddl"])
    actions = model_atoms(model)["action"]
    # pick-up, put-down: 4 each; unstack, knock-off: 16 each; stack: 12 (x != y)
    assert len(actions) == 4 + 4 + 16 + 16 + 12
    assert "action(knock_off(d,c))" in actions and "action(stack(a,a))" not in actions


# -- refused features and bad input -----------------------------------------------

DOMAIN_TEMPLATE = """(define (domain d)
  (:requirements :strips :typing :negative-preconditions :equality {requirements})
  (:types thing)
  {extra}
  (:predicates (p ?x - thing) (q ?x - thing))
  (:action a :parameters (?x - thing)
    :precondition {pre}
    :effect {eff}))
"""
PROBLEM = "(define (problem p) (:domain d) (:objects o - thing) (:init (p o)) (:goal (q o)))"


def domain(pre="(p ?x)", eff="(q ?x)", extra="", requirements=""):
    return DOMAIN_TEMPLATE.format(pre=pre, eff=eff, extra=extra, requirements=requirements)


UNSUPPORTED = [
    (
        domain(
            extra="(:functions (fuel) - number)",
            pre="(> (fuel) 1)",
            requirements=":numeric-fluents",
        ),
        "numeric comparisons (>)",
    ),
    (
        domain(
            extra="(:functions (fuel) - number)",
            eff="(and (q ?x) (increase (fuel) 1))",
            requirements=":numeric-fluents",
        ),
        "numeric effects (increase)",
    ),
    (
        domain(
            extra="(:functions (fuel) - number)",
            eff="(decrease (fuel) 1)",
            requirements=":numeric-fluents",
        ),
        "numeric effects (decrease)",
    ),
    (
        domain(
            extra="(:functions (fuel) - number)",
            pre="(= (fuel) 1)",
            requirements=":numeric-fluents",
        ),
        "numeric fluents (= on a function)",
    ),
    (domain(eff="(oneof (q ?x) (p ?x))"), "non-deterministic effects (oneof)"),
    (domain().replace(":action a", ":durative-action a"), "durative actions"),
    (domain().replace("(:action a", "(:process a"), "processes"),
    (domain().replace("(:action a", "(:event a"), "events"),
    (domain(extra="(:constraints (always (p o)))"), "constraints"),
    (domain(pre="(preference p1 (p ?x))"), "preferences"),
    (domain(requirements=":durative-actions"), ":durative-actions"),
    (domain(requirements=":timed-initial-literals"), ":timed-initial-literals"),
]


@pytest.mark.parametrize("text,feature", UNSUPPORTED)
def test_unsupported_features_are_named(tmp_path, text, feature):
    (tmp_path / "d.pddl").write_text(text)
    (tmp_path / "p.pddl").write_text(PROBLEM)
    with pytest.raises(InputError) as error:
        Model.load([tmp_path / "d.pddl", tmp_path / "p.pddl"])
    message = str(error.value)
    assert feature in message and "\n" not in message
    assert message.startswith(str(tmp_path / "d.pddl"))


def test_the_template_itself_is_supported(tmp_path):
    (tmp_path / "d.pddl").write_text(
        domain(pre="(and (p ?x) (not (q ?x)) (= ?x o))").replace(
            "(:types thing)", "(:types thing) (:constants o - thing)"
        )
    )
    (tmp_path / "p.pddl").write_text(PROBLEM.replace("(:objects o - thing)", ""))
    model = Model.load([tmp_path / "p.pddl", tmp_path / "d.pddl"])
    assert str(find_plan(model).plan) == "a(o)"


@pytest.mark.parametrize(
    "text,needle",
    [
        (domain().replace("(:action a", "(:action a ("), "d.pddl:6:14: syntax error"),
        (domain()[:-4], "unexpected end of file"),
        (domain(pre="(and (p ?x) (q ?y))"), "unknown variable ?y"),
        ("(define (problem x) (:domain d) (:init) (:goal (and)))", "one domain file"),
        ("hello", "not a PDDL domain or problem"),
    ],
)
def test_bad_pddl_is_one_input_error(tmp_path, text, needle):
    (tmp_path / "d.pddl").write_text(text)
    (tmp_path / "p.pddl").write_text(PROBLEM)
    with pytest.raises(InputError) as error:
        Model.load([tmp_path / "d.pddl", tmp_path / "p.pddl"])
    assert needle in str(error.value) and "\n" not in str(error.value)


def test_problem_for_another_domain(tmp_path):
    (tmp_path / "d.pddl").write_text(domain())
    (tmp_path / "p.pddl").write_text(PROBLEM.replace("(:domain d)", "(:domain other)"))
    with pytest.raises(InputError, match="for domain other"):
        Model.load([tmp_path / "d.pddl", tmp_path / "p.pddl"])


def test_command_line_errors_are_one_line_with_exit_code_2(tmp_path):
    (tmp_path / "d.pddl").write_text(domain(eff="(oneof (p ?x) (q ?x))"))
    (tmp_path / "broken.pddl").write_text(domain().replace("(:types", "(:types (", 1))
    (tmp_path / "p.pddl").write_text(PROBLEM)
    for files, needle in [
        (
            ["d.pddl", "p.pddl"],
            "d.pddl:8: unsupported PDDL feature: non-deterministic effects (oneof)",
        ),
        (["broken.pddl", "p.pddl"], "broken.pddl:3:"),
        (["p.pddl"], "one domain file"),
    ]:
        run = ethasp("plan", *files, cwd=tmp_path)
        assert run.returncode == 2 and needle in run.stderr, run.stderr
        assert len(run.stderr.strip().splitlines()) == 1 and "Traceback" not in run.stderr


# -- commands ---------------------------------------------------------------------


def test_plan_prints_pddl_and_json_keeps_terms():
    run = ethasp("plan", *TROLLEY_PDDL, "--all")
    assert run.returncode == 0, run.stderr
    assert "(pull)" in run.stdout and "(refrain)" in run.stdout
    run = ethasp("plan", "care-domain.pddl", "care-problem.pddl", "care-utility.lp", "--json")
    assert run.returncode == 0, run.stderr
    plan = json.loads(run.stdout)["plan"]
    assert plan[0] == "pick_up(pills_bob,kitchen)" and len(plan) == 4
    run = ethasp("plan", "care-domain.pddl", "care-problem.pddl", "care-utility.lp")
    assert "plan of 4 steps: (pick-up pills-bob kitchen) (move kitchen hall)" in run.stdout


def test_validate_accepts_both_forms_and_reports_in_pddl(tmp_path):
    files = [str(PDDL / "care-domain.pddl"), str(PDDL / "care-problem.pddl")]
    pddl_form = (
        "(move kitchen hall) (move hall corridor-1) (move corridor-1 corridor-2) "
        "(move corridor-2 store-room) (pick-up pills-ann store-room) "
        "(move store-room corridor-2) (move corridor-2 corridor-1) "
        "(move corridor-1 hall) (move hall living-room) (give pills-ann ann living-room)"
    )
    run = ethasp("validate", *files, "--plan", pddl_form)
    assert run.returncode == 0 and "valid plan of 10 steps" in run.stdout, run.stdout
    assert "(treated ann)" in run.stdout
    asp_form = "move(kitchen,hall) move(hall,bedroom)"
    run = ethasp("validate", *files, "--plan", asp_form)
    assert run.returncode == 2
    assert (
        "step 2: action (move hall bedroom) is not applicable: precondition "
        "(not (sleeping-in bedroom)) does not hold and no action changes it"
    ) in run.stdout
    run = ethasp("validate", *files, "--plan", "(move kitchen hall)", "--json")
    data = json.loads(run.stdout)
    assert data["plan"] == ["move(kitchen,hall)"] and data["unmet_goals"] == ["treated(ann)"]


def test_bundled_pddl_by_name_from_another_directory(tmp_path):
    run = ethasp(
        "plan",
        "gripper-domain.pddl",
        "gripper-problem.pddl",
        "gripper-utility.lp",
        "--json",
        cwd=tmp_path,
    )
    assert run.returncode == 0, run.stderr
    assert len(json.loads(run.stdout)["plan"]) == 8


@pytest.mark.parametrize(
    "name,length", [("blocksworld", 7), ("gripper", 8), ("care", 4), ("trolley", 1)]
)
def test_bundled_examples_plan_and_validate(name, length):
    model = Model.load(
        [PDDL / f"{name}-domain.pddl", PDDL / f"{name}-problem.pddl", PDDL / f"{name}-utility.lp"]
    )
    assert isinstance(model.naming, PddlNaming)
    result = find_plan(model)
    assert result.status == "found" and len(result.plan) == length
    assert validate(model, result.plan).valid
    shown = Plan.parse(model.naming.actions(result.plan))
    assert shown == result.plan


# -- the PDDL trolley is the ASP trolley ------------------------------------------


def test_trolley_models_agree():
    asp = Model.load([MODELS / "trolley.lp"])
    pddl = Model.load(TROLLEY_PDDL)
    assert model_atoms(asp) == model_atoms(pddl)


def test_trolley_plans_and_validation_agree():
    asp = Model.load([MODELS / "trolley.lp"])
    pddl = Model.load(TROLLEY_PDDL)
    plans = [set(find_plan(model, all_plans=True).plans) for model in (asp, pddl)]
    assert plans[0] == plans[1] and len(plans[0]) == 2
    for length in range(3):
        for actions in itertools.product(["pull", "refrain"], repeat=length):
            plan = Plan.parse(" ".join(actions))
            assert validate(asp, plan) == validate(pddl, plan)


def _without_plan(data):
    """A JSON answer minus the fields that name the model's files."""
    return {key: value for key, value in data.items() if key not in ("model", "files")}


_PDDL_FACT = re.compile(r"\(not \(([a-z][-a-z0-9]*)\)\)|\(([a-z][-a-z0-9]*)\)")
_REASONS = ("sufficient_reasons", "necessary_reasons", "inus_reasons", "chosen_reason")


def _asp_reasons(data):
    """A JSON answer of a PDDL task with its reasons' PDDL atoms written as ASP
    terms (``Bad((one-will-die))`` as ``Bad(one_will_die)``), for comparing
    with the same model written in ASP (nullary atoms only)."""

    def asp(match):
        negative, positive = match.groups()
        return f"-{negative.replace('-', '_')}" if negative else positive.replace("-", "_")

    def walk(value, reasons=False):
        if isinstance(value, dict):
            return {key: walk(item, key in _REASONS) for key, item in value.items()}
        if isinstance(value, list):
            return [walk(item, reasons) for item in value]
        return _PDDL_FACT.sub(asp, value) if reasons and isinstance(value, str) else value

    return walk(data)


def test_trolley_verdicts_agree():
    for asp_plan, pddl_plan in [("pull", "(pull)"), ("refrain", "(refrain)")]:
        asp = ethasp("judge", str(MODELS / "trolley.lp"), "--plan", asp_plan, "--json")
        pddl = ethasp("judge", *TROLLEY_PDDL, "--plan", pddl_plan, "--json")
        assert asp.returncode == 0 and pddl.returncode == 0, (asp.stderr, pddl.stderr)
        # The same verdicts, reasons and words; the PDDL task's reasons in PDDL names.
        assert "Caused((one-will-die))" in pddl.stdout or "Caused((five-will-die))" in pddl.stdout
        assert _without_plan(json.loads(asp.stdout)) == _asp_reasons(
            _without_plan(json.loads(pddl.stdout))
        )
    run = ethasp("judge", *TROLLEY_PDDL, "--plan", "(pull)")
    # The final state of a PDDL task: the atoms that hold (closed world).
    assert run.returncode == 0 and "final state: (done) (one-will-die) (utility" in run.stdout


def test_query_and_principled_plan_on_pddl():
    run = ethasp("query", *TROLLEY_PDDL, "Caused(one_will_die)", "--plan", "(pull)")
    assert run.returncode == 0 and run.stdout.strip() == "true", run.stderr
    asp = ethasp("plan", str(MODELS / "trolley.lp"), "--principle", "do-no-harm", "--json")
    pddl = ethasp("plan", *TROLLEY_PDDL, "--principle", "do-no-harm", "--json")
    assert json.loads(asp.stdout) == _asp_reasons(json.loads(pddl.stdout))
    assert json.loads(pddl.stdout)["plan"] == ["refrain"]


UNTYPED = """
(define (domain hands)
  (:predicates (ball ?b) (hand ?h) (free ?h) (holds ?h ?b) (on-floor ?b) (near ?b ?h))
  (:action grab :parameters (?h ?b)
    :precondition (and (hand ?h) (ball ?b) (free ?h) (on-floor ?b) (near ?b ?h))
    :effect (and (holds ?h ?b) (not (free ?h)) (not (on-floor ?b)))))
"""

UNTYPED_PROBLEM = """
(define (problem two) (:domain hands)
  (:objects left b1 b2)
  (:init (hand left) (ball b1) (ball b2) (free left) (on-floor b1) (on-floor b2) (near b1 left))
  (:goal (holds left b1)))
"""


def test_static_predicates_decide_which_actions_exist():
    """A predicate that no action changes is static: it holds in every state
    exactly when it holds initially.  A precondition on one (of any arity,
    positive or negative) decides which actions exist, as a type does (untyped
    domains write types so: (ball ?b)); pre/3 keeps it, for reasons and words.
    A changed predicate (free, on-floor) stays a precondition only."""
    program = translated(UNTYPED, UNTYPED_PROBLEM)
    assert (
        "pddl_action(grab(H,B)) :- has_type(H,object), has_type(B,object), "
        "init(hand(H)), init(ball(B)), init(near(B,H))."
    ) in program
    assert "pre(grab(H,B),near(B,H),true) :- pddl_action(grab(H,B))." in program
    assert "pre(grab(H,B),free(H),true) :- pddl_action(grab(H,B))." in program
    actions = ground_model(program)["action"]
    assert actions == {"action(grab(left,b1))"}


def test_negative_static_preconditions_decide_which_actions_exist():
    domain = UNTYPED.replace("(near ?b ?h))\n    :effect", "(not (near ?b ?h)))\n    :effect")
    program = translated(domain, UNTYPED_PROBLEM)
    assert "not init(near(B,H))" in program
    assert "pre(grab(H,B),near(B,H),false) :- pddl_action(grab(H,B))." in program
    assert ground_model(program)["action"] == {"action(grab(left,b2))"}


LINKED = """
(define (domain links)
  (:requirements :adl :derived-predicates)
  (:predicates (link ?x ?y) (on ?x) (lit ?x))
  (:derived (lit ?x) (exists (?y) (and (link ?y ?x) (on ?y))))
  (:action switch :parameters (?x) :precondition (forall (?y) (imply (link ?y ?x) (lit ?y)))
    :effect (on ?x)))
"""

LINKED_PROBLEM = """
(define (problem three) (:domain links)
  (:objects a b c)
  (:init (link a b) (link b c) (on a))
  (:goal (on c)))
"""


@pytest.mark.parametrize(
    "annotation",
    [
        "pddl_static(free(left)).",  # a changed atom called static
        "pddl_candidate(grab(left,b2)).",
        "pddl_static_failure(grab(left,b2),near(b2,left),true).",  # changing validation's words
        "pddl_schema_instance(grab(left,b2)).",
    ],
)
def test_what_only_the_translation_writes_is_reserved(tmp_path, annotation):
    """The atoms the pruning trusts and the rules validation explains with are
    the translation's: an annotation file defining them is refused."""
    files = []
    for name, text in (("d.pddl", UNTYPED), ("p.pddl", UNTYPED_PROBLEM), ("extra.lp", annotation)):
        (tmp_path / name).write_text(text)
        files.append(str(tmp_path / name))
    with pytest.raises(InputError, match=r"extra.lp:1: the model defines pddl_"):
        Model.load(files)


def test_static_literals_decide_which_axioms_exist(tmp_path):
    """As for actions: an axiom instance (of a derived predicate, or of the
    auxiliary variable of a quantified precondition) whose literal on a static
    predicate fails initially never holds, so it is not written."""
    program = translated(LINKED, LINKED_PROBLEM)
    assert "init(link(Y,X))" in program
    ground = clingo.Control(logger=lambda code, message: None)
    for name in ("planning/pddl.lp", "planning/model.lp"):
        ground.load(str(ENCODINGS / name))
    ground.add("base", [], program)
    ground.ground([("base", [])])
    axioms = sorted(str(atom.symbol) for atom in ground.symbolic_atoms.by_signature("axiom", 2))
    # one instance per link (of 9 pairs), for lit/1 and for the auxiliary
    # variable of switch's forall (a link into its object from a dark one)
    assert axioms == [
        "axiom(formula_1(b),(1,a))",
        "axiom(formula_1(c),(1,b))",
        "axiom(lit(b),(1,1,a))",
        "axiom(lit(c),(1,1,b))",
    ], axioms
    files = []
    for name, text in (("d.pddl", LINKED), ("p.pddl", LINKED_PROBLEM)):
        (tmp_path / name).write_text(text)
        files.append(tmp_path / name)
    result = find_plan(Model.load(files))  # switch c: lit(b) holds (a is on)
    assert result.status == "found" and [str(a) for a in result.plan] == ["switch(c)"]


def test_a_changed_predicate_is_not_static():
    """An effect, even a conditional one, makes a predicate not static."""
    domain = UNTYPED.replace(
        "(not (on-floor ?b)))))", "(not (on-floor ?b)) (when (free ?h) (near ?b ?h)))))"
    )
    program = translated(domain, UNTYPED_PROBLEM)
    assert "init(near(B,H))" not in program
    assert ground_model(program)["action"] == {"action(grab(left,b1))", "action(grab(left,b2))"}


@pytest.mark.parametrize(
    "annotation",
    [
        "eff(grab(left,b2),near(b2,left),true).",
        "ceff(grab(left,b1),k,near(b2,left),true). cpre(grab(left,b1),k,free(left),true).",
        "action(push(b2)). eff(push(b2),near(b2,left),true).",
        "pddl_add(grab(left,b1),ball(left)).",
    ],
)
def test_an_annotation_that_changes_a_static_atom_is_refused(tmp_path, annotation):
    """Pruning by static preconditions trusts that no action changes them: an
    annotation file's effect on a static atom (here near(b2,left), which would
    make grab(left,b2) applicable, though the translation dropped it) is
    refused with one line, never planned with silently."""
    files = []
    for name, text in (("d.pddl", UNTYPED), ("p.pddl", UNTYPED_PROBLEM), ("extra.lp", annotation)):
        (tmp_path / name).write_text(text)
        files.append(str(tmp_path / name))
    with pytest.raises(InputError, match="which no action of the PDDL domain changes"):
        Model.load(files)
    run = ethasp("plan", *files)
    assert run.returncode == 2 and len(run.stderr.strip().splitlines()) == 1, run.stderr
    assert "no action of the PDDL domain changes" in run.stderr
    # an effect on a changed predicate, and a fact on a static one, are fine
    (tmp_path / "extra.lp").write_text(
        "init(near(b2,left)). eff(grab(left,b1),on_floor(b2),false)."
    )
    assert find_plan(Model.load(files)).status == "found"


def test_validation_names_a_failing_static_precondition():
    """An instance of an action schema whose static precondition fails is no
    action; validating a plan that names it says which precondition fails."""
    model = Model.load([PDDL / "care-domain.pddl", PDDL / "care-problem.pddl"])
    result = validate(model, Plan.parse("(move kitchen hall) (move hall bedroom)"))
    assert not result.valid and result.static
    assert (result.failure_step, result.failure_action) == (2, "move(hall,bedroom)")
    assert result.unmet_preconditions == ["-sleeping_in(bedroom)"]
    assert result.message(model.naming) == (
        "step 2: action (move hall bedroom) is not applicable: precondition "
        "(not (sleeping-in bedroom)) does not hold and no action changes it"
    )
    # (door kitchen store-room) is false initially and no action changes it
    result = validate(model, Plan.parse("(move kitchen store-room)"))
    assert result.failure_step == 1 and result.unmet_preconditions == ["door(kitchen,store_room)"]
    # an earlier step that fails a precondition comes first
    result = validate(model, Plan.parse("(move hall kitchen) (move hall bedroom)"))
    assert result.failure_step == 1 and not result.static
    for plan in (
        "(move kitchen kitchen)",
        "(fly kitchen)",
        "(move kitchen pills-ann)",
        "(move kitchen hall) (move hall bedroom) (fly kitchen)",
    ):
        with pytest.raises(InputError, match="unknown action"):
            validate(model, Plan.parse(plan))


def test_a_question_naming_an_action_that_never_applies_says_why():
    from ethasp.questions.contrast import check_question
    from ethasp.questions.question import Question

    model = Model.load([PDDL / "care-domain.pddl", PDDL / "care-problem.pddl"])
    plan = Plan.parse("(move kitchen hall)")
    with pytest.raises(
        InputError,
        match=r"action \(move hall bedroom\) never applies: "
        r"precondition \(not \(sleeping-in bedroom\)\) does "
        "not hold and no action changes it",
    ):
        check_question(model, Question.parse("why not (move hall bedroom)"), plan)
    with pytest.raises(InputError, match=r"unknown action \(fly hall\)"):
        check_question(model, Question.parse("why not (fly hall)"), plan)
