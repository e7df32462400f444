"""Fitting an L to a room polygon far from its bounding box (issue 14).

The thesis rectangularizes every space (§5.3.1): a long L-shaped corridor becomes a short fat
rectangle of the same area, which changes how a robot explores it and can make the spec
infeasible (§6.1.2); its first item of future work is rooms made of several rectangles (§7).
`fit_l` finds the L, that is the bounding box less one corner notch, that covers the
polygon best (least area in one but not the other), and cuts it into the two rectangles
(arms) the spec language writes as a room line and an `arms` line.

The polygon is sampled on a regular grid over its bounding box (cell centres inside or
not), so plans with slanted walls fit too; every notch size on that grid and every corner is
tried, each in constant time from a 2D prefix sum.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

GRID = 64
"""Cells per side of the sampling grid: 1.6 % of a side, about 10 cm on a 6 m room."""


@dataclass(frozen=True, slots=True)
class LFit:
    """Two boxes (x0, y0, x1, y1) in the polygon's units whose union is the fitted L, and
    how much of each is covered by the polygon."""

    first: tuple[float, float, float, float]
    """The larger arm (the room line)."""
    second: tuple[float, float, float, float]
    """The other arm (the `arms` line)."""
    first_fill: float
    """Share of the first box inside the polygon."""
    second_fill: float
    mismatch: float
    """Area in the L but not the polygon plus area in the polygon but not the L, as a share
    of the polygon's area."""
    box_mismatch: float
    """The same for the bounding box (the thesis' rectangle before scaling)."""


def coverage(polygon: list[tuple[float, float]], box: tuple[float, float, float, float],
             cells: int = GRID) -> np.ndarray:
    """cells x cells booleans: is the centre of each cell of `box` inside the polygon?
    Row 0 is the box's low y. Even-odd rule, vectorised over the cells."""
    x0, y0, x1, y1 = box
    xs = x0 + (np.arange(cells) + 0.5) * (x1 - x0) / cells
    ys = y0 + (np.arange(cells) + 0.5) * (y1 - y0) / cells
    px, py = np.meshgrid(xs, ys)
    inside = np.zeros_like(px, dtype=bool)
    count = len(polygon)
    for index in range(count):
        (ax, ay), (bx, by) = polygon[index], polygon[(index + 1) % count]
        if ay == by:
            continue
        crosses = (ay > py) != (by > py)
        at_x = ax + (py - ay) * (bx - ax) / (by - ay)
        inside ^= crosses & (px < at_x)
    return inside


def fit_l(polygon: list[tuple[float, float]], cells: int = GRID) -> LFit | None:
    """The best L for the polygon, or None when no L fits better than its bounding box."""
    xs = [p[0] for p in polygon]
    ys = [p[1] for p in polygon]
    box = (min(xs), min(ys), max(xs), max(ys))
    width, height = box[2] - box[0], box[3] - box[1]
    if width <= 0 or height <= 0:
        return None
    inside = coverage(polygon, box, cells)
    covered = int(inside.sum())
    if covered == 0:
        return None
    total = cells * cells
    box_mismatch = (total - covered) / covered
    best = None
    # the notch is a corner block of nx columns and ny rows; orient the grid so that the
    # notch is always at the top right, then prefix sums give its covered cells at once
    for corner in range(4):
        grid = inside
        if corner & 1:
            grid = grid[:, ::-1]
        if corner & 2:
            grid = grid[::-1, :]
        # prefix[r, c]: covered cells in the top-right block of r rows and c columns
        flipped = grid[::-1, ::-1].astype(np.int32)
        prefix = np.zeros((cells + 1, cells + 1), dtype=np.int32)
        prefix[1:, 1:] = flipped.cumsum(0).cumsum(1)
        rows = np.arange(cells + 1)[:, None]
        cols = np.arange(cells + 1)[None, :]
        notch_area = rows * cols
        notch_covered = prefix
        # mismatch of the L = (L area - covered in L) + (covered in notch)
        mismatch = (total - notch_area) - (covered - notch_covered) + notch_covered
        mismatch[0, :] = mismatch[:, 0] = total * 4  # an empty notch is the box itself
        mismatch[cells, :] = mismatch[:, cells] = total * 4  # a full-side notch is a rectangle
        r, c = np.unravel_index(int(np.argmin(mismatch)), mismatch.shape)
        value = int(mismatch[r, c])
        if best is None or value < best[0]:
            best = (value, corner, int(r), int(c))
    value, corner, notch_rows, notch_cols = best
    if value >= total - covered:
        return None
    # back to the polygon's frame: the notch's extent from the box's corner
    notch_w = notch_cols * width / cells
    notch_h = notch_rows * height / cells
    right = not corner & 1  # the notch touches the box's right side (else its left)
    top = not corner & 2  # ... its top (else its bottom)
    # the notch's inner edges lie on the grid; a wall of the polygon within a cell is the
    # real edge (the usual case: real plans are mostly rectilinear)
    inner_x = _snap(box[2] - notch_w if right else box[0] + notch_w, xs, width / cells)
    inner_y = _snap(box[3] - notch_h if top else box[1] + notch_h, ys, height / cells)
    nx0, nx1 = (inner_x, box[2]) if right else (box[0], inner_x)
    ny0, ny1 = (inner_y, box[3]) if top else (box[1], inner_y)
    # the two ways to cut an L into two rectangles; keep the one whose larger arm is largest
    full_width_band = (box[0], box[1], box[2], ny0) if top else (box[0], ny1, box[2], box[3])
    rest_of_height = (nx1, ny0, box[2], ny1) if not right else (box[0], ny0, nx0, ny1)
    full_height_band = (box[0], box[1], nx0, box[3]) if right else (nx1, box[1], box[2], box[3])
    rest_of_width = (nx0, box[1], nx1, ny0) if top else (nx0, ny1, nx1, box[3])
    cuts = [(full_width_band, rest_of_height), (full_height_band, rest_of_width)]
    first, second = max(cuts, key=lambda cut: _area(cut[0]))
    return LFit(
        first=first,
        second=second,
        first_fill=_fill(inside, box, first, cells),
        second_fill=_fill(inside, box, second, cells),
        mismatch=value / covered,
        box_mismatch=box_mismatch,
    )


def _snap(value: float, coordinates: list[float], reach: float) -> float:
    """The polygon coordinate nearest `value` if it lies within `reach`, else `value`."""
    nearest = min(coordinates, key=lambda c: abs(c - value))
    if abs(nearest - value) > reach or nearest in (min(coordinates), max(coordinates)):
        return value  # too far, or onto the box's own side: the notch would vanish
    return nearest


def _area(box) -> float:
    return (box[2] - box[0]) * (box[3] - box[1])


def _fill(inside: np.ndarray, box, part, cells: int) -> float:
    """Share of `part`'s cells inside the polygon (cells whose centres lie in `part`)."""
    x0, y0, x1, y1 = box
    c0 = int(round((part[0] - x0) / (x1 - x0) * cells))
    c1 = int(round((part[2] - x0) / (x1 - x0) * cells))
    r0 = int(round((part[1] - y0) / (y1 - y0) * cells))
    r1 = int(round((part[3] - y0) / (y1 - y0) * cells))
    block = inside[r0:r1, c0:c1]
    return float(block.mean()) if block.size else 1.0
