"""ROS map_server map: `STEM.pgm` (binary P5) + `STEM.yaml`, the same grid as Stage's bitmap.

Grey levels follow map_saver: 0 for occupied cells, 254 for free ones; with `negate 0`,
map_server reads p = (255 − v) / 255, so 0 → 1.0 (> occupied_thresh 0.65: occupied) and
254 → 0.004 (< free_thresh 0.196: free). `origin` is the pose of the lower-left pixel in
the layout's frame, so map coordinates equal Stage's world coordinates.
"""

from __future__ import annotations

import json

from layoutdsl.emit.templating import format_number
from layoutdsl.layout import Layout
from layoutdsl.emit.raster import DEFAULT_RESOLUTION, OccupancyGrid, rasterize_layout

FREE_VALUE = 254
OCCUPIED_VALUE = 0
OCCUPIED_THRESH = 0.65
FREE_THRESH = 0.196


def pgm_bytes(grid: OccupancyGrid, comment: str = "") -> bytes:
    """The grid as a binary (P5) PGM, row 0 at the top."""
    image = grid.to_image(free=FREE_VALUE, occupied=OCCUPIED_VALUE)
    rows, cols = grid.shape
    header = "P5\n"
    if comment:
        header += "".join(f"# {line}\n" for line in comment.splitlines())
    header += f"{cols} {rows}\n255\n"
    return header.encode("ascii", errors="replace") + image.tobytes()


def map_yaml(grid: OccupancyGrid, image_name: str) -> str:
    """map_server's YAML for the grid saved as `image_name` beside it."""
    ox, oy = grid.origin
    return (
        # JSON strings are YAML strings: quoting keeps odd stems (spaces, colons) intact
        f"image: {json.dumps(image_name)}\n"
        f"resolution: {format_number(grid.resolution, 6)}\n"
        f"origin: [{format_number(ox, 6)}, {format_number(oy, 6)}, 0.0]\n"
        f"negate: 0\n"
        f"occupied_thresh: {OCCUPIED_THRESH}\n"
        f"free_thresh: {FREE_THRESH}\n"
    )


def render(
    layout: Layout, stem: str, *, resolution: float = DEFAULT_RESOLUTION, **_options: object
) -> dict[str, bytes]:
    """File name -> content: `stem.pgm` and `stem.yaml`."""
    grid = rasterize_layout(layout, resolution)
    comment = f"layoutdsl map of {layout.name}".encode("ascii", errors="replace").decode("ascii")
    return {
        f"{stem}.pgm": pgm_bytes(grid, comment),
        f"{stem}.yaml": map_yaml(grid, f"{stem}.pgm").encode("utf-8"),
    }
