"""The MuJoCo scene in real MuJoCo: the robot's rangefinders see the walls the 2D map has.

Every reading is compared with a ray cast on the occupancy grid (the Stage bitmap and ROS
map) from the same pose. A reading agrees when the two distances differ by at most one
grid cell plus the wall-thickness rounding (`tolerance`). At grazing angles a half-cell
offset of a wall face moves the hit far along the ray, so such a ray also agrees when
each hit point lies on the other model's walls within the same tolerance: MuJoCo's hit is
on (within tolerance of) an occupied cell and the grid's hit is on a MuJoCo wall box.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from _emit_support import HERE, load_case, planted_layouts, school_layout
from _sim_support import LARGE_PLANS, distance_to_boxes, distance_to_occupied, grid_ray_distances, large_layout
from layoutdsl.emit import mjcf, render_outputs
from layoutdsl.emit.stage import LASER_FOV, LASER_RANGE, robot_start_room
from layoutdsl.emit.walls import wall_geometry
from layoutdsl.layout import Layout
from layoutdsl.emit.raster import rasterize_layout

MAX_RANGE = LASER_RANGE[1]
SETTLE_STEPS = 50


def _load(layout: Layout, **options) -> tuple[mujoco.MjModel, mujoco.MjData]:
    text = mjcf.render(layout, "plan", **options)["plan.mjcf.xml"].decode()
    model = mujoco.MjModel.from_xml_string(text)
    return model, mujoco.MjData(model)


def _wall_boxes(model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray:
    """The scene's wall boxes as (x0, y0, x1, y1), read from the compiled MuJoCo model."""
    boxes = []
    for index in range(model.ngeom):
        if model.geom(index).name.startswith("wall_"):
            (cx, cy, _), (hx, hy, _) = data.geom_xpos[index], model.geom_size[index]
            boxes.append((cx - hx, cy - hy, cx + hx, cy + hy))
    return np.array(boxes)


def _place(model, data, x: float, y: float, yaw: float) -> None:
    """Put the robot at (x, y) facing `yaw`, at rest on the floor, and step the simulation."""
    mujoco.mj_resetData(model, data)
    data.qpos[0:2] = (x, y)
    data.qpos[3:7] = (math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2))
    for _ in range(SETTLE_STEPS):
        mujoco.mj_step(model, data)


def _readings(model, data) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per rangefinder: its origin (x, y), horizontal unit direction and horizontal distance."""
    origins, directions, distances = [], [], []
    for index in range(mjcf.LASER_SAMPLES):
        site = data.site(f"laser_{index:03d}")
        axis = site.xmat.reshape(3, 3)[:, 2]  # a rangefinder looks along its site's z axis
        horizontal = math.hypot(axis[0], axis[1])
        reading = data.sensor(f"laser_{index:03d}").data[0]
        origins.append(site.xpos[:2].copy())
        directions.append(axis[:2] / horizontal)
        distances.append(MAX_RANGE if reading < 0 else min(MAX_RANGE, reading * horizontal))
    return np.array(origins), np.array(directions), np.array(distances)


def _compare(layout: Layout, model, data, grid) -> dict[str, float]:
    """Check every reading against the grid; return statistics for the report."""
    tolerance = grid.resolution + wall_geometry(layout).inset + 1e-3
    origins, directions, sim = _readings(model, data)
    x, y = origins.mean(axis=0)
    assert np.abs(origins - (x, y)).max() < 1e-9, "the laser sites share one origin"
    assert grid.is_free(x, y), f"robot at ({x:.2f}, {y:.2f}) stands in a wall of the map"
    ref = grid_ray_distances(grid, x, y, directions, MAX_RANGE)
    difference = np.abs(sim - ref)
    close = difference <= tolerance
    far = ~close
    if far.any():
        sim_hits = origins[far] + directions[far] * sim[far, None]
        ref_hits = origins[far] + directions[far] * ref[far, None]
        on_map = distance_to_occupied(grid, sim_hits) <= tolerance
        on_walls = distance_to_boxes(_wall_boxes(model, data), ref_hits) <= tolerance
        # rays reaching the 30 m cut-off in both models agree whatever lies beyond
        both_max = (sim[far] >= MAX_RANGE - tolerance) & (ref[far] >= MAX_RANGE - tolerance)
        bad = ~((on_map & on_walls) | both_max)
        assert not bad.any(), (
            f"{bad.sum()} readings disagree with the map at ({x:.2f}, {y:.2f}): "
            f"sim {sim[far][bad][:5]}, map {ref[far][bad][:5]}"
        )
    return {
        "rays": len(sim),
        "within": int(close.sum()),
        "median": float(np.median(difference)),
        "max_within": float(difference[close].max()) if close.any() else 0.0,
    }


def _door_pose(layout: Layout, grid) -> tuple[float, float, float, float, str]:
    """A pose 1 m in front of a door, looking through it; and the distance to the door."""
    for portal in layout.portals:
        a, b = layout.room(portal.a), layout.room(portal.b)
        px, py = portal.centre
        if portal.vertical:
            side = -1.0 if a.x < b.x else 1.0
            x, y, yaw = px + side * 1.0, py, 0.0 if side < 0 else math.pi
            margin = min(abs(y - a.y), abs(a.y2 - y))
        else:
            side = -1.0 if a.y < b.y else 1.0
            x, y, yaw = px, py + side * 1.0, math.pi / 2 if side < 0 else -math.pi / 2
            margin = min(abs(x - a.x), abs(a.x2 - x))
        inside = a.x + 0.4 < x < a.x2 - 0.4 and a.y + 0.4 < y < a.y2 - 0.4
        if inside and margin > 0.5 and portal.width >= 0.8:
            return x, y, yaw, 1.0, f"{a.id}->{b.id}"
    raise AssertionError(f"{layout.name}: no door to look through")


def _poses(layout: Layout) -> list[tuple[float, float, float]]:
    """Room centres of three rooms (first, middle, last), facing three directions."""
    rooms = [layout.rooms[0], layout.rooms[len(layout.rooms) // 2], layout.rooms[-1]]
    return [(*room.centre, yaw) for room, yaw in zip(rooms, (0.4, 2.1, -1.9), strict=True)]


LAYOUTS = {**planted_layouts(), "synthetic_school_106": school_layout(), "thin_walls": load_case(HERE / "thin_walls")}


@pytest.mark.parametrize("name", sorted(LAYOUTS) + list(LARGE_PLANS))
def test_rangefinders_agree_with_the_occupancy_grid(name: str) -> None:
    layout = large_layout(name) if name in LARGE_PLANS else LAYOUTS[name]
    grid = rasterize_layout(layout)
    model, data = _load(layout)
    # the robot starts where the Stage robot does and settles on its wheels
    start = robot_start_room(layout)
    mujoco.mj_resetData(model, data)
    for _ in range(SETTLE_STEPS):
        mujoco.mj_step(model, data)
    base = data.body("robot").xpos
    assert abs(base[0] - start.centre[0]) < 0.02 and abs(base[1] - start.centre[1]) < 0.02
    assert 0.0 < base[2] < 0.2, "the robot stands on the floor"
    _compare(layout, model, data, grid)
    for x, y, yaw in _poses(layout):
        _place(model, data, x, y, yaw)
        _compare(layout, model, data, grid)
    # looking through a door: the straight-ahead ray passes it and ends in the next room
    x, y, yaw, to_door, pair = _door_pose(layout, grid)
    _place(model, data, x, y, yaw)
    _compare(layout, model, data, grid)
    ahead = data.sensor(f"laser_{mjcf.LASER_SAMPLES // 2:03d}").data[0]
    assert ahead > to_door + layout.walldim + 0.1, f"{pair}: the ray ahead stopped at {ahead:.2f} m, before the door"


def test_laser_ring_is_the_thesis_laser() -> None:
    model, _ = _load(school_layout())
    assert model.nsensor == mjcf.LASER_SAMPLES
    angles = mjcf.laser_angles()
    assert math.isclose(math.degrees(angles[-1] - angles[0]), LASER_FOV)
    assert all(math.isclose(model.sensor_cutoff[i], MAX_RANGE) for i in range(model.nsensor))
    assert model.nu == 2, "two wheel motors"


def test_robot_drives_on_its_wheels() -> None:
    layout = school_layout()
    model, data = _load(layout)
    mujoco.mj_forward(model, data)
    start = data.body("robot").xpos.copy()
    data.ctrl[:] = (4.0, 4.0)  # rad/s on both wheels: straight ahead (+x)
    for _ in range(500):
        mujoco.mj_step(model, data)
    moved = data.body("robot").xpos - start
    assert moved[0] > 0.2 and abs(moved[1]) < 0.1 * moved[0]


def test_without_robot_and_with_wall_height() -> None:
    layout = school_layout()
    model, data = _load(layout, robot=False, wall_height=3.2)
    mujoco.mj_forward(model, data)
    assert model.nsensor == 0 and model.nbody == 1 and model.nu == 0
    walls = [i for i in range(model.ngeom) if model.geom(i).name.startswith("wall_")]
    assert walls and all(math.isclose(2 * model.geom_size[i][2], 3.2) for i in walls)
    assert len(walls) == len(wall_geometry(layout).boxes)


def test_same_layout_same_bytes() -> None:
    layout = school_layout()
    first = render_outputs(layout, "plan", ["mjcf", "sdf"])
    assert first == render_outputs(layout, "plan", ["mjcf", "sdf"])
