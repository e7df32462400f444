"""Property: on random guillotine layouts, the bitmap's topology is the portal graph."""

from __future__ import annotations

from _emit_support import region_meetings
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from layoutdsl.layout import Layout, PlacedRoom, make_portal, shared_wall
from layoutdsl.emit.raster import rasterize_layout

MIN_SIDE = 1.2


@st.composite
def guillotine_layouts(draw) -> tuple[Layout, float]:
    """Rooms from recursive splits of a rectangle (walls `walldim` thick), random doors."""
    walldim = draw(st.sampled_from([0.01, 0.04, 0.1, 0.2, 0.3]))
    resolution = draw(st.sampled_from([0.025, 0.05, 0.1]))
    width = draw(st.floats(4.0, 14.0))
    height = draw(st.floats(4.0, 14.0))
    rects = [(0.0, 0.0, width, height)]
    for _ in range(draw(st.integers(1, 7))):
        index = draw(st.integers(0, len(rects) - 1))
        x, y, w, h = rects[index]
        along_x = draw(st.booleans())
        side = w if along_x else h
        if side < 2 * MIN_SIDE + walldim:
            continue
        cut = draw(st.floats(MIN_SIDE, side - MIN_SIDE - walldim))
        if along_x:
            parts = [(x, y, cut, h), (x + cut + walldim, y, w - cut - walldim, h)]
        else:
            parts = [(x, y, w, cut), (x, y + cut + walldim, w, h - cut - walldim)]
        rects[index : index + 1] = parts
    rooms = tuple(PlacedRoom(f"R{i}", "ROOM", "R", *rect) for i, rect in enumerate(rects))
    portals = []
    for i, a in enumerate(rooms):
        for b in rooms[i + 1 :]:
            wall = shared_wall(a, b)
            if wall is None:
                continue
            axis, _middle, lo, hi = wall
            gap = max(b.x - a.x2, a.x - b.x2) if axis == "x" else max(b.y - a.y2, a.y - b.y2)
            # only rooms that face each other across one wall, along at least a door
            if abs(gap - walldim) > 1e-9 or hi - lo < 0.8:
                continue
            if draw(st.booleans()):
                door = draw(st.floats(0.6, min(1.2, hi - lo)))
                portals.append(make_portal(a, b, draw(st.sampled_from("ei")), door))
    return Layout("random", width, height, walldim, rooms, tuple(portals)), resolution


@settings(max_examples=60, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(guillotine_layouts())
def test_random_layouts_connect_exactly_through_their_portals(case: tuple[Layout, float]) -> None:
    layout, resolution = case
    met = region_meetings(layout, rasterize_layout(layout, resolution))
    assert met == {frozenset((p.a, p.b)) for p in layout.portals}
