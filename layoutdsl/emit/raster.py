"""The one occupancy rasterization shared by the Stage bitmap, the ROS map and the evaluator.

Two entry points, one grid type:

- `rasterize_layout` for a generated `Layout` (metres, y up): everything outside the rooms is
  wall, room interiors are free, and every portal carves an opening of its width through
  the wall gap between its two rooms, so the free space connects two rooms exactly where
  the layout has a portal between them.
- `rasterize_building` for a building XML plan (the thesis, §6.3.6): WALL segments drawn as lines
  of a fixed width, room polygons painted free, each PORTAL carved as a door opening of
  the plan's door length along the wall it sits on; outside every space is occupied.

Both crop the grid to the building and keep a one-cell occupied frame, so the bounding box
of the dark pixels is the whole image. Stage stretches exactly that box to the floorplan
model's `size`, so `size = shape × resolution` holds with no distortion.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from PIL import Image, ImageDraw

from layoutdsl.importer.building import Building, Space
from layoutdsl.layout import Layout, PlacedRoom, Portal, facing_parts

DEFAULT_RESOLUTION = 0.05
"""Metres per cell: the resolution of the maps used in the thesis' experiments (§6.3)."""

REAL_WALL_WIDTH = 0.15
"""Width in metres of a wall line of a real plan (§6.3.6: "a line with a predefined width")."""

# Tolerance for float noise when testing whether a cell centre lies inside a rectangle.
_EPS = 1e-9


@dataclass(frozen=True)
class OccupancyGrid:
    """A boolean occupancy grid in a metric frame.

    `occupied[row, col]` is True for wall/outside; row 0 is the TOP row (image order).
    `origin` is the (x, y) in metres of the grid's lower-left corner in the plan's frame
    (y up), as ROS map_server's `origin` expects.
    """

    occupied: np.ndarray
    resolution: float
    origin: tuple[float, float]

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols)."""
        return self.occupied.shape  # type: ignore[return-value]

    @property
    def width_m(self) -> float:
        """Extent along x in metres."""
        return self.occupied.shape[1] * self.resolution

    @property
    def height_m(self) -> float:
        """Extent along y in metres."""
        return self.occupied.shape[0] * self.resolution

    @property
    def centre(self) -> tuple[float, float]:
        """The centre of the grid in the plan's frame."""
        return (self.origin[0] + self.width_m / 2, self.origin[1] + self.height_m / 2)

    def world_to_cell(self, x: float, y: float) -> tuple[int, int]:
        """(row, col) of the cell containing the point (x, y); may lie outside the grid."""
        col = math.floor((x - self.origin[0]) / self.resolution)
        row_from_bottom = math.floor((y - self.origin[1]) / self.resolution)
        return (self.occupied.shape[0] - 1 - row_from_bottom, col)

    def cell_to_world(self, row: int, col: int) -> tuple[float, float]:
        """The centre (x, y) of a cell in the plan's frame."""
        x = self.origin[0] + (col + 0.5) * self.resolution
        y = self.origin[1] + (self.occupied.shape[0] - row - 0.5) * self.resolution
        return (x, y)

    def contains(self, row: int, col: int) -> bool:
        """True when (row, col) is a cell of the grid."""
        rows, cols = self.occupied.shape
        return 0 <= row < rows and 0 <= col < cols

    def is_free(self, x: float, y: float) -> bool:
        """True when the point lies in a free cell of the grid."""
        row, col = self.world_to_cell(x, y)
        return self.contains(row, col) and not bool(self.occupied[row, col])

    def to_image(self, free: int = 255, occupied: int = 0) -> Image.Image:
        """An 8-bit grey image of the grid (free and occupied grey levels as given)."""
        pixels = np.where(self.occupied, np.uint8(occupied), np.uint8(free)).astype(np.uint8)
        return Image.fromarray(pixels, mode="L")


# ----------------------------------------------------------------------------- layouts


def _snap_down(value: float, resolution: float) -> float:
    return math.floor(value / resolution + _EPS) * resolution


def _snap_up(value: float, resolution: float) -> float:
    return math.ceil(value / resolution - _EPS) * resolution


def _centre_range(lo: float, hi: float, origin: float, resolution: float) -> tuple[int, int]:
    """Half-open index range of cells whose centres lie strictly inside (lo, hi)."""
    first = math.floor((lo - origin) / resolution - 0.5 + _EPS) + 1
    last = math.ceil((hi - origin) / resolution - 0.5 - _EPS) - 1
    return first, max(first, last + 1)


def _layout_frame(layout: Layout, resolution: float) -> tuple[float, float, int, int]:
    """Grid origin (x0, y0) and size (rows, cols) enclosing the rooms with an outer wall."""
    # Cropped to the rooms, not the boundary: unused boundary space is no part of the
    # building, and a simulator gains nothing from a slab of solid wall.
    xs = [r.x for r in layout.parts()] or [0.0]
    ys = [r.y for r in layout.parts()] or [0.0]
    x2s = [r.x2 for r in layout.parts()] or [layout.width]
    y2s = [r.y2 for r in layout.parts()] or [layout.height]
    # The outer wall is as thick as an inner one but never thinner than a cell: the one-cell
    # frame Stage needs and the wall are then the same pixels.
    wall = max(layout.walldim, resolution)
    x0 = _snap_down(min(xs) - wall, resolution)
    y0 = _snap_down(min(ys) - wall, resolution)
    x1 = _snap_up(max(x2s) + wall, resolution)
    y1 = _snap_up(max(y2s) + wall, resolution)
    cols = max(3, round((x1 - x0) / resolution))
    rows = max(3, round((y1 - y0) / resolution))
    return x0, y0, rows, cols


def room_cell_labels(layout: Layout, resolution: float = DEFAULT_RESOLUTION) -> tuple[np.ndarray, tuple[float, float]]:
    """Per-cell index of the room whose interior holds the cell centre, -1 elsewhere.

    Row 0 is the top row. Returns the label array and the grid origin. The topology tests
    use it to know which room a free cell belongs to.
    """
    x0, y0, rows, cols = _layout_frame(layout, resolution)
    labels = np.full((rows, cols), -1, dtype=np.int32)
    for index, room in enumerate(layout.rooms):
        for x, y, x2, y2 in _interior_boxes(room, resolution):
            c_lo, c_hi = _centre_range(x, x2, x0, resolution)
            b_lo, b_hi = _centre_range(y, y2, y0, resolution)  # rows counted from bottom
            c_lo, c_hi = max(c_lo, 1), min(c_hi, cols - 1)
            b_lo, b_hi = max(b_lo, 1), min(b_hi, rows - 1)
            if c_lo >= c_hi or b_lo >= b_hi:
                continue
            labels[rows - b_hi : rows - b_lo, c_lo:c_hi] = index
    return labels, (x0, y0)


def _interior_boxes(room: PlacedRoom, resolution: float) -> list[tuple[float, float, float, float]]:
    """(x, y, x2, y2) boxes whose cells are the room's: its rectangles, and for an L a bridge
    half a cell across the line where its arms meet, so the cells centred on that line are
    the room's too (a row of them would otherwise be a wall inside the L)."""
    parts = room.parts
    boxes = [(p.x, p.y, p.x2, p.y2) for p in parts]
    if len(parts) == 2:
        a, b = parts
        half = resolution / 2
        if math.isclose(a.x2, b.x, abs_tol=1e-6) or math.isclose(b.x2, a.x, abs_tol=1e-6):
            line = a.x2 if math.isclose(a.x2, b.x, abs_tol=1e-6) else a.x
            boxes.append((line - half, max(a.y, b.y), line + half, min(a.y2, b.y2)))
        else:
            line = a.y2 if math.isclose(a.y2, b.y, abs_tol=1e-6) else a.y
            boxes.append((max(a.x, b.x), line - half, min(a.x2, b.x2), line + half))
    return boxes


def _separate_rooms(labels: np.ndarray) -> np.ndarray:
    """Cells to turn into wall so no two rooms touch, even diagonally.

    When walldim is below the resolution two rooms can own neighbouring cells; marking the
    cell of every differing 8-neighbour pair whose partner lies right, up, up-right or
    down-right covers each pair exactly once, so the wall is one cell thick.
    """
    rows, cols = labels.shape
    wall = np.zeros_like(labels, dtype=bool)
    inside = labels >= 0
    for d_row, d_col in ((0, 1), (-1, 0), (-1, 1), (1, 1)):
        here = labels[max(0, -d_row) : rows - max(0, d_row), 0 : cols - d_col]
        there = labels[max(0, d_row) : rows - max(0, -d_row), d_col:cols]
        clash = (here >= 0) & (there >= 0) & (here != there)
        wall[max(0, -d_row) : rows - max(0, d_row), 0 : cols - d_col] |= clash
    return wall & inside


def _door_cells(
    portal: Portal, layout: Layout, x0: float, y0: float, rows: int, cols: int, resolution: float
) -> tuple[slice, slice] | None:
    """The (rows, cols) block of cells a portal opens: its width across the wall gap."""
    a, b = facing_parts(layout.room(portal.a), layout.room(portal.b))
    half = portal.width / 2
    cx, cy = portal.centre
    if portal.vertical:
        left, right = (a, b) if a.x < b.x else (b, a)
        # from just inside the left room to just inside the right one
        gap_lo, gap_hi = left.x2 - resolution, right.x + resolution
        span_lo = max(cy - half, a.y, b.y)
        span_hi = min(cy + half, a.y2, b.y2)
        c_lo, c_hi = _centre_range(gap_lo, gap_hi, x0, resolution)
        b_lo, b_hi = _centre_range(span_lo, span_hi, y0, resolution)
        if b_lo >= b_hi:  # a door narrower than a cell still opens the cell at its centre
            b_lo = math.floor((cy - y0) / resolution)
            b_hi = b_lo + 1
    else:
        low, high = (a, b) if a.y < b.y else (b, a)
        gap_lo, gap_hi = low.y2 - resolution, high.y + resolution
        span_lo = max(cx - half, a.x, b.x)
        span_hi = min(cx + half, a.x2, b.x2)
        c_lo, c_hi = _centre_range(span_lo, span_hi, x0, resolution)
        b_lo, b_hi = _centre_range(gap_lo, gap_hi, y0, resolution)
        if c_lo >= c_hi:
            c_lo = math.floor((cx - x0) / resolution)
            c_hi = c_lo + 1
    c_lo, c_hi = max(c_lo, 1), min(c_hi, cols - 1)
    b_lo, b_hi = max(b_lo, 1), min(b_hi, rows - 1)
    if c_lo >= c_hi or b_lo >= b_hi:
        return None
    return slice(rows - b_hi, rows - b_lo), slice(c_lo, c_hi)


def rasterize_layout(layout: Layout, resolution: float = DEFAULT_RESOLUTION) -> OccupancyGrid:
    """Occupancy grid of a layout: rooms free, walls and outside occupied, portals open."""
    if not resolution > 0:
        raise ValueError(f"resolution must be positive, got {resolution}")
    labels, (x0, y0) = room_cell_labels(layout, resolution)
    rows, cols = labels.shape
    occupied = labels < 0
    occupied |= _separate_rooms(labels)
    index_of = {room.id: index for index, room in enumerate(layout.rooms)}
    for portal in layout.portals:
        block = _door_cells(portal, layout, x0, y0, rows, cols, resolution)
        if block is None:
            continue
        row_slice, col_slice = block
        a, b = index_of[portal.a], index_of[portal.b]
        # Never open a cell that touches a third room (8-neighbourhood): that would join
        # rooms the layout keeps apart (possible only when walls are a single cell thick).
        # Blocks stay one cell inside the grid, so the surrounding ring always exists.
        ring = labels[row_slice.start - 1 : row_slice.stop + 1, col_slice.start - 1 : col_slice.stop + 1]
        height, width = row_slice.stop - row_slice.start, col_slice.stop - col_slice.start
        touches_third = np.zeros((height, width), dtype=bool)
        for d_row in range(3):
            for d_col in range(3):
                near = ring[d_row : d_row + height, d_col : d_col + width]
                touches_third |= (near >= 0) & (near != a) & (near != b)
        occupied[row_slice, col_slice] &= touches_third
    return OccupancyGrid(occupied=occupied, resolution=resolution, origin=(x0, y0))


# ----------------------------------------------------------------------------- real plans


def _space_points(space: Space) -> list[tuple[float, float]]:
    points = [(p.x, p.y) for p in space.polygon]
    for segment in space.segments:
        points.append((segment.p1.x, segment.p1.y))
        points.append((segment.p2.x, segment.p2.y))
    if not points:
        points = [(space.bbox.min_x, space.bbox.min_y), (space.bbox.max_x, space.bbox.max_y)]
    return points


def _nearest_wall_direction(space: Space, px: float, py: float, tie: float) -> tuple[float, float] | None:
    """Unit direction (file units) of the WALL segment of `space` the point (px, py) lies on.

    A door point often sits where two walls meet (the file splits the wall there, and
    hand-drawn jogs add short slanted pieces); among the walls within `tie` of the nearest
    one the longest wins, because that is the wall the door is in.
    """
    candidates: list[tuple[float, float, tuple[float, float]]] = []
    for segment in space.segments:
        if segment.cls != "WALL":
            continue
        ax, ay, bx, by = segment.p1.x, segment.p1.y, segment.p2.x, segment.p2.y
        dx, dy = bx - ax, by - ay
        length_sq = dx * dx + dy * dy
        if length_sq == 0:
            continue
        t = max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / length_sq))
        distance = math.hypot(px - (ax + t * dx), py - (ay + t * dy))
        length = math.sqrt(length_sq)
        candidates.append((distance, length, (dx / length, dy / length)))
    if not candidates:
        return None
    nearest = min(distance for distance, _, _ in candidates)
    close = [c for c in candidates if c[0] <= nearest + tie]
    return max(close, key=lambda c: c[1])[2]


def _wall_run(
    space: Space, px: float, py: float, ux: float, uy: float, tolerance: float
) -> tuple[float, float] | None:
    """The stretch of `space`'s boundary along the door line through (px, py), as an interval.

    Positions are measured along (ux, uy) from the door point, in file units. Segments
    parallel to the door and within `tolerance` of its line are merged when they touch
    (hand-drawn plans leave small gaps); the run containing the door point is returned.
    """
    intervals: list[tuple[float, float]] = []
    for segment in space.segments:
        ax, ay, bx, by = segment.p1.x, segment.p1.y, segment.p2.x, segment.p2.y
        dx, dy = bx - ax, by - ay
        length = math.hypot(dx, dy)
        if length == 0:
            continue
        if abs(dx * uy - dy * ux) / length > 0.1:  # not parallel (about 6°)
            continue
        if abs((ax - px) * uy - (ay - py) * ux) > tolerance:  # not on the door's line
            continue
        ta = (ax - px) * ux + (ay - py) * uy
        tb = (bx - px) * ux + (by - py) * uy
        intervals.append((min(ta, tb), max(ta, tb)))
    if not intervals:
        return None
    intervals.sort()
    runs: list[list[float]] = []
    for lo, hi in intervals:
        if runs and lo <= runs[-1][1] + tolerance:
            runs[-1][1] = max(runs[-1][1], hi)
        else:
            runs.append([lo, hi])
    for lo, hi in runs:
        if lo - tolerance <= 0.0 <= hi + tolerance:
            return (lo, hi)
    return None


def _door_interval(half_length: float, runs: list[tuple[float, float]], clearance: float) -> tuple[float, float]:
    """The door's extent along its wall: slid (or, if need be, cut) to fit every run.

    A door drawn near a corner would otherwise reach past the end of its wall, or cut the
    end of the perpendicular wall there, and open into a third room; the door must stay on
    the wall both of its rooms share, `clearance` away from its ends.
    """
    lo, hi = -half_length, half_length
    if not runs:
        return lo, hi
    run_lo = max(r[0] for r in runs)
    run_hi = min(r[1] for r in runs)
    if run_hi - run_lo > 2 * clearance:
        run_lo, run_hi = run_lo + clearance, run_hi - clearance
    if run_hi <= run_lo:  # the rooms' walls do not overlap: keep the door where it is
        return lo, hi
    if run_hi - run_lo <= 2 * half_length:
        return run_lo, run_hi
    shift = max(0.0, run_lo - lo) - max(0.0, hi - run_hi)
    return lo + shift, hi + shift


def rasterize_building(
    building: Building, resolution: float = DEFAULT_RESOLUTION, wall_width: float = REAL_WALL_WIDTH
) -> OccupancyGrid:
    """Occupancy grid of a building XML plan, following the thesis' map preparation (§6.3.6).

    Every WALL segment is a black line `wall_width` metres wide, every space polygon is free
    inside, and every PORTAL is a door opening: its own length when it is a segment, else
    the plan's door size (`<real_distance>`), along the wall it lies on, kept within the
    wall the two rooms share. The plan's frame in metres is x = x_file·s, y = −y_file·s
    (s = metres per file unit): the file's y grows downwards, the grid's frame grows upwards.
    """
    if not resolution > 0:
        raise ValueError(f"resolution must be positive, got {resolution}")
    scale = building.metres_per_unit
    if not (math.isfinite(scale) and scale > 0):
        raise ValueError(f"building `{building.name}` has an unusable scale ({scale} m per unit)")
    all_points = [pt for space in building.spaces for pt in _space_points(space)]
    if not all_points:
        raise ValueError(f"building `{building.name}` has no spaces to rasterize")
    margin = wall_width + resolution
    xs = [x * scale for x, _ in all_points]
    ys = [-y * scale for _, y in all_points]
    x0 = _snap_down(min(xs) - margin, resolution)
    y0 = _snap_down(min(ys) - margin, resolution)
    cols = max(3, round((_snap_up(max(xs) + margin, resolution) - x0) / resolution))
    rows = max(3, round((_snap_up(max(ys) + margin, resolution) - y0) / resolution))
    top = y0 + rows * resolution

    def to_pixel(fx: float, fy: float) -> tuple[float, float]:
        # Pillow's pixel (i, j) covers [i, i+1) x [j, j+1), so pixel coordinates are plain.
        return ((fx * scale - x0) / resolution, (top + fy * scale) / resolution)

    image = Image.new("L", (cols, rows), 0)
    draw = ImageDraw.Draw(image)
    for space in building.spaces:
        if len(space.polygon) >= 3:
            draw.polygon([to_pixel(p.x, p.y) for p in space.polygon], fill=255)
    line_px = max(1, round(wall_width / resolution))
    for space in building.spaces:
        for segment in space.segments:
            if segment.cls == "WALL":
                draw.line(
                    [to_pixel(segment.p1.x, segment.p1.y), to_pixel(segment.p2.x, segment.p2.y)],
                    fill=0,
                    width=line_px,
                )
    for corners in _door_openings(building, wall_width, resolution):
        draw.polygon([to_pixel(x, y) for x, y in corners], fill=255)
    occupied = np.asarray(image) < 128
    # the one-cell frame that makes the dark-pixel bounding box equal the image
    occupied[0, :] = occupied[-1, :] = True
    occupied[:, 0] = occupied[:, -1] = True
    return OccupancyGrid(occupied=occupied, resolution=resolution, origin=(x0, y0))


def _door_openings(building: Building, wall_width: float, resolution: float) -> list[list[tuple[float, float]]]:
    """Each PORTAL's opening as a rotated rectangle (four corners, file units)."""
    scale = building.metres_per_unit
    spaces = {space.id: space for space in building.spaces}
    # Deep enough to cross a wall line and the small gaps hand-drawn plans leave between
    # the walls of two neighbouring spaces, shallow enough not to cut far into the rooms.
    half_depth = (1.5 * wall_width + resolution) / scale
    tolerance = max(2 * wall_width, 0.1) / scale
    openings = []
    for space in building.spaces:
        other_of = {p.segment_id: p.targets for p in space.portals}
        for segment in space.segments:
            if segment.cls != "PORTAL":
                continue
            ax, ay, bx, by = segment.p1.x, segment.p1.y, segment.p2.x, segment.p2.y
            length_units = math.hypot(bx - ax, by - ay)
            cx, cy = (ax + bx) / 2, (ay + by) / 2
            if length_units * scale > resolution:
                ux, uy = (bx - ax) / length_units, (by - ay) / length_units
                half_length = length_units / 2
            else:
                found = _nearest_wall_direction(space, cx, cy, tolerance / 2)
                if found is None:
                    continue
                ux, uy = found
                half_length = building.real_distance_m / scale / 2
            sharing = [space] + [spaces[t] for t in other_of.get(segment.id, ()) if t in spaces and t != space.id]
            runs = [run for sp in sharing if (run := _wall_run(sp, cx, cy, ux, uy, tolerance)) is not None]
            lo, hi = _door_interval(half_length, runs, wall_width / scale)
            nx, ny = -uy, ux
            openings.append(
                [
                    (cx + t * ux + d * nx * half_depth, cy + t * uy + d * ny * half_depth)
                    for t, d in ((lo, -1), (hi, -1), (hi, 1), (lo, 1))
                ]
            )
    return openings
