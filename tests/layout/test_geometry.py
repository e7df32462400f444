"""Plain-rectangle helpers of layoutdsl.layout.geometry, against hand-drawn cases."""

from __future__ import annotations

from layoutdsl.layout.geometry import gap_between, rooms_between


def test_the_gap_between_rooms_facing_each_other_runs_along_their_facing_stretch():
    assert gap_between((0, 0, 2, 4), (5, 1, 2, 4)) == (2, 1, 5, 4)   # side by side: x 2..5, y 1..4
    assert gap_between((1, 6, 4, 2), (0, 0, 3, 3)) == (1, 3, 3, 6)   # one above the other


def test_the_gap_between_rooms_diagonal_to_each_other_is_the_box_between_their_nearest_corners():
    assert gap_between((0, 0, 2, 2), (5, 6, 2, 2)) == (2, 2, 5, 6)
    assert gap_between((5, 6, 2, 2), (0, 0, 2, 2)) == (2, 2, 5, 6)


def test_rooms_between_lists_what_reaches_into_the_gap_most_covering_first():
    geometry = {
        "a": (0, 0, 2, 4),
        "b": (6, 0, 2, 4),
        "wide": (2.5, -1, 3, 6),     # covers 3 x 4 of the 4 x 4 gap
        "corner": (2, 3, 0.5, 3),    # reaches 0.5 x 1 into it
        "touching": (2, 4, 4, 1),    # only touches its top edge
        "far": (20, 20, 1, 1),
    }
    assert rooms_between(geometry, "a", "b") == ["wide", "corner"]
    assert rooms_between(geometry, "b", "a") == ["wide", "corner"]
    assert rooms_between({"a": (0, 0, 2, 4), "b": (6, 0, 2, 4)}, "a", "b") == []
