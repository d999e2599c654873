"""Where the encodings (logic programs) and bundled models are."""

import os
from pathlib import Path

_HERE = Path(__file__).resolve().parent


def _first_existing(*candidates: Path) -> Path:
    for candidate in candidates:
        if candidate.is_dir():
            return candidate
    return candidates[0]


# Installed, the encodings live inside the package; in a source checkout they
# are the top-level folder beside it.
ENCODINGS = _first_existing(_HERE / "encodings", _HERE.parent / "encodings")
MODELS = _first_existing(_HERE / "asp", _HERE.parent / "asp")


def encoding(name: str) -> Path:
    """The path of an encoding, e.g. ``encoding("planning/transition.lp")``."""
    path = ENCODINGS / name
    if not path.is_file():
        raise FileNotFoundError(f"encoding not found: {path}")
    return path


def bundled_model(name: str | os.PathLike) -> Path | None:
    """The bundled model file or folder that ``name`` names, or None.

    The naming rule: ``name`` is a path in the folder of bundled models
    (``asp/`` of the source tree), such as ``trolley.lp``,
    ``hera/robot-and-frank.yaml``, ``pddl/gripper-domain.pddl`` or the folder
    ``hera``; a leading ``asp/`` may be given (``asp`` alone names the whole
    folder), the ``.lp`` of an ASP file left out (``trolley``), and a file
    named by its file name alone when no other bundled file has that name
    (``robot-and-frank.yaml``).  Nothing outside that folder is named.
    """
    text = os.fspath(name).replace("\\", "/").strip("/")
    if not text or Path(os.fspath(name)).is_absolute():
        return None
    parts = [part for part in text.split("/") if part not in ("", ".")]
    if ".." in parts:
        return None
    if parts[:1] == ["asp"]:
        parts = parts[1:]
    candidates = [MODELS.joinpath(*parts)] if parts else [MODELS]
    if parts and not parts[-1].endswith(".lp"):
        candidates.append(MODELS.joinpath(*parts[:-1], parts[-1] + ".lp"))
    for candidate in candidates:
        if candidate.is_file() or candidate.is_dir():
            return candidate
    if len(parts) == 1:
        same = [path for path in MODELS.rglob("*") if path.name == parts[0] and path.is_file()]
        if len(same) == 1:
            return same[0]
    return None


def model_path(name: str | os.PathLike) -> Path:
    """The file or folder a model name means: the path as given when it exists
    (or cannot be checked), else the bundled model of that name
    (:func:`bundled_model`), else the path as given (reading it then says
    that there is no such file)."""
    path = Path(name)
    try:
        if path.exists():
            return path
    except (OSError, ValueError):  # a name too long, ...: reading it says so
        return path
    return bundled_model(name) or path


def bundled_name(path: Path) -> str:
    """The name of a bundled model file or folder: its path in the folder of
    bundled models (``hera/trolley.yaml``; ``asp`` for the folder itself)."""
    relative = Path(path).relative_to(MODELS).as_posix()
    return "asp" if relative == "." else relative


def bundled_names() -> list[str]:
    """The names of the bundled model files, as the naming rule gives them at
    their shortest with their folder: ``trolley``, ``hera/trolley.yaml``, ..."""
    names = []
    for path in sorted(MODELS.rglob("*")):
        if not path.is_file() or path.suffix not in (".lp", ".pddl", ".yaml", ".json"):
            continue
        relative = path.relative_to(MODELS).as_posix()
        names.append(relative.removesuffix(".lp") if "/" not in relative else relative)
    return names
