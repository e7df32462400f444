"""Building XML writer (the thesis, §5.2, §5.7): a Layout in the format of the real plans.

Units follow the real files: 1 file unit = 1 cm (`represented_distance` 90 pixel ↔
`real_distance` 90 cm), x to the right, y DOWNWARDS: y_file = (height − y_m) × 100. Space ids
are the spec's room ids (§5.7). Each room's space_representation walks its walls (four,
or an L-room's six) clockwise on screen from the top-left corner; a wall holding a portal is split there and the
portal is a PORTAL segment on that room's own wall edge, as long as the door. Line segment
and building ids are uuid5 values derived from the building name, room id and index, so
the same layout always gives the same file. Obstacles have no element in this format and
are not written.
"""

from __future__ import annotations

import uuid
from dataclasses import dataclass

from layoutdsl.importer.building import BuildingPortal, LineSegment, Point
from layoutdsl.layout import Layout, PlacedRoom, Portal

UNITS_PER_METRE = 100.0
"""1 file unit = 1 cm."""
DOOR_CM = 90.0
"""The scale's door: `represented_distance` 90 units is `real_distance` 90 cm."""

_NAMESPACE = uuid.UUID("6f1f9a52-6c2e-4d8e-9a1d-3b7d0c4e8a10")
"""Fixed namespace for layoutdsl's deterministic uuid5 ids."""


@dataclass(frozen=True, slots=True)
class XmlSpace:
    id: str
    rtype: str
    label: str
    centroid: Point
    max_x: Point
    max_y: Point
    min_x: Point
    min_y: Point
    polygon: tuple[Point, ...]
    segments: tuple[LineSegment, ...]
    portals: tuple[BuildingPortal, ...]


@dataclass(frozen=True, slots=True)
class XmlBuilding:
    id: str
    name: str
    represented_distance: float
    real_distance_cm: float
    spaces: tuple[XmlSpace, ...]


def _uid(*parts: str) -> str:
    return str(uuid.uuid5(_NAMESPACE, "/".join(parts)))


Edge = tuple[tuple[float, float], tuple[float, float]]
"""A wall edge of a room's outline, (start, end) in metres, walked clockwise on screen."""


def _edges(room: PlacedRoom) -> list[Edge]:
    """The room's outline clockwise on screen (y down) from its top-left corner, as the real
    files walk it: 4 edges for a rectangle, 6 for an L."""
    corners = list(reversed(room.polygon))  # the outline is counter-clockwise with y up
    first = max(range(len(corners)), key=lambda i: (corners[i][1], -corners[i][0]))
    corners = corners[first:] + corners[:first]
    return [(corners[i], corners[(i + 1) % len(corners)]) for i in range(len(corners))]


def _portal_edge(edges: list[Edge], portal: Portal) -> tuple[int, float, float] | None:
    """(index of the edge the portal opens in, its span along that edge), or None.

    The portal lies on the wall's middle line just outside the room: its edge is the
    nearest parallel one that the door overlaps."""
    cx, cy = portal.centre
    half = portal.width / 2
    best = None
    for index, ((x1, y1), (x2, y2)) in enumerate(edges):
        vertical = x1 == x2
        if vertical != portal.vertical:
            continue
        if vertical:
            distance, (lo, hi) = abs(x1 - cx), (max(cy - half, min(y1, y2)), min(cy + half, max(y1, y2)))
        else:
            distance, (lo, hi) = abs(y1 - cy), (max(cx - half, min(x1, x2)), min(cx + half, max(x1, x2)))
        if hi > lo and (best is None or distance < best[0]):
            best = (distance, index, lo, hi)
    return None if best is None else best[1:]


def _space(layout: Layout, room: PlacedRoom) -> XmlSpace:
    height = layout.height

    def pt(x_m: float, y_m: float) -> Point:
        return Point(round(x_m * UNITS_PER_METRE, 1), round((height - y_m) * UNITS_PER_METRE, 1))

    # Clockwise on screen (y down) from the top-left corner: for a rectangle the top edge
    # left→right, right edge top→bottom, bottom edge right→left, left edge bottom→top (as
    # the real files do); an L's six edges likewise.
    edges = _edges(room)
    # Door openings on each edge, as (lo, hi, portal) in metres along the edge.
    openings: dict[int, list[tuple[float, float, Portal]]] = {index: [] for index in range(len(edges))}
    for portal in layout.portals:
        if room.id not in (portal.a, portal.b):
            continue
        found = _portal_edge(edges, portal)
        if found is not None:
            index, lo, hi = found
            openings[index].append((lo, hi, portal))

    segments: list[LineSegment] = []
    portals: list[BuildingPortal] = []
    polygon: list[Point] = []
    for index, ((x1, y1), (x2, y2)) in enumerate(edges):
        # a coordinate along the edge (x on a horizontal one, y on a vertical one) -> point
        if x1 == x2:
            start, end, at = y1, y2, (lambda t, x=x1: (x, t))
        else:
            start, end, at = x1, x2, (lambda t, y=y1: (t, y))
        forward = end >= start
        ordered = sorted(openings[index], key=lambda item: item[0], reverse=not forward)
        cursor = start
        pieces: list[tuple[float, float, Portal | None]] = []
        for lo, hi, portal in ordered:
            near, far = (lo, hi) if forward else (hi, lo)
            if (near - cursor) * (1 if forward else -1) > 1e-9:
                pieces.append((cursor, near, None))
            pieces.append((near, far, portal))
            cursor = far
        if (end - cursor) * (1 if forward else -1) > 1e-9 or not pieces:
            pieces.append((cursor, end, None))
        for p_start, p_end, portal in pieces:
            seg_id = _uid(layout.name, room.id, "segment", str(len(segments)))
            p1, p2 = pt(*at(p_start)), pt(*at(p_end))
            polygon.append(p1)
            if portal is None:
                segments.append(LineSegment(seg_id, p1, p2, "WALL", "EXPLICIT"))
            else:
                kind = "EXPLICIT" if portal.kind == "e" else "IMPLICIT"
                segments.append(LineSegment(seg_id, p1, p2, "PORTAL", kind))
                portals.append(BuildingPortal(seg_id, kind, (portal.a, portal.b), segments[-1]))
    polygon.append(polygon[0])  # the real files close the polygon
    cx, cy = room.centre
    x_lo, y_lo, x_hi, y_hi = room.bounds
    return XmlSpace(
        id=room.id,
        rtype=room.rtype,
        label=room.label,
        centroid=pt(cx, cy),
        max_x=pt(x_hi, y_hi),
        max_y=pt(x_hi, y_lo),
        min_x=pt(x_lo, y_lo),
        min_y=pt(x_lo, y_hi),
        polygon=tuple(polygon),
        segments=tuple(segments),
        portals=tuple(portals),
    )


def building_model(layout: Layout) -> XmlBuilding:
    """The values the building XML template prints, derived from the layout alone."""
    return XmlBuilding(
        id=_uid(layout.name, "building"),
        name=layout.name,
        represented_distance=DOOR_CM,
        real_distance_cm=DOOR_CM,
        spaces=tuple(_space(layout, room) for room in layout.rooms),
    )


def render_xml(layout: Layout) -> str:
    """The building XML text of a layout."""
    from layoutdsl.emit.templating import environment

    template = environment().get_template("building.xml.j2")
    return template.render(building=building_model(layout))


def render(layout: Layout, stem: str, **_options: object) -> dict[str, bytes]:
    """File name -> content for the XML emitter: `stem.xml`."""
    return {f"{stem}.xml": render_xml(layout).encode("utf-8")}
