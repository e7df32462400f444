"""specs/l_corridor.lay compiles, and its drawing, Stage bitmap and 3D worlds show the L (issue 14).

The checks read the written files (layout JSON, PNG, Stage world and bitmap, MuJoCo, Gazebo
and glTF worlds, XML) and judge them with their own arithmetic: the corridor is two rectangles
flush at a corner; the pixels (or rays) along the line where its arms meet are corridor, not
wall; just outside the L's inner corner is wall (an L, not its bounding box).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from PIL import Image

from gltf_frame import walls_in_layout_frame
from layoutdsl.cli import main
from layoutdsl.emit.png import ROOM_TINTS, WALL, drawing
from layoutdsl.layout import Layout

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "specs" / "l_corridor.lay"


@pytest.fixture(scope="module")
def out(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("l_corridor")
    assert main(["compile", str(SPEC), "-o", str(folder), "-q", "--time-limit", "30",
                 "--emit", "xml,png,world,map,mjcf,sdf,gltf"]) == 0
    return folder


def _corridor(out: Path):
    layout = Layout.from_json((out / "l_corridor.layout.json").read_text())
    corridor = layout.room("C0")
    assert corridor.arm is not None
    a = (corridor.x, corridor.y, corridor.x + corridor.w, corridor.y + corridor.h)
    ax, ay, aw, ah = corridor.arm
    b = (ax, ay, ax + aw, ay + ah)
    return layout, a, b


def _join(a, b):
    """(the join segment's two ends, the L's inner corner, the outward diagonal there)."""
    eps = 1e-6
    if abs(a[2] - b[0]) < eps or abs(b[2] - a[0]) < eps:  # side by side: a vertical join line
        x = a[2] if abs(a[2] - b[0]) < eps else a[0]
        lo, hi = max(a[1], b[1]), min(a[3], b[3])
        ends = ((x, lo), (x, hi))
        # the inner corner is the end of the join that is not a corner of both boxes' span
        inner_y = hi if hi < max(a[3], b[3]) else lo
        short = a if (a[3] - a[1]) < (b[3] - b[1]) else b
        out_x = 1 if short[0] >= x - eps else -1
        out_y = 1 if inner_y == hi else -1
        return ends, (x, inner_y), (out_x, out_y)
    y = a[3] if abs(a[3] - b[1]) < eps else a[1]
    lo, hi = max(a[0], b[0]), min(a[2], b[2])
    ends = ((lo, y), (hi, y))
    inner_x = hi if hi < max(a[2], b[2]) else lo
    short = a if (a[2] - a[0]) < (b[2] - b[0]) else b
    out_y = 1 if short[1] >= y - eps else -1
    out_x = 1 if inner_x == hi else -1
    return ends, (inner_x, y), (out_x, out_y)


def test_the_corridor_is_an_l_of_two_flush_rectangles(out: Path) -> None:
    layout, a, b = _corridor(out)
    (p, q), corner, _ = _join(a, b)
    length = abs(q[0] - p[0]) + abs(q[1] - p[1])
    assert length >= min(a[2] - a[0], a[3] - a[1], b[2] - b[0], b[3] - b[1]) - 1e-6
    # aligned at one end: the union is an L, six corners
    assert len(layout.room("C0").polygon) == 6
    bbox = (min(a[0], b[0]), min(a[1], b[1]), max(a[2], b[2]), max(a[3], b[3]))
    union = (a[2] - a[0]) * (a[3] - a[1]) + (b[2] - b[0]) * (b[3] - b[1])
    assert union < 0.95 * (bbox[2] - bbox[0]) * (bbox[3] - bbox[1]), "not far from its bounding box"


def _samples(p, q, n=9):
    return [(p[0] + (q[0] - p[0]) * (i + 1) / (n + 1), p[1] + (q[1] - p[1]) * (i + 1) / (n + 1)) for i in range(n)]


def test_the_stage_bitmap_shows_the_l(out: Path) -> None:
    layout, a, b = _corridor(out)
    (p, q), corner, (dx, dy) = _join(a, b)
    world = (out / "l_corridor.world").read_text()
    block = world[world.index("\nfloorplan\n"):]  # the model, not the comment or the definition
    size = [float(v) for v in re.search(r"size \[ ([\d.]+) ([\d.]+)", block).groups()]
    pose = [float(v) for v in re.search(r"pose \[ ([-\d.]+) ([-\d.]+)", block).groups()]
    image = Image.open(out / "l_corridor.world.png").convert("L")
    cols, rows = image.size
    x0, y_top = pose[0] - size[0] / 2, pose[1] + size[1] / 2

    def pixel(x: float, y: float) -> int:
        col = int((x - x0) / size[0] * cols)
        row = int((y_top - y) / size[1] * rows)
        return image.getpixel((col, row))

    free = [pixel(x, y) for x, y in _samples(p, q)]
    assert all(v > 128 for v in free), f"wall between the arms of the L: {free}"
    for box in (a, b):
        assert pixel((box[0] + box[2]) / 2, (box[1] + box[3]) / 2) > 128
    half = layout.walldim / 2
    assert pixel(corner[0] + dx * half, corner[1] + dy * half) < 128, "no wall at the L's inner corner"


def test_the_png_shows_the_l(out: Path) -> None:
    layout, a, b = _corridor(out)
    (p, q), corner, (dx, dy) = _join(a, b)
    plan = drawing(layout)
    # the drawing's metre -> pixel map, read off the corridor's two painted rectangles
    painted = [item for item in plan.items if getattr(item, "tag", "") == "room C0"]
    assert len(painted) == 2
    first = painted[0]
    scale = (first.x1 - first.x0) / (a[2] - a[0])
    image = Image.open(out / "l_corridor.png").convert("RGB")

    def pixel(x: float, y: float) -> str:
        px = first.x0 + (x - a[0]) * scale
        py = first.y0 + (a[3] - y) * scale
        return "#%02x%02x%02x" % image.getpixel((int(px), int(py)))

    # away from the label, which is drawn over the larger arm's centre
    along = [pixel(x, y) for x, y in _samples(p, q)]
    assert along.count(ROOM_TINTS["C"]) >= 7, f"the arms' meeting line is not corridor: {along}"
    half = layout.walldim / 2
    assert pixel(corner[0] + dx * half, corner[1] + dy * half) == WALL


def test_the_3d_worlds_show_the_l(out: Path) -> None:
    # MuJoCo loads the MJCF and casts rays down from above the walls; the SDF's wall boxes
    # are read from its text, the glTF's from the mesh trimesh loads: each must leave the
    # arms' meeting line free and wall the L's inner corner
    import mujoco
    import numpy as np
    import trimesh

    layout, a, b = _corridor(out)
    (p, q), corner, (dx, dy) = _join(a, b)
    half = layout.walldim / 2
    outside = (corner[0] + dx * half, corner[1] + dy * half)
    model = mujoco.MjModel.from_xml_path(str(out / "l_corridor.mjcf.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)

    def mujoco_wall(x: float, y: float) -> bool:
        hit = np.zeros(1, dtype=np.int32)
        distance = mujoco.mj_ray(model, data, np.array([x, y, 10.0]), np.array([0.0, 0.0, -1.0]), None, 1, -1, hit)
        return distance >= 0 and model.geom(int(hit[0])).name.startswith("wall_")

    def wall_in(boxes: np.ndarray):
        """Whether a point lies strictly inside one of the (x0, y0, x1, y1) wall boxes."""
        def wall_at(x: float, y: float) -> bool:
            return bool(((boxes[:, 0] < x) & (x < boxes[:, 2]) & (boxes[:, 1] < y) & (y < boxes[:, 3])).any())
        return wall_at

    sdf_boxes = []
    for element in ET.parse(out / "l_corridor.sdf").getroot().iter("collision"):
        if element.get("name", "").startswith("wall_"):
            cx, cy = (float(v) for v in element.find("pose").text.split()[:2])
            sx, sy = (float(v) for v in element.find("geometry/box/size").text.split()[:2])
            sdf_boxes.append((cx - sx / 2, cy - sy / 2, cx + sx / 2, cy + sy / 2))
    assert sdf_boxes
    sdf_wall = wall_in(np.array(sdf_boxes))

    walls = walls_in_layout_frame(trimesh.load(out / "l_corridor.glb", process=False))
    # each wall a closed box of its own: eight vertices apiece, in the order written
    corners = walls.vertices.reshape(-1, 8, 3)
    lows, highs = corners.min(axis=1), corners.max(axis=1)
    assert len(corners) == len(sdf_boxes) and (highs[:, 2] - lows[:, 2] > 1.0).all()
    gltf_wall = wall_in(np.column_stack([lows[:, :2], highs[:, :2]]))

    for world, wall_at in (("mjcf", mujoco_wall), ("sdf", sdf_wall), ("gltf", gltf_wall)):
        along = [wall_at(x, y) for x, y in _samples(p, q)]
        assert not any(along), f"{world}: wall between the arms of the L: {along}"
        assert wall_at(*outside), f"{world}: no wall at the L's inner corner"


def test_the_xml_space_has_six_corners(out: Path) -> None:
    root = ET.parse(out / "l_corridor.xml").getroot()
    for space in root.iter("space"):
        if space.get("id") != "C0":
            continue
        points = [(float(p.get("x")), float(p.get("y"))) for p in space.find("bounding_polygon").iter("point")]
        break
    else:
        pytest.fail("no space C0")
    # door openings split edges: keep only the corners where the outline turns
    ring = points[:-1]
    corners = [pt for i, pt in enumerate(ring)
               if not (ring[i - 1][0] == pt[0] == ring[(i + 1) % len(ring)][0]
                       or ring[i - 1][1] == pt[1] == ring[(i + 1) % len(ring)][1])]
    assert len(corners) == 6


def test_the_same_seed_gives_the_same_l_layout(out: Path, tmp_path: Path) -> None:
    assert main(["compile", str(SPEC), "-o", str(tmp_path), "-q", "--time-limit", "30"]) == 0
    first = Layout.from_json((out / "l_corridor.layout.json").read_text())
    again = Layout.from_json((tmp_path / "l_corridor.layout.json").read_text())
    assert (first.rooms, first.portals) == (again.rooms, again.portals)
    assert (out / "l_corridor.xml").read_bytes() == (tmp_path / "l_corridor.xml").read_bytes()


def test_variants_of_the_l_spec_keep_the_l_and_verify(tmp_path: Path) -> None:
    # a variant polishes its start with nothing searched after: the model is built with
    # only the separations of the start's relations, the L's join kept (model.settle_separations)
    from layoutdsl.compile.variants import compile_variants
    from layoutdsl.layout.verify import verify
    from layoutdsl.solve import SolveOptions
    from layoutdsl.api import load_spec

    spec, diagnostics = load_spec(str(SPEC))
    assert spec is not None, diagnostics
    result = compile_variants(spec, 2, seed=0, options=SolveOptions(time_limit=20, quiet=True), workers=1)
    assert all(layout is not None for layout in result.layouts)
    for layout in result.layouts:
        assert verify(spec, layout) == []
        assert layout.room("C0").arm is not None
