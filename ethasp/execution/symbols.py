"""clingo's symbols between processes.

A :class:`clingo.Symbol` pickles as its address in clingo's symbol table,
which means nothing in another process (a worker, an engine's child: a
crash, or another symbol).  Importing this module makes symbols pickle as
their text, read back with :func:`clingo.parse_term`; every module of
:mod:`ethasp.execution` that sends data between processes imports it.
"""

from __future__ import annotations

import copyreg

import clingo


def symbol(text: str) -> clingo.Symbol:
    """The symbol of a pickled symbol's text."""
    return clingo.parse_term(text)


def _reduce(value: clingo.Symbol):
    return symbol, (str(value),)


copyreg.pickle(clingo.Symbol, _reduce)
