"""The command line's streams and small promises: ``-`` as a model file reads
standard input, ``--svg -`` writes standard output (the answer then goes to
standard error), ``-V``, the real defaults in ``--help``, ``dialogue --json``
refused in one line, ``plan --reasons-limit``, and long reasons shortened in
text output (whole in JSON)."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from conftest import MODELS, ROOT

from ethasp.interfaces.shortening import reasons_lines, shorten_literal, shorten_reason

TROLLEY = (MODELS / "trolley.lp").read_text()
CARE = [
    str(MODELS / "pddl" / name)
    for name in ("care-domain.pddl", "care-problem.pddl", "care-utility.lp")
]


def ethasp(*args: str, stdin: str | bytes | None = None, cwd=ROOT) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    binary = isinstance(stdin, bytes)
    return subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", *args],
        capture_output=True,
        text=not binary,
        cwd=cwd,
        env=env,
        input=stdin if stdin is not None else ("" if not binary else b""),
    )


def one_line_error(run, code: int = 2) -> str:
    stderr = run.stderr if isinstance(run.stderr, str) else run.stderr.decode()
    assert run.returncode == code, (run.returncode, stderr)
    assert stderr.count("\n") == 1 and stderr.startswith("ethasp: error: "), stderr
    return stderr


# -- standard input -----------------------------------------------------------------------


def test_a_model_from_standard_input(tmp_path):
    run = ethasp("judge", "-", "--plan", "pull", "--principle", "do-no-harm", stdin=TROLLEY)
    assert run.returncode == 0, run.stderr
    assert "the death of the one person is caused by the man's action" in run.stdout
    # with more files: an annotation read from standard input
    rules = "\n".join(line for line in TROLLEY.splitlines() if "label" not in line)
    labels = "\n".join(line for line in TROLLEY.splitlines() if "label" in line)
    (tmp_path / "rules.lp").write_text(rules)
    both = ethasp(
        "plan", str(tmp_path / "rules.lp"), "-", "--principle", "deontology", stdin=labels
    )
    assert both.returncode == 0 and "The man can pull the lever." in both.stdout, both.stderr


def test_bad_models_from_standard_input_are_one_line():
    assert "<stdin>:" in one_line_error(ethasp("plan", "-", stdin="variable(a). action(b"))
    assert "<stdin>:1:" in one_line_error(ethasp("plan", "-", stdin="variable(a). p(X)."))
    assert "looks like PDDL" in one_line_error(
        ethasp("plan", "-", stdin=(MODELS / "pddl" / "care-domain.pddl").read_text())
    )
    assert "HERA situation" in one_line_error(ethasp("plan", "-", stdin='{"actions": []}'))
    assert "not UTF-8" in one_line_error(ethasp("plan", "-", stdin=b"variable(\xff)."))
    assert "only once" in one_line_error(ethasp("plan", "-", "-", stdin=TROLLEY))
    assert "empty" in one_line_error(ethasp("plan", "-", stdin=""))
    assert "standard input" in one_line_error(ethasp("dialogue", "-", stdin=TROLLEY))


# -- standard output -----------------------------------------------------------------------


def test_svg_to_standard_output_and_the_answer_to_standard_error():
    run = ethasp("judge", "trolley", "--plan", "pull", "--svg", "-")
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith("<svg ") and run.stdout.rstrip().endswith("</svg>")
    assert "deontology: permissible (proven)" in run.stderr
    as_json = ethasp("plan", "trolley", "--svg", "-", "--json")
    assert as_json.stdout.startswith("<svg ")
    assert json.loads(as_json.stderr)["plan"] == ["pull"]  # the least shortest plan
    none = ethasp(
        "plan",
        "-",
        "--svg",
        "-",
        "--max-horizon",
        "1",
        stdin="variable(a;b). action(x). pre(x,a,true). eff(x,b,true). goal(b,true).",
    )
    assert none.returncode == 0 and none.stdout == ""
    assert "no picture was written to standard output" in none.stderr


# -- small promises -------------------------------------------------------------------------


def test_version_short_and_long():
    short, long = ethasp("-V"), ethasp("--version")
    assert (
        short.returncode == 0 and short.stdout == long.stdout and short.stdout.startswith("ethasp ")
    )


def test_help_shows_real_defaults_and_what_models_may_be():
    judge = " ".join(ethasp("judge", "--help").stdout.split())
    assert "(default 10; 0: no explanations)" in judge and "DEFAULT_LIMIT" not in judge
    serve = " ".join(ethasp("serve", "--help").stdout.split())
    assert "HERA situation or causal agency model (.yaml, .json)" in serve
    assert "--log-requests" in serve
    plan = " ".join(ethasp("plan", "--help").stdout.split())
    assert "--reasons-limit N with --principle" in plan
    assert "- reads an ASP model from standard input" in plan
    dialogue = " ".join(ethasp("dialogue", "--help").stdout.split())
    assert "--json" not in dialogue and "standard input" not in dialogue


def test_dialogue_json_is_refused_in_one_line():
    assert "--save FILE" in one_line_error(ethasp("dialogue", "trolley", "--json", stdin="quit\n"))


def test_answers_need_at_least_one_reason():
    for command in (["ask", "trolley", "--question", "why refrain"], ["dialogue", "trolley"]):
        assert "must be from 1" in one_line_error(ethasp(*command, "--reasons-limit", "0"))


def test_plan_reasons_limit_and_bounded_reason_lines():
    run = ethasp("plan", *CARE, "--principle", "do-no-harm", "--quiet")
    assert run.returncode == 0, run.stderr
    assert max(map(len, run.stdout.splitlines()[1:4])) < 1000  # not 46,000 characters
    reasons = [line for line in run.stdout.splitlines() if line.startswith("    {")]
    assert reasons and all(len(line) <= 100 for line in reasons)
    assert "(long reasons are shortened here; --json prints them whole)" in run.stdout
    whole = json.loads(ethasp("plan", *CARE, "--principle", "do-no-harm", "--json").stdout)
    sufficient = whole["judgements"][0]["sufficient_reasons"]
    # whole in JSON: longer than the 100 characters a line of text shows
    assert len(sufficient) == 10 and len(", ".join(sufficient[0])) > 100
    limited = ethasp("plan", *CARE, "--principle", "do-no-harm", "--reasons-limit", "2", "--json")
    assert len(json.loads(limited.stdout)["judgements"][0]["sufficient_reasons"]) == 2
    silent = ethasp("plan", "trolley", "--principle", "do-no-harm", "--reasons-limit", "0")
    assert silent.returncode == 0 and "reasons" not in silent.stdout
    assert silent.stdout.startswith("plan of 1 step permissible under do-no-harm: refrain")


def test_short_reasons_stay_on_one_line():
    run = ethasp("judge", "trolley", "--plan", "pull")
    assert (
        "  necessary reasons: {GEq(done & -five_will_die & one_will_die, done & "
        "five_will_die & -one_will_die)}" in run.stdout
    )
    assert "shortened" not in run.stdout


def test_shortening():
    both = " & ".join(f"f({i})" for i in range(50))
    geq = f"not GEq(a & {both}, -a & {both})"
    short = shorten_literal(geq, 100)
    assert short == "not GEq(a & \u2026 [50 shared], -a & \u2026 [50 shared])"
    long_sides = (
        f"GEq(a & b & c & d & e & g & h & {both}, -a & -b & -c & -d & -e & -g & -h & {both})"
    )
    assert "[" in shorten_literal(long_sides, 60) and len(shorten_literal(long_sides, 60)) <= 72
    assert shorten_literal("Caused(" + "x" * 300 + ")", 50) == "Caused(" + "x" * 42 + "\u2026"
    reason = [f"not Bad(fact_{i})" for i in range(40)]
    text = shorten_reason(reason, 80)
    assert len(text) <= 80 and text.endswith(" more}") and text.startswith("{not Bad(fact_0), ")
    lines, cut = reasons_lines("sufficient", [reason, reason[:2]], True, 80)
    assert lines[0] == "  sufficient reasons (2; limit reached, more may exist):"
    assert lines[2] == "    {not Bad(fact_0), not Bad(fact_1)}" and cut
    assert reasons_lines("necessary", [["Bad(a)"], ["Caused(a)"]], False) == (
        ["  necessary reasons: {Bad(a)}; {Caused(a)}"],
        False,
    )
