"""The solved Layout: plain numbers, the emitters' only input.

Metres, boundary frame (origin bottom-left, y up), rectangles by bottom-left corner, as in
the spec. Nothing here knows about Pyomo or SCIP.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field


@dataclass(frozen=True, slots=True)
class PlacedRoom:
    """A room as placed: bottom-left corner (x, y), width w along x, height h along y."""

    id: str
    label: str
    rtype: str
    x: float
    y: float
    w: float
    h: float

    @property
    def x2(self) -> float:
        return self.x + self.w

    @property
    def y2(self) -> float:
        return self.y + self.h

    @property
    def centre(self) -> tuple[float, float]:
        return (self.x + self.w / 2, self.y + self.h / 2)

    @property
    def area(self) -> float:
        return self.w * self.h


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
    """'optimal', 'gap_limit', 'time_limit', 'node_limit', 'solution_limit' or 'construction'."""
    objective: float | None = None
    """(5.1) recomputed from the placed rooms, not SCIP's figure."""
    bound: float | None = None
    gap: float | None = None
    seconds: float | None = None
    first_feasible_seconds: float | None = None
    seed: int = 0
    method: str = ""
    """How the first feasible layout was found (e.g. 'construction', 'scip', 'cycles')."""


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

    def room(self, room_id: str) -> PlacedRoom:
        for room in self.rooms:
            if room.id == room_id:
                return room
        raise KeyError(room_id)

    def to_json(self) -> str:
        return json.dumps(asdict(self), indent=2, sort_keys=False) + "\n"

    @staticmethod
    def from_json(text: str) -> Layout:
        data = json.loads(text)
        solve = data.get("solve")
        return Layout(
            name=data["name"],
            width=data["width"],
            height=data["height"],
            walldim=data["walldim"],
            rooms=tuple(PlacedRoom(**r) for r in data["rooms"]),
            portals=tuple(Portal(**p) for p in data["portals"]),
            obstacles=tuple(PlacedObstacle(**o) for o in data.get("obstacles", ())),
            solve=SolveInfo(**solve) if solve else None,
        )


def shared_wall(a: PlacedRoom, b: PlacedRoom) -> tuple[str, float, float, float] | None:
    """The wall two rooms face each other across, or None when they face no common wall.

    Returns (axis, middle, lo, hi): axis 'x' means the rooms sit side by side along x and
    the wall is the vertical line x = middle spanning y in [lo, hi]; axis 'y' means one is
    above the other and the wall is y = middle spanning x in [lo, hi]. The rooms face each
    other across the axis with the smaller separation.
    """
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
