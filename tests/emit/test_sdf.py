"""The Gazebo world: parsed by libsdformat where it is installed, checked against the spec's rules always.

libsdformat is not on PyPI. Where its development files and a C++ compiler are present
(Debian: `apt-get install g++ libsdformat-dev pkg-config`), `sdformat_check.cc` is built
and loads every world strictly (warnings and unknown elements are errors). Everywhere, the
world is checked against the SDFormat 1.9 element rules for every element it uses
(allowed children, required attributes, value types, unique sibling names), and its
walls against the layout's wall geometry.
"""

from __future__ import annotations

import math
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from _emit_support import HERE, load_case, planted_layouts, school_layout
from _sim_support import LARGE_PLANS, large_layout
from layoutdsl.emit import sdf
from layoutdsl.emit.stage import robot_start_room
from layoutdsl.emit.walls import wall_geometry

LAYOUTS = {**planted_layouts(), "synthetic_school_106": school_layout(), "thin_walls": load_case(HERE / "thin_walls")}
NAMES = sorted(LAYOUTS) + list(LARGE_PLANS)


def _layout(name: str):
    return large_layout(name) if name in LARGE_PLANS else LAYOUTS[name]


def _text(name: str) -> str:
    return sdf.render(_layout(name), "plan")["plan.sdf"].decode()


# ------------------------------------------------------------------ libsdformat


@pytest.fixture(scope="module")
def sdformat_check(tmp_path_factory) -> Path:
    compiler = shutil.which("g++")
    pkg_config = shutil.which("pkg-config")
    if compiler is None or pkg_config is None:
        pytest.skip("libsdformat check needs g++ and pkg-config (apt-get install g++ pkg-config libsdformat-dev)")
    for package in ("sdformat14", "sdformat13", "sdformat12"):
        flags = subprocess.run([pkg_config, "--cflags", "--libs", package], capture_output=True, text=True)
        if flags.returncode == 0:
            break
    else:
        pytest.skip("libsdformat's development files are not installed (apt-get install libsdformat-dev)")
    binary = tmp_path_factory.mktemp("sdformat") / "sdformat_check"
    build = subprocess.run(
        [compiler, "-std=c++17", str(HERE / "sdformat_check.cc"), "-o", str(binary), *flags.stdout.split()],
        capture_output=True,
        text=True,
    )
    assert build.returncode == 0, build.stderr
    return binary


@pytest.mark.parametrize("name", NAMES)
def test_libsdformat_loads_the_world(name: str, sdformat_check: Path, tmp_path: Path) -> None:
    path = tmp_path / "plan.sdf"
    path.write_text(_text(name))
    result = subprocess.run([str(sdformat_check), str(path)], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    boxes = len(wall_geometry(_layout(name)).boxes)
    assert f"collisions {boxes} visuals {boxes} static 1" in result.stdout


def test_libsdformat_check_rejects_a_broken_world(sdformat_check: Path, tmp_path: Path) -> None:
    path = tmp_path / "plan.sdf"
    path.write_text(_text("office_small").replace("<static>true", "<static>maybe", 1))
    assert subprocess.run([str(sdformat_check), str(path)], capture_output=True).returncode != 0


# ------------------------------------------------------------------ element rules

# SDFormat 1.9 (sdformat.org/spec?ver=1.9): for each element used, its allowed children.
CHILDREN = {
    "sdf": {"world"},
    "world": {"light", "model", "frame", "physics", "scene", "gravity", "plugin", "include"},
    "light": {"cast_shadows", "pose", "diffuse", "specular", "direction", "attenuation", "intensity", "visualize"},
    "model": {"static", "link", "pose", "frame", "joint", "self_collide", "allow_auto_disable"},
    "link": {"collision", "visual", "pose", "inertial", "kinematic", "gravity"},
    "collision": {"geometry", "pose", "surface", "laser_retro"},
    "visual": {"geometry", "pose", "material", "cast_shadows", "transparency"},
    "geometry": {"box", "plane", "mesh", "cylinder", "sphere"},
    "box": {"size"},
    "plane": {"normal", "size"},
    "material": {"ambient", "diffuse", "specular", "emissive"},
    "frame": {"pose"},
}
REQUIRED_ATTRIBUTES = {
    "sdf": {"version"},
    "world": {"name"},
    "model": {"name"},
    "link": {"name"},
    "collision": {"name"},
    "visual": {"name"},
    "light": {"name", "type"},
    "frame": {"name"},
}
FLOATS = {"pose": 6, "size": None, "normal": 3, "diffuse": 4, "specular": 4, "ambient": 4, "direction": 3}
BOOLEANS = {"static", "cast_shadows"}


def _check(element: ET.Element, path: str) -> None:
    tag = element.tag
    where = f"{path}/{tag}"
    missing = REQUIRED_ATTRIBUTES.get(tag, set()) - set(element.attrib)
    assert not missing, f"{where} lacks {missing}"
    if tag in CHILDREN:
        for child in element:
            assert child.tag in CHILDREN[tag], f"<{child.tag}> is not allowed in {where}"
        named = [(c.tag, c.get("name")) for c in element if c.get("name") is not None]
        assert len(named) == len(set(named)), f"sibling names repeat in {where}"
        for child in element:
            _check(child, where)
        return
    text = (element.text or "").split()
    if tag in FLOATS:
        values = [float(v) for v in text]
        expected = FLOATS[tag] or (3 if path.endswith("box") else 2)
        assert len(values) == expected and all(map(math.isfinite, values)), f"{where}: {text}"
        if tag == "size":
            assert all(v > 0 for v in values), f"{where}: sizes must be positive"
    elif tag in BOOLEANS:
        assert text in (["true"], ["false"], ["1"], ["0"]), f"{where}: {text}"
    else:
        raise AssertionError(f"unexpected leaf <{tag}> in {path}")


@pytest.mark.parametrize("name", NAMES)
def test_world_follows_the_sdformat_element_rules(name: str) -> None:
    root = ET.fromstring(_text(name))
    assert root.tag == "sdf" and root.get("version") == sdf.SDF_VERSION
    assert [light.get("type") for light in root.iter("light")] == ["directional"]
    _check(root, "")


@pytest.mark.parametrize("name", ["office_small", "office_floorplanLOWER"])
def test_world_walls_and_start_frame(name: str) -> None:
    layout = _layout(name)
    root = ET.fromstring(sdf.render(layout, "plan", wall_height=3.0)["plan.sdf"].decode())
    boxes = wall_geometry(layout, 3.0).boxes
    collisions = root.findall("./world/model[@name='building']/link/collision")
    assert len(collisions) == len(boxes)
    for box, collision in zip(boxes, collisions, strict=True):
        x, y, z = map(float, collision.findtext("pose").split()[:3])
        sx, sy, sz = map(float, collision.findtext("geometry/box/size").split())
        assert (x - sx / 2, y - sy / 2, x + sx / 2, y + sy / 2) == pytest.approx((box.x0, box.y0, box.x1, box.y1), abs=1e-6)
        assert (z, sz) == pytest.approx((1.5, 3.0))
    start = root.find("./world/frame[@name='robot_start']/pose").text.split()
    assert tuple(map(float, start[:2])) == pytest.approx(robot_start_room(layout).centre, abs=1e-6)


def test_world_name_is_a_legal_sdformat_name() -> None:
    from dataclasses import replace

    layout = replace(planted_layouts()["office_small"], name="__lab::one")
    root = ET.fromstring(sdf.render(layout, "plan")["plan.sdf"].decode())
    assert root.find("world").get("name") == "lab_one"
