"""Many cases at once: ``ethasp batch`` and :func:`ethasp.batch`.

One concept per module: :mod:`~ethasp.batch.cases` (which cases: files,
folders, manifests), :mod:`~ethasp.batch.task` (what is computed for a case),
:mod:`~ethasp.batch.output` (the JSON lines file, hashes, resuming),
:mod:`~ethasp.batch.pool` (local warm worker processes),
:mod:`~ethasp.batch.cluster` (a Dask cluster), :mod:`~ethasp.batch.progress`
(the progress bar), :mod:`~ethasp.batch.report` (the HTML report) and
:mod:`~ethasp.batch.run` (a batch put together).
"""

import sys
import types

from ethasp.batch.cases import Case, discover
from ethasp.batch.run import Batch, batch

__all__ = ["Batch", "Case", "batch", "discover"]


class _Package(types.ModuleType):
    """``ethasp.batch`` names this package once it is imported (Python sets the
    attribute); calling it runs :func:`ethasp.batch.run.batch`, so that
    ``ethasp.batch(...)`` works either way."""

    def __call__(self, *args, **kwargs):
        return batch(*args, **kwargs)


sys.modules[__name__].__class__ = _Package
