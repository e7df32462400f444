"""The one wall geometry of the 3D worlds (MuJoCo, Gazebo, glTF): boxes derived from a layout.

The thesis names 3D generation as future work; every 3D emitter takes its walls from
`wall_geometry` so that the three simulators and the 2D occupancy map
(`layoutdsl.emit.raster.rasterize_layout`) describe one building:

- each room's interior is free; around it runs a wall of the layout's wall thickness
  (`walldim`, thesis §5.5), so the wall between two adjacent rooms fills their gap exactly;
- the gap between two rooms that share a portal is wall along their whole common side,
  except for the portal's opening, cut with the same width and position the raster carves
  (explicit doors and implicit openings alike are left open, as in the raster: no emitter
  models a door leaf);
- walls are never thinner than `MIN_WALL_THICKNESS` (one cell of the default map, the
  thinnest wall the raster can draw): a thinner wall grows into both rooms by half the
  difference, and `WallGeometry.inset` says by how much each room's free interior shrank.

Frame: metres, the layout's frame (origin at the boundary's bottom-left corner, y up),
z up from the floor at z = 0: the frame of the Stage world and the ROS map.

The occupied region (walls, minus rooms, minus openings) is computed exactly on the grid
of all rectangle coordinates and merged into disjoint boxes, so boxes never overlap and
ray casts, meshes and collision shapes see the same surfaces.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from layoutdsl.emit.templating import format_number
from layoutdsl.layout import Layout, PlacedRoom, facing_parts, shared_wall
from layoutdsl.emit.raster import DEFAULT_RESOLUTION

DEFAULT_WALL_HEIGHT = 2.5
"""Wall height in metres: a common storey's clear height, tall enough for any ground robot's sensors."""

MIN_WALL_THICKNESS = DEFAULT_RESOLUTION
"""The thinnest wall built: one cell of the default occupancy map (5 cm)."""

# Coordinates are rounded to this many decimals (1 nm) so that edges computed along
# different paths (a room's edge, its neighbour's wall face) coincide exactly.
_DECIMALS = 9

SNAP = 1e-3
"""Edges closer than this (1 mm) along an axis are made one: solver output aligns rooms
only to its tolerance, and a sub-millimetre sliver box would be a degenerate collision
shape (MuJoCo rejects a box of size 0) while no simulator could tell the difference."""

Rect = tuple[float, float, float, float]
"""(x0, y0, x1, y1) in metres, x0 < x1 and y0 < y1."""


@dataclass(frozen=True, slots=True)
class WallBox:
    """An axis-aligned wall block from the floor (z = 0) up to the wall height."""

    x0: float
    y0: float
    x1: float
    y1: float

    @property
    def centre(self) -> tuple[float, float]:
        return ((self.x0 + self.x1) / 2, (self.y0 + self.y1) / 2)

    @property
    def size(self) -> tuple[float, float]:
        """(extent along x, extent along y)."""
        return (self.x1 - self.x0, self.y1 - self.y0)


@dataclass(frozen=True, slots=True)
class WallGeometry:
    """The walls of a layout, and the facts the emitters and their tests need."""

    boxes: tuple[WallBox, ...]
    height: float
    thickness: float
    """Thickness of every wall, metres: `walldim`, or `MIN_WALL_THICKNESS` if that is larger."""
    inset: float
    """How far each room's free interior lies inside the room's rectangle (0 unless walls grew)."""
    openings: tuple[Rect, ...]
    """Each portal's opening through its wall, in the order of `layout.portals`."""
    extent: Rect
    """Bounding box of the walls."""

    @property
    def centre(self) -> tuple[float, float]:
        x0, y0, x1, y1 = self.extent
        return ((x0 + x1) / 2, (y0 + y1) / 2)


def vector(*values: float) -> str:
    """Numbers as MJCF and SDFormat write vectors: space-separated, to the micrometre.

    A micrometre is finer than any simulator's contact tolerance and drops float noise,
    so equal layouts give equal bytes.
    """
    return " ".join(format_number(value, 6) for value in values)


def _r(value: float) -> float:
    return round(value, _DECIMALS) + 0.0  # + 0.0 turns -0.0 into 0.0


def _rect(x0: float, y0: float, x1: float, y1: float) -> Rect:
    return (_r(x0), _r(y0), _r(x1), _r(y1))


def _interior(room: PlacedRoom, inset: float) -> Rect:
    return _rect(room.x + inset, room.y + inset, room.x2 - inset, room.y2 - inset)


def _interiors(room: PlacedRoom, inset: float) -> list[Rect]:
    """A room's free interior: one rectangle, or an L's two arms and, when walls grew into
    the rooms (inset > 0), the strip between the arms' shrunk interiors along their join:
    an L has no wall inside."""
    parts = room.parts
    rects = [_interior(part, inset) for part in parts]
    if len(parts) == 2 and inset > 0:
        a, b = parts
        if abs(a.x2 - b.x) < SNAP or abs(b.x2 - a.x) < SNAP:
            line = a.x2 if abs(a.x2 - b.x) < SNAP else a.x
            rects.append(_rect(line - inset, max(a.y, b.y) + inset, line + inset, min(a.y2, b.y2) - inset))
        else:
            line = a.y2 if abs(a.y2 - b.y) < SNAP else a.y
            rects.append(_rect(max(a.x, b.x) + inset, line - inset, min(a.x2, b.x2) - inset, line + inset))
    return rects


def _portal_rects(layout: Layout, inset: float) -> tuple[list[Rect], list[Rect]]:
    """For each portal: the wall filling its rooms' gap along their common side, and its opening.

    The opening spans the portal's width centred on the portal, clipped to the side both
    rooms share, exactly as `rasterize_layout` clips the door it carves.
    """
    fills: list[Rect] = []
    openings: list[Rect] = []
    for portal in layout.portals:
        # an L-room's portal is in the wall of its arm that faces the other room
        a, b = facing_parts(layout.room(portal.a), layout.room(portal.b))
        wall = shared_wall(a, b)
        if wall is None:  # the verifier never lets this through; nothing to open
            continue
        axis, _, lo, hi = wall
        ia, ib = _interior(a, inset), _interior(b, inset)
        half = portal.width / 2
        cx, cy = portal.centre
        if axis == "x":
            left, right = (ia, ib) if ia[0] < ib[0] else (ib, ia)
            gap = (left[2], right[0])
            common = (lo + inset, hi - inset)
            span = (max(cy - half, common[0]), min(cy + half, common[1]))
            fills.append(_rect(gap[0], common[0], gap[1], common[1]))
            openings.append(_rect(gap[0], span[0], gap[1], span[1]))
        else:
            low, high = (ia, ib) if ia[1] < ib[1] else (ib, ia)
            gap = (low[3], high[1])
            common = (lo + inset, hi - inset)
            span = (max(cx - half, common[0]), min(cx + half, common[1]))
            fills.append(_rect(common[0], gap[0], common[1], gap[1]))
            openings.append(_rect(span[0], gap[0], span[1], gap[1]))
    return fills, openings


def _snapped_axis(values: list[float]) -> np.ndarray:
    """The distinct coordinates along an axis, keeping the first of any run closer than SNAP."""
    ordered = np.unique(np.array(values))
    kept = [ordered[0]]
    for value in ordered[1:]:
        if value - kept[-1] >= SNAP:
            kept.append(value)
    return np.array(kept)


def _index(axis: np.ndarray, value: float) -> int:
    """Index of the kept coordinate that stands for `value` (the nearest one)."""
    position = int(np.searchsorted(axis, value))
    if position == len(axis) or (position > 0 and value - axis[position - 1] < axis[position] - value):
        position -= 1
    return position


def _paint(grid: np.ndarray, xs: np.ndarray, ys: np.ndarray, rect: Rect, value: bool) -> None:
    x0, y0, x1, y1 = rect
    i0, i1 = _index(xs, x0), _index(xs, x1)
    j0, j1 = _index(ys, y0), _index(ys, y1)
    grid[j0:j1, i0:i1] = value


def _merge(grid: np.ndarray, xs: np.ndarray, ys: np.ndarray) -> list[WallBox]:
    """Disjoint boxes covering the True cells: runs along x, stacked while identical in y."""
    boxes: list[WallBox] = []
    open_runs: dict[tuple[int, int], int] = {}
    rows = grid.shape[0]
    for j in range(rows + 1):
        runs: set[tuple[int, int]] = set()
        if j < rows:
            padded = np.concatenate(([0], grid[j].astype(np.int8), [0]))
            edges = np.flatnonzero(np.diff(padded))
            runs = set(zip(edges[0::2].tolist(), edges[1::2].tolist(), strict=True))
        for run in sorted(set(open_runs) - runs):
            start = open_runs.pop(run)
            boxes.append(WallBox(float(xs[run[0]]), float(ys[start]), float(xs[run[1]]), float(ys[j])))
        for run in runs:
            open_runs.setdefault(run, j)
    boxes.sort(key=lambda b: (b.y0, b.x0, b.y1, b.x1))
    return boxes


def wall_geometry(layout: Layout, height: float = DEFAULT_WALL_HEIGHT) -> WallGeometry:
    """The wall boxes of a layout (see the module docstring for the rules)."""
    if not height > 0:
        raise ValueError(f"wall height must be positive, got {height}")
    if not layout.rooms:
        raise ValueError(f"layout `{layout.name}` has no rooms")
    inset = max(0.0, (MIN_WALL_THICKNESS - layout.walldim) / 2)
    thickness = layout.walldim + 2 * inset
    interiors = [rect for room in layout.rooms for rect in _interiors(room, inset)]
    surrounds = [_rect(x0 - thickness, y0 - thickness, x1 + thickness, y1 + thickness) for x0, y0, x1, y1 in interiors]
    fills, openings = _portal_rects(layout, inset)
    rects = [*surrounds, *interiors, *fills, *openings]
    xs = _snapped_axis([c for r in rects for c in (r[0], r[2])])
    ys = _snapped_axis([c for r in rects for c in (r[1], r[3])])
    grid = np.zeros((len(ys) - 1, len(xs) - 1), dtype=bool)
    for rect in (*surrounds, *fills):
        _paint(grid, xs, ys, rect, True)
    for rect in interiors:
        _paint(grid, xs, ys, rect, False)
    for rect in openings:
        _paint(grid, xs, ys, rect, False)
    boxes = _merge(grid, xs, ys)
    extent = (
        min(b.x0 for b in boxes),
        min(b.y0 for b in boxes),
        max(b.x1 for b in boxes),
        max(b.y1 for b in boxes),
    )
    return WallGeometry(tuple(boxes), float(height), _r(thickness), _r(inset), tuple(openings), extent)
