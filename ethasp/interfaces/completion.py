"""Shell completion scripts for bash and zsh, made from the command line's parser.

``ethasp completion bash`` and ``ethasp completion zsh`` print a script that
completes the commands, each command's options, principle names after
``--principle`` and ``--under``, file names and the bundled models' names as
MODEL, and file names after the options that take a file.  The script is
static text made from the argparse parser when it is printed, so it stays
true to ``--help`` and needs neither ethasp nor Python at completion time;
print it again after an upgrade.

Principle names: ``judge`` takes every principle of ``encodings/principles/``
and the groups ``paper``, ``hera``, ``all``; the commands that make plans
under a principle (``plan``, ``ask``, ``dialogue``, ``serve``) take those
with a restriction encoding (``encodings/restrictions/``).
"""

from __future__ import annotations

import argparse
import re
from dataclasses import dataclass, field

from ethasp.resources import ENCODINGS, bundled_names

FILE_OPTIONS = {"svg", "plan_file", "save", "load"}  # dests whose value is a file
PRINCIPLE_OPTIONS = {"principle", "under"}
GROUPS = ("paper", "hera", "all")


@dataclass
class Option:
    """One option of a command: its spellings, whether it takes a value and
    what completes that value (``file``, ``principle``, a list, or nothing)."""

    names: list[str]
    help: str
    takes_value: bool
    values: str | list[str] | None = None


@dataclass
class Command:
    name: str
    help: str
    options: list[Option] = field(default_factory=list)
    positional: str | list[str] | None = None  # model (files and bundled names), a list


def principle_names(restricting: bool) -> list[str]:
    """Principle names for completion (see the module's docstring)."""
    from ethasp.principles.principle import available_principles

    names = [
        p.name
        for p in available_principles()
        if not restricting or (ENCODINGS / "restrictions" / f"{p.asp_name}.lp").is_file()
    ]
    return names if restricting else names + list(GROUPS)


def bundled_models() -> list[str]:
    """The names of the bundled model files (:func:`ethasp.resources.bundled_names`)."""
    return bundled_names()


def commands(parser: argparse.ArgumentParser) -> list[Command]:
    """The commands of the parser, with their options and what completes them."""
    found = []
    for action in parser._actions:
        if not isinstance(action, argparse._SubParsersAction):
            continue
        helps = {choice.dest: choice.help or "" for choice in action._choices_actions}
        for name, sub in action.choices.items():
            command = Command(name, helps.get(name, ""))
            for option in sub._actions:
                if not option.option_strings:
                    if option.choices:
                        command.positional = list(option.choices)
                    elif option.dest == "model":
                        command.positional = "model"
                    continue
                takes = option.nargs != 0
                values: str | list[str] | None = None
                if option.dest in FILE_OPTIONS:
                    values = "file"
                elif option.dest in PRINCIPLE_OPTIONS:
                    values = principle_names(restricting=name != "judge")
                elif option.choices:
                    values = list(option.choices)
                command.options.append(
                    Option(list(option.option_strings), option.help or "", takes, values)
                )
            found.append(command)
    return found


def _words(values: list[str]) -> str:
    return " ".join(values)


def bash_script(parser: argparse.ArgumentParser) -> str:
    """The bash completion script."""
    all_commands = commands(parser)
    models = _words(bundled_models())
    lines = [
        "# bash completion for ethasp (made by: ethasp completion bash)",
        "# Install: ethasp completion bash > ~/.local/share/bash-completion/completions/ethasp",
        "_ethasp() {",
        '    local cur="${COMP_WORDS[COMP_CWORD]}" prev="${COMP_WORDS[COMP_CWORD-1]}"',
        '    local command="" i',
        "    for ((i = 1; i < COMP_CWORD; i++)); do",
        '        case "${COMP_WORDS[i]}" in',
        "            -*) ;;",
        '            *) command="${COMP_WORDS[i]}"; break ;;',
        "        esac",
        "    done",
        '    if [[ -z "$command" ]]; then',
        f'        COMPREPLY=($(compgen -W "{_words([c.name for c in all_commands])} '
        f'-h --help -V --version" -- "$cur"))',
        "        return",
        "    fi",
        '    case "$command" in',
    ]
    for command in all_commands:
        lines.append(f"        {command.name})")
        cases = []
        for option in command.options:
            if not option.takes_value:
                continue
            names = "|".join(option.names)
            if option.values == "file":
                cases.append(
                    f"                {names}) compopt -o filenames 2>/dev/null; "
                    f'COMPREPLY=($(compgen -f -- "$cur")); return ;;'
                )
            elif isinstance(option.values, list):
                cases.append(
                    f"                {names}) COMPREPLY=($(compgen -W "
                    f'"{_words(option.values)}" -- "$cur")); return ;;'
                )
            else:
                cases.append(f"                {names}) return ;;")
        if cases:
            lines += ['            case "$prev" in', *cases, "            esac"]
        options = _words([name for option in command.options for name in option.names])
        lines += [
            '            if [[ "$cur" == -* ]]; then',
            f'                COMPREPLY=($(compgen -W "{options}" -- "$cur"))',
            "                return",
            "            fi",
        ]
        if command.positional == "model":
            lines += [
                "            compopt -o filenames 2>/dev/null",
                f'            COMPREPLY=($(compgen -f -- "$cur") $(compgen -W "{models}" '
                f'-- "$cur"))',
            ]
        elif isinstance(command.positional, list):
            lines.append(
                f'            COMPREPLY=($(compgen -W "{_words(command.positional)}" -- "$cur"))'
            )
        lines.append("            ;;")
    lines += ["    esac", "}", "complete -F _ethasp ethasp", ""]
    return "\n".join(lines)


def _zsh_text(text: str) -> str:
    """Help text for a zsh description: its first clause, without the
    characters that zsh's specifications treat specially."""
    first = re.split(r" \(|; ", text, maxsplit=1)[0]
    first = re.sub(r"[\[\]:'\\`$]", "", first)
    return first[:70].rstrip()


def _zsh_option(option: Option) -> list[str]:
    help_text = _zsh_text(option.help)
    if not option.takes_value:
        action = ""
    elif option.values == "file":
        action = ":file:_files"
    elif isinstance(option.values, list):
        action = f":value:({' '.join(option.values)})"
    else:
        action = ":value: "
    exclusive = f"({' '.join(option.names)})" if len(option.names) > 1 else ""
    return [f"'{exclusive}{name}[{help_text}]{action}'" for name in option.names]


def zsh_script(parser: argparse.ArgumentParser) -> str:
    """The zsh completion script."""
    all_commands = commands(parser)
    lines = [
        "#compdef ethasp",
        "# zsh completion for ethasp (made by: ethasp completion zsh)",
        "# Install: ethasp completion zsh > ~/.zfunc/_ethasp, with fpath+=(~/.zfunc) before",
        "# compinit in ~/.zshrc; or: source <(ethasp completion zsh) after compinit.",
        "_ethasp_models() {",
        "    _files",
        f"    compadd -- {_words(bundled_models())}",
        "}",
        "_ethasp() {",
        '    local curcontext="$curcontext" state line',
        "    typeset -A opt_args",
        "    _arguments -C \\",
        "        '(- *)'{-h,--help}'[show help and exit]' \\",
        "        '(- *)'{-V,--version}'[show the version and exit]' \\",
        "        '1:command:->command' \\",
        "        '*::argument:->argument'",
        "    case $state in",
        "        command)",
        "            local -a commands",
        "            commands=(",
    ]
    for command in all_commands:
        lines.append(f"                '{command.name}:{_zsh_text(command.help)}'")
    lines += [
        "            )",
        "            _describe -t commands 'ethasp command' commands",
        "            ;;",
        "        argument)",
        "            case $words[1] in",
    ]
    for command in all_commands:
        specs = [spec for option in command.options for spec in _zsh_option(option)]
        if command.positional == "model":
            specs.append("'*:model:_ethasp_models'")
        elif isinstance(command.positional, list):
            specs.append(f"'1:value:({' '.join(command.positional)})'")
        lines.append(f"                {command.name})")
        lines.append("                    _arguments \\")
        lines += [f"                        {spec} \\" for spec in specs[:-1]]
        lines.append(f"                        {specs[-1]}")
        lines.append("                    ;;")
    lines += [
        "            esac",
        "            ;;",
        "    esac",
        "}",
        'if [[ "${funcstack[1]}" == _ethasp ]]; then',
        '    _ethasp "$@"',
        "else",
        "    compdef _ethasp ethasp",
        "fi",
        "",
    ]
    return "\n".join(lines)


def script(shell: str, parser: argparse.ArgumentParser) -> str:
    """The completion script for ``shell`` (bash or zsh)."""
    return bash_script(parser) if shell == "bash" else zsh_script(parser)
