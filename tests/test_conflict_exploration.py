"""The exploration of conflicts and goal subsets (MARCO) on its own, with the
decisions given by a stub: a family of sets is unreachable exactly where a
set contains one of the family's conflicts.  The conflicts and goal subsets
found must be the family's minimal conflicts and maximal reachable sets,
and a conflict must be found by insertion where decisions give no core (a
planner's search exhausts the states to decide an unreachable set): one
unreachable set decided per item of the conflict, not one per item left out.
"""

import itertools

from hypothesis import given, settings
from hypothesis import strategies as st

from ethasp.planning.budget import Budget
from ethasp.planning.search import FOUND, NONE
from ethasp.principles.conflict import Exploration
from ethasp.principles.goal_items import Reach


class Decisions:
    """Reachability of sets of items by a family of conflicts; each decision
    counted, by its answer (``core``: answer unreachable sets with the
    conflict they contain, as a solver's core would)."""

    def __init__(self, conflicts, core: bool = False):
        self.family = [frozenset(c) for c in conflicts]
        self.core = core
        self.budget = Budget()
        self.decided: list[tuple[frozenset, str]] = []

    def relaxed_core(self, items: frozenset) -> frozenset | None:
        # Relaxed reachability knows the conflicts of one item.
        return next((c for c in self.family if len(c) == 1 and c <= items), None)

    def reach(self, items: frozenset) -> Reach:
        hit = next((c for c in self.family if c <= items), None)
        status = FOUND if hit is None else NONE
        self.decided.append((items, status))
        return Reach(status, core=hit if (self.core and hit is not None) else None)


def minimal(family) -> set[frozenset]:
    sets = {frozenset(c) for c in family}
    return {s for s in sets if not any(t < s for t in sets)}


def maximal_reachable(n: int, family) -> set[frozenset]:
    reachable = [
        frozenset(s)
        for size in range(n + 1)
        for s in itertools.combinations(range(n), size)
        if not any(frozenset(c) <= frozenset(s) for c in family)
    ]
    return {s for s in reachable if not any(s < t for t in reachable)}


FAMILIES = st.integers(min_value=1, max_value=7).flatmap(
    lambda n: st.tuples(
        st.just(n),
        st.lists(st.sets(st.integers(0, n - 1), max_size=n), min_size=1, max_size=4),
    )
)


@settings(max_examples=150, deadline=None)
@given(FAMILIES, st.booleans())
def test_the_exploration_finds_every_minimal_conflict_and_maximal_subset(drawn, core):
    n, family = drawn
    decisions = Decisions(family, core)
    exploration = Exploration(decisions, list(range(n)))
    exploration.run()
    assert exploration.complete and exploration.exact
    assert set(exploration.conflicts) == minimal(family)
    assert set(exploration.subsets) == maximal_reachable(n, family)


def test_a_conflict_without_a_core_is_found_by_insertion():
    # Ten items, one conflict of two (items 3 and 7).  Deletion would decide
    # eight unreachable sets (one per item left out); insertion decides one
    # per item of the conflict, and the conflict itself.
    decisions = Decisions([{3, 7}])
    exploration = Exploration(decisions, list(range(10)))
    found = exploration._shrink(frozenset(range(10)), None)
    assert found == frozenset({3, 7})
    unreachable = [items for items, status in decisions.decided if status == NONE]
    assert len(unreachable) <= 3, unreachable


def test_a_conflict_with_a_core_is_shrunk_from_the_core():
    decisions = Decisions([{3, 7}], core=True)
    exploration = Exploration(decisions, list(range(10)))
    found = exploration._shrink(frozenset(range(10)), frozenset({3, 5, 7}))
    assert found == frozenset({3, 7})
    # Only subsets of the core were decided.
    assert all(items <= {3, 5, 7} for items, _ in decisions.decided)


def test_an_empty_conflict_is_found_by_insertion():
    # No set is reachable, not even the empty one: the conflict is empty.
    decisions = Decisions([set()])
    exploration = Exploration(decisions, list(range(4)))
    assert exploration._shrink(frozenset(range(4)), None) == frozenset()


def test_a_set_known_unreachable_is_not_decided_again():
    # The whole set was proven unreachable before (the contrast's search):
    # it is not decided again, and relaxed reachability's core still serves.
    decisions = Decisions([{2}, {0, 3}])
    every = frozenset(range(5))
    exploration = Exploration(decisions, sorted(every), unreachable=[every])
    exploration.run()
    assert set(exploration.conflicts) == {frozenset({2}), frozenset({0, 3})}
    assert every not in [items for items, _ in decisions.decided]
    # Relaxed reachability named {2} within the whole set: the empty set is the
    # only one decided for it (no insertion over the items before 2), and the
    # next decision is the map's next seed.
    assert [items for items, _ in decisions.decided[:2]] == [frozenset(), frozenset({0, 1, 3, 4})]
