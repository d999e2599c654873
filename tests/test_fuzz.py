"""Fuzzing: mutated models, PDDL files, formulas and questions, through every
command.  Whatever the input, ethasp answers (exit 0, a valid JSON answer) or
refuses it (exit 2, one line on standard error), never prints a traceback,
and never runs on past its time limit.

Mutations are byte edits (delete, insert, replace a character), token edits
(delete, duplicate, swap, replace a token; numbers at clingo's limits) and
splices (a fact or a rule of a reserved predicate, a line of an encoding).
Every run gets a small --time-limit and --max-horizon.  The example counts
are kept small for CI; ETHASP_FUZZ_SCALE=20 (say) multiplies them for a longer
campaign.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import re
import sys
import threading

import pytest
from conftest import ENCODINGS, MODELS
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ethasp.interfaces.cli import main
from ethasp.planning.driver.namespace import reserved

pytestmark = pytest.mark.slow  # every test of this file runs ethasp many times

LIMITS = ["--time-limit", "2", "--max-horizon", "3"]
# A guard against hangs (not a measure of speed): far beyond the time limit and
# the CLI's own end for commands that overrun it.
HANG = 120.0

ASP_MODELS = {path.stem: path.read_text() for path in sorted(MODELS.glob("*.lp"))}
PLANS = {
    "trolley": "pull",
    "footbridge": "push",
    "heist": "",
    "rescue": "",
    "lightning": "drop_match",
    "errand": "drive hand_over",
    "trolley-alarm": "",
}
ACTIONS = {
    "trolley": ["pull", "refrain"],
    "footbridge": ["push", "refrain"],
    "heist": ["stage_heist", "buy_flowers"],
    "rescue": ["take_key", "break_door"],
    "lightning": ["drop_match", "keep_match"],
    "errand": ["drive", "cross_lawn"],
    "trolley-alarm": ["alarm", "pull"],
}
PDDL = {path.name: path.read_text() for path in sorted((MODELS / "pddl").glob("*"))}
PDDL_TASKS = [("trolley", "(pull)"), ("care", ""), ("blocksworld", ""), ("gripper", "")]
ENCODING_LINES = [
    line
    for path in sorted(ENCODINGS.rglob("*.lp"))
    for line in path.read_text().splitlines()
    if line.strip() and not line.lstrip().startswith("%")
]
RESERVED = sorted(reserved(pddl=True))

FORMULAS = [
    "Good(pull)",
    "Bad(one_will_die) -> not Caused(one_will_die)",
    "GEq(-five_will_die & one_will_die & done, five_will_die & -one_will_die & done)",
    "not (Caused(-five_will_die) or Neutral(refrain)) and true",
    "GEq((), done)",
]
QUESTIONS = [
    "why refrain rather than pull",
    "why pull",
    "why not pull",
    "why refrain before pull",
    "why pull?",
    "WHY NOT refrain",
]

TOKEN = re.compile(r"[A-Za-z_'][A-Za-z0-9_']*|\d+|\s+|.", re.S)
CHARACTERS = "()[]{},.;:-_'\"%#&|+*/\\<>=!~@? \n\tabzXY0129é€\x7f"
NUMBERS = [
    "0",
    "-1",
    "2147483647",
    "2147483648",
    "-2147483648",
    "3000000000",
    "99999999999999999999",
    "1073741823",
    "0x7FFFFFFF",
    "0xFFFFFFFFF",
]


# -- mutations -----------------------------------------------------------------------


def _splice(draw) -> str:
    kind = draw(st.sampled_from(["fact", "rule", "encoding"]))
    if kind == "encoding":
        return draw(st.sampled_from(ENCODING_LINES))
    name, arity = draw(st.sampled_from(RESERVED))
    arguments = ",".join(
        draw(st.sampled_from(["x", "X", "1", "pull", "done", "true"])) for _ in range(arity)
    )
    atom = f"{name}({arguments})" if arity else name
    if kind == "fact":
        return f"{atom}."
    return f"{atom} :- variable(X)." if "X" in atom else f"{atom} :- action(pull)."


@st.composite
def mutated(draw, text: str, splices: bool = True) -> str:
    """``text`` after one to three edits."""
    for _ in range(draw(st.integers(1, 3))):
        tokens = TOKEN.findall(text)
        # Token edits and splices keep more programs parseable, so they are drawn
        # more often than byte edits.
        kind = draw(
            st.sampled_from(
                ["delete", "insert", "replace", "token-delete", "token-duplicate", "token-swap"]
                + ["token-replace", "number"] * 3
                + (["splice"] * 3 if splices else [])
            )
        )
        if kind in ("delete", "insert", "replace"):
            index = draw(st.integers(0, max(0, len(text) - 1)))
            char = draw(st.sampled_from(CHARACTERS))
            text = (
                text[:index] + text[index + 1 :]
                if kind == "delete"
                else text[:index] + char + text[index:]
                if kind == "insert"
                else text[:index] + char + text[index + 1 :]
            )
            continue
        if kind == "splice":
            lines = text.split("\n")
            index = draw(st.integers(0, len(lines)))
            text = "\n".join([*lines[:index], _splice(draw), *lines[index:]])
            continue
        if not tokens:
            continue
        index = draw(st.integers(0, len(tokens) - 1))
        if kind == "token-delete":
            del tokens[index]
        elif kind == "token-duplicate":
            tokens.insert(index, tokens[index])
        elif kind == "token-swap":
            other = draw(st.integers(0, len(tokens) - 1))
            tokens[index], tokens[other] = tokens[other], tokens[index]
        elif kind == "token-replace":
            words = sorted({t for t in tokens if t[:1].isalpha()} | {n for n, _ in RESERVED})
            tokens[index] = draw(st.sampled_from(words))
        else:
            numbers = [i for i, token in enumerate(tokens) if token.isdigit()]
            target = draw(st.sampled_from(numbers)) if numbers else index
            tokens[target] = draw(st.sampled_from(NUMBERS))
        text = "".join(tokens)
    return text


# -- running a command --------------------------------------------------------------


def run(arguments: list[str], stdin: str = "") -> tuple[int, str, str]:
    """ethasp in-process, in a thread, so that a hang fails the test instead of
    stalling it."""
    result: list = []

    def go() -> None:
        out, err = io.StringIO(), io.StringIO()
        saved = sys.stdin
        sys.stdin = io.StringIO(stdin)
        try:
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                code = main(arguments)
        except BaseException as error:
            result.append(error)
            return
        finally:
            sys.stdin = saved
        result.append((code, out.getvalue(), err.getvalue()))

    thread = threading.Thread(target=go, daemon=True)
    thread.start()
    thread.join(HANG)
    assert not thread.is_alive(), f"ethasp {' '.join(arguments)[:200]} did not end"
    if isinstance(result[0], BaseException):
        raise result[0]
    return result[0]


JSON_KEYS = {
    "plan": "status",
    "judge": "judgements",
    "query": "value",
    "ask": "status",
    "validate": "valid",
}


def check(arguments: list[str], stdin: str = "") -> None:
    code, out, err = run(arguments, stdin)
    command = arguments[0]
    # Warnings (PDDL read leniently: undeclared requirements, ignored costs) are
    # lines of their own, "FILE: warning: ..."; besides them, one error line.
    err = "".join(line + "\n" for line in err.splitlines() if ": warning: " not in line)
    assert "Traceback" not in out + err, err
    if code == 0:
        assert err == "", err
        if "--json" in arguments:
            assert JSON_KEYS[command] in json.loads(out)
        else:
            assert out.strip()
    elif code == 2 and command == "validate" and not err:  # a sequence that is no plan
        if "--json" in arguments:
            assert json.loads(out)["valid"] is False
        else:
            assert out.startswith("not a plan: ") and out.count("\n") == 1, out
    else:
        assert code == 2, (code, err)
        lines = err.splitlines()
        assert len(lines) == 1 and lines[0].startswith("ethasp: error: "), err


def command_lines(model: list[str], plan: str, actions: list[str], draw) -> list[str]:
    kind = draw(st.sampled_from(["plan", "validate", "judge", "query", "ask", "dialogue"]))
    plan_args = ["--plan", plan]
    if kind == "plan":
        extra = draw(st.sampled_from([[], ["--all"], ["--principle", "do-no-harm"]]))
        return ["plan", *model, "--json", *LIMITS, *extra]
    if kind == "validate":
        return ["validate", *model, *plan_args, "--json"]
    if kind == "judge":
        return ["judge", *model, *plan_args, "--json", "--reasons-limit", "2", *LIMITS]
    if kind == "query":
        return ["query", *model, *plan_args, "--json", draw(st.sampled_from(FORMULAS))]
    first, second = actions
    question = draw(
        st.sampled_from(
            [
                f"why {first}",
                f"why {first} rather than {second}",
                f"why not {second}",
                f"why {second} before {first}",
            ]
        )
    )
    if kind == "ask":
        return ["ask", *model, "--question", question, "--json", "--reasons-limit", "2", *LIMITS]
    return ["dialogue", *model, "--save", "-", "--reasons-limit", "2", *LIMITS]


def fuzz(examples: int) -> settings:
    examples *= int(os.environ.get("ETHASP_FUZZ_SCALE", "1"))
    return settings(
        max_examples=examples,
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
    )


# -- the fuzzers --------------------------------------------------------------------


@fuzz(180)
@given(data=st.data())
def test_mutated_asp_models(data, tmp_path_factory):
    name = data.draw(st.sampled_from(sorted(ASP_MODELS)))
    text = data.draw(mutated(ASP_MODELS[name]))
    folder = tmp_path_factory.mktemp("model")
    path = folder / f"{name}.lp"
    path.write_text(text)
    arguments = command_lines([str(path)], PLANS[name], ACTIONS[name], data.draw)
    stdin = "why " + ACTIONS[name][0] + "\nundo\nplan\n" if arguments[0] == "dialogue" else ""
    check(arguments, stdin)


@fuzz(90)
@given(data=st.data())
def test_mutated_pddl_tasks(data, tmp_path_factory):
    task, plan = data.draw(st.sampled_from(PDDL_TASKS))
    files = [f"{task}-domain.pddl", f"{task}-problem.pddl", f"{task}-utility.lp"]
    changed = data.draw(st.sampled_from(files))
    folder = tmp_path_factory.mktemp("pddl")
    for name in files:
        text = PDDL[name]
        if name == changed:
            text = data.draw(mutated(text, splices=name.endswith(".lp")))
        (folder / name).write_text(text)
    model = [str(folder / name) for name in files]
    kind = data.draw(st.sampled_from(["plan", "validate", "judge"]))
    if kind == "plan":
        check(["plan", *model, "--json", *LIMITS])
    elif kind == "validate":
        check(["validate", *model, "--plan", plan or "(nothing)", "--json"])
    else:
        check(
            [
                "judge",
                *model,
                "--plan",
                plan or "(nothing)",
                "--json",
                "--reasons-limit",
                "2",
                *LIMITS,
            ]
        )


@fuzz(240)
@given(st.sampled_from(FORMULAS).flatmap(lambda text: mutated(text, splices=False)))
def test_mutated_formulas(formula):
    check(["query", "trolley", "--plan", "pull", "--json", formula])


@fuzz(75)
@given(
    st.sampled_from(QUESTIONS).flatmap(lambda text: mutated(text, splices=False)),
    st.sampled_from(["ask", "dialogue"]),
)
def test_mutated_questions(question, command):
    if command == "ask":
        check(["ask", "trolley", "--question", question, "--json", "--reasons-limit", "2", *LIMITS])
    else:
        check(
            ["dialogue", "trolley", "--save", "-", "--reasons-limit", "2", *LIMITS],
            stdin=question + "\nhistory\n",
        )


@fuzz(120)
@given(st.text(alphabet=CHARACTERS + "\x00\udcff", max_size=40))
def test_random_plans_and_formulas(text):
    check(["judge", "trolley", "--plan", text, "--json", "--reasons-limit", "1", *LIMITS])
    check(["query", "trolley", "--plan", "pull", text])
