"""The input readers: models written in other languages, translated into facts
of the model vocabulary (``encodings/planning/model.lp``).

PDDL domains and problems (:mod:`ethasp.planning.readers.pddl`, parsed by
:mod:`ethasp.planning.readers.pddl_syntax`) and HERA's situations
(:mod:`ethasp.planning.readers.situation`).  A reader produces text that
clingo grounds like any model file; what the facts mean is decided by the
encodings alone.
"""

#: The heads of the rules over pddl_candidate/1 that a PDDL translation writes
#: (see encodings/planning/static.lp); here, where reading them needs no reader.
SCHEMA_PREDICATES = ("pddl_schema_instance", "pddl_static_failure")
