"""3D mesh writer: `STEM.glb` (binary glTF 2.0), the walls and the floor as triangle meshes.

Built with trimesh (the `sim` extra: `pip install 'layoutdsl[sim]'`), which writes glTF's
binary buffers, accessors and bounds to the specification; the walls are
`layoutdsl.emit.walls.wall_geometry`'s boxes, each a closed box of its own (12 triangles,
vertices not shared with its neighbours), all in one mesh `walls`; the floor is the mesh
`floor`, a 1 cm slab just below z = 0.

Frame: glTF is y-up by its specification ("+Y is up", units are metres), so both nodes
carry the rotation that turns the layout's z-up frame into glTF's:
(x, y, z)_layout -> (x, z, -y)_glTF, a -90° turn about x. Loaders that honour the node
transform (Blender, Isaac Sim, Habitat, trimesh) put the building upright, with the
layout's x and y on the ground plane and a point at layout (x, y) at glTF (x, 0, -y).
"""

from __future__ import annotations

import io

import numpy as np

from layoutdsl.emit.walls import DEFAULT_WALL_HEIGHT, WallGeometry, wall_geometry
from layoutdsl.layout import Layout

SUFFIX = ".glb"

INSTALL_HINT = "pip install 'layoutdsl[sim]'"

Z_UP_TO_Y_UP = np.array(
    [[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, -1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
)
"""The scene node's transform: layout (x, y, z) -> glTF (x, z, -y)."""

FLOOR_THICKNESS = 0.01

# the eight corners of a unit box and its twelve outward-facing triangles
_CORNERS = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=np.float64)
_TRIANGLES = np.array(
    [
        [0, 2, 1], [1, 2, 3],  # bottom (z = 0), facing -z
        [4, 5, 6], [5, 7, 6],  # top, facing +z
        [0, 1, 4], [1, 5, 4],  # y = 0, facing -y
        [2, 6, 3], [3, 6, 7],  # y = 1, facing +y
        [0, 4, 2], [2, 4, 6],  # x = 0, facing -x
        [1, 3, 5], [3, 7, 5],  # x = 1, facing +x
    ],
    dtype=np.int64,
)  # fmt: skip


class MissingExtra(RuntimeError):
    """The optional mesh library is not installed."""


def _trimesh():
    try:
        import trimesh
    except ImportError as error:
        raise MissingExtra(f"--emit gltf needs the mesh library trimesh: {INSTALL_HINT}") from error
    return trimesh


def available() -> bool:
    """True when the mesh library is installed."""
    try:
        _trimesh()
    except MissingExtra:
        return False
    return True


def box_arrays(lows: np.ndarray, highs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and triangles of closed, separate boxes (one per row of lows/highs)."""
    count = len(lows)
    extents = highs - lows
    vertices = lows[:, None, :] + _CORNERS[None, :, :] * extents[:, None, :]
    faces = _TRIANGLES[None, :, :] + 8 * np.arange(count)[:, None, None]
    return vertices.reshape(-1, 3), faces.reshape(-1, 3)


def scene(geometry: WallGeometry):
    """A trimesh Scene: meshes `walls` and `floor` under one y-up node `building`."""
    trimesh = _trimesh()
    boxes = geometry.boxes
    lows = np.array([[b.x0, b.y0, 0.0] for b in boxes])
    highs = np.array([[b.x1, b.y1, geometry.height] for b in boxes])
    vertices, faces = box_arrays(lows, highs)
    # process=False keeps each box's own eight vertices: merging the corners that touching
    # boxes share would make the boxes one non-manifold surface instead of closed solids.
    walls = trimesh.Trimesh(vertices, faces, process=False)
    walls.visual = trimesh.visual.ColorVisuals(walls, vertex_colors=[237, 232, 219, 255])
    x0, y0, x1, y1 = geometry.extent
    floor_vertices, floor_faces = box_arrays(np.array([[x0, y0, -FLOOR_THICKNESS]]), np.array([[x1, y1, 0.0]]))
    floor = trimesh.Trimesh(floor_vertices, floor_faces, process=False)
    floor.visual = trimesh.visual.ColorVisuals(floor, vertex_colors=[200, 200, 196, 255])
    built = trimesh.Scene(base_frame="world")
    built.add_geometry(walls, node_name="walls", geom_name="walls", transform=Z_UP_TO_Y_UP)
    built.add_geometry(floor, node_name="floor", geom_name="floor", transform=Z_UP_TO_Y_UP)
    return built


def render_glb(geometry: WallGeometry) -> bytes:
    buffer = io.BytesIO()
    scene(geometry).export(buffer, file_type="glb")
    return buffer.getvalue()


def render(
    layout: Layout,
    stem: str,
    *,
    wall_height: float = DEFAULT_WALL_HEIGHT,
    **_options: object,
) -> dict[str, bytes]:
    """File name -> content: `stem.glb`."""
    _trimesh()  # fail with the install hint before any work
    return {f"{stem}{SUFFIX}": render_glb(wall_geometry(layout, wall_height))}
