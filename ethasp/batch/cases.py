"""The cases of a batch: model files found on the command line, in folders and in manifests.

A case is one planning model (its files, loaded together by
:meth:`ethasp.planning.model.Model.load`) with what a batch asks of it: its
own plan, principles and questions when a manifest gives them.  Cases come from

* a model file: ``.lp``, a HERA situation (``.yaml``, ``.yml``, ``.json``), or
  a PDDL file (a domain and a problem given side by side are one case);
* a folder, searched recursively for file names that match a glob (by default
  every model file): each ``.lp`` file and each situation is a case; in a
  directory with PDDL files, each problem is paired with its domain (the
  domain whose name its ``(:domain ...)`` names, else the one whose file name
  matches: ``X-domain.pddl`` with ``X-problem.pddl``, ``domain-p01.pddl`` or
  ``p01-domain.pddl`` with ``p01.pddl``, or the directory's only domain), and
  the ``.lp`` files of that directory are annotations: of the pairs whose
  name they start with (``blocksworld-utility.lp`` for ``blocksworld-...``),
  else of every pair of the directory;
* a manifest, CSV (a ``.csv`` file) or YAML (a ``.yaml`` file whose top level
  has ``cases``): one case per row, with the columns ``files`` (required),
  ``name``, ``plan``, ``principles`` and ``questions``; file names are
  relative to the manifest's folder.

A name that is no file or folder names a bundled model or folder
(:func:`ethasp.resources.bundled_model`: ``trolley``, ``hera``, ``asp``); its
cases are named by their bundled names (``hera/trolley.yaml``).

Bad manifests and unreadable folders are :class:`~ethasp.errors.InputError`
(the batch does not start); a bad model file becomes its case's error line
when the case runs.
"""

from __future__ import annotations

import csv
import fnmatch
import hashlib
import io
import os
import re
import shlex
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

from ethasp.errors import InputError
from ethasp.resources import bundled_model, bundled_name

ASP_SUFFIXES = (".lp",)
SITUATION_SUFFIXES = (".yaml", ".yml", ".json")
PDDL_SUFFIXES = (".pddl",)
MODEL_SUFFIXES = ASP_SUFFIXES + SITUATION_SUFFIXES + PDDL_SUFFIXES
MANIFEST_COLUMNS = ("files", "name", "plan", "principles", "questions")

# #include directives (outside comments and strings), PDDL headers.
_INCLUDE = re.compile(r'%\*.*?(?:\*%|\Z)|%[^\n]*|#include\s*"([^"]*)"|"(?:\\.|[^"\\])*"?', re.S)
_PDDL_COMMENT = re.compile(r";[^\n]*")
_PDDL_DEFINE = re.compile(r"\(\s*define\s*\(\s*(domain|problem)\s+([^\s()]+)", re.I)
_PDDL_DOMAIN_OF = re.compile(r"\(\s*:domain\s+([^\s()]+)", re.I)


@dataclass(frozen=True)
class Case:
    """One model and what the batch asks of it.

    ``files`` are loaded together; ``name`` is the case's name in the output
    (by default its files, joined by `` + ``).  ``plan`` (text, actions
    separated by spaces), ``principles`` and ``questions`` come from a
    manifest row and override the batch's; None: the batch's (the plan: the
    model's own, if any).  ``problem`` is set when the case cannot be made
    (a PDDL problem without a domain): it runs as an error line.
    """

    files: tuple[str, ...]
    name: str = ""
    plan: str | None = None
    principles: tuple[str, ...] | None = None
    questions: tuple[str, ...] | None = None
    problem: str | None = None
    kind: str = "plan"  # "cam": a causal agency model's choice (see choices())

    def __post_init__(self):
        if not self.name:
            object.__setattr__(self, "name", " + ".join(self.files))

    @classmethod
    def of(cls, value: Case | str | os.PathLike | Sequence[str | os.PathLike]) -> Case:
        """A case from a Case, a file, or a sequence of files (loaded together)."""
        if isinstance(value, Case):
            return value
        if isinstance(value, (str, os.PathLike)):
            return cls((os.fspath(value),))
        return cls(tuple(os.fspath(item) for item in value))


@dataclass
class Inputs:
    """What a case reads: its files and the files they include, with their bytes."""

    files: dict[str, bytes] = field(default_factory=dict)  # path as named -> content
    included: dict[str, bytes] = field(default_factory=dict)
    unreadable: list[str] = field(default_factory=list)

    def digest(self) -> str:
        """A hash of every byte read (the case files in order, then the included ones)."""
        digest = hashlib.sha256()
        for kind, files in (("file", self.files), ("included", self.included)):
            for content in files.values():  # by content: a moved folder keeps its results
                digest.update(f"{kind}\0{len(content)}\0".encode())
                digest.update(content)
        for name in self.unreadable:
            digest.update(f"unreadable\0{name}\0".encode())
        return digest.hexdigest()


def choices(case: Case) -> list[Case]:
    """A case of a causal agency model without a plan: one case per action (a
    batch judges every choice), named ``NAME: ACTION``; with a plan, the case
    marked as one of a causal agency model; any other case as it is.  A file
    that cannot be read is left to the case's run, which says why."""
    from ethasp.planning.readers.hera_data import CAM, is_hera_file, kind_of, load_data, name_term

    models = [Path(name) for name in case.files if is_hera_file(Path(name))]
    if case.problem is not None or len(models) != 1:
        return [case]
    try:
        data = load_data(models[0], models[0].read_text(encoding="utf-8"))
        if kind_of(data, str(models[0])) != CAM:
            return [case]
        actions = data.get("actions") if "action" not in data else [data["action"]]
        names = [str(name_term(str(action))) for action in actions]
    except (InputError, OSError, UnicodeDecodeError, TypeError, AttributeError):
        return [case]
    if case.plan is not None or not names:
        return [replace(case, kind="cam")]
    return [replace(case, name=f"{case.name}: {name}", plan=name, kind="cam") for name in names]


def read_inputs(case: Case) -> Inputs:
    """The bytes of a case's files and of the files they ``#include`` (resolved
    as clingo does: from the working directory, then from the including file).
    A file that cannot be read is listed as unreadable (its case's run says why)."""
    inputs = Inputs()
    pending = [Path(name) for name in case.files]
    seen: set[Path] = set()
    first = True
    while pending:
        batch_of_files, pending = pending, []
        for path in batch_of_files:
            try:
                resolved = path.resolve()
            except (OSError, RuntimeError, ValueError):
                resolved = path
            if resolved in seen:
                continue
            seen.add(resolved)
            try:
                content = path.read_bytes()
            except (OSError, ValueError):
                inputs.unreadable.append(str(path))
                continue
            (inputs.files if first else inputs.included)[str(path)] = content
            if path.suffix.lower() not in ASP_SUFFIXES or b"#include" not in content:
                continue
            text = content.decode("utf-8", "replace")
            for match in _INCLUDE.finditer(text):
                if match.group(1):
                    for candidate in (Path(match.group(1)), path.parent / match.group(1)):
                        if candidate.is_file():
                            pending.append(candidate)
                            break
        first = False
    return inputs


# -- folders --------------------------------------------------------------------------------


def _pddl_header(path: Path) -> tuple[str | None, str | None, str | None]:
    """(kind, name, the domain a problem names) from a PDDL file's first part."""
    try:
        with open(path, "rb") as stream:
            text = stream.read(1 << 16).decode("utf-8", "replace")
    except OSError:
        return None, None, None
    text = _PDDL_COMMENT.sub("", text)
    define = _PDDL_DEFINE.search(text)
    if define is None:
        return None, None, None
    kind, name = define.group(1).lower(), define.group(2).lower()
    domain = _PDDL_DOMAIN_OF.search(text) if kind == "problem" else None
    return kind, name, domain.group(1).lower() if domain else None


def _key(stem: str, word: str) -> str:
    """A file name's stem without the word domain or problem and its separator."""
    return re.sub(rf"[-_.]?{word}[-_.]?", "-", stem.lower(), count=1).strip("-")


def _pddl_cases(directory: Path, pddl: list[Path], asp: list[Path]) -> list[Case]:
    """The cases of a directory that holds PDDL files (see the module docstring)."""
    domains, problems, cases = [], [], []
    for path in pddl:
        kind, name, domain = _pddl_header(path)
        if kind == "domain":
            domains.append((path, name))
        elif kind == "problem":
            problems.append((path, domain))
        else:
            cases.append(
                Case(
                    (str(path),),
                    problem=f"{path}: not a PDDL domain or problem "
                    "(it should start with (define (domain "
                    "...) or (define (problem ...))",
                )
            )
    pairs: list[tuple[Path, Path, str]] = []
    for problem, wanted in problems:
        key = _key(problem.stem, "problem")
        named = [path for path, name in domains if name == wanted]
        if len(named) != 1:
            matching = [
                path
                for path, _ in (domains if not named else [(p, None) for p in named])
                if _key(path.stem, "domain") == key
            ]
            if len(matching) == 1:
                named = matching
            elif len(domains) == 1:
                named = [domains[0][0]]
            else:
                named = []
        if not named:
            cases.append(
                Case(
                    (str(problem),),
                    problem=(
                        f"{problem}: no domain file pairs with this PDDL problem in "
                        f"{directory} (name them X-domain.pddl and X-problem.pddl, "
                        "or list the case in a manifest)"
                    ),
                )
            )
            continue
        pairs.append((named[0], problem, key))
    for domain, problem, key in pairs:
        own = [path for path in asp if key and path.stem.lower().startswith(key)]
        if not own:
            own = [
                path
                for path in asp
                if not any(k and path.stem.lower().startswith(k) for _, _, k in pairs)
            ]
        cases.append(Case(tuple(str(path) for path in [domain, problem, *sorted(own)])))
    return cases


def _walk(folder: Path, pattern: str | None) -> list[Case]:
    """The cases found in a folder and its subfolders."""
    by_directory: dict[Path, list[Path]] = {}
    try:
        for root, directories, names in os.walk(folder, onerror=_raise, followlinks=False):
            directories.sort()
            chosen = []
            for name in sorted(names):
                suffix = Path(name).suffix.lower()
                if suffix not in MODEL_SUFFIXES:
                    continue
                if pattern is not None and not fnmatch.fnmatch(name, pattern):
                    continue
                chosen.append(Path(root) / name)
            if chosen:
                by_directory[Path(root)] = chosen
    except OSError as error:
        raise InputError(
            f"{error.filename or folder}: cannot be searched ({error.strerror or error})"
        ) from None
    cases = []
    for directory, paths in by_directory.items():
        pddl = [p for p in paths if p.suffix.lower() in PDDL_SUFFIXES]
        asp = [p for p in paths if p.suffix.lower() in ASP_SUFFIXES]
        if pddl:
            cases += _pddl_cases(directory, pddl, asp)
            asp = []
        cases += [
            Case((str(p),)) for p in paths if p.suffix.lower() in SITUATION_SUFFIXES or p in asp
        ]
    return cases


def _raise(error: OSError) -> None:
    raise error


# -- manifests ------------------------------------------------------------------------------


def is_manifest(path: Path) -> bool:
    """A CSV file, or a YAML file whose top level has ``cases``."""
    suffix = path.suffix.lower()
    if suffix == ".csv":
        return True
    if suffix not in (".yaml", ".yml") or not path.is_file():
        return False
    try:
        with open(path, "rb") as stream:
            head = stream.read(1 << 16).decode("utf-8", "replace")
    except OSError:
        return False
    return re.search(r"^cases\s*:", head, re.M) is not None


def _words(value, where: str, column: str, separator: str | None = None) -> tuple[str, ...]:
    """A manifest cell as a list: a YAML list, or text split at ``separator``
    (None: at commas and white space, with shell quoting)."""
    if value is None:
        return ()
    if isinstance(value, (list, tuple)):
        items = value
    elif isinstance(value, str):
        if separator is not None:
            items = value.split(separator)
        else:
            try:
                items = shlex.split(value.replace(",", " ") if column == "principles" else value)
            except ValueError as error:
                raise InputError(f"{where}: column {column}: {error}") from None
    else:
        raise InputError(
            f"{where}: column {column} must be text or a list, not {type(value).__name__}"
        )
    result = []
    for item in items:
        if not isinstance(item, (str, int, float)) or isinstance(item, bool):
            raise InputError(f"{where}: column {column}: not text: {item!r}")
        text = str(item).strip()
        if text:
            result.append(text)
    return tuple(result)


def _row_case(row: dict, folder: Path, where: str) -> Case:
    unknown = sorted(set(map(str, row)) - set(MANIFEST_COLUMNS) - {"file"})
    if unknown:
        raise InputError(
            f"{where}: unknown column {unknown[0]!r} (columns: {', '.join(MANIFEST_COLUMNS)})"
        )
    files = _words(row.get("files", row.get("file")), where, "files")
    if not files:
        raise InputError(f"{where}: no files (the column files names the case's model files)")
    resolved = [
        _resolve(
            name
            if Path(name).is_absolute()
            else os.path.join(folder, name)
            if str(folder) not in ("", ".")
            else name,
            name,
        )
        for name in files
    ]
    paths = tuple(path for path, _ in resolved)
    plan = row.get("plan")
    if plan is not None and not isinstance(plan, str):
        # A YAML list is a plan given (the empty list: the empty plan); an
        # empty cell (empty text) gives none.
        plan = " ".join(_words(plan, where, "plan"))
    elif plan is not None:
        plan = plan.strip() or None
    principles = _words(row.get("principles"), where, "principles") or None
    questions = _words(row.get("questions"), where, "questions", ";") or None
    name = row.get("name")
    name = str(name).strip() if name is not None and str(name).strip() else ""
    name = name or " + ".join(shown for _, shown in resolved)
    return Case(paths, name, plan, principles, questions)


def _resolve(path: str, name: str) -> tuple[str, str]:
    """The file a case names and the name it is shown by: ``path`` when it
    exists, else the bundled model or folder ``name`` names (by the naming
    rule of :func:`ethasp.resources.bundled_model`), shown by its bundled name."""
    try:
        if Path(path).exists():
            return path, path
    except (OSError, ValueError):  # a name too long, ...: its case's error line says so
        return path, path
    bundled = bundled_model(name)
    return (path, path) if bundled is None else (str(bundled), bundled_name(bundled))


def read_manifest(path: Path) -> list[Case]:
    """The cases of a CSV or YAML manifest (see the module docstring)."""
    from ethasp.planning.terms import read_text

    text = read_text(path, "manifest")
    folder = path.parent
    if path.suffix.lower() == ".csv":
        try:
            rows = list(csv.DictReader(io.StringIO(text)))
        except csv.Error as error:
            raise InputError(f"{path}: not a CSV manifest ({error})") from None
        if not rows:
            raise InputError(
                f"{path}: the manifest lists no case (a header row with the "
                "column files, then one row per case)"
            )
        cases = []
        for number, row in enumerate(rows, start=2):
            if None in row:
                raise InputError(f"{path}:{number}: more cells than columns")
            cleaned = {key.strip(): value for key, value in row.items() if key is not None}
            if not any((value or "").strip() for value in cleaned.values()):
                continue
            cases.append(_row_case(cleaned, folder, f"{path}:{number}"))
        return cases
    import yaml

    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        where = f"{path}:{mark.line + 1}" if mark is not None else str(path)
        raise InputError(
            f"{where}: not a YAML manifest "
            f"({' '.join(str(getattr(error, 'problem', error)).split())})"
        ) from None
    rows = data.get("cases") if isinstance(data, dict) else None
    if not isinstance(rows, list) or not rows:
        raise InputError(f"{path}: a YAML manifest needs a list 'cases' of cases")
    cases = []
    for number, row in enumerate(rows, start=1):
        if not isinstance(row, dict):
            raise InputError(
                f"{path}: case {number} must be a mapping with files, name, "
                "plan, principles, questions"
            )
        cases.append(_row_case(row, folder, f"{path}: case {number}"))
    return cases


# -- all together ---------------------------------------------------------------------------


def discover(
    items: Iterable[Case | str | os.PathLike | Sequence[str]], pattern: str | None = None
) -> list[Case]:
    """The cases of model files, folders (searched recursively; ``pattern``, a
    glob, chooses file names), manifests and :class:`Case` objects, each once,
    in the order given.  Consecutive PDDL files on the command line (a domain
    and a problem, with the ``.lp`` annotation files after them) are one case.
    Raises InputError for a name that is neither a file nor a folder, a folder
    with no model file, or a bad manifest."""
    cases: list[Case] = []
    pddl_run: list[str] = []
    pddl_shown: list[str] = []  # their names in the output

    def close_run() -> None:
        if pddl_run:
            cases.append(Case(tuple(pddl_run), " + ".join(pddl_shown)))
            pddl_run.clear()
            pddl_shown.clear()

    for item in items:
        if isinstance(item, Case) or not isinstance(item, (str, os.PathLike)):
            close_run()
            cases.append(Case.of(item))
            continue
        name, shown = _resolve(os.fspath(item), os.fspath(item))
        path = Path(name)
        suffix = path.suffix.lower()
        if pddl_run and suffix in ASP_SUFFIXES and path.is_file():
            pddl_run.append(name)  # an annotation file of the PDDL case
            pddl_shown.append(shown)
            continue
        if suffix in PDDL_SUFFIXES and not path.is_dir():
            if sum(1 for n in pddl_run if n.lower().endswith(".pddl")) >= 2:
                close_run()
            pddl_run.append(name)
            pddl_shown.append(shown)
            continue
        close_run()
        if path.is_dir():
            found = _walk(path, pattern)
            if not found:
                what = f"matching {pattern!r}" if pattern else "(.lp, .pddl, .yaml, .json)"
                raise InputError(f"{shown}: no model file {what} in this folder")
            if shown != name:  # a bundled folder: its cases by their bundled names
                found = [
                    replace(case, name=" + ".join(bundled_name(Path(f)) for f in case.files))
                    for case in found
                ]
            cases += found
        elif is_manifest(path):
            cases += read_manifest(path)
        elif path.exists():
            cases.append(Case((name,), shown))  # an unreadable file is its case's error line
        else:
            raise InputError(f"{name}: no such file or folder")
    close_run()
    unique: dict[tuple, Case] = {}
    for case in cases:
        unique.setdefault((case.name, case.files, case.plan, case.principles, case.questions), case)
    return list(unique.values())
