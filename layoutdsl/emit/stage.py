"""Stage world writer (the thesis, §6.3.2, §6.3.6): `STEM.world` and its bitmap `STEM.world.png`.

The bitmap is the shared rasterization (`layoutdsl.emit.raster.rasterize_layout`): walls black,
free space and door openings white, cropped to the outer walls with a one-cell black frame.
Stage stretches the bounding box of a bitmap's dark pixels to the floorplan's `size` and
centres it on its `pose`; because the frame makes that box the whole image, `size` is the
image's extent in metres and `pose` is the image centre, so Stage's world coordinates equal
the layout's frame (metres, origin at the boundary's bottom-left corner, y up).

The world file defines every model it uses (no `include`, so nothing depends on files the
user lacks) and follows the conventions of Stage's `worlds/simple.world` and stage_ros's
`willow-erratic.world`: a differential-drive `position` robot carrying a `ranger` with
`sensor( range [0 30] fov 270 samples 1081 )` (a 270° / 30 m laser, §6.3.2).
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass

from layoutdsl.layout import Layout, PlacedRoom
from layoutdsl.emit.raster import DEFAULT_RESOLUTION, OccupancyGrid, rasterize_layout

BITMAP_SUFFIX = ".world.png"
"""The Stage bitmap is `STEM.world.png`, beside the world file (Stage resolves it relative)."""

STAGE_RESOLUTION = 0.02
"""Stage's own ray-tracing grid (its default, and the value of the reference worlds)."""

FLOORPLAN_HEIGHT = 0.8
"""Wall height in metres (the `size` z of Stage's simple.world floorplan)."""

LASER_RANGE = (0.0, 30.0)
LASER_FOV = 270.0
LASER_SAMPLES = 1081

WINDOW_PIXELS = (800, 700)
"""Largest GUI window; the scale is chosen so the whole plan fits."""


@dataclass(frozen=True, slots=True)
class StageWorld:
    """The values the world template prints."""

    name: str
    bitmap: str
    resolution: float
    floorplan_size: tuple[float, float, float]
    floorplan_pose: tuple[float, float, float, float]
    robot_room: str
    robot_pose: tuple[float, float, float, float]
    window_size: tuple[int, int]
    window_scale: float
    window_center: tuple[float, float]
    laser_range: tuple[float, float] = LASER_RANGE
    laser_fov: float = LASER_FOV
    laser_samples: int = LASER_SAMPLES


def robot_start_room(layout: Layout, robot_room: str | None = None) -> PlacedRoom:
    """Where the robot starts: the given room, else the first entrance (E), else the first room."""
    if robot_room is not None:
        return layout.room(robot_room)
    for room in layout.rooms:
        if room.rtype == "E":
            return room
    return layout.rooms[0]


def _quoted_name(text: str) -> str:
    # Stage's world-file strings cannot escape a double quote; keep the name readable.
    return "".join(ch if ch.isprintable() and ch != '"' else "_" for ch in text)


def world_model(layout: Layout, grid: OccupancyGrid, stem: str, robot_room: str | None = None) -> StageWorld:
    """The world's values for a layout and its bitmap grid."""
    width, height = grid.width_m, grid.height_m
    cx, cy = grid.centre
    room = robot_start_room(layout, robot_room)
    rx, ry = room.centre
    scale = math.floor(min(WINDOW_PIXELS[0] / width, WINDOW_PIXELS[1] / height) * 1000) / 1000
    return StageWorld(
        name=_quoted_name(layout.name),
        bitmap=f"{stem}{BITMAP_SUFFIX}",
        resolution=min(STAGE_RESOLUTION, grid.resolution),
        floorplan_size=(width, height, FLOORPLAN_HEIGHT),
        floorplan_pose=(cx, cy, 0.0, 0.0),
        robot_room=room.id,
        robot_pose=(rx, ry, 0.0, 0.0),
        window_size=(math.ceil(width * scale), math.ceil(height * scale)),
        window_scale=scale,
        window_center=(cx, cy),
    )


def render_world(layout: Layout, grid: OccupancyGrid, stem: str, robot_room: str | None = None) -> str:
    """The `.world` text for a layout whose bitmap is `grid`."""
    from layoutdsl.emit.templating import environment

    template = environment().get_template("world.world.j2")
    return template.render(world=world_model(layout, grid, stem, robot_room))


def bitmap_png(grid: OccupancyGrid) -> bytes:
    """The grid as a black-and-white PNG (black = wall), 8-bit grey.

    8-bit rather than 1-bit: every image loader Stage has been built with reads 8-bit
    grey, and the file stays small because it compresses to almost nothing.
    """
    buffer = io.BytesIO()
    grid.to_image().save(buffer, format="PNG", optimize=True)
    return buffer.getvalue()


def render(
    layout: Layout,
    stem: str,
    *,
    robot_room: str | None = None,
    resolution: float = DEFAULT_RESOLUTION,
    **_options: object,
) -> dict[str, bytes]:
    """File name -> content: `stem.world` and its bitmap `stem.world.png`."""
    grid = rasterize_layout(layout, resolution)
    return {
        f"{stem}.world": render_world(layout, grid, stem, robot_room).encode("utf-8"),
        f"{stem}{BITMAP_SUFFIX}": bitmap_png(grid),
    }
