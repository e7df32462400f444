"""The glTF mesh, reloaded with trimesh: closed boxes, upright, and on the 2D map's walls.

The slice at half wall height is rasterized here with an even-odd scanline of its own
(cell centres, as the occupancy grid samples) and compared with the grid cell by cell:
- no free cell of the map lies inside a mesh wall unless an occupied cell is next to it;
- every occupied map cell bordering free space has mesh wall within one cell of it;
- at every door the mesh is open where the map is, to within a cell at each jamb.
"""

from __future__ import annotations

import io

import numpy as np
import pytest

from _emit_support import load_case, planted_layouts, school_layout, HERE
from _sim_support import LARGE_PLANS, large_layout
from gltf_frame import walls_in_layout_frame
from layoutdsl.emit import gltf
from layoutdsl.emit.walls import wall_geometry
from layoutdsl.layout import Layout
from layoutdsl.emit.raster import OccupancyGrid, rasterize_layout

trimesh = pytest.importorskip("trimesh", reason="the sim extra (trimesh) is not installed")

LAYOUTS = {
    **planted_layouts(),
    "synthetic_school_106": school_layout(),
    "thin_walls": load_case(HERE / "thin_walls"),
}


def _layout(name: str) -> Layout:
    return large_layout(name) if name in LARGE_PLANS else LAYOUTS[name]


def _reload(layout: Layout, wall_height: float = 2.5):
    data = gltf.render(layout, "plan", wall_height=wall_height)["plan.glb"]
    return trimesh.load(io.BytesIO(data), file_type="glb", process=False)


def _scanline(segments: np.ndarray, grid: OccupancyGrid) -> np.ndarray:
    """Cells whose centre lies inside the closed outlines `segments` (N × 2 × 2), even-odd rule."""
    rows, cols = grid.occupied.shape
    inside = np.zeros((rows, cols), dtype=bool)
    xs = grid.origin[0] + (np.arange(cols) + 0.5) * grid.resolution
    (ax, ay), (bx, by) = segments[:, 0].T, segments[:, 1].T
    for row in range(rows):
        y = grid.origin[1] + (rows - row - 0.5) * grid.resolution
        crosses = (ay <= y) != (by <= y)
        t = (y - ay[crosses]) / (by[crosses] - ay[crosses])
        at = np.sort(ax[crosses] + t * (bx[crosses] - ax[crosses]))
        inside[row] = np.searchsorted(at, xs) % 2 == 1
    return inside


def _dilate(mask: np.ndarray) -> np.ndarray:
    """Grow a mask by one cell (8-neighbourhood)."""
    grown = mask.copy()
    padded = np.pad(mask, 1)
    rows, cols = mask.shape
    for dr in range(3):
        for dc in range(3):
            grown |= padded[dr : dr + rows, dc : dc + cols]
    return grown


def _run(line: np.ndarray, index: int) -> int:
    """Length of the run of True around `index` in a 1-D mask (0 if it is False there)."""
    if not line[index]:
        return 0
    lo = index
    while lo > 0 and line[lo - 1]:
        lo -= 1
    hi = index
    while hi < len(line) - 1 and line[hi + 1]:
        hi += 1
    return hi - lo + 1


def _door_width(open_cells: np.ndarray, portal, grid: OccupancyGrid) -> int:
    """Cells open along the wall line through a door: the narrowest run among the lines of
    cells within one cell of the door's centre line (a thin wall may sit in either)."""
    row, col = grid.world_to_cell(*portal.centre)
    if portal.vertical:
        return min(_run(open_cells[:, c], row) for c in (col - 1, col, col + 1))
    return min(_run(open_cells[r, :], col) for r in (row - 1, row, row + 1))


@pytest.mark.parametrize("name", sorted(LAYOUTS) + list(LARGE_PLANS))
def test_mesh_slice_lies_on_the_map_walls(name: str) -> None:
    layout = _layout(name)
    grid = rasterize_layout(layout)
    walls = walls_in_layout_frame(_reload(layout))
    segments = trimesh.intersections.mesh_plane(walls, plane_normal=[0, 0, 1], plane_origin=[0, 0, 1.25])
    mesh_wall = _scanline(segments[:, :, :2], grid)
    free = ~grid.occupied

    intruding = mesh_wall & free & ~_dilate(grid.occupied)
    assert not intruding.any(), f"{intruding.sum()} free map cells lie deep inside mesh walls"

    boundary = grid.occupied & _dilate(free)
    uncovered = boundary & ~_dilate(mesh_wall)
    assert not uncovered.any(), f"{uncovered.sum()} map wall cells next to free space have no mesh wall"

    for portal in layout.portals:
        map_open, mesh_open = _door_width(free, portal, grid), _door_width(~mesh_wall, portal, grid)
        assert mesh_open > 0, f"door {portal.a}-{portal.b} is closed in the mesh"
        if map_open:  # a door the raster opened is as wide in the mesh, to a cell at each jamb
            assert abs(mesh_open - map_open) <= 2, (portal, map_open, mesh_open)


@pytest.mark.parametrize("name", ["office_small", "synthetic_school_106", "office_floorplanLOWER"])
def test_each_wall_box_is_a_closed_solid(name: str) -> None:
    layout = _layout(name)
    geometry = wall_geometry(layout)
    walls = walls_in_layout_frame(_reload(layout))
    assert len(walls.faces) == 12 * len(geometry.boxes)
    owners = np.full(len(walls.vertices), -1)
    for index in range(len(geometry.boxes)):
        faces = walls.faces[12 * index : 12 * index + 12]
        used = np.unique(faces)
        assert (owners[used] == -1).all(), "boxes share no vertices"
        owners[used] = index
        box = trimesh.Trimesh(walls.vertices, faces, process=True)
        assert box.is_watertight and box.is_winding_consistent
        lo, hi = box.bounds
        assert box.volume == pytest.approx(np.prod(hi - lo), rel=1e-5), "outward normals, box-shaped"
    total = sum((b.x1 - b.x0) * (b.y1 - b.y0) for b in geometry.boxes) * geometry.height
    assert walls.volume == pytest.approx(total, rel=1e-5)


def test_mesh_is_y_up_in_metres() -> None:
    layout = load_case(HERE / "small_office")
    scene = _reload(layout, wall_height=3.0)
    lo, hi = scene.bounds  # glTF frame: x east, y up, z = -north
    geometry = wall_geometry(layout, 3.0)
    x0, y0, x1, y1 = geometry.extent
    assert lo[1] == pytest.approx(-gltf.FLOOR_THICKNESS, abs=1e-6) and hi[1] == pytest.approx(3.0, abs=1e-5)
    assert (lo[0], hi[0]) == (pytest.approx(x0, abs=1e-5), pytest.approx(x1, abs=1e-5))
    assert (lo[2], hi[2]) == (pytest.approx(-y1, abs=1e-5), pytest.approx(-y0, abs=1e-5))


def test_same_layout_same_bytes() -> None:
    layout = school_layout()
    assert gltf.render(layout, "plan") == gltf.render(layout, "plan")
