"""compile/lshape.py: how the construction sees an L-room (two joined boxes)."""

from __future__ import annotations

import random

import pytest

from layoutdsl.compile.lshape import JOIN_OPTIONS, boxes_spec, join_option, joined_box, seed_arms
from layoutdsl.syntax.ast import Adjacency, Arm, Boundary, Room, Spec, arm_id


def _spec() -> Spec:
    corridor = Room("C0", 8, 12, 10, 1.5, 2.5, 2, 1, 20, "C", "CORRIDOR")
    office = Room("R0", 3, 5, 4, 3, 5, 4, 1, 1.5, "R", "OFFICE")
    return Spec("l", (corridor, office), Boundary(20, 20), (Adjacency("R0", "C0", 0.9, "e"),),
                arms=(Arm("C0", 1.5, 2.5, 2, 5, 8, 6, 1, 20),))


@pytest.mark.parametrize("option", JOIN_OPTIONS)
def test_a_joined_box_reads_back_as_its_option(option) -> None:
    room_box = (5.0, 5.0, 10.0, 2.0)
    arm = joined_box(room_box, (2.0, 6.0), option)  # sides differing from the box's: both ends differ
    assert join_option(room_box, arm) == option


def test_the_adjacency_goes_to_the_box_nearer_the_neighbour() -> None:
    spec = _spec()
    geometry = {"C0": (0.0, 0.0, 10.0, 2.0), arm_id("C0"): (0.0, 2.0, 2.0, 6.0), "R0": (2.2, 2.2, 4.0, 4.0)}
    boxes, joins = boxes_spec(spec, geometry)
    assert [r.id for r in boxes.rooms] == ["C0", "C0/arm", "R0"] and boxes.arms == ()
    assert joins == {("C0", "C0/arm")}
    # R0 sits 0.2 m right of the arm and 0.2 m above the corridor's box, sharing 4 m with
    # the box and 3.8 m with the arm: the box, which it faces along more wall
    (adjacency,) = boxes.adjacencies
    assert {adjacency.a, adjacency.b} == {"R0", "C0"}
    geometry["R0"] = (2.2, 4.5, 4.0, 4.0)  # now only beside the arm
    (adjacency,) = boxes_spec(spec, geometry)[0].adjacencies
    assert {adjacency.a, adjacency.b} == {"R0", "C0/arm"}


def test_seed_arms_joins_the_arm_where_it_overlaps_nothing() -> None:
    spec = _spec()
    geometry = {"C0": (0.0, 0.0, 10.0, 2.0), "R0": (0.0, 2.2, 4.0, 4.0)}
    seeded = seed_arms(spec, geometry, random.Random(0))
    arm = seeded[arm_id("C0")]
    option = join_option(geometry["C0"], arm)
    assert arm == joined_box(geometry["C0"], arm[2:], option)
    x, y, w, h = arm
    rx, ry, rw, rh = geometry["R0"]
    assert x >= rx + rw or x + w <= rx or y >= ry + rh or y + h <= ry, "the arm overlaps R0"
    assert 0 <= x and x + w <= 20 and 0 <= y and y + h <= 20
    assert sorted((w, h)) == [2, 6] and max(w, h) == (h if option.split(":")[0] in ("below", "above") else w), \
        "the arm meets the corridor with its short side"


def test_an_ls_other_box_is_kept_exactly_a_wall_from_its_neighbour() -> None:
    """R0 meets C0 on the arm; the corridor's own box may lie on the same line (the L's
    outer face is flush), so R0 and that box get no extra safety margin."""
    from layoutdsl.compile.lshape import beside_pairs

    spec = _spec()
    geometry = {"C0": (0.0, 0.0, 10.0, 2.0), arm_id("C0"): (0.0, 2.0, 2.0, 6.0), "R0": (2.2, 4.5, 4.0, 4.0)}
    boxes, joins = boxes_spec(spec, geometry)
    assert beside_pairs(boxes, joins) == {frozenset(("R0", "C0"))}
