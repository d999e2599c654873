"""Where the encodings (logic programs) and bundled models are."""

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


def bundled_model(name: str) -> Path:
    """The path of a bundled example model, e.g. ``bundled_model("trolley")``."""
    path = MODELS / (name if name.endswith(".lp") else name + ".lp")
    if not path.is_file():
        raise FileNotFoundError(f"bundled model not found: {path}")
    return path
