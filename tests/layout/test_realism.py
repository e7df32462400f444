"""layout.realism on hand-made layouts whose answers are worked out by hand."""

from __future__ import annotations

import pytest

from layoutdsl.layout import Layout, PlacedRoom
from layoutdsl.layout.realism import Space, find_slivers, measure_layout, measure_spaces

WALL = 0.2


def layout(*rooms: PlacedRoom) -> Layout:
    return Layout("hand", 40.0, 40.0, WALL, tuple(rooms), ())


def room(rid: str, x: float, y: float, w: float, h: float, label: str = "ROOM", rtype: str = "R",
         arm=None) -> PlacedRoom:
    return PlacedRoom(rid, label, rtype, x, y, w, h, arm)


def test_a_lone_entrance_is_open_along_its_whole_perimeter():
    result = measure_layout(layout(room("E", 0, 0, 4, 3, "ENTRANCE", "E")))
    assert result.entrances == ("E",) and result.open_entrances == ("E",)
    assert result.outside_length["E"] == pytest.approx(14.0, abs=0.11)
    assert result.void_area == 0 and result.slivers == ()


def test_an_entrance_walled_in_by_four_rooms_is_enclosed():
    # the entrance 4 x 4 at (5, 5); rooms a wall away on all four sides, each long enough
    # to close the corners
    rooms = [
        room("E", 5, 5, 4, 4, "ENTRANCE", "E"),
        room("S", 0, 0, 14, 4.8),                 # below: top edge at 4.8, 0.2 under the entrance
        room("N", 0, 9.2, 14, 4),                 # above
        room("W", 0, 5, 4.8, 4),                  # left
        room("X", 9.2, 5, 4.8, 4),                # right
    ]
    result = measure_layout(layout(*rooms))
    assert result.enclosed_entrances == ("E",)
    assert result.outside_length["E"] == 0
    assert result.void_area == 0  # the 0.2 m gaps are wall, not voids
    assert set(result.rooms_with_outside_wall) == {"S", "N", "W", "X"}


def test_a_narrow_passage_is_wall_and_a_wide_one_a_way_in():
    def with_passage(width: float):
        # two rooms side by side with a passage between them up to the entrance behind
        return measure_layout(layout(
            room("E", 0, 0, 10, 3, "ENTRANCE", "E"),
            room("A", 0, 3.2, 5 - width / 2, 4),
            room("B", 5 + width / 2, 3.2, 5 - width / 2, 4),
            room("C", -0.2 - 4, 0, 4, 7.2),  # left and right of the entrance, closing its sides
            room("D", 10.2, 0, 4, 7.2),
            room("F", -4.2, -4.2, 18.4, 4),  # below
        ))

    narrow, wide = with_passage(0.4), with_passage(1.2)
    assert narrow.enclosed_entrances == ("E",)
    assert wide.open_entrances == ("E",)
    # the passage's mouth on the entrance: its width (1.2 m) borders the outside
    assert wide.outside_length["E"] == pytest.approx(1.2, abs=0.11)
    assert [(s.a, s.b) for s in narrow.slivers] == [("A", "B")]
    assert narrow.slivers[0].width == pytest.approx(0.4)
    assert wide.slivers == ()


def test_a_courtyard_nobody_reaches_is_an_enclosed_void():
    # four rooms round a 3 x 3 hole, closed at the corners
    rooms = [
        room("S", 0, 0, 7.4, 2),
        room("N", 0, 5.4, 7.4, 2),
        room("W", 0, 2.2, 2, 3),
        room("X", 5.4, 2.2, 2, 3),
    ]
    result = measure_layout(layout(*rooms))
    # the hole is [2, 5.4] x [2, 5.4]: 3.4 x 3.4 = 11.56 m² (the 0.2 m strips above and
    # below W and X are wall, too narrow to count)
    assert result.void_area == pytest.approx(11.56, rel=0.05)
    room_area = 2 * 7.4 * 2 + 2 * 2 * 3
    assert result.void_share == pytest.approx(11.56 / room_area, rel=0.05)
    assert len(result.voids) == 1
    x, y = result.voids[0][1]
    assert 2 < x < 5.4 and 2 < y < 5.4


def test_an_l_room_borders_the_outside_along_its_six_edges():
    # box 6 x 2 with an arm 2 x 3 on top of its left end: an L of perimeter 2 * (6 + 5)
    result = measure_layout(layout(room("L", 0, 0, 6, 2, arm=(0, 2, 2, 3))))
    assert result.outside_length["L"] == pytest.approx(22.0, abs=0.2)


def test_a_rotated_polygon_is_measured_like_its_outline():
    # an original plan's space: a square 4 x 4 turned by 45 degrees (perimeter 16)
    diamond = Space("E", "ENTRANCE", "E", polygon=((2, 0), (4, 2), (2, 4), (0, 2)))
    result = measure_spaces([diamond], walldim=0.2)
    assert result.open_entrances == ("E",)
    assert result.room_area == pytest.approx(8.0)
    # a staircase of cells measures |dx| + |dy| per edge: 4 edges x (2 + 2) = 16 (L1 length)
    assert result.outside_length["E"] == pytest.approx(16.0, rel=0.05)
    assert result.slivers is None  # polygons: no exact sliver test


def test_slivers_are_between_a_wall_and_a_usable_width_only():
    def pair(gap: float):
        return [Space("A", "", "R", boxes=((0, 0, 3, 3),)), Space("B", "", "R", boxes=((3 + gap, 1, 6, 5),))]

    assert find_slivers(pair(0.2), walldim=0.2) == ()   # a wall
    assert find_slivers(pair(1.0), walldim=0.2) == ()   # usable
    (sliver,) = find_slivers(pair(0.35), walldim=0.2)
    assert (sliver.a, sliver.b, sliver.width, sliver.length) == ("A", "B", 0.35, 2.0)
    # touching only at a corner is no sliver
    corner = [Space("A", "", "R", boxes=((0, 0, 3, 3),)), Space("B", "", "R", boxes=((3.3, 3.3, 5, 5),))]
    assert find_slivers(corner, walldim=0.2) == ()


def test_only_entrances_count_as_entrances():
    spaces = [Space("a", "ENTRANCE HALL", "R", boxes=((0, 0, 2, 2),)),
              Space("b", "", "E", boxes=((3, 0, 5, 2),)),
              Space("c", "STAIRS", "E", boxes=((6, 0, 8, 2),))]
    assert measure_spaces(spaces).entrances == ("a", "b")
