"""The engines: searches in Python over the ground model, beside the encodings.

Some questions are answered better outside ASP: every reachable state at
once (binary decision diagrams), a plan found fast by greedy search, the best
reachable state.  The engines of this package answer them under one
contract.

1. **They read the ground model** that the encodings produce: the atoms of
   the vocabulary of ``encodings/planning/model.lp`` after clingo grounded
   the model, read from the planner (:mod:`ethasp.planning.driver.planner`),
   never a model's text.  The encodings stay the one definition of the
   semantics.  The restrictions of principles and questions are planning
   models in the same vocabulary (HModels), so every engine reads them too.
2. **Every plan they propose is checked by its trace** in the encodings
   (``encodings/planning/trace.lp``) before it is reported.
3. **Every negative claim** ("none", "no better state", a lower bound on the
   length of plans) **is cross-checked by property tests** against a
   brute-force oracle written from the paper's definitions
   (``tests/oracle.py``), on random models that draw exogenous events,
   conditional effects and derived variables (``tests/test_reachability.py``,
   ``tests/test_layers.py``, ``tests/test_greedy.py``,
   ``tests/test_properties_utilitarianism.py``).
4. **They run under the search's budget**: cut short by a limit (time,
   diagram nodes, configurations, states), they claim nothing, and the
   search goes on without them or answers ``bounded``.
5. **What an engine does not model, it does not answer.**  Each module
   declares the model features it handles (``FEATURES``); an engine, and its
   bound, is used only on a model whose features it handles
   (:func:`handles`, asked by the planner), and refuses any other.

The engines and the features they handle:

* ``reachability``: exact layers of states, computed with diagrams: the best
  utility of a reachable state, the first layer that meets a set of states,
  "none".  Conditional effects and derived variables; no exogenous events.
* ``explicit``: explicit layers of configurations (state, time), with the
  same claims, for models with events, up to a limit on the configurations.
  Every feature.
* ``layers``: beside plan search, lower bounds on the length of plans and
  shortest plans, from the diagrams or, with events, from the explicit
  layers.  Every feature.
* ``greedy``: any-plan search, a plan fast (not a shortest one), or "none"
  once every reachable state is expanded.  Every feature (with events, the
  states are configurations).
* ``best_state``: for utilitarianism, a reachable state better than a
  utility, or the best one, from the engines above or by clingo
  optimisation.  Every feature.
* ``cheapest``: for models with action costs, uniform-cost search over
  explicit configurations: a cheapest plan, a lower bound on the cost of
  every plan, or "none" once every reachable configuration is expanded.
  Every feature.
* ``cost_layers``: the same claims from layers of states by cost, with
  diagrams (run in turns with ``cheapest``).  Conditional effects and
  derived variables; no exogenous events.

``task`` holds what ``explicit``, ``greedy`` and ``cheapest`` search over: the explicit
states of the search model (bit masks), its actions and derived variables,
and the FF heuristic.
"""

from __future__ import annotations

from collections.abc import Iterable

# The features of a model that an engine may or may not handle.
EVENTS = "exogenous events"
CONDITIONAL_EFFECTS = "conditional effects"
DERIVED_VARIABLES = "derived variables"
ALL_FEATURES = frozenset({EVENTS, CONDITIONAL_EFFECTS, DERIVED_VARIABLES})


def handles(features: frozenset[str], present: Iterable[str]) -> bool:
    """Does an engine that handles ``features`` handle a model that has the
    features ``present``?"""
    return set(present) <= features
