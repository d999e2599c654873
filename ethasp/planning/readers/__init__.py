"""The input readers: models written in other languages, translated into facts
of the model vocabulary (``encodings/planning/model.lp``).

PDDL domains and problems (:mod:`ethasp.planning.readers.pddl`, parsed by
:mod:`ethasp.planning.readers.pddl_syntax`) and HERA's situations
(:mod:`ethasp.planning.readers.situation`).  A reader produces text that
clingo grounds like any model file; what the facts mean is decided by the
encodings alone.
"""
