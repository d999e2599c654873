"""The ethasp command line: a thin layer over the Python API.

One module per command (``plan``, ``validate``, ``judge``, ``query``, ``ask``,
``explain``, ``dialogue``, ``serve``, ``completion``, ``batch``, ``report``),
each with the function that adds its parser and the function that runs it; the
options that commands share are parent parsers (:mod:`.models`,
:mod:`.options`, :mod:`.output`); :mod:`.parser` puts the commands together and
:mod:`.execution` runs one.
"""

from ethasp.interfaces.cli.execution import main
from ethasp.interfaces.cli.parser import build_parser

__all__ = ["build_parser", "main"]
