"""Plain rectangles -> Layout: the one conversion every stage judges a geometry by.

The construction, the compile pipeline and explain all turn `Rect`s into a Layout here, so
a start is verified exactly as a compiled layout is.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from layoutdsl.layout import WELD, Layout, PlacedObstacle, PlacedRoom, SolveInfo, make_portal, round_layout_number
from layoutdsl.syntax.ast import Room, Spec, arm_id

Rect = tuple[float, float, float, float]
"""(x, y, w, h): bottom-left corner and size, metres, boundary frame."""

SIDES = ("left", "right", "below", "above")
"""Where the first rectangle of a pair lies relative to the second ("a is left of b"): the
one direction convention of the model's ω (5.8), the construction and the variants."""

OPPOSITE_SIDE = {"left": "right", "right": "left", "below": "above", "above": "below"}
"""The side b is on when a is on `side` of it."""


def separations(a: Rect, b: Rect) -> tuple[float, float]:
    """Gap between two rectangles along x and along y (negative: they overlap that much)."""
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    return (max(bx - ax - aw, ax - bx - bw), max(by - ay - ah, ay - by - bh))


def gap_between(a: Rect, b: Rect) -> tuple[float, float, float, float]:
    """(x1, y1, x2, y2) of the space between two rectangles that do not overlap: along the
    stretch where they face each other, or, where they face each other along neither axis,
    the box between their nearest corners."""
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    low_x, high_x = max(ax, bx), min(ax + aw, bx + bw)
    low_y, high_y = max(ay, by), min(ay + ah, by + bh)
    left, right = (ax + aw, bx) if ax + aw <= bx else (bx + bw, ax)
    below, above = (ay + ah, by) if ay + ah <= by else (by + bh, ay)
    if high_y > low_y:
        return (left, low_y, right, high_y)
    if high_x > low_x:
        return (low_x, below, high_x, above)
    return (left, below, right, above)


def rooms_between(geometry: Mapping[str, Rect], a: str, b: str) -> list[str]:
    """The rectangles of `geometry` other than a and b that reach into the gap between them
    (gap_between), the one covering most of it first (then by id)."""
    x1, y1, x2, y2 = gap_between(geometry[a], geometry[b])
    found = []
    for other, (x, y, w, h) in geometry.items():
        if other in (a, b):
            continue
        across, up = min(x2, x + w) - max(x1, x), min(y2, y + h) - max(y1, y)
        if across > 1e-6 and up > 1e-6:
            found.append((-across * up, other))
    return [other for _area, other in sorted(found)]


def _welded_arm(box: Rect, arm: Rect) -> Rect:
    """The arm with each edge within WELD of one of the box's edge lines moved onto it: the
    solver joins the two only to its tolerance, and an L whose edges miss each other by a
    nanometre would have a sliver of outline between its arms."""
    bx, by, bw, bh = box
    ax, ay, aw, ah = arm
    lines_x, lines_y = (bx, round_layout_number(bx + bw)), (by, round_layout_number(by + bh))

    def weld(value: float, lines: tuple[float, float]) -> float:
        return next((line for line in lines if abs(line - value) <= WELD), value)

    x1, x2 = weld(ax, lines_x), weld(round_layout_number(ax + aw), lines_x)
    y1, y2 = weld(ay, lines_y), weld(round_layout_number(ay + ah), lines_y)
    return (x1, y1, round_layout_number(x2 - x1), round_layout_number(y2 - y1))


def layout_from_rects(spec: Spec, rects: Mapping[str, Rect], info: SolveInfo | None = None) -> Layout:
    """A Layout from plain rectangles: rounded rooms, portals centred on their shared walls.

    An L-shaped room's second rectangle is `rects[arm_id(room.id)]`."""
    assert spec.boundary is not None
    placed = {}
    armed = {arm.room for arm in spec.arms}
    for room in spec.rooms:
        x, y, w, h = (round_layout_number(float(v)) for v in rects[room.id])
        arm = None
        if room.id in armed:
            arm = _welded_arm((x, y, w, h), tuple(round_layout_number(float(v)) for v in rects[arm_id(room.id)]))
        placed[room.id] = PlacedRoom(room.id, room.label, room.rtype, x, y, w, h, arm)
    portals = []
    for adj in spec.adjacencies:
        try:
            portals.append(make_portal(placed[adj.a], placed[adj.b], adj.kind, adj.door))
        except ValueError:
            continue  # no shared wall: the verifier reports the adjacency
    obstacles = tuple(PlacedObstacle(o.id, o.x, o.y, o.w, o.h) for o in spec.boundary.obstacles)
    return Layout(
        name=spec.name,
        width=spec.boundary.w,
        height=spec.boundary.h,
        walldim=spec.settings.walldim,
        rooms=tuple(placed[r.id] for r in spec.rooms),
        portals=tuple(portals),
        obstacles=obstacles,
        solve=info,
    )


@dataclass(frozen=True, slots=True)
class RoomSizes:
    """A room's size bounds in orientation-free form, as (5.4)-(5.6) read them."""

    lo_long: float
    hi_long: float
    lo_short: float
    hi_short: float
    min_ar: float
    max_ar: float
    corridor: bool
    target_long: float
    target_short: float

    @staticmethod
    def of(room: Room) -> RoomSizes:
        """Bounds of the long and the short side, whichever axis the room lies along."""
        return RoomSizes(
            lo_long=max(room.min_w, room.min_h),
            hi_long=max(room.max_w, room.max_h),
            lo_short=min(room.min_w, room.min_h),
            hi_short=min(room.max_w, room.max_h),
            min_ar=room.min_ar,
            max_ar=room.max_ar,
            corridor=room.is_corridor,
            target_long=max(room.target_w, room.target_h),
            target_short=min(room.target_w, room.target_h),
        )

    def bounds(self, long_along_x: bool) -> tuple[float, float, float, float]:
        """(w_lo, w_hi, h_lo, h_hi) for the given orientation."""
        if long_along_x:
            return self.lo_long, self.hi_long, self.lo_short, self.hi_short
        return self.lo_short, self.hi_short, self.lo_long, self.hi_long

    def targets(self, long_along_x: bool) -> tuple[float, float]:
        """(target w, target h) for the given orientation."""
        if long_along_x:
            return self.target_long, self.target_short
        return self.target_short, self.target_long
