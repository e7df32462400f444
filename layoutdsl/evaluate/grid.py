"""Grids the evaluator works on: robot inflation, coarsening, and which cell is in which room.

The occupancy itself always comes from `layoutdsl.emit.raster` (the Stage/ROS map rasterization);
this module only derives from it. Cells are (row, col) with row 0 at the top, as there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from PIL import Image, ImageDraw

from layoutdsl.importer.building import Building
from layoutdsl.emit.raster import OccupancyGrid


def disc_offsets(radius_cells: float) -> list[tuple[int, int]]:
    """Integer offsets (dr, dc) within a disc of the given radius (cells), centre included."""
    reach = int(math.floor(radius_cells))
    return [
        (dr, dc)
        for dr in range(-reach, reach + 1)
        for dc in range(-reach, reach + 1)
        if dr * dr + dc * dc <= radius_cells * radius_cells + 1e-9
    ]


def dilate(mask: np.ndarray, offsets: list[tuple[int, int]]) -> np.ndarray:
    """Cells within one of the offsets of a True cell (a binary dilation without scipy)."""
    h, w = mask.shape
    out = mask.copy()
    for dr, dc in offsets:
        if dr == 0 and dc == 0:
            continue
        # out[r + dr, c + dc] |= mask[r, c]
        r0, r1 = max(0, dr), min(h, h + dr)
        c0, c1 = max(0, dc), min(w, w + dc)
        if r0 < r1 and c0 < c1:
            out[r0:r1, c0:c1] |= mask[r0 - dr : r1 - dr, c0 - dc : c1 - dc]
    return out


def inflate(occupied: np.ndarray, radius_m: float, resolution: float) -> np.ndarray:
    """Cells whose centre lies within `radius_m` of an occupied cell's centre: where the
    centre of a round robot of that radius cannot be (the costmap's inscribed radius)."""
    if radius_m <= 0:
        return occupied.copy()
    return dilate(occupied, disc_offsets(radius_m / resolution))


def coarsen(occupied: np.ndarray, factor: int) -> np.ndarray:
    """A grid `factor` times coarser whose cell is occupied when any of its fine cells is.

    Conservative on purpose: an opening stays open only where it is at least one coarse
    cell wide, so a coarse path is also a fine one.
    """
    if factor <= 1:
        return occupied.copy()
    h, w = occupied.shape
    ph, pw = -h % factor, -w % factor
    padded = np.pad(occupied, ((0, ph), (0, pw)), constant_values=True)
    return padded.reshape((h + ph) // factor, factor, (w + pw) // factor, factor).any(axis=(1, 3))


@dataclass(frozen=True)
class RoomCells:
    """Which room each cell of a grid lies in, and where each room's centre is."""

    labels: np.ndarray
    """Index into `ids` of the room holding the cell centre; -1 outside every room."""
    ids: tuple[str, ...]
    centres: tuple[tuple[float, float], ...]
    """Area centroid of each room polygon in (row, col) cell coordinates (fractional)."""


def polygon_centroid(points: list[tuple[float, float]]) -> tuple[float, float]:
    """Area centroid of a simple polygon; the vertex mean when it is degenerate."""
    area2 = 0.0
    cx = cy = 0.0
    n = len(points)
    for i in range(n):
        x1, y1 = points[i]
        x2, y2 = points[(i + 1) % n]
        cross = x1 * y2 - x2 * y1
        area2 += cross
        cx += (x1 + x2) * cross
        cy += (y1 + y2) * cross
    if abs(area2) < 1e-12:
        return (sum(p[0] for p in points) / n, sum(p[1] for p in points) / n)
    return (cx / (3 * area2), cy / (3 * area2))


def room_cells(building: Building, grid: OccupancyGrid, room_ids: dict[str, str], factor: int = 1) -> RoomCells:
    """Label the cells of `grid` (coarsened by `factor`) with the room they lie in.

    `room_ids` maps each space id to the id the report calls it by. Uses the frame of
    `layoutdsl.emit.raster.rasterize_building`: metres x = x_file·s, y = -y_file·s.
    """
    scale = building.metres_per_unit
    rows, cols = grid.shape
    resolution = grid.resolution * factor
    top = grid.origin[1] + rows * grid.resolution

    def to_cell(fx: float, fy: float) -> tuple[float, float]:
        # (row, col) with cell centres on integers
        return ((top + fy * scale) / resolution - 0.5, (fx * scale - grid.origin[0]) / resolution - 0.5)

    out_rows, out_cols = -(-rows // factor), -(-cols // factor)
    image = Image.new("I", (out_cols, out_rows), -1)
    draw = ImageDraw.Draw(image)
    ids: list[str] = []
    centres: list[tuple[float, float]] = []
    for space in building.spaces:
        polygon = [(p.x, p.y) for p in space.polygon]
        if len(polygon) < 3:
            bb = space.bbox
            polygon = [(bb.min_x, bb.min_y), (bb.max_x, bb.min_y), (bb.max_x, bb.max_y), (bb.min_x, bb.max_y)]
        cells = [to_cell(x, y) for x, y in polygon]
        # Pillow's pixel (i, j) covers [i, i + 1): shift by half a cell to fill by centres
        draw.polygon([(c + 0.5, r + 0.5) for r, c in cells], fill=len(ids))
        ids.append(room_ids[space.id])
        centres.append(to_cell(*polygon_centroid(polygon)))
    labels = np.asarray(image, dtype=np.int64).astype(np.int32)
    return RoomCells(labels=labels, ids=tuple(ids), centres=tuple(centres))


def nearest_cell(mask: np.ndarray, point: tuple[float, float], within: np.ndarray | None = None) -> tuple[int, int] | None:
    """The True cell of `mask` nearest to a (row, col) point, preferring cells of `within`."""
    for candidates in ((mask & within) if within is not None else None, mask):
        if candidates is None:
            continue
        rr, cc = np.nonzero(candidates)
        if rr.size == 0:
            continue
        d2 = (rr - point[0]) ** 2 + (cc - point[1]) ** 2
        best = int(np.argmin(d2))  # first of equals: row-major order, deterministic
        return (int(rr[best]), int(cc[best]))
    return None
