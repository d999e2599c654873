"""The version of the installed package, from its metadata."""

from __future__ import annotations


def package_version() -> str:
    """The installed ethasp's version (``unknown`` for a checkout that is not installed)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("ethasp")
    except PackageNotFoundError:
        return "unknown"
