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
    assert office.x2 < corridor.x  # R0 is nowhere near C0's own rectangle
    assert verify(spec, layout) == []


def test_an_l_room_without_its_arm_is_a_shape_violation() -> None:
    spec, layout = _planted()
    assert "shape" in _rules(spec, _with_room(layout, "C0", arm=None))


@pytest.mark.parametrize("arm, why", [
    ((3.5, 9.0, 6.5, 1.8), "T: flush but not at a corner of the shared side"),
    ((3.5, 10.0, 6.5, 1.8), "overlapping the long arm"),
    ((3.3, 10.2, 6.5, 1.8), "a gap between the arms"),
])  # fmt: skip
def test_arms_that_do_not_form_an_l_are_a_join_violation(arm, why) -> None:
    spec, layout = _planted()
    assert "join" in _rules(spec, _with_room(layout, "C0", arm=arm)), why


def test_the_arm_keeps_its_own_size_bounds() -> None:
    """The arm line allows 6-9 m; a 10 m arm breaks it although the room line would allow it."""
    spec, layout = _planted()
    assert "size" in _rules(spec, _with_room(layout, "C0", arm=(0.0, 10.2, 10.0, 1.8)))


def test_a_room_overlapping_the_arm_is_an_overlap() -> None:
    spec, layout = _planted()
    moved = _with_room(layout, "R0", y=6.0)  # R0's top now runs 0.3 m into the arm
    assert "overlap" in _rules(spec, moved)


def test_the_outline_of_an_l_has_six_corners_counter_clockwise() -> None:
    outline = union_outline([(0, 0, 10, 2), (8, 2, 10, 8)])
    assert outline == ((0, 0), (10, 0), (10, 8), (8, 8), (8, 2), (0, 2))
    area = sum(x1 * y2 - x2 * y1 for (x1, y1), (x2, y2) in zip(outline, outline[1:] + outline[:1])) / 2
    assert area == 10 * 2 + 2 * 6  # positive: counter-clockwise; equal to the arms' areas
