"""Which planning system searches for plans: clingo, or an installed planner.

Plan search (:mod:`ethasp.planning.search`) runs on clingo and the engines
beside it, or hands the task to a planner of the planning community: Fast
Downward (:mod:`ethasp.planning.engines.downward`, installed with the
``planners`` extra).  The choice is the model's ``planning_system``
(``--planner`` on the command line), one of:

* ``clingo``: the encodings and the engines of this package, always;
* ``fast-downward``: Fast Downward wherever the search compiles
  (:func:`usable`), clingo elsewhere, with one line of warning;
* ``auto`` (the default): Fast Downward where it is installed, the search
  compiles and the task has at least :data:`AUTO_ACTIONS` usable ground
  actions (on smaller tasks clingo answers before a planner process has
  started), clingo otherwise, silently.

The choice depends on the options and the task alone, never on which
engine finishes first, so that the answer is the same on every run; a
planner that is missing or fails hands the search to clingo, with one line
of warning on standard error.
"""

from __future__ import annotations

import functools
import sys

AUTO, CLINGO, FAST_DOWNWARD = "auto", "clingo", "fast-downward"
CHOICES = (AUTO, CLINGO, FAST_DOWNWARD)
DEFAULT = AUTO

# Usable ground actions from which ``auto`` hands a search to Fast Downward.
AUTO_ACTIONS = 32

# Warnings already given by this process (each once).
_warned: set[str] = set()


@functools.cache
def installed() -> bool:
    """Is Fast Downward installed (the ``planners`` extra)?"""
    from ethasp.planning.engines import downward

    return downward.executable() is not None


def warn(text: str) -> None:
    """One line of warning on standard error, once per process."""
    if text not in _warned:
        _warned.add(text)
        print(f"ethasp: warning: {text}", file=sys.stderr, flush=True)


def usable(planner, setting=None, all_plans: bool = False) -> bool:
    """Does a search under ``setting`` (None: a search for reachable states of
    a utility, :mod:`ethasp.planning.engines.best_state`) hand its task to
    Fast Downward, by the planner's model's choice?  (It may still find that
    the task does not compile, or the planner may fail: then clingo
    searches.)"""
    choice = getattr(planner.model, "planning_system", DEFAULT)
    if choice == CLINGO:
        return False
    forced = choice == FAST_DOWNWARD
    why = _unsuited(planner, setting, all_plans)
    if why:
        if forced:
            warn(f"Fast Downward does not search {why}: clingo searches instead")
        return False
    if not installed():
        if forced:
            warn(
                "Fast Downward is not installed (pip install 'ethasp[planners]'): "
                "clingo searches instead"
            )
        return False
    return forced or len(planner.search_atoms("usable", 1)) >= AUTO_ACTIONS


def _unsuited(planner, setting, all_plans: bool) -> str:
    """Why a search is not one Fast Downward does (words), or the empty text."""
    from ethasp.planning.driver.planner import final_facts
    from ethasp.planning.engines import downward, handles

    if setting is None:
        pass
    elif all_plans:
        return "for all shortest plans"
    elif not setting.goal or setting.at_least is not None or setting.other_state is not None:
        return "for states of a utility"
    elif setting.constraints and final_facts(setting.constraints) is None:
        return "under a question's constraints that no HModel compiles"
    if not handles(downward.FEATURES, planner.features):
        return f"models with {' or '.join(sorted(planner.features - downward.FEATURES))}"
    return ""
