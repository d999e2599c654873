"""Shell completion: ``ethasp completion bash|zsh`` prints a script that the
shell accepts and that completes commands, options, principle names (those
that can restrict for the commands that make plans), bundled models and
files.  bash is driven through its completion function; zsh, where
installed, through a real interactive shell in a pseudo-terminal."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import pytest
from conftest import ROOT

from ethasp.interfaces.cli import build_parser
from ethasp.interfaces.completion import bundled_models, commands, principle_names, script

BASH = shutil.which("bash")
ZSH = shutil.which("zsh")


@pytest.fixture(scope="module")
def scripts(tmp_path_factory):
    folder = tmp_path_factory.mktemp("completion")
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    paths = {}
    for shell in ("bash", "zsh"):
        run = subprocess.run(
            [sys.executable, "-m", "ethasp.interfaces.cli", "completion", shell],
            capture_output=True,
            text=True,
            env=env,
        )
        assert run.returncode == 0 and run.stderr == "", run.stderr
        paths[shell] = folder / f"ethasp.{shell}"
        paths[shell].write_text(run.stdout)
    return paths


def test_the_scripts_follow_the_parser():
    parser = build_parser()
    names = {command.name for command in commands(parser)}
    assert {"plan", "judge", "ask", "dialogue", "serve", "completion"} <= names
    for shell in ("bash", "zsh"):
        text = script(shell, parser)
        for option in ("--principle", "--reasons-limit", "--svg", "--log-requests"):
            assert option in text
    restricting = principle_names(restricting=True)
    assert "deontology" in restricting and "kantian-humanity" not in restricting
    assert {"kantian-humanity", "paper", "all"} <= set(principle_names(restricting=False))
    assert "trolley" in bundled_models() and "hera/robot-and-frank.yaml" in bundled_models()


def test_a_commands_parser_alone_is_the_whole_parsers():
    # The command line builds only the parser of the command it runs.
    whole = build_parser()
    choices = whole._subparsers._group_actions[0].choices
    for name in ("plan", "ask", "completion"):
        alone = build_parser(name)
        only = alone._subparsers._group_actions[0].choices
        assert list(only) == [name]
        assert only[name].format_help() == choices[name].format_help()
    completion = build_parser("completion").parse_args(["completion", "bash"])
    assert len(commands(completion.build_parser())) == len(choices)  # every command
    assert build_parser("plna")._subparsers._group_actions[0].choices.keys() == choices.keys()


def test_an_unknown_shell_is_one_line():
    run = subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", "completion", "fish"],
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    assert run.returncode == 2 and run.stderr.count("\n") == 1 and "invalid choice" in run.stderr


@pytest.mark.skipif(BASH is None, reason="bash is not installed")
@pytest.mark.parametrize(
    "words, expected",
    [
        (["ethasp", "ju"], ["judge"]),
        (["ethasp", "-"], ["-h", "--help", "-V", "--version"]),
        (["ethasp", "judge", "trolley", "--pri"], ["--principle"]),
        (
            ["ethasp", "judge", "trolley", "--principle", "do"],
            ["do-no-harm", "do-no-instrumental-harm", "double-effect"],
        ),
        (["ethasp", "plan", "trolley", "--principle", "do"], ["do-no-harm"]),
        (["ethasp", "ask", "trolley", "--under", "util"], ["utilitarianism"]),
        (["ethasp", "judge", "trolley", "--principle", "pa"], ["paper"]),
        (["ethasp", "judge", "troll"], ["trolley", "trolley-alarm"]),
        (["ethasp", "judge", "hera/"], ["hera/robot-and-frank.yaml", "hera/trolley.yaml"]),
        (["ethasp", "judge", "asp/foot"], ["asp/footbridge.lp"]),
        (["ethasp", "completion", ""], ["bash", "zsh"]),
        (["ethasp", "serve", "trolley", "--log"], ["--log-requests"]),
        (["ethasp", "judge", "trolley", "--max-horizon", ""], []),
    ],
)
def test_bash_completes(scripts, words, expected):
    line = " ".join(f"'{word}'" for word in words)
    program = (
        f"source {scripts['bash']}\n"
        f"COMP_WORDS=({line}); COMP_CWORD={len(words) - 1}; COMPREPLY=()\n"
        "_ethasp 2>/dev/null\n"
        'printf "%s\\n" "${COMPREPLY[@]}"\n'
    )
    run = subprocess.run(
        [BASH, "--norc", "--noprofile", "-c", program], capture_output=True, text=True, cwd=ROOT
    )
    assert run.returncode == 0, run.stderr
    assert sorted(filter(None, run.stdout.split("\n"))) == sorted(expected)


ZSH_DRIVER = r"""
zmodload zsh/zpty
zpty z 'zsh -f -i'
zpty -w z "autoload -U compinit; compinit -u -D; source $1"
zpty -w -n z "$2"$'\t\t'
local all="" out
for i in {1..60}; do
  if zpty -r -t z out; then all+=$out; else sleep 0.1; fi
  [[ $all == *"$3"* ]] && break
done
print -r -- "$all"
zpty -d z
"""


@pytest.mark.skipif(ZSH is None, reason="zsh is not installed")
@pytest.mark.parametrize(
    "typed, shown, hidden",
    [
        ("ethasp judge trolley --principle do", ["double-effect", "do-no-instrumental-harm"], []),
        (
            "ethasp plan trolley --principle hera-",
            ["hera-deontology", "hera-utilitarianism"],
            ["hera-do-no-harm"],
        ),
        ("ethasp ser", ["serve"], []),
    ],
)
def test_zsh_completes(scripts, tmp_path, typed, shown, hidden):
    driver = tmp_path / "driver.zsh"
    driver.write_text(ZSH_DRIVER)
    run = subprocess.run(
        [ZSH, "-f", str(driver), str(scripts["zsh"]), typed, shown[-1]],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=120,
    )
    screen = run.stdout.replace("\r", "")
    for word in shown:
        assert word in screen, screen
    for word in hidden:
        assert word not in screen, screen


@pytest.mark.skipif(ZSH is None, reason="zsh is not installed")
def test_zsh_accepts_the_script(scripts):
    run = subprocess.run([ZSH, "-n", str(scripts["zsh"])], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
