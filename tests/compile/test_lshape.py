"""layout/lshape.py: how the generator sees an L-room (two joined boxes)."""

from __future__ import annotations

import random

import pytest

from dataclasses import replace

from layoutdsl.layout.lshape import JOIN_OPTIONS, arm_sizes, boxes_spec, join_option, joined_box, seed_arms
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
    from layoutdsl.layout.lshape import beside_pairs

    spec = _spec()
    geometry = {"C0": (0.0, 0.0, 10.0, 2.0), arm_id("C0"): (0.0, 2.0, 2.0, 6.0), "R0": (2.2, 4.5, 4.0, 4.0)}
    boxes, joins = boxes_spec(spec, geometry)
    assert beside_pairs(boxes, joins) == {frozenset(("R0", "C0"))}


def _room_overlap(a, b) -> float:
    """Overlap area of two (x, y, w, h) boxes, computed here independently."""
    dx = min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0])
    dy = min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1])
    return max(0.0, dx) * max(0.0, dy)


def test_seed_arms_turns_the_l_towards_a_neighbour_its_box_misses() -> None:
    """R0 is 2 m above the corridor's box, so no door there; of the places where the arm
    overlaps nothing, only the one at the box's left end, going up, meets R0 a wall apart."""
    spec = _spec()
    box = (5.0, 8.0, 10.0, 2.0)
    geometry = {"C0": box, "R0": (7.2, 12.0, 4.0, 4.0)}
    arm = seed_arms(spec, geometry, random.Random(0))[arm_id("C0")]
    assert arm == joined_box(box, (2.0, 6.0), "below:lo")
    # R0 lies a wall (0.2 m) right of the arm, facing it along 4 m
    assert abs(geometry["R0"][0] - (arm[0] + arm[2]) - 0.2) < 1e-9
    assert min(arm[1] + arm[3], 16.0) - max(arm[1], 12.0) == 4.0


def test_seed_arms_keeps_a_wall_from_rooms_in_a_generated_geometry_but_not_from_hints() -> None:
    """A hint geometry is the original plan's boxes: rooms overlap their neighbours by about
    a wall, and the arm's place in the plan is among them (against R1 here); a generated
    geometry keeps rooms a wall apart, so the same place would be a conflict."""
    spec = _spec()
    spec = replace(spec, rooms=spec.rooms + (Room("R1", 2, 4, 3, 5, 7, 6, 1, 3, "R", "OFFICE"),))
    box = (5.0, 8.0, 10.0, 2.0)
    # R0 meets the box from below; R1 overlaps the place above the box's left end by 0.1 m
    geometry = {"C0": box, "R0": (9.0, 4.8, 3.0, 3.0), "R1": (6.9, 10.0, 3.0, 6.0)}
    hinted = seed_arms(spec, geometry, random.Random(0), hints=True)[arm_id("C0")]
    assert hinted == joined_box(box, (2.0, 6.0), "below:lo"), "the arm lies among the rooms, against R1"
    generated = seed_arms(spec, geometry, random.Random(0))[arm_id("C0")]
    for other in ("R0", "R1"):
        x, y, w, h = geometry[other]
        assert _room_overlap(generated, (x - 0.2, y - 0.2, w + 0.4, h + 0.4)) == 0.0, f"the arm is closer than a wall to {other}"


def test_an_arm_beside_a_box_drawn_small_is_drawn_small_too() -> None:
    """The generator draws rooms shrunk; an arm seeded at full size beside a shrunk box would
    take the space the shrinking left. Its sides shrink by the box's scale, to its minimum."""
    spec = _spec()
    corridor, _ = spec.rooms
    (arm,) = spec.arms
    full = arm_sizes(arm, corridor, (0.0, 0.0, 10.0, 2.0))
    assert full == [(2.0, 6.0)]
    (w, h), = arm_sizes(arm, corridor, (0.0, 0.0, 9.0, 1.8))  # 0.9 of the box's target sides
    assert abs(w - 1.8) < 1e-9 and abs(h - 5.4) < 1e-9
    (w, h), = arm_sizes(arm, corridor, (0.0, 0.0, 5.0, 1.0))  # half: below the arm's minimum sides
    assert (w, h) == (1.5, 5.0)


def test_an_adjacency_goes_to_the_box_a_wall_away_not_to_one_overlapping_the_neighbour() -> None:
    spec = _spec()
    # R0 lies a wall above the corridor's box; the arm (seeded badly) runs through R0
    geometry = {"C0": (0.0, 0.0, 10.0, 2.0), arm_id("C0"): (3.0, 2.0, 2.0, 6.0), "R0": (2.0, 2.2, 4.0, 4.0)}
    (adjacency,) = boxes_spec(spec, geometry)[0].adjacencies
    assert {adjacency.a, adjacency.b} == {"R0", "C0"}


def test_an_arm_the_generator_drew_at_a_box_end_keeps_its_size_and_place() -> None:
    """The generator packs the arm as a room of its own, sized against its neighbours; moved
    back to its target size it would overlap them. Drawn a wall below the box's left end at
    2.4 x 7 (target 2 x 6), it is joined right there at 2.4 x 7."""
    spec = _spec()
    box = (0.0, 10.0, 10.0, 2.0)
    drawn = (0.0, 10.0 - 0.2 - 7.0, 2.4, 7.0)
    geometry = {"C0": box, arm_id("C0"): drawn, "R0": (3.0, 5.0, 4.0, 4.0)}
    seeded = seed_arms(spec, geometry, random.Random(0))[arm_id("C0")]
    assert seeded == joined_box(box, (2.4, 7.0), "above:lo")
    assert _room_overlap(seeded, geometry["R0"]) == 0.0
