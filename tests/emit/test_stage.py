"""The Stage world: documented property names only, exact floorplan size and pose, robot placement."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from _emit_support import CASES, load_case, pair_room, school_layout
from PIL import Image

from layoutdsl.emit import EmitError, write_outputs
from layoutdsl.emit.stage import render_world, robot_start_room
from layoutdsl.layout import Layout, PlacedRoom
from layoutdsl.emit.raster import rasterize_layout

# Property names Stage documents, per model type. Sources: the Stage manual's worldfile
# pages (rtv.github.io/Stage: "world", "worldgui", "model", "position", "ranger"), and the
# reference worlds in shared/reference/stage (simple.world, map.inc, sick.inc, pioneer.inc
# from rtv/Stage; willow-erratic.world from stage_ros). Stage run headless accepts any
# misspelling silently, so this list is the only guard.
WORLD_PROPERTIES = {
    "name", "interval_sim", "quit_time", "resolution", "show_clock", "show_clock_interval",
    "threads", "paused", "speedup", "include",
}
WINDOW_PROPERTIES = {
    "size", "center", "rotate", "scale", "show_data", "show_flags", "show_blocks",
    "show_clock", "show_footprints", "show_grid", "show_trailarrows", "show_trailrise",
    "show_trailfast", "show_occupancy", "pcam_on", "screenshots",
}
MODEL_PROPERTIES = {
    "bitmap", "boundary", "blob_return", "color", "color_rgba", "ctrl", "fiducial_key",
    "fiducial_return", "gripper_return", "gui_move", "gui_nose", "gui_grid", "gui_outline",
    "mass", "name", "map_resolution", "obstacle_return", "origin", "pose", "ranger_return",
    "size", "stack_children", "update_interval", "velocity", "watts", "watts_give",
    "watts_take", "joules", "joules_capacity", "kjoules", "alwayson", "say",
    "trail_length", "trail_interval", "friction", "block",
}
POSITION_PROPERTIES = MODEL_PROPERTIES | {
    "drive", "localization", "localization_origin", "odom_error", "velocity_bounds",
    "acceleration_bounds", "wheelbase",
}
RANGER_PROPERTIES = MODEL_PROPERTIES | {"sensor"}
SENSOR_PROPERTIES = {"pose", "size", "range", "fov", "samples", "color", "color_rgba", "noise"}
PROPERTIES = {
    "world": WORLD_PROPERTIES,
    "window": WINDOW_PROPERTIES,
    "model": MODEL_PROPERTIES,
    "position": POSITION_PROPERTIES,
    "ranger": RANGER_PROPERTIES,
    "sensor": SENSOR_PROPERTIES,
}

_TOKEN = re.compile(r'"[^"]*"|[\[\]()]|[^\s\[\]()"]+')


def _strip_comment(line: str) -> str:
    """The line up to a `#` that is not inside a string."""
    in_string = False
    for index, char in enumerate(line):
        if char == '"':
            in_string = not in_string
        elif char == "#" and not in_string:
            return line[:index]
    return line


def _tokens(text: str) -> list[str]:
    return _TOKEN.findall("\n".join(_strip_comment(line) for line in text.splitlines()))


class World:
    """A tiny reader of Stage's worldfile syntax, enough to check names and values."""

    def __init__(self, text: str) -> None:
        self.tokens = _tokens(text)
        self.pos = 0
        self.parents: dict[str, str] = {}
        self.properties: dict[str, object] = {}
        self.blocks: list[tuple[str, str, dict[str, object]]] = []  # (name, base type, props)
        self.problems: list[str] = []
        while self.pos < len(self.tokens):
            self._top_item()

    def _next(self) -> str:
        token = self.tokens[self.pos]
        self.pos += 1
        return token

    def _value(self) -> object:
        token = self._next()
        if token != "[":
            return token.strip('"')
        values = []
        while self.tokens[self.pos] != "]":
            values.append(self._next().strip('"'))
        self.pos += 1
        return values

    def base(self, name: str) -> str:
        seen = set()
        while name in self.parents and name not in seen:
            seen.add(name)
            name = self.parents[name]
        return name

    def _body(self, kind: str, context: str) -> dict[str, object]:
        props: dict[str, object] = {}
        assert self._next() == "("
        while self.tokens[self.pos] != ")":
            key = self._next()
            if self.tokens[self.pos] == "(":
                child_kind = "sensor" if key == "sensor" and kind == "ranger" else self.base(key)
                if key not in PROPERTIES.get(kind, set()) and child_kind not in PROPERTIES:
                    self.problems.append(f"{context}: unknown model or block `{key}`")
                child = self._body(child_kind, f"{context}/{key}")
                self.blocks.append((key, child_kind, child))
                props[key] = child
            else:
                if key not in PROPERTIES.get(kind, set()):
                    self.problems.append(f"{context}: `{key}` is not a documented {kind} property")
                props[key] = self._value()
        self.pos += 1
        return props

    def _top_item(self) -> None:
        key = self._next()
        if key == "define":
            name, parent = self._next(), self._next()
            self.parents[name] = parent
            kind = self.base(parent)
            if kind not in PROPERTIES:
                self.problems.append(f"define {name}: unknown parent type `{parent}`")
            self.blocks.append((f"define {name}", kind, self._body(kind, f"define {name}")))
        elif self.tokens[self.pos] == "(":
            kind = "window" if key == "window" else self.base(key)
            if kind not in PROPERTIES:
                self.problems.append(f"`{key}` is not a model type")
            self.blocks.append((key, kind, self._body(kind, key)))
        else:
            if key not in WORLD_PROPERTIES:
                self.problems.append(f"`{key}` is not a documented world property")
            self.properties[key] = self._value()

    def instance(self, name: str) -> dict[str, object]:
        found = [props for key, _kind, props in self.blocks if key == name]
        assert len(found) == 1, f"expected one `{name}` block, found {len(found)}"
        return found[0]


def _world(layout: Layout, tmp_path: Path, **options) -> tuple[World, Path]:
    write_outputs(layout, tmp_path, "plan", ["world"], **options)
    return World((tmp_path / "plan.world").read_text()), tmp_path


def test_the_checker_catches_a_misspelt_property() -> None:
    world = World('define floorplan model ( bitmapp "x.png" )\nfloorplan( sise [1 2 3] )\nquit_tim 5\n')
    assert len(world.problems) == 3


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_world_uses_only_documented_properties(case: Path, tmp_path: Path) -> None:
    world, _ = _world(load_case(case), tmp_path)
    assert world.problems == []
    assert "include" not in world.properties  # self-contained: no files the user lacks


@pytest.mark.parametrize("layout", [load_case(c) for c in CASES] + [school_layout(2, 4)], ids=[c.name for c in CASES] + ["school"])
def test_floorplan_size_and_pose_match_the_bitmap_exactly(layout: Layout, tmp_path: Path) -> None:
    world, folder = _world(layout, tmp_path)
    floorplan = world.instance("floorplan")
    bitmap = Image.open(folder / floorplan["bitmap"])  # relative to the world file
    pixels = np.asarray(bitmap.convert("L"))
    dark = np.argwhere(pixels < 128)
    # Stage stretches the dark pixels' bounding box to `size`: it must be the whole image
    assert dark.min(axis=0).tolist() == [0, 0]
    assert dark.max(axis=0).tolist() == [pixels.shape[0] - 1, pixels.shape[1] - 1]
    resolution = 0.05
    width, height, z = (float(v) for v in floorplan["size"])
    assert round(width / resolution) == pixels.shape[1] and width / resolution == pytest.approx(pixels.shape[1], abs=1e-6)
    assert height / resolution == pytest.approx(pixels.shape[0], abs=1e-6)
    assert z > 0
    grid = rasterize_layout(layout, resolution)
    pose = [float(v) for v in floorplan["pose"]]
    assert pose == pytest.approx([*grid.centre, 0, 0], abs=1e-9)
    # with that size and pose, a room centre maps to a free pixel: world frame = layout frame
    for room in layout.rooms:
        x, y = room.centre
        col = int((x - (pose[0] - width / 2)) / resolution)
        row = int(((pose[1] + height / 2) - y) / resolution)
        assert pixels[row, col] > 128, f"{room.id} centre falls on a wall in Stage's frame"


def test_robot_is_a_diff_drive_with_a_270_degree_30_metre_laser(tmp_path: Path) -> None:
    world, _ = _world(load_case(CASES[0]), tmp_path)
    robot_type = world.instance("define robot")
    assert world.base("robot") == "position" and robot_type["drive"] == "diff"
    laser = world.instance("define laser")
    assert world.base("laser") == "ranger"
    sensor = laser["sensor"]
    assert [float(v) for v in sensor["range"]] == [0.0, 30.0]
    assert float(sensor["fov"]) == 270.0 and int(sensor["samples"]) == 1081
    assert "laser" in robot_type  # the robot carries the laser


def _robot_pose(world: World) -> tuple[float, float]:
    robot = world.instance("robot")
    x, y, *_ = (float(v) for v in robot["pose"])
    return x, y


def test_robot_starts_in_the_first_entrance(tmp_path: Path) -> None:
    layout = load_case(Path(__file__).parent / "small_office")
    world, _ = _world(layout, tmp_path)
    assert _robot_pose(world) == pytest.approx(layout.room("E0").centre)


def test_robot_room_option_overrides_and_no_entrance_means_first_room(tmp_path: Path) -> None:
    layout = load_case(Path(__file__).parent / "small_office")
    world, _ = _world(layout, tmp_path / "a", robot_room="R1")
    assert _robot_pose(world) == pytest.approx(layout.room("R1").centre)
    assert robot_start_room(pair_room()).id == "R0"


def test_unknown_robot_room_is_an_error_before_anything_is_written(tmp_path: Path) -> None:
    layout = load_case(Path(__file__).parent / "small_office")
    with pytest.raises(EmitError, match="`R9`.*rooms: E0, C0"):
        write_outputs(layout, tmp_path, "plan", robot_room="R9")
    assert list(tmp_path.iterdir()) == []


def test_world_text_is_deterministic() -> None:
    layout = school_layout(2, 3)
    grid = rasterize_layout(layout)
    assert render_world(layout, grid, "x") == render_world(layout, rasterize_layout(layout), "x")


def test_quotes_in_the_name_cannot_break_the_world_file(tmp_path: Path) -> None:
    room = PlacedRoom("R0", "X", "R", 0, 0, 3, 3)
    world, _ = _world(Layout('my "big" house', 3, 3, 0.2, (room,), ()), tmp_path)
    assert world.problems == [] and world.instance("floorplan")["name"] == "my _big_ house"


def test_bitmap_is_pure_black_and_white(tmp_path: Path) -> None:
    write_outputs(school_layout(2, 3), tmp_path, "plan", ["world"])
    image = Image.open(tmp_path / "plan.world.png")
    assert image.mode == "L"
    assert set(np.unique(np.asarray(image)).tolist()) == {0, 255}
