"""The shared rasterization on real plans (the thesis, §6.3.6): every door opens.

Runs on examples/floorplans always, and on the whole corpus when it is beside the repository.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image, ImageDraw

from layoutdsl.importer.building import Building
from layoutdsl.importer import read_building
from layoutdsl.emit.raster import OccupancyGrid, rasterize_building

from real_plans import EXAMPLES, corpus_plans

# the examples always; the whole corpus when CI provides it beside the repository
PLANS = sorted({p.name: p for p in [*EXAMPLES.glob("*.xml"), *corpus_plans()]}.values())

WINDOW_M = 2.5
"""Half-size of the square around a door searched for the passage (a door is ~1 m)."""


def _space_labels(building: Building, grid: OccupancyGrid) -> np.ndarray:
    """Index of the space whose polygon covers each cell, -1 outside all of them."""
    scale = building.metres_per_unit
    rows, cols = grid.shape
    top = grid.origin[1] + rows * grid.resolution
    image = Image.new("I", (cols, rows), -1)
    draw = ImageDraw.Draw(image)
    for index, space in enumerate(building.spaces):
        if len(space.polygon) >= 3:
            points = [((p.x * scale - grid.origin[0]) / grid.resolution, (top + p.y * scale) / grid.resolution) for p in space.polygon]
            draw.polygon(points, fill=index)
    return np.asarray(image)


def _door_opens(grid: OccupancyGrid, labels: np.ndarray, point: tuple[float, float], a: int, b: int) -> bool:
    """True when free space leads from space `a` to space `b` near the door point."""
    row, col = grid.world_to_cell(*point)
    half = int(WINDOW_M / grid.resolution)
    r0, r1 = max(0, row - half), min(grid.shape[0], row + half)
    c0, c1 = max(0, col - half), min(grid.shape[1], col + half)
    free = ~grid.occupied[r0:r1, c0:c1]
    window = labels[r0:r1, c0:c1]
    target = free & (window == b)
    reached = free & (window == a)
    # grow the region reachable from `a` through free cells (4-connected) until it stops
    while True:
        if (reached & target).any():
            return True
        grown = reached.copy()
        grown[1:, :] |= reached[:-1, :]
        grown[:-1, :] |= reached[1:, :]
        grown[:, 1:] |= reached[:, :-1]
        grown[:, :-1] |= reached[:, 1:]
        grown &= free
        if np.array_equal(grown, reached):
            return False
        reached = grown


@pytest.mark.parametrize("plan", PLANS, ids=[p.stem for p in PLANS])
def test_every_door_of_a_real_plan_opens_and_the_grid_is_framed(plan: Path) -> None:
    building, diagnostics = read_building(plan)
    assert building is not None, [d.message for d in diagnostics]
    grid = rasterize_building(building)
    occupied = grid.occupied
    assert occupied[0].all() and occupied[-1].all() and occupied[:, 0].all() and occupied[:, -1].all()
    labels = _space_labels(building, grid)
    index = {space.id: i for i, space in enumerate(building.spaces)}
    scale = building.metres_per_unit
    closed = []
    for space in building.spaces:
        for portal in space.portals:
            other = next((t for t in portal.targets if t != space.id), None)
            if other not in index or portal.segment is None:
                continue
            seg = portal.segment
            point = ((seg.p1.x + seg.p2.x) / 2 * scale, -(seg.p1.y + seg.p2.y) / 2 * scale)
            if not _door_opens(grid, labels, point, index[space.id], index[other]):
                closed.append(f"{space.label} ({space.id[:8]}) -> {other[:8]} at {point}")
    assert closed == []
