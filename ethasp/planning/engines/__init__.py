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
2. **Every positive claim carries its witness, checked by its trace** in
   the encodings (``encodings/planning/trace.lp``) before it is reported: a
   plan they propose, and for a reachable state ("a better reachable state
   exists", a best reachable state) a plan that reaches it, whose trace
   ends in that state, of that utility.
3. **Every negative claim** ("none", "no better state", a lower bound on the
   length of plans) **is cross-checked by property tests** against the
   encodings themselves (clingo on the same random models at fixed
   horizons: ``encodings/planning/plan.lp``, ``encodings/judgement/best.lp``)
   and against a brute-force oracle written from the paper's definitions
   (``tests/oracle.py``), on random models that draw exogenous events,
   conditional effects and derived variables
   (``tests/test_properties_engines.py``, ``tests/test_reachability.py``,
   ``tests/test_layers.py``, ``tests/test_greedy.py``,
   ``tests/test_properties_utilitarianism.py``).
4. **They run under the search's budget**: cut short by a limit (time,
   diagram nodes, configurations, states), they claim nothing, and the
   search goes on without them or answers ``bounded``.
5. **What an engine does not model, it does not answer.**  Each module
   declares the model features it handles (``FEATURES``); the searches ask
   :func:`handles` (:meth:`ethasp.planning.driver.planner.Planner.handles`)
   before they use any engine, and choose another where the answer is no
   (the principles ask :func:`ethasp.planning.engines.best_state.unhandled`
   before they compare reachable states, and answer ``bounded`` without it);
   an engine given a model with a feature it does not handle refuses it
   (:func:`require` raises :class:`Unhandled`): no answer comes from an
   engine that ignored part of the model (``tests/test_engines_contract.py``
   tries every engine on every feature it does not handle).

The engines and the features they handle:

* ``reachability``: exact layers of states, computed with diagrams: the best
  utility of a reachable state, the first layer that meets a set of states,
  "none".  Conditional effects and derived variables; no exogenous events.
* ``explicit``: explicit layers of configurations (state, time), with the
  same claims, for models with events, up to a limit on the configurations.
  Every feature.
* ``layers``: beside plan search, lower bounds on the length of plans and
  shortest plans, from the diagrams (``reachability``) or, where the
  diagrams do not handle the model (events), from the explicit layers.
  Every feature.
* ``greedy``: any-plan search, a plan fast (not a shortest one), or "none"
  once every reachable state is expanded.  Conditional effects and derived
  variables; no exogenous events: on a model with events the planner runs
  the ``layers`` beside any-plan search instead (explicit layers of
  configurations, for the proof that no plan exists; the plan is the
  solver's).
* ``best_state``: for utilitarianism, a reachable state better than a
  utility, or the best one, each with a plan that reaches it: from
  ``reachability``, else ``explicit``, else ``downward`` (where the diagrams
  give up and the model's planning system is Fast Downward), else by clingo
  optimisation.  Every feature.
* ``cheapest``: for models with action costs, uniform-cost search over
  explicit configurations: a cheapest plan, a lower bound on the cost of
  every plan, or "none" once every reachable configuration is expanded.
  Every feature.
* ``cost_layers``: the same claims from layers of states by cost, with
  diagrams (run in turns with ``cheapest``).  Conditional effects and
  derived variables; no exogenous events.

* ``downward``: Fast Downward, a planner of the planning community, run as
  a child process on the task that ``sas`` writes from the ground model (the
  ``planners`` extra; chosen by :mod:`ethasp.planning.systems`): a shortest
  plan (A* with LM-cut, or h^max with conditional effects), some plan (lazy
  greedy search with FF), "none" once every state not recognised as a dead
  end is explored, and for ``best_state`` states worth at least a utility.
  Conditional effects; no exogenous events, no derived variables.

``sas`` writes what ``downward`` searches (and refuses events and derived
variables), with the mutex groups that ``groups`` proves on the search
model as finite-domain variables (it refuses events); ``task`` holds what
``explicit``, ``greedy`` and ``cheapest`` search over: the explicit states
of the search model (bit masks), its actions and derived variables, and the
FF heuristic.
"""

from __future__ import annotations

from collections.abc import Iterable

# The features of a model that an engine may or may not handle.
EVENTS = "exogenous events"
CONDITIONAL_EFFECTS = "conditional effects"
DERIVED_VARIABLES = "derived variables"
ALL_FEATURES = frozenset({EVENTS, CONDITIONAL_EFFECTS, DERIVED_VARIABLES})


class Unhandled(ValueError):
    """An engine was given a model with a feature it does not handle."""


def handles(features: frozenset[str], present: Iterable[str]) -> bool:
    """Does an engine that handles ``features`` handle a model that has the
    features ``present``?"""
    return set(present) <= features


def require(engine: str, features: frozenset[str], present: Iterable[str]) -> None:
    """An engine's refusal: :class:`Unhandled` unless it handles every feature
    ``present`` (``engine`` names it in the message)."""
    missing = sorted(set(present) - features)
    if missing:
        raise Unhandled(f"{engine} does not model {' or '.join(missing)}")


def ground_features(atoms) -> frozenset[str]:
    """The features of a model's ground atoms (``atoms``: anything with the
    planner's ``get(name, arity)``: the planner, or what an engine read of it)."""
    present = {
        EVENTS: bool(atoms.get("event_at", 2)),
        CONDITIONAL_EFFECTS: bool(atoms.get("ceff", 4)),
        DERIVED_VARIABLES: bool(atoms.get("derived", 1)),
    }
    return frozenset(feature for feature, there in present.items() if there)


def model_features(model) -> frozenset[str]:
    """The features of a ground model of the engines
    (:class:`ethasp.planning.engines.reachability.GroundModel`)."""
    present = {
        EVENTS: bool(model.events),
        CONDITIONAL_EFFECTS: any(
            effect.condition for action in model.actions for effect in action.effects
        ),
        DERIVED_VARIABLES: bool(model.axioms),
    }
    return frozenset(feature for feature, there in present.items() if there)
