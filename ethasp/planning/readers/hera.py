"""HERA's files, situations or causal agency models, told apart by their
content (:func:`ethasp.planning.readers.hera_data.kind_of`) and translated by
their readers (:mod:`ethasp.planning.readers.situation`,
:mod:`ethasp.planning.readers.cam`)."""

from __future__ import annotations

import sys
from collections.abc import Mapping
from pathlib import Path

from ethasp.planning.readers.cam import translate_data as translate_cam
from ethasp.planning.readers.hera_data import CAM, kind_of, load_data
from ethasp.planning.readers.situation import read_situation
from ethasp.planning.terms import read_text


def translate_file(path: Path, world: Mapping[str, bool] | None = None) -> tuple[str, str]:
    """A HERA file as (its kind, ``situation`` or ``cam``, and its ASP facts);
    warnings go to standard error.  ``world``: values of a causal agency
    model's background variables and events, over those of its file."""
    data = load_data(path, read_text(path))
    kind = kind_of(data, str(path))
    if kind == CAM:
        if world:
            data = dict(data, world={**(data.get("world") or {}), **world})
        text, warnings = translate_cam(data, str(path))
    else:
        text, warnings = read_situation(data, str(path))
    for line in warnings:
        print(line, file=sys.stderr)
    return kind, text
