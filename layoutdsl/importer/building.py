"""A building XML file (the thesis, §5.2) in memory: spaces, walls and portals, in file units.

Coordinates stay as the file has them: integer-ish "pixels", y growing downwards.
`Building.metres_per_unit` converts. The importer reads real plans into this model, the
XML emitter writes layouts in the same format, and the evaluator rasterizes both, so
originals and generated plans go through one reader.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from layoutdsl.layout.realism import Realism, measure_spaces
from layoutdsl.layout.realism import Space as RealismSpace
from layoutdsl.syntax.ast import ROOM_TYPES


def polygon_area(points) -> float:
    """The area enclosed by a polygon (shoelace), whatever its orientation or closure."""
    total = 0.0
    count = len(points)
    for index in range(count):
        a = points[index]
        b = points[(index + 1) % count]
        total += a.x * b.y - b.x * a.y
    return abs(total) / 2.0


@dataclass(frozen=True, slots=True)
class Point:
    x: float
    y: float


@dataclass(frozen=True, slots=True)
class LineSegment:
    """A wall or portal segment of a space (a real plan's portal has p1 == p2)."""

    id: str
    p1: Point
    p2: Point
    cls: str
    """'WALL' or 'PORTAL'."""
    type: str
    """'EXPLICIT' or 'IMPLICIT'."""


@dataclass(frozen=True, slots=True)
class BuildingPortal:
    """A `<portal>` of a space: its segment and the two spaces it joins."""

    segment_id: str
    type: str
    """'EXPLICIT' or 'IMPLICIT'."""
    targets: tuple[str, str]
    segment: LineSegment | None
    """The referenced segment of the same space, when it exists."""


@dataclass(frozen=True, slots=True)
class BoundingBox:
    min_x: float
    min_y: float
    max_x: float
    max_y: float

    @property
    def width(self) -> float:
        return self.max_x - self.min_x

    @property
    def height(self) -> float:
        return self.max_y - self.min_y


@dataclass(frozen=True, slots=True)
class Space:
    """A room of the plan."""

    id: str
    rtype: str
    """'R', 'C' or 'E' as written in `<type>`."""
    label: str
    centroid: Point | None
    bbox: BoundingBox
    polygon: tuple[Point, ...]
    segments: tuple[LineSegment, ...]
    portals: tuple[BuildingPortal, ...]
    line: int = 0
    """1-based line of the `<space>` element in its file (0 when unknown), for diagnostics."""

    @property
    def area(self) -> float:
        """The polygon's area in file units squared."""
        return polygon_area(self.polygon)

    @property
    def rectangularization_ratio(self) -> float:
        """sqrt(polygon area / bounding-box area) (the thesis, §5.3.1): the factor that turns the
        bounding box into a rectangle of the room's area. At most 1 (a self-intersecting
        polygon can claim more than its box; a room never fills more)."""
        box = self.bbox.width * self.bbox.height
        if box <= 0 or len(self.polygon) < 3:
            return 1.0  # no polygon to measure: the box is all there is
        return min(1.0, math.sqrt(self.area / box))

    @property
    def spec_type(self) -> str:
        """The room type of the spec: `<type>` when it is R, C or E, else R."""
        return self.rtype if self.rtype in ROOM_TYPES else "R"


@dataclass(frozen=True, slots=True)
class Building:
    """A whole building XML file."""

    name: str
    represented_distance: float
    """`<scale><represented_distance>`: file units spanning one door."""
    real_distance_m: float
    """`<scale><real_distance>` in metres: the door size."""
    spaces: tuple[Space, ...]

    @property
    def metres_per_unit(self) -> float:
        return self.real_distance_m / self.represented_distance

    def space(self, space_id: str) -> Space:
        for space in self.spaces:
            if space.id == space_id:
                return space
        raise KeyError(space_id)

    def spec_room_ids(self) -> dict[str, str]:
        """Space id -> spec room id: type letter and order within the type, in file order
        (R0, R1, ..., C0, ..., E0, ...; the thesis, §5.7)."""
        counters: dict[str, int] = {}
        ids: dict[str, str] = {}
        for space in self.spaces:
            number = counters.get(space.spec_type, 0)
            counters[space.spec_type] = number + 1
            ids[space.id] = f"{space.spec_type}{number}"
        return ids

    def portal_edges(self) -> dict[frozenset[str], str]:
        """Room pairs joined by at least one portal -> 'EXPLICIT' or 'IMPLICIT'.

        A pair with both kinds of portal counts as EXPLICIT (a door is the stronger claim).
        """
        edges: dict[frozenset[str], str] = {}
        for space in self.spaces:
            for portal in space.portals:
                a, b = portal.targets
                if a == b:
                    continue
                key = frozenset((a, b))
                if edges.get(key) != "EXPLICIT":
                    edges[key] = portal.type
        return edges


def realism_of_building(building: Building, ids: dict[str, str] | None = None) -> Realism:
    """layout.realism's measures on a plan's polygons (metres, y up, as rasterize_building),
    each space named by `ids` (space id -> name; default its own id)."""
    ids = ids or {}
    scale = building.metres_per_unit
    spaces = [RealismSpace(ids.get(space.id, space.id), space.label, space.rtype,
                           polygon=tuple((p.x * scale, -p.y * scale) for p in space.polygon))
              for space in building.spaces if len(space.polygon) >= 3]
    return measure_spaces(spaces)
