"""The limits of clingo terms, and reading terms from users' text within them.

clingo's integers are 32-bit: a literal beyond the range wraps silently
(``3000000000`` reads as ``-1294967296``).  clingo also recurses over the
nesting of terms and arithmetic when it parses, prints and grounds them, and
crashes (it does not raise) somewhere between 30,000 and 300,000 levels.
So every text that reaches clingo from a user, model files included, is
scanned first, and refused with one line when it

* writes an integer outside ``INT_MIN..INT_MAX``, or
* has a character that is not ASCII outside strings and comments (clingo
  reads only ASCII names, and its message about such a character makes its
  Python library abort), or a control character, or
* nests parentheses more than ``MAX_NESTING`` deep, or has more than
  ``MAX_NESTING`` arithmetic operators in one statement (term).

The limits are far beyond any planning model (and grounding terms nested
10,000 deep already takes seconds), and they make clingo's limits errors
instead of crashes.  :func:`parse_symbol` reads one ground term (an action,
a variable) this way: through ``clingo.parse_term``, never as rule text.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import clingo

from ethasp.errors import InputError

INT_MIN = -(2**31)
INT_MAX = 2**31 - 1

# The deepest nesting of parentheses, and the most arithmetic operators in one
# statement, that ethasp hands to clingo.
MAX_NESTING = 10_000

_OPERATORS = set("+-*/\\^&?~")
_DIGITS = frozenset("0123456789")
_LETTERS = frozenset("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_'")


def _ascii_word(char: str) -> bool:
    return char.isascii() and (char.isalnum() or char == "_")


_BASES = {"x": 16, "o": 8, "b": 2}


class LimitError(InputError):
    """A text beyond clingo's limits; ``reason`` says what, without the place."""

    def __init__(self, where: str, reason: str):
        super().__init__(f"{where}: {reason}")
        self.where = where
        self.reason = reason


class TermError(InputError):
    """A text that is not a term, or not within the limits; ``reason`` says why
    when more than "not a term" is to be said ('' otherwise)."""

    def __init__(self, what: str, message: str, reason: str = ""):
        super().__init__(f"{what}: {message}")
        self.reason = reason


@dataclass
class Scan:
    """What a scan of a program text found: the files it includes."""

    includes: list[tuple[str, int]] = field(default_factory=list)  # (name, line)


def _where(name: str, line: int, column: int | None = None) -> str:
    return f"{name}:{line}:{column}" if column is not None else f"{name}:{line}"


def _number(text: str, start: int) -> tuple[int, int]:
    """The value and end of the integer literal at ``start`` (decimal, 0x, 0o, 0b)."""
    end = start
    if text.startswith("0", start) and start + 2 <= len(text) and text[start + 1] in _BASES:
        base = _BASES[text[start + 1]]
        end = start + 2
        while end < len(text) and _ascii_word(text[end]):
            end += 1
        try:
            return int(text[start + 2 : end], base), end
        except ValueError:
            return 0, end  # clingo reports the syntax error
    while end < len(text) and text[end] in _DIGITS:
        end += 1
    return int(text[start:end]), end


# What the quick scan looks at: comments, strings and #script blocks (left
# out), #include directives, long or based integer literals, and whatever
# else it must count or refuse.
_SKIPPED = re.compile(r'%\*.*?(?:\*%|\Z)|%[^\n]*|"(?:\\.|[^"\\])*"?|#script\b.*?(?:#end|\Z)', re.S)
_INCLUDE = re.compile(
    r'%\*.*?(?:\*%|\Z)|%[^\n]*|#include\s*"([^"]*)"|"(?:\\.|[^"\\])*"?'
    r"|#script\b.*?(?:#end|\Z)",
    re.S,
)
_RISKY_NUMBER = re.compile(r"\d{10,}|0[xob]", re.I)
_CONTROL = re.compile(r"[\x00-\x08\x0e-\x1f]")
_STATEMENT_END = re.compile(r"(?<!\.)\.(?!\.)")


def scan_program(text: str, name: str) -> Scan:
    """Scan ASP text (a model file, a term) for clingo's limits; raise InputError.

    Comments, strings and ``#script`` blocks are skipped.  Returns the
    ``#include "file"`` directives found, for the caller to scan those too.
    A quick pass with regular expressions clears ordinary texts; a text it
    cannot clear is scanned character by character, which finds the place of
    any problem.
    """
    quick = _quick_scan(text)
    return quick if quick is not None else _scan_exactly(text, name)


def _quick_scan(text: str) -> Scan | None:
    """The scan of a text that is clearly within the limits, else None."""
    if not text.isascii() or _CONTROL.search(text):
        return None
    kept = _SKIPPED.sub(" ", text)
    if _RISKY_NUMBER.search(kept):
        return None
    if kept.count("(") > MAX_NESTING or len(kept) > 100_000:
        depth = deepest = 0
        for match in re.finditer(r"[()]", kept):
            depth = depth + 1 if match.group() == "(" else max(0, depth - 1)
            deepest = max(deepest, depth)
        if deepest > MAX_NESTING:
            return None
    if sum(kept.count(op) for op in _OPERATORS) > MAX_NESTING and any(
        sum(part.count(op) for op in _OPERATORS) > MAX_NESTING
        for part in _STATEMENT_END.split(kept)
    ):
        return None
    scan = Scan()
    if "#include" in text:
        for match in _INCLUDE.finditer(text):
            if match.group(1) is not None:
                scan.includes.append((match.group(1), text.count("\n", 0, match.start()) + 1))
    return scan


def _scan_exactly(text: str, name: str) -> Scan:
    """The character by character scan of :func:`scan_program`."""
    scan = Scan()
    index, line, line_start, length = 0, 1, 0, len(text)
    depth, operators = 0, 0
    while index < length:
        char = text[index]
        if char == "\n":
            line, line_start = line + 1, index + 1
            index += 1
        elif not char.isascii():
            # (clingo's message about such a character cuts it in the middle of its
            # UTF-8 bytes, which its Python library cannot decode: it aborts.)
            shown = char if char.isprintable() else f"U+{ord(char):04X}"
            raise LimitError(
                _where(name, line, index - line_start + 1),
                f"the character {shown!r} outside a string or comment (names in ASP are ASCII)",
            )
        elif char == "%":
            if text.startswith("%*", index):  # block comment
                end = text.find("*%", index + 2)
                end = length if end < 0 else end + 2
            else:  # line comment
                end = text.find("\n", index)
                end = length if end < 0 else end
            line += text.count("\n", index, end)
            if "\n" in text[index:end]:
                line_start = text.rfind("\n", index, end) + 1
            index = end
        elif char == '"':
            end = index + 1
            while end < length and text[end] != '"':
                end += 2 if text[end] == "\\" else 1
            line += text.count("\n", index, end)
            index = end + 1
        elif char == "#":
            end = index + 1
            while end < length and _ascii_word(text[end]):
                end += 1
            directive = text[index:end]
            if directive == "#script":
                stop = text.find("#end", end)
                stop = length if stop < 0 else stop + 4
                line += text.count("\n", index, stop)
                index = stop
                continue
            if directive == "#include":
                rest = text[end : end + 4096].lstrip()
                if rest.startswith('"'):
                    close = rest.find('"', 1)
                    if close > 0:
                        scan.includes.append((rest[1:close], line))
            index = end
        elif char in _LETTERS:
            index += 1
            while index < length and (_ascii_word(text[index]) or text[index] == "'"):
                index += 1
        elif char in _DIGITS:
            value, end = _number(text, index)
            if value > INT_MAX:
                literal = text[index:end]
                raise LimitError(
                    _where(name, line, index - line_start + 1),
                    f"the integer {literal} is out of range: clingo's integers are 32-bit, "
                    f"from {INT_MIN} to {INT_MAX}",
                )
            index = end
        elif char < " " and char not in "\t\r\f\v":
            raise LimitError(
                _where(name, line, index - line_start + 1),
                f"a control character {ord(char):#04x}: not a program text",
            )
        else:
            if char == "(":
                depth += 1
                if depth > MAX_NESTING:
                    raise LimitError(
                        _where(name, line, index - line_start + 1),
                        f"parentheses nested more than {MAX_NESTING} deep (the limit of ethasp)",
                    )
            elif char == ")":
                depth = max(0, depth - 1)
            elif (
                char == "."
                and not text.startswith("..", index)
                and not (index > 0 and text[index - 1] == ".")
            ):
                operators = 0  # end of a statement
            elif char in _OPERATORS and not (char in "-~" and index > 0 and text[index - 1] == ":"):
                operators += 1
                if operators > MAX_NESTING:
                    raise LimitError(
                        _where(name, line),
                        f"more than {MAX_NESTING} arithmetic operators in one statement "
                        "(the limit of ethasp)",
                    )
            index += 1
    return scan


def scan_file(path: Path, text: str | None = None, seen: set[Path] | None = None) -> None:
    """Scan a program file and the files it includes (as clingo finds them: relative
    to the working directory first, then to the including file)."""
    seen = set() if seen is None else seen
    resolved = path.resolve()
    if resolved in seen:
        return
    seen.add(resolved)
    if text is None:
        text = read_text(path)
    scan = scan_program(text, str(path))
    for name, line in scan.includes:
        for candidate in (Path(name), path.parent / name):
            if candidate.is_file():
                try:
                    included = candidate.read_text()
                except (OSError, UnicodeDecodeError) as exc:
                    raise InputError(
                        f"{path}:{line}: the included file {name} cannot be read ({_reason(exc)})"
                    ) from None
                scan_file(candidate, included, seen)
                break
        # A missing file is reported by clingo, with its place.


def _reason(exc: Exception) -> str:
    if isinstance(exc, UnicodeDecodeError):
        return f"not UTF-8 text: byte {exc.object[exc.start]:#04x} at offset {exc.start}"
    if isinstance(exc, OSError) and exc.strerror:
        return exc.strerror
    return " ".join(str(exc).split())


def read_text(path: Path, what: str = "") -> str:
    """The text of a file a user names, or an InputError saying why it cannot be read."""
    label = f"{what} {path}".strip()
    try:
        if path.is_dir():
            raise InputError(f"{label}: is a directory, not a file")
        if not path.exists():
            raise InputError(f"{label}: no such file")
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        raise InputError(f"{label}: cannot be read ({_reason(exc)})") from None


def _arithmetic(text: str) -> str | None:
    """The first arithmetic operator of a term text (outside strings), if any.

    A minus sign counts when it is binary (after a term); a unary minus (``-a``,
    ``-5``) is part of the term.
    """
    index, previous = 0, ""
    while index < len(text):
        char = text[index]
        if char == '"':
            index += 1
            while index < len(text) and text[index] != '"':
                index += 2 if text[index] == "\\" else 1
            previous = '"'
        elif char in "+*/\\^&?~|" or (
            char == "-" and previous and (previous.isalnum() or previous in ")\"'_")
        ):
            return char
        elif text.startswith("..", index):
            return ".."
        elif not char.isspace():
            previous = char
        index += 1
    return None


def parse_symbol(text: str, what: str = "term") -> clingo.Symbol:
    """A ground term written by a user (``push(man)``), read by ``clingo.parse_term``.

    Refused with an InputError: anything that is not one term (rule text such
    as ``a). evil :- b(``, variables, ``a;b``), arithmetic (which clingo would
    evaluate, and could wrap), integers out of range, and nesting beyond
    :data:`MAX_NESTING`.
    """
    stripped = text.strip()
    if not stripped:
        raise TermError(what, "empty term", "empty")
    try:
        stripped.encode("utf-8")
    except UnicodeEncodeError:  # bytes that were not UTF-8 (kept as surrogates)
        raise TermError(what, "not UTF-8 text", "not UTF-8 text") from None
    try:
        scan_program(stripped, what)
    except LimitError as error:
        raise TermError(what, error.reason, error.reason) from None
    operator = _arithmetic(stripped)
    if operator is not None:
        reason = f"arithmetic such as '{operator}' is not allowed in a name"
        raise TermError(what, f"not a term: {_short(stripped)!r} ({reason})", reason)
    try:
        symbol = clingo.parse_term(stripped, logger=lambda code, message: None)
    except RuntimeError:
        raise TermError(what, f"not a term: {_short(stripped)!r}") from None
    return symbol


def _short(text: str, limit: int = 60) -> str:
    """A text cut for a message."""
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 3] + "..."
