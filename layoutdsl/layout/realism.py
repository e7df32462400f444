"""Does a layout look like a building one can enter? Pure geometry on placed rooms.

The measures of issue 40, each computed on a raster of the rooms (default 5 cm cells):

- **the outside**: empty space connected to the world beyond the building. Gaps narrower
  than `min_gap` (0.6 m) between rooms count as wall: the outside is what a 0.6 m square
  can reach when it comes in from beyond the building's bounding box (a morphological
  opening of the free space, kept where it is connected to the border);
- **entrances open to the outside**: an entrance (a space labelled ENTRANCE, or typed E
  with no label) is open when at least `min_opening` (0.9 m) of its outline borders the
  outside;
- **enclosed voids**: empty space at least `min_gap` wide that the outside does not reach,
  as a share of the rooms' area (a courtyard no door leads to, a hole between rooms);
- **rooms with an outside wall**: rooms with at least `min_opening` of outline on the outside;
- **slivers**: gaps between two rooms' facing walls wider than a wall (walldim) but
  narrower than `usable_width`: neither wall nor usable space (rectangular rooms only).

The same functions measure an original plan's polygons (`measure_spaces`), so a generated
layout can be held against the plan it came from. Nothing here knows about the solver.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from layoutdsl.layout.verify import USABLE_WIDTH  # a gap narrower is a sliver: the rule compile keeps

MIN_GAP = 0.6
"""Metres: a gap between rooms narrower than this is wall, not a way in (issue 40)."""
MIN_OPENING = 0.9
"""Metres of outline on the outside that make an entrance open (a door's width)."""
RESOLUTION = 0.05
"""Metres per raster cell."""
MAX_CELLS = 6_000_000
"""The raster is coarsened beyond this many cells (a 120 x 50 m plan at 5 cm is 2.4 M)."""

Box = tuple[float, float, float, float]
"""(x1, y1, x2, y2), metres, y up."""
Point = tuple[float, float]


@dataclass(frozen=True, slots=True)
class Space:
    """One room as the measures see it: its id, label, type and shape (boxes or polygon)."""

    id: str
    label: str
    rtype: str
    boxes: tuple[Box, ...] = ()
    """Axis-parallel rectangles whose union is the room (a generated layout)."""
    polygon: tuple[Point, ...] = ()
    """Its outline, when it is not made of boxes (an original plan's space)."""

    @property
    def is_entrance(self) -> bool:
        """Labelled ENTRANCE (any case, any words around it), or typed E without a label."""
        label = (self.label or "").strip().upper()
        return "ENTRANCE" in label or (self.rtype.upper() == "E" and label in ("", "E"))


@dataclass(frozen=True, slots=True)
class Sliver:
    """Two rooms whose facing walls are `width` apart along `length` metres."""

    a: str
    b: str
    width: float
    length: float


@dataclass(frozen=True, slots=True)
class Realism:
    """The realism measures of one layout or plan."""

    outside_length: dict[str, float]
    """Per room: metres of its outline that border the outside."""
    entrances: tuple[str, ...]
    """The entrance rooms, in the order given."""
    room_area: float
    void_area: float
    """Square metres of enclosed voids."""
    voids: tuple[tuple[float, Point], ...]
    """Each enclosed void: (area m², a point inside it)."""
    slivers: tuple[Sliver, ...] | None
    """None when the shapes are not rectangles (an original plan)."""
    min_opening: float = MIN_OPENING

    @property
    def open_entrances(self) -> tuple[str, ...]:
        return tuple(e for e in self.entrances if self.outside_length[e] >= self.min_opening - 1e-9)

    @property
    def enclosed_entrances(self) -> tuple[str, ...]:
        return tuple(e for e in self.entrances if e not in self.open_entrances)

    @property
    def void_share(self) -> float:
        """Enclosed voids as a share of the rooms' area."""
        return self.void_area / self.room_area if self.room_area > 0 else 0.0

    @property
    def rooms_with_outside_wall(self) -> tuple[str, ...]:
        return tuple(r for r, length in self.outside_length.items() if length >= self.min_opening - 1e-9)

    def summary(self) -> dict:
        """Plain numbers for reports and JSON."""
        return {
            "entrances": len(self.entrances),
            "entrances_open": len(self.open_entrances),
            "enclosed_entrances": list(self.enclosed_entrances),
            "void_share": round(self.void_share, 4),
            "void_area": round(self.void_area, 2),
            "rooms": len(self.outside_length),
            "rooms_with_outside_wall": len(self.rooms_with_outside_wall),
            "slivers": None if self.slivers is None else len(self.slivers),
        }


def spaces_of_layout(layout) -> list[Space]:
    """The rooms of a solved `layoutdsl.layout.Layout` (an L-room as its two boxes)."""
    return [Space(room.id, room.label, room.rtype, boxes=tuple((p.x, p.y, p.x2, p.y2) for p in room.parts))
            for room in layout.rooms]


def measure_layout(layout, **limits) -> Realism:
    """The realism measures of a solved Layout (see the module doc; keyword limits:
    min_gap, min_opening, usable_width, resolution)."""
    return measure_spaces(spaces_of_layout(layout), walldim=layout.walldim, **limits)


def measure_spaces(spaces: Sequence[Space], *, walldim: float = 0.2, min_gap: float = MIN_GAP,
                   min_opening: float = MIN_OPENING, usable_width: float = USABLE_WIDTH,
                   resolution: float = RESOLUTION) -> Realism:
    """The realism measures of rooms given as boxes or polygons (metres, y up)."""
    if not spaces:
        return Realism({}, (), 0.0, 0.0, (), ())
    grid = _Raster.of(spaces, resolution, margin=2 * min_gap + 4 * resolution)
    occupied = grid.ids >= 0
    outside, enclosed = _outside_and_enclosed(occupied, grid.res, min_gap)
    # a room cell borders the outside when its 4-neighbour across the room's edge is outside;
    # each such cell edge is `res` metres of outline
    lengths = np.zeros(len(spaces))
    for shift_axis, step in ((0, 1), (0, -1), (1, 1), (1, -1)):
        neighbour_outside = np.roll(outside, -step, axis=shift_axis)
        hit = occupied & neighbour_outside
        if shift_axis == 0:
            hit[-1 if step == 1 else 0, :] = False
        else:
            hit[:, -1 if step == 1 else 0] = False
        lengths += np.bincount(grid.ids[hit], minlength=len(spaces)) * grid.res
    voids = []
    void_labels, count = ndimage.label(enclosed)
    for index in range(1, count + 1):
        cells = np.argwhere(void_labels == index)
        row, col = cells[len(cells) // 2]
        voids.append((float(len(cells) * grid.res**2), grid.point(row, col)))
    room_area = sum(_area(space) for space in spaces)
    all_boxes = all(space.boxes for space in spaces)
    return Realism(
        outside_length={space.id: round(float(lengths[i]), 6) for i, space in enumerate(spaces)},
        entrances=tuple(space.id for space in spaces if space.is_entrance),
        room_area=room_area,
        void_area=float(enclosed.sum() * grid.res**2),
        voids=tuple(sorted(voids, key=lambda v: -v[0])),
        slivers=find_slivers(spaces, walldim, usable_width) if all_boxes else None,
        min_opening=min_opening,
    )


def _outside_and_enclosed(occupied: np.ndarray, res: float, min_gap: float) -> tuple[np.ndarray, np.ndarray]:
    """(outside, enclosed) cell masks: free space the outside reaches through openings at
    least min_gap wide, and free space at least min_gap wide that it does not reach."""
    probe = max(1, math.ceil(min_gap / res - 1e-9))
    free = ~occupied
    # where a min_gap square fits entirely in free space (anchored at its lower-left cell)
    fits = _erode_square(free, probe)
    labels, _ = ndimage.label(fits)
    border = np.unique(np.concatenate([labels[0, :], labels[-1, :], labels[:, 0], labels[:, -1]]))
    border = border[border > 0]
    outside_anchor = np.isin(labels, border)
    outside = _dilate_square(outside_anchor, probe)
    enclosed_anchor = fits & ~outside_anchor
    return outside, _dilate_square(enclosed_anchor, probe) & ~outside


def void_area(spaces: Sequence[Space], *, min_gap: float = MIN_GAP, resolution: float = RESOLUTION) -> float:
    """m² of enclosed voids among the spaces: measure_spaces' void_area alone, without its
    outside lengths and slivers."""
    if not spaces:
        return 0.0
    grid = _Raster.of(spaces, resolution, margin=2 * min_gap + 4 * resolution)
    _outside, enclosed = _outside_and_enclosed(grid.ids >= 0, grid.res, min_gap)
    return float(enclosed.sum() * grid.res**2)


def voids_at(spaces: Sequence[Space], points: Sequence[Point], *, min_gap: float = MIN_GAP,
             resolution: float = RESOLUTION) -> list[tuple[int, float]]:
    """For each point, the enclosed void of the spaces (measure_spaces) it lies in: (a
    number for the void, 1 and up, and its area in m²), or (0, 0.0) outside every void."""
    if not spaces:
        return [(0, 0.0)] * len(points)
    grid = _Raster.of(spaces, resolution, margin=2 * min_gap + 4 * resolution)
    _outside, enclosed = _outside_and_enclosed(grid.ids >= 0, grid.res, min_gap)
    labels, _count = ndimage.label(enclosed)
    areas = np.bincount(labels.ravel()) * grid.res**2
    rows, cols = labels.shape
    found = []
    for px, py in points:
        col, row = int((px - grid.x0) // grid.res), int((py - grid.y0) // grid.res)
        label = int(labels[row, col]) if 0 <= row < rows and 0 <= col < cols else 0
        found.append((label, float(areas[label]) if label else 0.0))
    return found


def find_slivers(spaces: Sequence[Space], walldim: float, usable_width: float = USABLE_WIDTH,
                 tolerance: float = 1e-3) -> tuple[Sliver, ...]:
    """Facing walls of two different rooms more than a wall and less than `usable_width`
    apart, along more than a wall's thickness (rectangular rooms; exact, no raster)."""
    return tuple(gap for gap in facing_gaps(spaces, walldim, usable_width - tolerance, tolerance)
                 if gap.width > walldim + tolerance)


def facing_gaps(spaces: Sequence[Space], walldim: float, below: float,
                tolerance: float = 1e-3) -> tuple[Sliver, ...]:
    """Facing walls of two different rooms less than `below` apart (a wall apart included),
    along more than a wall's thickness, each pair once (its longest stretch)."""
    parts = [(space.id, box) for space in spaces for box in space.boxes]
    found: dict[tuple[str, str], Sliver] = {}
    for i, (a, ba) in enumerate(parts):
        for b, bb in parts[i + 1:]:
            if a == b:
                continue
            for gap, overlap in _facing(ba, bb):
                if gap < below and overlap > walldim + tolerance:
                    key = (a, b) if a < b else (b, a)
                    sliver = Sliver(key[0], key[1], round(gap, 6), round(overlap, 6))
                    if key not in found or found[key].length < sliver.length:
                        found[key] = sliver
    return tuple(found[key] for key in sorted(found))


def _facing(a: Box, b: Box) -> Iterable[tuple[float, float]]:
    """(gap, length of the facing stretch) for each axis on which the boxes face each other."""
    overlap_y = min(a[3], b[3]) - max(a[1], b[1])
    if overlap_y > 0:
        gap = max(b[0] - a[2], a[0] - b[2])
        if gap >= 0:
            yield gap, overlap_y
    overlap_x = min(a[2], b[2]) - max(a[0], b[0])
    if overlap_x > 0:
        gap = max(b[1] - a[3], a[1] - b[3])
        if gap >= 0:
            yield gap, overlap_x


def _area(space: Space) -> float:
    if space.boxes:
        return sum((x2 - x1) * (y2 - y1) for x1, y1, x2, y2 in space.boxes)
    pts = space.polygon
    return abs(sum(pts[i][0] * pts[(i + 1) % len(pts)][1] - pts[(i + 1) % len(pts)][0] * pts[i][1]
                   for i in range(len(pts)))) / 2


def _erode_square(mask: np.ndarray, k: int) -> np.ndarray:
    """Cells (r, c) such that the k x k square with (r, c) as its lowest corner is all True."""
    out = mask.copy()
    for axis in (0, 1):
        run = out.copy()
        for shift in range(1, k):
            shifted = np.zeros_like(out)
            if axis == 0:
                shifted[:-shift, :] = out[shift:, :]
            else:
                shifted[:, :-shift] = out[:, shift:]
            run &= shifted
        out = run
    return out


def _dilate_square(anchor: np.ndarray, k: int) -> np.ndarray:
    """Every cell of the k x k squares whose lowest corner is an anchor cell."""
    out = anchor.copy()
    for axis in (0, 1):
        run = out.copy()
        for shift in range(1, k):
            if axis == 0:
                run[shift:, :] |= out[:-shift, :]
            else:
                run[:, shift:] |= out[:, :-shift]
        out = run
    return out


@dataclass(slots=True)
class _Raster:
    """Room ids per cell (-1: free), cell (row, col) centred at (x0 + (col + .5) res, y0 + (row + .5) res)."""

    ids: np.ndarray
    x0: float
    y0: float
    res: float

    @staticmethod
    def of(spaces: Sequence[Space], resolution: float, margin: float) -> _Raster:
        xs, ys = [], []
        for space in spaces:
            for x1, y1, x2, y2 in space.boxes:
                xs += [x1, x2]
                ys += [y1, y2]
            for x, y in space.polygon:
                xs.append(x)
                ys.append(y)
        x0, y0 = min(xs) - margin, min(ys) - margin
        width, height = max(xs) + margin - x0, max(ys) + margin - y0
        res = max(resolution, math.sqrt(width * height / MAX_CELLS))
        cols, rows = math.ceil(width / res), math.ceil(height / res)
        ids = np.full((rows, cols), -1, dtype=np.int32)
        centres_x = x0 + (np.arange(cols) + 0.5) * res
        centres_y = y0 + (np.arange(rows) + 0.5) * res
        for index, space in enumerate(spaces):
            for x1, y1, x2, y2 in space.boxes:
                c1, c2 = np.searchsorted(centres_x, [x1, x2])
                r1, r2 = np.searchsorted(centres_y, [y1, y2])
                ids[r1:r2, c1:c2] = index
            if space.polygon:
                ids[_polygon_mask(space.polygon, centres_x, centres_y)] = index
        return _Raster(ids, x0, y0, res)

    def point(self, row: int, col: int) -> Point:
        return (round(self.x0 + (col + 0.5) * self.res, 3), round(self.y0 + (row + 0.5) * self.res, 3))


def _polygon_mask(polygon: Sequence[Point], centres_x: np.ndarray, centres_y: np.ndarray) -> np.ndarray:
    """Cells whose centre lies inside the polygon (even-odd rule, within its bounding box)."""
    mask = np.zeros((len(centres_y), len(centres_x)), dtype=bool)
    px = [p[0] for p in polygon]
    py = [p[1] for p in polygon]
    c1, c2 = np.searchsorted(centres_x, [min(px), max(px)])
    r1, r2 = np.searchsorted(centres_y, [min(py), max(py)])
    if c1 >= c2 or r1 >= r2:
        return mask
    gx, gy = np.meshgrid(centres_x[c1:c2], centres_y[r1:r2])
    inside = np.zeros(gx.shape, dtype=bool)
    n = len(polygon)
    for i in range(n):
        xa, ya = polygon[i]
        xb, yb = polygon[(i + 1) % n]
        if ya == yb:
            continue
        crosses = (ya > gy) != (yb > gy)
        x_at = xa + (gy - ya) * (xb - xa) / (yb - ya)
        inside ^= crosses & (gx < x_at)
    mask[r1:r2, c1:c2] = inside
    return mask
