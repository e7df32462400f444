"""Small building plans built in memory: rectangles in centimetres (1 unit = 1 cm)."""

from __future__ import annotations

from layoutdsl.importer.building import BoundingBox, Building, BuildingPortal, LineSegment, Point, Space


def rect_space(space_id, rtype, label, x, y, w, h, doors=()):
    """A rectangular space; `doors` lists ((px, py), other space id, kind) on its walls."""
    corners = [Point(x, y), Point(x + w, y), Point(x + w, y + h), Point(x, y + h)]
    segments = [
        LineSegment(f"{space_id}-w{i}", corners[i], corners[(i + 1) % 4], "WALL", "EXPLICIT") for i in range(4)
    ]
    portals = []
    for n, ((px, py), other, kind) in enumerate(doors):
        seg = LineSegment(f"{space_id}-p{n}", Point(px, py), Point(px, py), "PORTAL", kind)
        segments.append(seg)
        portals.append(BuildingPortal(seg.id, kind, (space_id, other), seg))
    return Space(
        id=space_id,
        rtype=rtype,
        label=label,
        centroid=Point(x + w / 2, y + h / 2),
        bbox=BoundingBox(x, y, x + w, y + h),
        polygon=tuple(corners),
        segments=tuple(segments),
        portals=tuple(portals),
    )


def building(spaces, name="synthetic"):
    """A building whose door is 90 cm drawn as 90 units."""
    return Building(name=name, represented_distance=90.0, real_distance_m=0.9, spaces=tuple(spaces))


def corridor_plan(close_door: bool = False):
    """E0 (4 x 4 m) - C0 (12 x 1.2 m corridor) - E1 (4 x 4 m), in a row along x.

    With `close_door`, the C0-E1 portal is left out (a closed door: a missing adjacency).
    """
    e1_doors = () if close_door else (((1600, 200), "C0", "EXPLICIT"),)
    c0_doors = [((400, 200), "E0", "EXPLICIT")]
    if not close_door:
        c0_doors.append(((1600, 200), "E1", "EXPLICIT"))
    return building(
        [
            rect_space("E0", "E", "ENTRANCE", 0, 0, 400, 400, (((400, 200), "C0", "EXPLICIT"),)),
            rect_space("C0", "C", "CORRIDOR", 400, 140, 1200, 120, tuple(c0_doors)),
            rect_space("E1", "E", "ENTRANCE", 1600, 0, 400, 400, e1_doors),
        ]
    )
