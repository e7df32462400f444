"""Emitters: the files a user takes away from `layoutdsl compile`.

Each emitter reads only a `Layout` (never Pyomo objects) and writes its files atomically:

| format  | files                                   | module               |
|---------|-----------------------------------------|----------------------|
| `xml`   | `STEM.xml` (building XML, the thesis, §5.2)    | `layoutdsl.emit.xml` |
| `png`   | `STEM.png` (drawing, the thesis, §5.6)         | `layoutdsl.emit.png` |
| `svg`   | `STEM.svg` (the same drawing as vectors, rooms' tooltips) | `layoutdsl.emit.svg` |
| `world` | `STEM.world` + its bitmap `STEM.world.png` (Stage) | `layoutdsl.emit.stage` |
| `map`   | `STEM.pgm` + `STEM.yaml` (ROS map_server) | `layoutdsl.emit.rosmap` |
| `mjcf`  | `STEM.mjcf.xml` (MuJoCo scene, robot with a laser ring) | `layoutdsl.emit.mjcf` |
| `sdf`   | `STEM.sdf` (Gazebo world, SDFormat)     | `layoutdsl.emit.sdf` |
| `gltf`  | `STEM.glb` (binary glTF 2.0 mesh; needs the `sim` extra) | `layoutdsl.emit.gltf` |

The three 3D formats share one wall geometry (`layoutdsl.emit.walls`), derived from the
layout like the occupancy raster, and are not written unless asked for: `DEFAULT_FORMATS`
stays the thesis' 2D set. Their options: `wall_height` (metres) and `robot` (MJCF only:
include the wheeled robot and its rangefinder ring).

`write_outputs` renders every requested format in memory first and then writes the whole
set with `layoutdsl.emit.atomic.write_files_atomic`, so a failure anywhere leaves none of the
call's files behind.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from pathlib import Path

from layoutdsl.emit.atomic import write_files_atomic
from layoutdsl.layout import Layout
from layoutdsl.emit.raster import DEFAULT_RESOLUTION
from layoutdsl.emit.walls import DEFAULT_WALL_HEIGHT

DEFAULT_FORMATS = ("xml", "png", "world", "map")
DRAWING_FORMATS = ("svg",)
"""2D outputs written only when asked for: the PNG's drawing as vectors."""
WORLD_3D_FORMATS = ("mjcf", "sdf", "gltf")
FORMATS = DEFAULT_FORMATS + DRAWING_FORMATS + WORLD_3D_FORMATS

MAX_WALL_HEIGHT = 100.0
"""Tallest wall accepted, metres: anything taller is a typo, not a building."""

MAX_BITMAP_CELLS = 100_000_000
"""Largest Stage/ROS bitmap: 10 000 × 10 000 cells (500 m square at 5 cm)."""


class EmitError(ValueError):
    """A request the emitters cannot honour (unknown format, unknown robot room, ...)."""


Renderer = Callable[..., dict[str, bytes]]
Emitter = Callable[..., list[Path]]


def _renderers() -> dict[str, Renderer]:
    # Imported lazily so that importing layoutdsl.emit stays cheap.
    from layoutdsl.emit import gltf, mjcf, png, rosmap, sdf, stage, svg, xml

    return {
        "xml": xml.render,
        "png": png.render,
        "svg": svg.render,
        "world": stage.render,
        "map": rosmap.render,
        "mjcf": mjcf.render,
        "sdf": sdf.render,
        "gltf": gltf.render,
    }


def write_rendered(files: Mapping[str, bytes], outdir: Path) -> list[Path]:
    """Write rendered files (name -> bytes) into `outdir`, all or nothing."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    return write_files_atomic({outdir / name: data for name, data in files.items()})


def _emitter(name: str) -> Emitter:
    def emit(
        layout: Layout,
        outdir: Path,
        stem: str,
        *,
        robot_room: str | None = None,
        resolution: float = DEFAULT_RESOLUTION,
        wall_height: float = DEFAULT_WALL_HEIGHT,
        robot: bool = True,
    ) -> list[Path]:
        parse_formats([name])
        check_options(layout, robot_room=robot_room, resolution=resolution, wall_height=wall_height)
        files = _renderers()[name](
            layout, stem, robot_room=robot_room, resolution=resolution, wall_height=wall_height, robot=robot
        )
        return write_rendered(files, outdir)

    emit.__name__ = f"emit_{name}"
    emit.__doc__ = f"Write the `{name}` output of a layout into a directory; return the paths."
    return emit


EMITTERS: dict[str, Emitter] = {name: _emitter(name) for name in FORMATS}
"""Format name -> emitter(layout, outdir, stem, *, robot_room=None, resolution=0.05, wall_height=2.5, robot=True)."""


def parse_formats(formats: Iterable[str] | str) -> tuple[str, ...]:
    """Validate format names (a list or a comma-separated string); keep order, drop repeats."""
    if isinstance(formats, str):
        formats = [part.strip() for part in formats.split(",") if part.strip()]
    chosen: list[str] = []
    for name in formats:
        if name not in EMITTERS:
            valid = ", ".join(EMITTERS)
            raise EmitError(f"unknown output format `{name}` (valid formats: {valid})")
        if name not in chosen:
            chosen.append(name)
    if not chosen:
        raise EmitError(f"no output format chosen (valid formats: {', '.join(EMITTERS)})")
    if "gltf" in chosen:
        from layoutdsl.emit import gltf

        if not gltf.available():
            raise EmitError(f"output format `gltf` needs the optional mesh library trimesh: {gltf.INSTALL_HINT}")
    return tuple(chosen)


def check_options(
    layout: Layout, *, robot_room: str | None, resolution: float, wall_height: float = DEFAULT_WALL_HEIGHT
) -> None:
    """Reject bad emitter options before anything is rendered or written."""
    if not (wall_height > 0 and wall_height <= MAX_WALL_HEIGHT):
        raise EmitError(f"wall height must be a positive number of metres up to {MAX_WALL_HEIGHT:g}, got {wall_height}")
    if not (resolution > 0 and resolution < 10):
        raise EmitError(f"resolution must be a positive number of metres per cell, got {resolution}")
    if robot_room is not None and robot_room not in {room.id for room in layout.rooms}:
        ids = ", ".join(room.id for room in layout.rooms)
        raise EmitError(f"--robot-room `{robot_room}` is not a room of `{layout.name}` (rooms: {ids})")
    if not layout.rooms:
        raise EmitError(f"layout `{layout.name}` has no rooms to emit")
    room_ids = {room.id for room in layout.rooms}
    for portal in layout.portals:
        for end in (portal.a, portal.b):
            if end not in room_ids:
                raise EmitError(f"layout `{layout.name}` has a portal to unknown room `{end}`")
    # The bitmaps hold a few bytes per cell; refuse sizes that would exhaust memory
    # instead of failing (or swapping) halfway through.
    span_x = max(r.x2 for r in layout.parts()) - min(r.x for r in layout.parts())
    span_y = max(r.y2 for r in layout.parts()) - min(r.y for r in layout.parts())
    cells = (span_x / resolution + 4) * (span_y / resolution + 4)
    if cells > MAX_BITMAP_CELLS:
        raise EmitError(
            f"a {span_x:g} m × {span_y:g} m bitmap at {resolution:g} m per cell has {cells:.3g} cells "
            f"(at most {MAX_BITMAP_CELLS:.0e}); choose a coarser resolution"
        )


def render_outputs(
    layout: Layout,
    stem: str,
    formats: Iterable[str] | str = DEFAULT_FORMATS,
    *,
    robot_room: str | None = None,
    resolution: float = DEFAULT_RESOLUTION,
    wall_height: float = DEFAULT_WALL_HEIGHT,
    robot: bool = True,
) -> dict[str, bytes]:
    """Render the chosen formats in memory: file name -> content (nothing is written)."""
    chosen = parse_formats(formats)
    check_options(layout, robot_room=robot_room, resolution=resolution, wall_height=wall_height)
    renderers = _renderers()
    files: dict[str, bytes] = {}
    for name in chosen:
        files.update(
            renderers[name](
                layout, stem, robot_room=robot_room, resolution=resolution, wall_height=wall_height, robot=robot
            )
        )
    return files


def write_outputs(
    layout: Layout,
    outdir: Path,
    stem: str,
    formats: Iterable[str] | str = DEFAULT_FORMATS,
    *,
    robot_room: str | None = None,
    resolution: float = DEFAULT_RESOLUTION,
    wall_height: float = DEFAULT_WALL_HEIGHT,
    robot: bool = True,
) -> list[Path]:
    """Write the chosen formats for a layout into `outdir`, all-or-nothing; return the paths.

    Raises EmitError (a ValueError) for an unknown format or robot room, before any file is
    written; I/O errors propagate as OSError after every file of this call is rolled back.
    """
    files = render_outputs(
        layout, stem, formats, robot_room=robot_room, resolution=resolution, wall_height=wall_height, robot=robot
    )
    return write_rendered(files, outdir)


__all__ = [
    "DEFAULT_FORMATS",
    "DRAWING_FORMATS",
    "EMITTERS",
    "FORMATS",
    "WORLD_3D_FORMATS",
    "EmitError",
    "check_options",
    "parse_formats",
    "render_outputs",
    "write_outputs",
    "write_rendered",
]
