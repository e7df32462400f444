"""The verifier on L-shaped rooms: the planted L layout passes, every broken L rule is named."""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import pytest

from layoutdsl.layout import make_portal, union_outline
from layoutdsl.layout.verify import verify

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
from planted_specs import l_corridor  # noqa: E402


def _planted():
    spec, layout, _ = l_corridor()
    return spec, layout


def _with_room(layout, room_id, **changes):
    """The layout with one room changed and its portals recomputed."""
    rooms = tuple(replace(r, **changes) if r.id == room_id else r for r in layout.rooms)
    by_id = {r.id: r for r in rooms}
    portals = []
    for portal in layout.portals:
        try:
            portals.append(make_portal(by_id[portal.a], by_id[portal.b], portal.kind, portal.width))
        except ValueError:
            pass
    return replace(layout, rooms=rooms, portals=tuple(portals))


def _rules(spec, layout):
    return {v.rule for v in verify(spec, layout)}


def test_the_planted_l_layout_is_valid() -> None:
    spec, layout = _planted()
    assert verify(spec, layout) == []
    corridor = layout.room("C0")
    assert corridor.arm is not None and len(corridor.polygon) == 6


def test_a_door_on_the_arm_meets_the_adjacency() -> None:
    """R0 touches only the arm of C0: the adjacency R0-C0 holds through the arm alone."""
    spec, layout = _planted()
    corridor, office = layout.room("C0"), layout.room("R0")
    assert office.y > corridor.y2 + 1  # R0 is nowhere near C0's own rectangle
    assert verify(spec, layout) == []


def test_an_l_room_without_its_arm_is_a_shape_violation() -> None:
    spec, layout = _planted()
    assert "shape" in _rules(spec, _with_room(layout, "C0", arm=None))


@pytest.mark.parametrize("arm, why", [
    ((5.0, 1.8, 1.8, 8.0), "T: flush but not at a corner of the shared side"),
    ((0.0, 1.5, 1.8, 8.0), "overlapping the long arm"),
    ((0.0, 2.0, 1.8, 8.0), "a gap between the arms"),
])  # fmt: skip
def test_arms_that_do_not_form_an_l_are_a_join_violation(arm, why) -> None:
    spec, layout = _planted()
    assert "join" in _rules(spec, _with_room(layout, "C0", arm=arm)), why


def test_the_arm_keeps_its_own_size_bounds() -> None:
    """The arm line allows 6-9 m; a 9.5 m arm breaks it although the room line would allow it."""
    spec, layout = _planted()
    assert "size" in _rules(spec, _with_room(layout, "C0", arm=(0.0, 1.8, 1.8, 9.5)))


def test_the_arm_keeps_running_across_as_its_lines_say() -> None:
    """The room line is wide and the arm line tall: an arm lying along the box is a
    different shape (a wide corridor), not the L the spec describes."""
    spec, layout = _planted()
    violations = verify(spec, _with_room(layout, "C0", arm=(0.0, 1.8, 8.0, 1.8)))
    assert any(v.rule == "join" and "runs along" in v.message for v in violations)


def test_a_room_overlapping_the_arm_is_an_overlap() -> None:
    spec, layout = _planted()
    moved = _with_room(layout, "R0", x=1.5)  # R0's left side now runs 0.3 m into the arm
    assert "overlap" in _rules(spec, moved)


def test_the_outline_of_an_l_has_six_corners_counter_clockwise() -> None:
    outline = union_outline([(0, 0, 10, 2), (8, 2, 10, 8)])
    assert outline == ((0, 0), (10, 0), (10, 8), (8, 8), (8, 2), (0, 2))
    area = sum(x1 * y2 - x2 * y1 for (x1, y1), (x2, y2) in zip(outline, outline[1:] + outline[:1])) / 2
    assert area == 10 * 2 + 2 * 6  # positive: counter-clockwise; equal to the arms' areas


def test_an_arm_a_nanometre_short_of_its_box_still_outlines_one_l() -> None:
    """Solver noise: the arm's right edge 1e-9 m left of the box's. The outline is still the
    L's six corners (it was the arm alone: the sliver between split the union), and the
    layout built from such rectangles has the two edges on one line."""
    from layoutdsl.layout.geometry import layout_from_rects

    outline = union_outline([(14.23057974, 6.9, 19.76, 12.18), (12.49, 6.9, 14.230579739, 9.7)])
    assert len(outline) == 6
    spec, layout = _planted()
    box = layout.room("C0")
    rects = {room.id: (room.x, room.y, room.w, room.h) for room in layout.rooms}
    rects["C0/arm"] = (box.arm[0], box.arm[1] + 1e-9, box.arm[2], box.arm[3] - 1e-9)
    welded = layout_from_rects(spec, rects).room("C0")
    assert welded.arm[1] == box.y2 and len(welded.polygon) == 6
