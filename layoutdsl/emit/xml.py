"""Building XML writer (the thesis, §5.2, §5.7): a Layout in the format of the real plans.

Units follow the real files: 1 file unit = 1 cm (`represented_distance` 90 pixel ↔
`real_distance` 90 cm), x to the right, y DOWNWARDS: y_file = (height − y_m) × 100. Space ids
are the spec's room ids (§5.7). Each room's space_representation walks its four walls
clockwise on screen from the top-left corner; a wall holding a portal is split there and the
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


def _portal_span_on_edge(room: PlacedRoom, portal: Portal) -> tuple[str, float, float]:
    """Which edge of `room` the portal opens in ('top', 'right', 'bottom', 'left') and its span."""
    cx, cy = portal.centre
    half = portal.width / 2
    room_cx, room_cy = room.centre
    # The portal lies on the wall middle line, just outside this room: the side of the
    # room's centre it falls on names the edge.
    if portal.vertical:
        edge = "right" if cx > room_cx else "left"
        lo, hi = max(cy - half, room.y), min(cy + half, room.y2)
    else:
        edge = "top" if cy > room_cy else "bottom"
        lo, hi = max(cx - half, room.x), min(cx + half, room.x2)
    return edge, lo, hi


def _space(layout: Layout, room: PlacedRoom) -> XmlSpace:
    height = layout.height

    def pt(x_m: float, y_m: float) -> Point:
        return Point(round(x_m * UNITS_PER_METRE, 1), round((height - y_m) * UNITS_PER_METRE, 1))

    # Door openings on each edge, as (lo, hi, portal) in metres along the edge.
    openings: dict[str, list[tuple[float, float, Portal]]] = {"top": [], "right": [], "bottom": [], "left": []}
    for portal in layout.portals:
        if room.id not in (portal.a, portal.b):
            continue
        edge, lo, hi = _portal_span_on_edge(room, portal)
        if hi > lo:
            openings[edge].append((lo, hi, portal))

    # Clockwise on screen (y down) from the top-left corner: top edge left→right, right edge
    # top→bottom, bottom edge right→left, left edge bottom→top (as the real files do).
    # Each edge: (start, end) in metres and a function mapping a coordinate along it to a point.
    edges = (
        ("top", room.x, room.x2, lambda t: (t, room.y2)),
        ("right", room.y2, room.y, lambda t: (room.x2, t)),
        ("bottom", room.x2, room.x, lambda t: (t, room.y)),
        ("left", room.y, room.y2, lambda t: (room.x, t)),
    )
    segments: list[LineSegment] = []
    portals: list[BuildingPortal] = []
    polygon: list[Point] = []
    for edge, start, end, at in edges:
        forward = end >= start
        ordered = sorted(openings[edge], key=lambda item: item[0], reverse=not forward)
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
    return XmlSpace(
        id=room.id,
        rtype=room.rtype,
        label=room.label,
        centroid=pt(cx, cy),
        max_x=pt(room.x2, room.y2),
        max_y=pt(room.x2, room.y),
        min_x=pt(room.x, room.y),
        min_y=pt(room.x, room.y2),
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
