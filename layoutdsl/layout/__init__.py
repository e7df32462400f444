"""The solved Layout: plain numbers, the emitters' only input.

Metres, boundary frame (origin bottom-left, y up), rectangles by bottom-left corner, as in
the spec. Nothing here knows about Pyomo or SCIP.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field, replace


@dataclass(frozen=True, slots=True)
class PlacedRoom:
    """A room as placed: bottom-left corner (x, y), width w along x, height h along y.

    An L-shaped room also has its `arm`, the second rectangle (x, y, w, h), flush against
    the first along a full edge at a corner: the room is their union, with no wall between
    them. Code that draws, rasterises or measures a room goes through `parts` (or
    `polygon`), never through x, y, w, h alone.
    """

    id: str
    label: str
    rtype: str
    x: float
    y: float
    w: float
    h: float
    arm: tuple[float, float, float, float] | None = None

    @property
    def x2(self) -> float:
        return self.x + self.w

    @property
    def y2(self) -> float:
        return self.y + self.h

    @property
    def is_l_shaped(self) -> bool:
        return self.arm is not None

    @property
    def parts(self) -> tuple[PlacedRoom, ...]:
        """The room's rectangles as rooms of one rectangle each (same id, label and type)."""
        if self.arm is None:
            return (self,)
        return (replace(self, arm=None), PlacedRoom(self.id, self.label, self.rtype, *self.arm))

    @property
    def centre(self) -> tuple[float, float]:
        """The centre of the room's (larger) rectangle: a point inside the room, where a
        robot can be placed (an L's centroid may lie outside it)."""
        part = max(self.parts, key=lambda p: (p.w * p.h, -p.x, -p.y))
        return (part.x + part.w / 2, part.y + part.h / 2)

    @property
    def area(self) -> float:
        return sum(p.w * p.h for p in self.parts)

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """(x_min, y_min, x_max, y_max) of the whole room."""
        parts = self.parts
        return (min(p.x for p in parts), min(p.y for p in parts),
                max(p.x2 for p in parts), max(p.y2 for p in parts))

    @property
    def polygon(self) -> tuple[tuple[float, float], ...]:
        """The room's outline, counter-clockwise from its lowest-left corner: 4 corners for a
        rectangle, 6 for an L."""
        if self.arm is None:
            return ((self.x, self.y), (self.x2, self.y), (self.x2, self.y2), (self.x, self.y2))
        return union_outline([(p.x, p.y, p.x2, p.y2) for p in self.parts])


def union_outline(boxes: list[tuple[float, float, float, float]]) -> tuple[tuple[float, float], ...]:
    """The outline of a union of boxes (x1, y1, x2, y2) that forms one simple rectilinear
    polygon (an L, or a rectangle): its corners counter-clockwise, from the lowest-left one.

    Traced on the grid of the boxes' coordinates: from each corner the outline leaves in the
    one direction that keeps the union on its left. Coordinates closer than WELD (solver
    noise: an arm's x + w one nanometre short of its box's x) are one.
    """
    xs, weld_x = _welded([v for b in boxes for v in (b[0], b[2])])
    ys, weld_y = _welded([v for b in boxes for v in (b[1], b[3])])
    boxes = [(weld_x[b[0]], weld_y[b[1]], weld_x[b[2]], weld_y[b[3]]) for b in boxes]

    def covered(i: int, j: int) -> bool:
        """Is grid cell (i, j), between xs[i], xs[i+1] and ys[j], ys[j+1], in the union?"""
        if not (0 <= i < len(xs) - 1 and 0 <= j < len(ys) - 1):
            return False
        cx, cy = (xs[i] + xs[i + 1]) / 2, (ys[j] + ys[j + 1]) / 2
        return any(b[0] <= cx <= b[2] and b[1] <= cy <= b[3] for b in boxes)

    def leaving(i: int, j: int) -> tuple[int, int] | None:
        """The direction the outline leaves grid point (i, j) in, None if it is no corner
        (or not on the outline)."""
        ll, lr, ur, ul = covered(i - 1, j - 1), covered(i, j - 1), covered(i, j), covered(i - 1, j)
        # (direction, cell on its left, cell on its right)
        for step, left, right in (((1, 0), ur, lr), ((0, 1), ul, ur), ((-1, 0), ll, ul), ((0, -1), lr, ll)):
            if left and not right:
                arriving = _ARRIVING[step]
                if arriving(ll, lr, ur, ul):
                    return step
        return None

    corners = [(i, j) for j in range(len(ys)) for i in range(len(xs)) if leaving(i, j) is not None]
    start = corners[0]
    outline = [start]
    current = start
    while True:
        di, dj = leaving(*current)
        i, j = current[0] + di, current[1] + dj
        while (i, j) not in corners:
            i, j = i + di, j + dj
        if (i, j) == start:
            break
        outline.append((i, j))
        current = (i, j)
    return tuple((xs[i], ys[j]) for i, j in outline)


WELD = 1e-6
"""Metres within which two coordinates of one room's outline are the same line (the
verifier's tolerance)."""


def _welded(values: list[float]) -> tuple[list[float], dict[float, float]]:
    """The distinct coordinates, runs closer than WELD merged into their first, and the map
    from each value to the coordinate that stands for it."""
    kept: list[float] = []
    stands_for: dict[float, float] = {}
    for value in sorted(set(values)):
        if not kept or value - kept[-1] > WELD:
            kept.append(value)
        stands_for[value] = kept[-1]
    return kept, stands_for


# A grid point is a corner when the outline turns there: the edge leaving it in a direction
# is not the continuation of an edge arriving in the same direction. For each leaving
# direction, the test that the edge arriving straight (from the opposite side) is absent.
_ARRIVING = {
    (1, 0): lambda ll, lr, ur, ul: not (ul and not ll),
    (0, 1): lambda ll, lr, ur, ul: not (ll and not lr),
    (-1, 0): lambda ll, lr, ur, ul: not (lr and not ur),
    (0, -1): lambda ll, lr, ur, ul: not (ur and not ul),
}


@dataclass(frozen=True, slots=True)
class PlacedObstacle:
    id: str
    x: float
    y: float
    w: float
    h: float


@dataclass(frozen=True, slots=True)
class Portal:
    """A door (explicit) or opening (implicit) between two adjacent rooms.

    The segment (x1, y1)-(x2, y2) lies on the middle line of the wall between the rooms,
    centred on the wall they share, `width` metres long.
    """

    a: str
    b: str
    kind: str
    """'e' explicit (a door) or 'i' implicit (no barrier)."""
    width: float
    x1: float
    y1: float
    x2: float
    y2: float

    @property
    def centre(self) -> tuple[float, float]:
        return ((self.x1 + self.x2) / 2, (self.y1 + self.y2) / 2)

    @property
    def vertical(self) -> bool:
        """True when the door lies in a vertical wall (the rooms are side by side in x)."""
        return abs(self.x2 - self.x1) < abs(self.y2 - self.y1)


@dataclass(frozen=True, slots=True)
class SolveInfo:
    """How the layout was found. Timing fields are the only run-to-run difference."""

    status: str
    """'optimal', 'gap_limit', 'time_limit', 'node_limit', 'solution_limit', 'construction' or
    'solver_crashed' (the search died or hung natively; the layout is the verified start it had)."""
    objective: float | None = None
    """(5.1) recomputed from the placed rooms, not SCIP's figure."""
    bound: float | None = None
    gap: float | None = None
    seconds: float | None = None
    first_feasible_seconds: float | None = None
    seed: int = 0
    method: str = ""
    """How the first feasible layout was found (e.g. 'construction', 'scip')."""
    grown_boundary: tuple[float, float] | None = None
    """(width, height) the boundary grew to for this arrangement (compile --grow-boundary),
    None when it kept the spec's."""
    wall_clock_limited: bool = False
    """The time limit (the outer cap) stopped a stage before its deterministic work limits:
    this layout may differ from the one the same spec and seed give on an idle machine
    (solve.SolveOutcome.wall_clock_limited)."""


@dataclass(frozen=True, slots=True)
class Layout:
    """A verified building layout."""

    name: str
    width: float
    """Boundary width (x), metres."""
    height: float
    """Boundary height (y), metres."""
    walldim: float
    rooms: tuple[PlacedRoom, ...]
    portals: tuple[Portal, ...]
    obstacles: tuple[PlacedObstacle, ...] = ()
    solve: SolveInfo | None = field(default=None)

    def parts(self) -> tuple[PlacedRoom, ...]:
        """Every room's rectangles (an L-room gives two, under its one id)."""
        return tuple(part for room in self.rooms for part in room.parts)

    def room(self, room_id: str) -> PlacedRoom:
        for room in self.rooms:
            if room.id == room_id:
                return room
        raise KeyError(room_id)

    def to_json(self) -> str:
        data = asdict(self)
        for room in data["rooms"]:
            if room["arm"] is None:
                del room["arm"]  # a rectangular room's JSON is as it was before L-rooms
        return json.dumps(data, indent=2, sort_keys=False) + "\n"

    @staticmethod
    def from_json(text: str) -> Layout:
        data = json.loads(text)
        solve = data.get("solve")
        return Layout(
            name=data["name"],
            width=data["width"],
            height=data["height"],
            walldim=data["walldim"],
            rooms=tuple(_placed_room(r) for r in data["rooms"]),
            portals=tuple(Portal(**p) for p in data["portals"]),
            obstacles=tuple(PlacedObstacle(**o) for o in data.get("obstacles", ())),
            solve=_solve_info(solve) if solve else None,
        )


def _solve_info(data: dict) -> SolveInfo:
    grown = data.get("grown_boundary")
    return SolveInfo(**{**data, "grown_boundary": tuple(grown) if grown is not None else None})


def _placed_room(data: dict) -> PlacedRoom:
    arm = data.get("arm")
    return PlacedRoom(**{**data, "arm": tuple(arm) if arm is not None else None})


def facing_parts(a: PlacedRoom, b: PlacedRoom) -> tuple[PlacedRoom, PlacedRoom]:
    """The rectangles of two rooms that face each other across the longest shared wall
    (for rectangular rooms, the rooms themselves): the pair a portal between them sits on."""
    best = None
    for part_a in a.parts:
        for part_b in b.parts:
            wall = _single_shared_wall(part_a, part_b)
            if wall is None:
                continue
            gap = max(part_b.x - part_a.x2, part_a.x - part_b.x2, part_b.y - part_a.y2, part_a.y - part_b.y2)
            key = (round(gap, 9), -(wall[3] - wall[2]))
            if best is None or key < best[0]:
                best = (key, part_a, part_b)
    if best is None:
        return a.parts[0], b.parts[0]
    return best[1], best[2]


def shared_wall(a: PlacedRoom, b: PlacedRoom) -> tuple[str, float, float, float] | None:
    """The wall two rooms face each other across, or None when they face no common wall.

    Returns (axis, middle, lo, hi): axis 'x' means the rooms sit side by side along x and
    the wall is the vertical line x = middle spanning y in [lo, hi]; axis 'y' means one is
    above the other and the wall is y = middle spanning x in [lo, hi]. The rooms face each
    other across the axis with the smaller separation. For L-shaped rooms, the wall of
    their facing parts (`facing_parts`).
    """
    return _single_shared_wall(*facing_parts(a, b)) if a.arm or b.arm else _single_shared_wall(a, b)


def _single_shared_wall(a: PlacedRoom, b: PlacedRoom) -> tuple[str, float, float, float] | None:
    gap_x = max(b.x - a.x2, a.x - b.x2)
    gap_y = max(b.y - a.y2, a.y - b.y2)
    if gap_x >= gap_y:
        lo, hi = max(a.y, b.y), min(a.y2, b.y2)
        if hi <= lo:
            return None
        middle = (a.x2 + b.x) / 2 if a.x < b.x else (b.x2 + a.x) / 2
        return ("x", middle, lo, hi)
    lo, hi = max(a.x, b.x), min(a.x2, b.x2)
    if hi <= lo:
        return None
    middle = (a.y2 + b.y) / 2 if a.y < b.y else (b.y2 + a.y) / 2
    return ("y", middle, lo, hi)


def make_portal(a: PlacedRoom, b: PlacedRoom, kind: str, width: float) -> Portal:
    """The portal between two adjacent rooms, centred on the wall they share."""
    wall = shared_wall(a, b)
    if wall is None:
        raise ValueError(f"rooms {a.id} and {b.id} share no wall")
    axis, middle, lo, hi = wall
    centre = (lo + hi) / 2
    half = width / 2
    if axis == "x":
        return Portal(a.id, b.id, kind, width, middle, centre - half, middle, centre + half)
    return Portal(a.id, b.id, kind, width, centre - half, middle, centre + half, middle)


def round_layout_number(value: float) -> float:
    """Round solver noise away (1e-9 m) so equal solves serialise identically."""
    rounded = round(value, 9)
    return 0.0 if rounded == 0 or math.isclose(rounded, 0.0, abs_tol=1e-12) else rounded
