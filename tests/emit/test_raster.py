"""The shared rasterization: topology equals the layout's, framing, frames of reference."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from _emit_support import (
    CASES,
    SPEC_FILES,
    assert_topology_matches,
    load_case,
    pair_room,
    planted_layouts,
    region_meetings,
    school_layout,
    spec_adjacency,
)

from layoutdsl.importer.building import BoundingBox, Building, BuildingPortal, LineSegment, Point, Space
from layoutdsl.layout import Layout, PlacedRoom, make_portal
from layoutdsl.emit.raster import OccupancyGrid, rasterize_building, rasterize_layout

# Layouts whose bitmap topology must equal their portal graph. The lead extends this with
# the compiled layout of every spec in specs/ (a parametrization over compiled layouts).
TOPOLOGY_LAYOUTS = {
    **{case.name: (lambda case=case: load_case(case)) for case in CASES},
    "pair": pair_room,
    "school_106_rooms": school_layout,
    "school_thin_walls": lambda: school_layout(2, 5, walldim=0.01),
}


@pytest.mark.parametrize("name", sorted(TOPOLOGY_LAYOUTS))
def test_rooms_meet_exactly_where_the_layout_has_portals(name: str) -> None:
    assert_topology_matches(TOPOLOGY_LAYOUTS[name]())


@pytest.mark.parametrize("resolution", [0.02, 0.05, 0.1])
def test_topology_holds_at_other_resolutions(resolution: float) -> None:
    assert_topology_matches(load_case(CASES[0].parent / "small_office"), resolution)


def test_the_topology_check_sees_a_missing_door_and_an_extra_opening() -> None:
    layout = pair_room()
    closed = Layout(layout.name, layout.width, layout.height, layout.walldim, layout.rooms, ())
    assert region_meetings(layout, rasterize_layout(closed)) == set()
    assert region_meetings(closed, rasterize_layout(layout)) == {frozenset(("R0", "R1"))}


def test_a_door_opens_its_width_and_no_more() -> None:
    layout = pair_room()  # door 0.9 m in the vertical wall x in [3.0, 3.2]
    grid = rasterize_layout(layout, 0.05)
    row_free = [grid.is_free(3.1, y) for y in np.arange(0.025, 3.0, 0.05)]
    opening = sum(row_free) * 0.05
    assert opening == pytest.approx(0.9, abs=0.05)
    assert grid.is_free(3.1, 1.5) and not grid.is_free(3.1, 0.3) and not grid.is_free(3.1, 2.7)


def test_walls_thinner_than_a_cell_still_separate_rooms() -> None:
    a = PlacedRoom("R0", "A", "R", 0.0, 0.0, 2.0, 2.0)
    b = PlacedRoom("R1", "B", "R", 2.01, 0.0, 2.0, 2.0)
    layout = Layout("thin", 4.01, 2.0, 0.01, (a, b), ())
    grid = rasterize_layout(layout, 0.05)
    assert region_meetings(layout, grid) == set()
    with_door = Layout("thin", 4.01, 2.0, 0.01, (a, b), (make_portal(a, b, "e", 0.8),))
    assert region_meetings(with_door, rasterize_layout(with_door, 0.05)) == {frozenset(("R0", "R1"))}


@pytest.mark.parametrize("name", ["small_office", "thin_walls", "single_room"])
def test_grid_is_framed_by_walls_and_cropped_to_the_building(name: str) -> None:
    layout = load_case(CASES[0].parent / name)
    grid = rasterize_layout(layout)
    occ = grid.occupied
    assert occ[0, :].all() and occ[-1, :].all() and occ[:, 0].all() and occ[:, -1].all()
    # cropped: every side of the frame is within one outer wall of a room
    wall = max(layout.walldim, grid.resolution) + grid.resolution
    assert grid.origin[0] >= min(r.x for r in layout.rooms) - wall - 1e-9
    assert grid.origin[1] >= min(r.y for r in layout.rooms) - wall - 1e-9
    assert grid.origin[0] + grid.width_m <= max(r.x2 for r in layout.rooms) + wall + 1e-9
    assert grid.origin[1] + grid.height_m <= max(r.y2 for r in layout.rooms) + wall + 1e-9


def test_world_and_cell_conversions_are_inverse() -> None:
    grid = OccupancyGrid(np.zeros((4, 6), dtype=bool), 0.5, (-1.0, 2.0))
    assert grid.world_to_cell(-1.0 + 0.1, 2.0 + 0.1) == (3, 0)  # lower-left point -> bottom row
    assert grid.world_to_cell(1.9, 3.9) == (0, 5)
    for row in range(4):
        for col in range(6):
            assert grid.world_to_cell(*grid.cell_to_world(row, col)) == (row, col)
    assert grid.width_m == 3.0 and grid.height_m == 2.0 and grid.centre == (0.5, 3.0)


def test_rasterizing_is_deterministic() -> None:
    layout = school_layout(2, 4)
    assert np.array_equal(rasterize_layout(layout).occupied, rasterize_layout(layout).occupied)


def test_bad_resolution_is_a_value_error() -> None:
    with pytest.raises(ValueError, match="resolution"):
        rasterize_layout(pair_room(), 0.0)


# ----------------------------------------------------------------------------- real plans


def _rect_space(space_id: str, x0: float, y0: float, w: float, h: float, door: tuple[float, float] | None, other: str = "") -> Space:
    corners = [(x0, y0), (x0 + w, y0), (x0 + w, y0 + h), (x0, y0 + h)]
    segments = [
        LineSegment(f"{space_id}-w{i}", Point(*corners[i]), Point(*corners[(i + 1) % 4]), "WALL", "EXPLICIT")
        for i in range(4)
    ]
    portals = ()
    if door is not None:
        segment = LineSegment(f"{space_id}-p", Point(*door), Point(*door), "PORTAL", "EXPLICIT")
        segments.append(segment)
        if other:
            portals = (BuildingPortal(segment.id, "EXPLICIT", (space_id, other), segment),)
    return Space(
        id=space_id,
        rtype="R",
        label="ROOM",
        centroid=Point(x0 + w / 2, y0 + h / 2),
        bbox=BoundingBox(x0, y0, x0 + w, y0 + h),
        polygon=tuple(Point(*c) for c in corners),
        segments=tuple(segments),
        portals=portals,
    )


def _square(space_id: str, x0: float, y0: float, size: float, portal_at: tuple[float, float] | None) -> Space:
    return _rect_space(space_id, x0, y0, size, size, portal_at)


def _two_squares(with_portal: bool) -> Building:
    # two 3 m squares sharing the wall x = 300 (file units: 1 unit = 1 cm), a point door
    # at (300, 150) in both spaces, as the real plans write doors
    door = (300.0, 150.0) if with_portal else None
    return Building("two", 90.0, 0.9, (_square("A", 0, 0, 300, door), _square("B", 300, 0, 300, door)))


def _connected(grid: OccupancyGrid, p: tuple[float, float], q: tuple[float, float]) -> bool:
    from collections import deque

    free = ~grid.occupied
    start, goal = grid.world_to_cell(*p), grid.world_to_cell(*q)
    seen = {start}
    queue = deque([start])
    while queue:
        cell = queue.popleft()
        if cell == goal:
            return True
        r, c = cell
        for nxt in ((r + 1, c), (r - 1, c), (r, c + 1), (r, c - 1)):
            if grid.contains(*nxt) and free[nxt] and nxt not in seen:
                seen.add(nxt)
                queue.append(nxt)
    return False


def test_a_real_plan_point_portal_opens_a_door_of_the_scale_length() -> None:
    grid = rasterize_building(_two_squares(with_portal=True))
    centre_a, centre_b = (1.5, -1.5), (4.5, -1.5)  # frame: x = x_file·s, y = −y_file·s
    assert grid.is_free(*centre_a) and grid.is_free(*centre_b)
    assert _connected(grid, centre_a, centre_b)
    opening = sum(grid.is_free(3.0, -y) for y in np.arange(0.0, 3.0, grid.resolution)) * grid.resolution
    assert opening == pytest.approx(0.9, abs=2 * grid.resolution)


def test_a_real_plan_without_portal_keeps_rooms_apart_and_is_framed() -> None:
    grid = rasterize_building(_two_squares(with_portal=False))
    assert not _connected(grid, (1.5, -1.5), (4.5, -1.5))
    occ = grid.occupied
    assert occ[0, :].all() and occ[-1, :].all() and occ[:, 0].all() and occ[:, -1].all()
    assert not grid.is_free(-0.5, -1.5)  # outside every space


def test_real_plan_grid_covers_the_plan_in_metres() -> None:
    grid = rasterize_building(_two_squares(with_portal=True), resolution=0.1)
    assert grid.origin[0] <= 0.0 and grid.origin[0] + grid.width_m >= 6.0
    assert grid.origin[1] <= -3.0 and grid.origin[1] + grid.height_m >= 0.0
    assert math.isclose(grid.resolution, 0.1)


def test_a_real_plan_door_near_a_corner_stays_on_the_shared_wall() -> None:
    # L (3 × 3 m) has a closet C (1 × 1 m) and a room R beside it along x = 300; the
    # closet's door is drawn 0.2 m from its corner, so a centred 0.9 m door would reach
    # past the closet into R. It must be slid onto the wall L and C share.
    door = (300.0, 80.0)
    building = Building(
        "corner",
        90.0,
        0.9,
        (
            _rect_space("L", 0, 0, 300, 300, door, "C"),
            _rect_space("C", 300, 0, 100, 100, door, "L"),
            _rect_space("R", 300, 100, 300, 200, None),
        ),
    )
    grid = rasterize_building(building)
    centre = {"L": (1.5, -1.5), "C": (3.5, -0.5), "R": (4.5, -2.0)}
    assert _connected(grid, centre["L"], centre["C"])
    assert not _connected(grid, centre["L"], centre["R"])
    assert not _connected(grid, centre["C"], centre["R"])


# ----------------------------------------------------------------------------- specs/


PLANTED = planted_layouts()


@pytest.mark.parametrize("source", ["planted", "compiled"])
@pytest.mark.parametrize("spec_file", SPEC_FILES, ids=[p.stem for p in SPEC_FILES])
def test_bitmap_topology_equals_the_specs_adjacency_for_every_spec(
    spec_file: Path, source: str, compiled_spec_layouts
) -> None:
    """On the verified planted layout and on what `compile` makes of the spec."""
    if source == "planted":
        assert spec_file.stem in PLANTED, f"no planted layout for {spec_file.name} in bench/planted_specs.py"
        layout = PLANTED[spec_file.stem]
    else:
        layout = compiled_spec_layouts[spec_file.stem][1]
    edges, _rooms = spec_adjacency(spec_file)
    met = region_meetings(layout, rasterize_layout(layout))
    assert met == set(edges)
