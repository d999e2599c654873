"""The clingo driver: one grounding of a model, and the searches over it.

:mod:`ethasp.planning.driver.planner` grounds a model once and answers every
search from that control (multi-shot solving, assumptions);
:mod:`ethasp.planning.driver.incremental` grounds the time steps one by one;
:mod:`ethasp.planning.driver.namespace` keeps model files out of what the
encodings define (the reserved predicates, computed once and cached).
"""
