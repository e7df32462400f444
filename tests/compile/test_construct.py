"""The first-feasible construction (issue 6): verified rectangles, fast, deterministic."""

from __future__ import annotations

import time
from dataclasses import replace

import pytest

from layoutdsl.syntax.ast import Boundary, Cluster, ClusterMember, Hint, Obstacle, Position
from layoutdsl.compile.construct import (
    construct_start,
    hard_violations,
    rects_to_layout,
)
from layoutdsl.layout.verify import verify

from _specs import adjacent, cycle_spec, room, tree_spec

from real_plans import EXAMPLES


def assert_verified(spec, rects) -> None:
    assert rects is not None, "construction found no layout"
    assert verify(spec, rects_to_layout(spec, rects)) == []


def test_tree_without_hints_is_verified():
    spec = tree_spec()
    assert_verified(spec, construct_start(spec, deadline=time.monotonic() + 20))


def test_cycle_without_hints_is_verified():
    spec = cycle_spec()
    assert_verified(spec, construct_start(spec, deadline=time.monotonic() + 20))


def test_obstacle_position_cluster_and_on_boundary_are_honoured():
    base = tree_spec()
    rooms = tuple(replace(r, on_boundary=True) if r.id == "R5" else r for r in base.rooms)
    spec = replace(
        base,
        rooms=rooms,
        boundary=Boundary(24.0, 18.0, (Obstacle("O0", 10.0, 0.0, 3.0, 4.0),)),
        positions=(Position("C0", 3.0, 9.0),),
        clusters=(Cluster("K0", (ClusterMember("R0", 0.0, 0.0), ClusterMember("R1", 4.5, 0.0))),),
    )
    rects = construct_start(spec, deadline=time.monotonic() + 20)
    assert_verified(spec, rects)
    x, y, w, h = rects["C0"]
    assert x <= 3.0 <= x + w and y <= 9.0 <= y + h
    ox, oy, ow, oh = 10.0, 0.0, 3.0, 4.0
    for rx, ry, rw, rh in rects.values():
        assert rx + rw <= ox or rx >= ox + ow or ry + rh <= oy or ry >= oy + oh


def test_same_seed_gives_same_rectangles():
    spec = cycle_spec()
    first = construct_start(spec, seed=3, randomize=True, deadline=time.monotonic() + 20)
    second = construct_start(spec, seed=3, randomize=True, deadline=time.monotonic() + 20)
    assert first == second


def test_hints_that_overlap_still_give_a_verified_layout():
    # every room hinted at the same spot: the repair has to pull them all apart
    spec = tree_spec()
    hints = tuple(Hint(r.id, 5.0, 5.0, r.target_w, r.target_h) for r in spec.rooms)
    spec = replace(spec, hints=hints)
    assert_verified(spec, construct_start(spec, deadline=time.monotonic() + 20))


def test_an_impossible_spec_gives_none_within_the_deadline():
    # two rooms of at least 8 m each side by side cannot fit a 10 m wide boundary
    spec = replace(
        cycle_spec(),
        rooms=(room("A", 10.0, 10.0, var=0.2), room("B", 10.0, 10.0, var=0.2)),
        boundary=Boundary(10.0, 10.0),
        adjacencies=(adjacent("A", "B"),),
    )
    began = time.monotonic()
    assert construct_start(spec, deadline=began + 3) is None
    assert time.monotonic() - began < 6


def test_own_check_rejects_overlap_and_missing_wall():
    spec = cycle_spec()
    rects = construct_start(spec, deadline=time.monotonic() + 20)
    assert hard_violations(spec, rects) == []
    x, y, w, h = rects["A"]
    broken = dict(rects, B=(x + 0.5, y + 0.5, w, h))
    assert hard_violations(spec, broken)


@pytest.mark.parametrize("plan", ["school_Lamuniere1.xml", "school_Sabadell3.xml"])
def test_small_real_plans_construct_fast(plan):
    from layoutdsl.importer import ImportOptions, import_building

    spec, diagnostics = import_building(EXAMPLES / plan, ImportOptions(hints=True))
    assert spec is not None, diagnostics
    began = time.monotonic()
    rects = construct_start(spec, deadline=began + 30)
    assert time.monotonic() - began < 10
    assert_verified(spec, rects)
    # the hints keep the plan's total room area close to the original's
    target = sum(r.target_w * r.target_h for r in spec.rooms)
    assert abs(sum(w * h for _, _, w, h in rects.values()) / target - 1) < 0.25
