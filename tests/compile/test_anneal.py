"""The sequence-pair annealer: packings never overlap, doors are met, seeds decide.

Geometry is checked here with plain arithmetic of its own, not with the annealer's score.
"""

from __future__ import annotations

import itertools
import random
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from layoutdsl.api import load_spec
from layoutdsl.compile.anneal import _door_lists, _pack, anneal_geometry
from layoutdsl.compile.anneal_runs import AnnealingRuns
from layoutdsl.compile.construct import annealable
from layoutdsl.compile.generate import RoomSizes
from layoutdsl.layout.verify import verify
from layoutdsl.syntax.ast import Obstacle

SPECS = Path(__file__).resolve().parents[2] / "specs"
TOL = 1e-6


def _office():
    spec, _ = load_spec(str(SPECS / "office_small.lay"))
    assert spec is not None
    return spec


def _gaps(a, b):
    """Gap along x and along y between two (x, y, w, h) rectangles (negative: overlap)."""
    return (max(b[0] - a[0] - a[2], a[0] - b[0] - b[2]), max(b[1] - a[1] - a[3], a[1] - b[1] - b[3]))


@pytest.mark.parametrize("seed", range(5))
def test_every_sequence_pair_packs_rooms_a_wall_apart(seed):
    """Any sequence pair, sizes and doors: the packing (with its pull and stretch towards
    doors) keeps every two rooms at least a wall apart along some axis, inside the first
    quadrant, and each room between its drawn size and the most it may grow to."""
    rng = np.random.default_rng(seed)
    n, wall = 14, 0.2
    p, q = rng.permutation(n).astype(np.int64), rng.permutation(n).astype(np.int64)
    w, h = rng.uniform(1, 6, n), rng.uniform(1, 6, n)
    max_w, max_h = w * rng.uniform(1, 2, n), h * rng.uniform(1, 2, n)
    edges = [(i, int(rng.integers(i)), 1.0) for i in range(1, n)]
    door_ptr, door_to = _door_lists(n, edges)
    x, y, packed_w, packed_h = _pack(p, q, w, h, wall, door_ptr, door_to, max_w, max_h)
    assert np.all(w - TOL <= packed_w) and np.all(packed_w <= max_w + TOL)
    assert np.all(h - TOL <= packed_h) and np.all(packed_h <= max_h + TOL)
    rects = [(x[i], y[i], packed_w[i], packed_h[i]) for i in range(n)]
    assert min(x) >= 0 and min(y) >= 0
    for a, b in itertools.combinations(rects, 2):
        assert max(_gaps(a, b)) >= wall - TOL


@pytest.mark.parametrize("seed", range(5))
def test_without_doors_each_room_sits_at_the_longest_path_from_the_origin(seed):
    """Rooms left of b (before it in P and Q) push it right, rooms below it (after it in P,
    before it in Q) push it up: checked by scanning every pair, as the definition says."""
    rng = np.random.default_rng(100 + seed)
    n, wall = 40, 0.2
    p, q = rng.permutation(n).astype(np.int64), rng.permutation(n).astype(np.int64)
    w, h = rng.uniform(1, 6, n), rng.uniform(1, 6, n)
    door_ptr, door_to = _door_lists(n, [])
    x, y, _, _ = _pack(p, q, w, h, wall, door_ptr, door_to, w, h)
    where_p = {room: k for k, room in enumerate(p)}
    where_q = {room: k for k, room in enumerate(q)}
    for b in q:  # Q's order: every room pushing b is placed before it
        left = [x[a] + w[a] + wall for a in range(n) if where_p[a] < where_p[b] and where_q[a] < where_q[b]]
        below = [y[a] + h[a] + wall for a in range(n) if where_p[a] > where_p[b] and where_q[a] < where_q[b]]
        assert x[b] == pytest.approx(max(left, default=0.0))
        assert y[b] == pytest.approx(max(below, default=0.0))


def test_a_rung_between_two_rails_is_stretched_to_meet_both():
    """Rail 0 at the bottom, rail 2 on top of a tall room 3, rung 1 between the rails on
    rail 0: the packing lengthens the rung (it may grow) to meet rail 2 and keeps rail 0's
    door, where moving it up would lose that door."""
    wall = 0.2
    # 0 below everything (last in P, first in Q); 1 left of 3 (before it in both); 1 and 3
    # below 2 (after it in P, before it in Q)
    p = np.array([2, 1, 3, 0], dtype=np.int64)
    q = np.array([0, 1, 3, 2], dtype=np.int64)
    w = np.array([10.0, 2.0, 10.0, 3.0])
    h = np.array([2.0, 3.0, 2.0, 5.0])
    max_w, max_h = w.copy(), h.copy()
    max_h[1] = 8.0
    door_ptr, door_to = _door_lists(4, [(0, 1, 1.0), (1, 2, 1.0)])
    x, y, packed_w, packed_h = _pack(p, q, w, h, wall, door_ptr, door_to, max_w, max_h)
    assert y[1] == pytest.approx(y[0] + h[0] + wall)  # still on rail 0
    assert y[1] + packed_h[1] + wall == pytest.approx(y[2])  # and now up to rail 2
    assert packed_h[1] == pytest.approx(5.0)  # as tall as room 3 beside it


def test_a_small_office_anneals_to_a_packing_with_every_door_met():
    spec = _office()
    geometry, violation = anneal_geometry(spec, seed=0)
    assert violation == pytest.approx(0.0, abs=1e-9)
    wall = spec.settings.walldim
    width, height = spec.boundary.w, spec.boundary.h
    for room in spec.rooms:
        x, y, w, h = geometry[room.id]
        assert -TOL <= x and x + w <= width + TOL and -TOL <= y and y + h <= height + TOL
        sizes = RoomSizes.of(room)
        long_side, short_side = max(w, h), min(w, h)
        assert sizes.lo_long - TOL <= long_side <= sizes.hi_long + TOL
        assert sizes.lo_short - TOL <= short_side <= sizes.hi_short + TOL
    for a, b in itertools.combinations(spec.rooms, 2):
        assert max(_gaps(geometry[a.id], geometry[b.id])) >= wall - TOL
    for adj in spec.adjacencies:
        gx, gy = _gaps(geometry[adj.a], geometry[adj.b])
        need = adj.door / spec.settings.door_utilization
        # one wall apart on one axis, facing each other along the door's wall on the other
        assert (abs(gx - wall) <= TOL and -gy >= need - TOL) or (abs(gy - wall) <= TOL and -gx >= need - TOL)
    # the onB entrance touches the boundary
    x, y, w, h = geometry["E0"]
    assert min(x, y, width - x - w, height - y - h) <= TOL


def test_the_same_seed_gives_the_same_geometry_and_other_seeds_others():
    spec = _office()
    first, _ = anneal_geometry(spec, seed=3)
    again, _ = anneal_geometry(spec, seed=3)
    other, _ = anneal_geometry(spec, seed=4)
    assert first == again
    assert first != other


def test_a_run_cut_off_by_its_deadline_returns_nothing():
    assert anneal_geometry(_office(), seed=0, deadline=time.monotonic() - 1.0) is None


def test_a_ladder_of_corridors_constructs_from_annealed_geometries_alone(monkeypatch):
    """A spec with a ladder (layoutdsl.compile.ladders) anneals from the start; with the
    greedy and spring geometries taken away, the construction still finds a layout, which
    the independent verifier accepts."""
    from _specs import ladder_spec, tree_spec

    from layoutdsl.compile import construct

    spec = ladder_spec()
    assert construct._anneal_order(spec) == "first" and construct._anneal_order(tree_spec()) is None
    monkeypatch.setattr(construct, "GENERATED_TRIES", 0)
    assert construct._seed_geometries(spec, random.Random(0), False, False) == []
    rects = construct.construct_start(spec, seed=0, use_hints=False, deadline=time.monotonic() + 30)
    assert rects is not None
    assert verify(spec, construct.rects_to_layout(spec, rects)) == []


def test_a_run_from_a_layout_keeps_every_door_met():
    """A run asked for from a geometry starts from its sequence pair: from a packing that
    already meets every door, the run ends with every door met too."""
    spec = _office()
    layout, violation = anneal_geometry(spec, seed=0)
    assert violation == 0.0
    runs = AnnealingRuns(spec, seed=1, deadline=time.monotonic() + 60, workers=1)
    try:
        runs.submit(layout)
        run = runs.wait(lambda v: True, time.monotonic() + 60)
        while run is not None and not run[2]:  # a random-start run finished first
            run = runs.wait(lambda v: True, time.monotonic() + 60)
    finally:
        runs.close()
    geometry, violation, from_geometry = run
    assert from_geometry and violation == 0.0
    assert set(geometry) == {room.id for room in spec.rooms}


def test_idle_workers_anneal_from_random_sequence_pairs():
    spec = _office()
    runs = AnnealingRuns(spec, seed=0, deadline=time.monotonic() + 60, workers=2)
    try:
        run = runs.wait(lambda v: True, time.monotonic() + 60)
    finally:
        runs.close()
    geometry, violation, from_geometry = run
    assert not from_geometry and violation >= 0.0 and len(geometry) == len(spec.rooms)


def test_annealing_runs_past_their_deadline_give_nothing():
    runs = AnnealingRuns(_office(), seed=0, deadline=time.monotonic() - 1.0)
    try:
        assert runs.wait(lambda v: True, time.monotonic() + 1.0) is None
    finally:
        runs.close()


def test_specs_with_pinned_rooms_are_left_to_the_greedy_placement():
    spec = _office()
    assert annealable(spec)
    boundary = replace(spec.boundary, obstacles=(Obstacle("O1", 0.0, 0.0, 1.0, 1.0),))
    assert not annealable(replace(spec, boundary=boundary))


class _Finished:
    """An annealing with a finished run close enough to a layout, every time it is asked."""

    order = "first"

    def start(self):
        pass

    def promising(self):
        return True

    def take(self):
        return None


def test_the_hints_geometries_come_before_any_annealed_one():
    """A spec with hints asks for its own arrangement: its hint geometries are tried first
    even when an annealed geometry is waiting; after them, a finished annealed geometry goes
    before the next greedy one."""
    from layoutdsl.compile import construct

    def maker():
        return None

    candidates = [("hints", maker), ("hints", maker), ("generated", maker), ("graph", maker)]
    kinds = [kind for kind, _, _ in itertools.islice(construct._in_turn(candidates, _Finished()), 5)]
    assert kinds == ["hints", "hints", "annealed", "annealed", "annealed"]
    kinds = [kind for kind, _, last in construct._in_turn(candidates, None)]
    assert kinds == ["hints", "hints", "generated", "graph"]


class _Waiting(_Finished):
    """The annealing of a plan the satellites split (order "alone"), no run done yet."""

    order = "alone"

    def promising(self):
        return False

    def wait(self):
        return None


def test_a_split_plan_waits_for_annealed_geometries_after_its_hints():
    """A plan with a large cycle block anneals on both cores: after its hints, it waits for
    annealed geometries and repairs no greedy one, even while none is done."""
    from layoutdsl.compile import construct

    def maker():
        return None

    annealing = _Waiting()
    candidates = [("hints", maker), ("generated", maker), ("graph", maker)]
    tried = list(itertools.islice(construct._in_turn(candidates, annealing), 4))
    assert [kind for kind, _, _ in tried] == ["hints", "annealed", "annealed", "annealed"]
    assert all(make == annealing.wait for _, make, _ in tried[1:])


def test_a_split_plan_gives_an_annealed_geometry_few_repair_rounds(monkeypatch):
    """More runs keep coming for a plan the satellites split: its annealed geometries get
    ANNEALED_ROUNDS repair rounds; those of other plans as many as they need."""
    import random
    import time

    from layoutdsl.compile import construct

    spec = _office()
    geometry = {r.id: (0.0, 0.0, r.target_w, r.target_h) for r in spec.rooms}
    limits = []

    def repair(problem, geometry_, deadline, seed, **options):
        limits.append(options["max_rounds"])
        return geometry_  # "repaired": the construction returns it

    class _Done(_Waiting):
        taken_violation = 1.0

        def wait(self):
            return geometry

    monkeypatch.setattr(construct, "_repair", repair)
    problem = construct._Problem.of(spec)
    for order, expected in (("alone", construct.ANNEALED_ROUNDS), ("first", None)):
        annealing = _Done()
        annealing.order = order
        rects = construct._first_repaired(spec, problem, [], time.monotonic() + 5.0, 0, random.Random(0),
                                          annealing)
        assert rects == geometry and limits.pop() == expected


def test_the_finished_run_nearest_a_layout_is_taken_first():
    """Runs finish while a repair holds the construction: the nearest to a layout goes
    first, whatever the order they finished in, and the unfit are dropped."""
    runs = AnnealingRuns(_office(), seed=0, deadline=None, workers=0)
    try:
        runs.done = [({"A": 1}, 3.0, False), ({"B": 1}, 0.0, True), ({"C": 1}, 7.0, False),
                     ({"D": 1}, 0.0, False)]
        fit = lambda violation: violation <= 6.0  # noqa: E731
        assert [runs.pop_done(fit)[0] for _ in range(3)] == [{"B": 1}, {"D": 1}, {"A": 1}]
        assert runs.pop_done(fit) is None and runs.done == []
    finally:
        runs.close()


def test_an_annealed_repair_gives_way_only_to_a_far_nearer_run():
    from layoutdsl.compile import construct

    annealing = construct.Annealing.__new__(construct.Annealing)
    annealing.runs = AnnealingRuns(_office(), seed=0, deadline=None, workers=0)
    try:
        annealing.runs.done = [({}, 0.9, False)]
        annealing.taken_violation = 2.0
        assert construct._give_way(annealing, "annealed")()
        annealing.taken_violation = 1.2
        assert not construct._give_way(annealing, "annealed")()
        assert construct._give_way(annealing, "generated")()  # any repairable run
        assert construct._give_way(annealing, "hints") is None
        assert construct._give_way(None, "generated") is None
    finally:
        annealing.runs.close()


def test_a_quick_try_gives_up_after_its_seed_geometries(monkeypatch):
    from layoutdsl.compile import construct

    spec = _office()
    repairs = []
    monkeypatch.setattr(construct, "_repair", lambda *args, **kwargs: repairs.append(args[1]))
    geometry, _ = anneal_geometry(spec, seed=0)
    candidates = [("generated", lambda: geometry)] * 5
    problem = construct._Problem.of(spec)
    rects = construct._first_repaired(spec, problem, candidates, time.monotonic() + 30, 0,
                                      random.Random(0), None, max_geometries=2)
    assert rects is None and len(repairs) == 2
    repairs.clear()
    construct._first_repaired(spec, problem, candidates, time.monotonic() + 30, 0, random.Random(0), None)
    assert len(repairs) == 5
