"""The model's namespace (ethasp.planning.driver.namespace): what the encodings
define or read is reserved, derived from the encodings themselves; a model
defines only its vocabulary and predicates of its own; no user text becomes
rule text."""

from __future__ import annotations

import inspect
from pathlib import Path

import clingo
import pytest
from clingo import ast
from clorm import Predicate
from conftest import ENCODINGS, MODELS

import ethasp.vocabulary
from ethasp import Model, Plan, query
from ethasp.errors import InputError
from ethasp.planning.driver.namespace import (
    MODEL_VOCABULARY,
    PDDL_VOCABULARY,
    TRANSLATION_ONLY,
    VOCABULARY,
    encoding_predicates,
    reserved,
)
from ethasp.planning.plan import parse_action
from ethasp.questions.dialogue import Dialogue
from ethasp.questions.question import Question

TROLLEY = (MODELS / "trolley.lp").read_text()


def head_signatures(path: Path) -> set[tuple[str, int]]:
    """The predicates in the heads of an encoding's rules (and its #external
    statements), read with clingo's parser independently of ethasp."""
    found: set[tuple[str, int]] = set()

    def atoms(node):
        if isinstance(node, ast.AST):
            if node.ast_type == ast.ASTType.SymbolicAtom:
                term = node.symbol
                if term.ast_type == ast.ASTType.UnaryOperation:
                    term = term.argument
                if term.ast_type == ast.ASTType.Function:
                    found.add((term.name, len(term.arguments)))
                elif term.ast_type == ast.ASTType.SymbolicTerm:
                    found.add((term.symbol.name, len(term.symbol.arguments)))
                return
            for key in node.child_keys:
                if key not in ("body", "condition"):
                    atoms(getattr(node, key))
        elif isinstance(node, (list, ast.ASTSequence)):
            for child in node:
                atoms(child)

    def visit(statement):
        if statement.ast_type == ast.ASTType.Rule:
            atoms(statement.head)
        elif statement.ast_type == ast.ASTType.External:
            atoms(statement.atom)

    ast.parse_files([str(path)], visit, logger=lambda code, message: None)
    return found


ENCODING_FILES = sorted(ENCODINGS.rglob("*.lp"))


@pytest.mark.parametrize("path", ENCODING_FILES, ids=lambda p: str(p.relative_to(ENCODINGS)))
def test_every_head_predicate_of_every_encoding_is_reserved(path):
    pddl_only = path.relative_to(ENCODINGS).as_posix() == "planning/pddl.lp"
    for signature in head_signatures(path):
        if signature in VOCABULARY and signature not in TRANSLATION_ONLY:
            continue
        assert signature in reserved(pddl=True), signature
        if not pddl_only and signature not in TRANSLATION_ONLY:
            assert signature in reserved(pddl=False), signature


def test_the_two_derivations_agree():
    """Grounding each encoding (fast, used for the check) and parsing it (used for
    messages) find the same predicates."""
    parsed = {signature for mentions in encoding_predicates().values() for signature in mentions}
    assert reserved(pddl=True) == frozenset(parsed - (set(VOCABULARY) - set(TRANSLATION_ONLY)))


def test_the_vocabulary_is_not_reserved_and_the_time_domain_is():
    assert set(VOCABULARY) & reserved(pddl=True) == set(TRANSLATION_ONLY)
    assert not set(VOCABULARY) & reserved(pddl=False)  # a saved translation may write them
    assert {("time", 1), ("step", 1), ("horizon", 1)} <= reserved()
    assert ("ceff", 4) in MODEL_VOCABULARY and ("cpre", 4) in MODEL_VOCABULARY
    assert set(PDDL_VOCABULARY) == {
        ("pddl_action", 1),
        ("pddl_subtype", 2),
        ("pddl_object", 2),
        ("pddl_add", 2),
        ("pddl_del", 2),
        ("pddl_candidate", 1),
        ("pddl_schema_instance", 1),
        ("pddl_static_failure", 3),
        ("pddl_static", 1),
        ("pddl_value", 2),
    }


def test_every_predicate_crossing_into_python_is_vocabulary_or_reserved():
    predicates = [getattr(ethasp.vocabulary, name) for name in ethasp.vocabulary.__all__]
    assert len(predicates) > 40
    for cls in predicates:
        if inspect.isclass(cls) and issubclass(cls, Predicate) and cls is not Predicate:
            signature = (cls.meta.name, cls.meta.arity)
            assert signature in VOCABULARY or signature in reserved(), signature


# -- what models may do ------------------------------------------------------------------

PLAUSIBLE = """
block(a;b;c). table(t). position(P) :- block(P). position(T) :- table(T).
on(a,t). on(b,a). on(c,t).
variable(on(X,Y)) :- block(X), position(Y), X != Y.
variable(clear(X)) :- position(X).
action(move(X,Y,Z)) :- block(X), position(Y), position(Z), X != Y, X != Z, Y != Z.
pre(move(X,Y,Z),on(X,Y),true) :- action(move(X,Y,Z)).
pre(move(X,Y,Z),clear(X),true) :- action(move(X,Y,Z)).
pre(move(X,Y,Z),clear(Z),true) :- action(move(X,Y,Z)), block(Z).
eff(move(X,Y,Z),on(X,Y),false) :- action(move(X,Y,Z)).
eff(move(X,Y,Z),on(X,Z),true) :- action(move(X,Y,Z)).
eff(move(X,Y,Z),clear(Y),true) :- action(move(X,Y,Z)), block(Y).
eff(move(X,Y,Z),clear(Z),false) :- action(move(X,Y,Z)), block(Z).
init(on(X,Y)) :- on(X,Y).
init(clear(X)) :- position(X), not on(_,X).
goal(on(a,b),true).
length(3). val(a,1,2). part(x). atom(y). sub(z). edge(a,b,c). target(t). harm(a,b). gain(a,b).
keep(a). flip(a). need(a,b). jump(a,b,c). touched(a,b). checked(a). opposite(a,b). about(a,b).
magnitude(a,b). nogood(a). shared(a). valued(a,b). primary(a,b,c,d). tv(a,b). actual(a,b).
neg(a). and(a,b). imp(a,b). good(a). bad(a). neutral(a). caused(a). geq(a).
utility(move(X,Y,Z),-1) :- action(move(X,Y,Z)), harm(X,_), X = a.
utility(V,true,1) :- fact(V,true), V = on(a,b).
#const n = 3.
#show on/2.
#defined occurs/2.
"""


def test_plausible_names_are_free_for_models():
    """Block worlds name block/1; ethics models name harm/2: the encodings' internal
    predicates have distinctive names, so these are the model's own."""
    model = Model.from_string(PLAUSIBLE)
    assert len(Plan.parse("move(b,a,t) move(a,t,b)")) == 2
    assert query(model, Plan.parse("move(b,a,t) move(a,t,b)"), "Caused(on(a,b))").value


@pytest.mark.parametrize(
    "text, message",
    [
        ("member(deontology, bad(action(refrain))).", "defines member/2"),
        ("weight(action(pull),-5).", "defines weight/2"),
        ("occurs(pull,1).", "defines occurs/2"),
        ("-holds(done,1).", "defines holds/2"),
        ("formula(query, all(empty)).", "defines formula/2"),
        ("conj(c(1),done,true).", "defines conj/3"),
        ("explain(deontology).", "defines explain/1"),
        ("satisfied(X) :- action(X).", "defines satisfied/1"),
        ("{ verdict(deontology,false) }.", "defines verdict/2"),
        ("verdict(deontology,false) | mine.", "defines verdict/2"),
        ("mine :- #sum{ 1 : holds(done,0) } > 0.", "reads holds/2"),
        ("#external best_utility(100).", "defines best_utility/1"),
        ("#show caused(done,true).", "shows caused/2"),
        ("#show final/2.", "shows final/2"),
        ("#show X : action(X).", "#show term X"),
        ("time(5).", "defines time/1"),
        (":- occurs(pull,_).", "reads occurs/2"),
        ("mine(X) :- final(X,true).", "reads final/2"),
        ("#minimize{ 1 : action(pull) }.", "optimisation statement"),
        ("#maximize{ 1 : action(pull) }.", "optimisation statement"),
        (":~ action(pull). [1@2]", "optimisation statement"),
        ("#heuristic action(pull). [1,true]", "#heuristic"),
        ("#project action/1.", "#project"),
        ("#project action(pull).", "#project"),
        ("#edge (a,b).", "#edge"),
        ("#program check(t).", "#program check"),
        ("#const true = false.", "constant true"),
        ("#const deontology = do_no_harm.", "constant deontology"),
        ("mine :- &diff{ a - b } <= 1.", "theory atom"),
        ("{ init(done) }.", "more than one answer set"),
        ("mine :- not other. other :- not mine.", "more than one answer set"),
        (":- action(pull).", "no answer set"),
        ("goal(done).", "goal/1 is not in the model vocabulary"),
        ("utility(pull,true,-1,x).", "utility/4 is not in the model vocabulary"),
    ],
)
def test_models_cannot_change_the_encodings(text, message):
    with pytest.raises(InputError, match=message.replace("(", r"\(").replace(")", r"\)")):
        Model.from_string(TROLLEY + "\n" + text + "\n", name="m.lp")


def test_the_issue_example_is_refused_with_its_place(tmp_path):
    model = tmp_path / "trolley.lp"
    model.write_text(TROLLEY + "member(deontology, bad(action(refrain))).\n")
    line = len(TROLLEY.splitlines()) + 1
    with pytest.raises(InputError) as error:
        Model.load([model])
    message = str(error.value)
    assert message.startswith(f"{model}:{line}: the model defines member/2")
    # (the first principle file that defines member/2)
    assert "defined by encodings/principles/" in message and "\n" not in message


def test_an_included_file_is_checked_where_it_is(tmp_path):
    (tmp_path / "extra.lp").write_text("mine.\nweight(action(pull),9).\n")
    model = tmp_path / "model.lp"
    model.write_text(TROLLEY + '#include "extra.lp".\n')
    with pytest.raises(InputError, match=r"extra\.lp:2: the model defines weight/2"):
        Model.load([model])


def test_pddl_typing_is_readable_by_annotations_and_reserved_for_them():
    assert ("has_type", 2) in reserved(pddl=True) and ("has_type", 2) not in reserved()
    pddl = MODELS / "pddl"
    Model.load(
        [
            pddl / "blocksworld-domain.pddl",
            pddl / "blocksworld-problem.pddl",
            pddl / "blocksworld-utility.lp",
        ]
    )
    # In an ASP model, object/1 is a name of the model's own.
    Model.from_string(TROLLEY + "object(ball).\n")


# -- no user text becomes rule text ---------------------------------------------------------

HOSTILE = [
    "a). evil :- b(",
    "pull). #show occurs/2. x(",
    "pull.\nmember(x,y)",
    "a :- b",
    "#script (python) import os #end",
    "f(X)",
    "a;b",
    "pull, refrain",
    "p :- q.",
    '"unterminated',
    "pull %* comment",
    "(a)) :- (b",
]


@pytest.mark.parametrize("text", [*HOSTILE, "", "   "])
def test_hostile_actions_are_not_terms(text):
    with pytest.raises(InputError):
        parse_action(text)


@pytest.mark.parametrize("text", HOSTILE)
def test_hostile_plans_formulas_and_questions_are_refused(text, trolley_path):
    model = Model.load([trolley_path])
    if text == "a;b":  # a plan of two actions: plans may separate actions by semicolons
        assert Plan.parse(text).to_list() == ["a", "b"]
    else:
        with pytest.raises(InputError):
            Plan.parse(text)
    with pytest.raises(InputError):
        query(model, Plan.parse("pull"), f"Good({text})")
    with pytest.raises(InputError):
        Dialogue.start(model, "deontology", Plan.parse("pull")).ask(Question("why", text))


def test_a_saved_dialogue_cannot_inject_rules(trolley_path, tmp_path):
    model = Model.load([trolley_path])
    data = Dialogue.start(model, "deontology", Plan.parse("pull")).to_json()
    data["plan"] = ["pull). evil :- b("]
    with pytest.raises(InputError, match="not an action term"):
        Dialogue.from_json(data, model)


def test_facts_reach_clingo_as_symbols_not_text(trolley_path):
    """A term whose name is rule text stays one atom (it is never printed and re-read)."""
    model = Model.load([trolley_path])
    odd = clingo.Function("a). evil :- b(", [])
    ctl = model.planner.program(["planning/model.lp"], symbols=[clingo.Function("mine", [odd])])
    names = {atom.symbol.name for atom in ctl.symbolic_atoms}
    assert "evil" not in names and "mine" in names


def test_the_encodings_predicates_are_kept_per_content_of_the_encodings(tmp_path, monkeypatch):
    """Grounding every encoding alone (to learn what it mentions) happens once
    per content of the encodings: the result is kept in the cache folder,
    read back at the next start, and recomputed when the file is unreadable."""
    from ethasp.planning.driver import namespace

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    namespace._all_mentioned.cache_clear()
    try:
        first = namespace._all_mentioned()
        (cache,) = (tmp_path / "ethasp").glob("namespace-*.json")
        for name in ("planning/transition.lp", "restrictions/do_no_harm.lp"):
            assert first[name] == namespace._ground_alone(name)
        namespace._all_mentioned.cache_clear()
        grounded = []
        monkeypatch.setattr(
            namespace, "_ground_alone", lambda name: grounded.append(name) or frozenset()
        )
        assert namespace._all_mentioned() == first and grounded == []  # read back
        cache.write_text("{not json")
        namespace._all_mentioned.cache_clear()
        namespace._all_mentioned()
        assert len(grounded) == len(first)  # recomputed
    finally:
        namespace._all_mentioned.cache_clear()
