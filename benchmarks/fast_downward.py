"""Fast Downward for the benchmarks: its driver script, from the PyPI package
``up-fast-downward`` (a benchmark extra, never a dependency of ethasp)."""

from __future__ import annotations

import importlib.util
from pathlib import Path


def fast_downward_driver() -> Path | None:
    """The driver script of the up-fast-downward package, if it is installed."""
    spec = importlib.util.find_spec("up_fast_downward")
    if spec is None or not spec.submodule_search_locations:
        return None
    for location in spec.submodule_search_locations:
        driver = Path(location) / "downward" / "fast-downward.py"
        if driver.is_file():
            return driver
    return None
