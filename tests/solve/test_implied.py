"""The final sizing leaves out the pairs whose fixed relation other pairs imply, and only those."""

from __future__ import annotations

from collections import deque

from layoutdsl.solve.relations import _relations_fixed, _without_implied

from spec_cases import FIVE, FIVE_RECTS


def _chain(kept, first, second, axis_of, before):
    """A chain of two or more kept relations along one axis from `first` to `second`
    (breadth first over the kept pairs, read independently of the code under test)."""
    steps = {}
    for (a, b), (direction,) in kept.items():
        u, v = (a, b) if direction in ("left", "below") else (b, a)
        steps.setdefault((axis_of(direction), u), []).append(v)
    axis = axis_of(before)
    queue, seen = deque([(first, 0)]), {first}
    while queue:
        room, length = queue.popleft()
        for nxt in steps.get((axis, room), []):
            if nxt == second and length + 1 >= 2:
                return True
            if nxt not in seen:
                seen.add(nxt)
                queue.append((nxt, length + 1))
    return False


def test_a_pair_is_left_out_only_when_a_chain_of_kept_relations_implies_it():
    problem, _geometry, options, _ = _relations_fixed(FIVE, FIVE_RECTS, lambda room, rect: room)
    kept = _without_implied(problem, options, keep=set())
    dropped = set(options) - set(kept)
    # A lies above the corridor C, which lies above D: A above D says nothing new
    assert ("A", "D") in dropped
    # every door stays, whatever else implies it
    assert all(frozenset(pair) not in problem.walls for pair in dropped)

    def axis_of(direction):
        return "x" if direction in ("left", "right") else "y"

    for a, b in dropped:
        (direction,) = options[(a, b)]
        first, second = (a, b) if direction in ("left", "below") else (b, a)
        assert _chain(kept, first, second, axis_of, direction), (a, b, direction)


def test_pairs_asked_to_stay_stay():
    problem, _geometry, options, _ = _relations_fixed(FIVE, FIVE_RECTS, lambda room, rect: room)
    assert ("A", "D") in _without_implied(problem, options, keep={("A", "D")})
