"""Independent checks for the 3D worlds: ray casts on the occupancy grid and the layouts to test.

Nothing here uses the wall geometry module: the references are the occupancy grid
(`rasterize_layout`, the map Stage and ROS see) and plain geometry.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from layoutdsl.layout import Layout
from layoutdsl.emit.raster import OccupancyGrid

ROOT = Path(__file__).resolve().parents[2]
FIXTURE_LAYOUTS = ROOT / "tests" / "fixtures" / "layouts"
LARGE_PLANS = ("office_floorplanLOWER", "school_stjoseph_scatholichighschool")
"""Compiled layouts of real plans, 55 and 105 rooms (tests/fixtures/layouts/README.md)."""

MARCH_STEP_FRACTION = 20
"""Rays march in steps of 1/20 cell: a hit is located to 2.5 mm on the 5 cm grid."""


def large_layout(name: str = LARGE_PLANS[0]) -> Layout:
    return Layout.from_json((FIXTURE_LAYOUTS / f"{name}.layout.json").read_text())


def grid_ray_distances(grid: OccupancyGrid, x: float, y: float, directions: np.ndarray, max_range: float) -> np.ndarray:
    """Distance from (x, y) along each unit direction (N × 2) to the first occupied cell.

    Leaving the grid counts as a hit (the grid's frame is occupied); a ray that meets
    nothing within `max_range` reads `max_range`.
    """
    step = grid.resolution / MARCH_STEP_FRACTION
    ts = np.arange(0.0, max_range + step, step)
    px = x + directions[:, 0:1] * ts[None, :]
    py = y + directions[:, 1:2] * ts[None, :]
    rows, cols = grid.occupied.shape
    col = np.floor((px - grid.origin[0]) / grid.resolution).astype(np.int64)
    row = rows - 1 - np.floor((py - grid.origin[1]) / grid.resolution).astype(np.int64)
    outside = (row < 0) | (row >= rows) | (col < 0) | (col >= cols)
    hit = outside.copy()
    inside = ~outside
    hit[inside] = grid.occupied[row[inside], col[inside]]
    first = np.where(hit.any(axis=1), hit.argmax(axis=1), len(ts) - 1)
    return np.minimum(ts[first], max_range)


def distance_to_occupied(grid: OccupancyGrid, points: np.ndarray) -> np.ndarray:
    """Euclidean distance from each point (N × 2) to the nearest occupied cell (0 inside one)."""
    out = np.empty(len(points))
    rows, cols = grid.occupied.shape
    reach = 4  # cells searched around the point; farther reads as > 4 cells
    for index, (px, py) in enumerate(points):
        row, col = grid.world_to_cell(px, py)
        r0, r1 = max(0, row - reach), min(rows, row + reach + 1)
        c0, c1 = max(0, col - reach), min(cols, col + reach + 1)
        block = np.argwhere(grid.occupied[r0:r1, c0:c1])
        if not grid.contains(row, col) or len(block) == 0:
            out[index] = 0.0 if not grid.contains(row, col) else math.inf
            continue
        cell_rows, cell_cols = block[:, 0] + r0, block[:, 1] + c0
        left = grid.origin[0] + cell_cols * grid.resolution
        bottom = grid.origin[1] + (rows - 1 - cell_rows) * grid.resolution
        dx = np.maximum(0.0, np.maximum(left - px, px - (left + grid.resolution)))
        dy = np.maximum(0.0, np.maximum(bottom - py, py - (bottom + grid.resolution)))
        out[index] = float(np.sqrt(dx * dx + dy * dy).min())
    return out


def distance_to_boxes(boxes: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Euclidean distance from each point (N × 2) to the nearest box (M × 4: x0, y0, x1, y1)."""
    px, py = points[:, 0:1], points[:, 1:2]
    dx = np.maximum(0.0, np.maximum(boxes[None, :, 0] - px, px - boxes[None, :, 2]))
    dy = np.maximum(0.0, np.maximum(boxes[None, :, 1] - py, py - boxes[None, :, 3]))
    return np.sqrt(dx * dx + dy * dy).min(axis=1)
