"""MuJoCo scene writer: `STEM.mjcf.xml` (MJCF), the building and an optional wheeled robot.

The walls are `layoutdsl.emit.walls.wall_geometry`'s boxes as static `box` geoms of the
world body, on a floor plane, in the layout's frame (metres, z up), so a pose means the same
place here, in the Stage world and on the ROS map.

The robot (unless turned off) stands where the Stage robot starts (`robot_start_room`: the
centre of the first entrance room, or `--robot-room`), facing +x as in Stage. It is a
differential-drive base on a free joint: two driven wheels with velocity actuators
`left_wheel` / `right_wheel` (rad/s) and a frictionless caster. On top sits the thesis'
laser (§6.3.2: 270°, 30 m) as a ring of `rangefinder` sensors `laser_000` ... one per
sample, ordered from -135° to +135° (counter-clockwise, 0° straight ahead), each with a
30 m cutoff; a ray that hits nothing within 30 m reads -1, as MuJoCo defines.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from layoutdsl.emit.stage import LASER_FOV, LASER_RANGE, robot_start_room
from layoutdsl.emit.walls import DEFAULT_WALL_HEIGHT, WallGeometry, vector, wall_geometry
from layoutdsl.layout import Layout

SUFFIX = ".mjcf.xml"

LASER_SAMPLES = 271
"""Rangefinders in the ring: one per degree over 270°. Stage's laser has 1081 samples
(0.25°); MuJoCo casts each rangefinder as its own ray every step, and one per degree keeps
a step cheap while every reading still has a Stage sample at the same angle."""

LASER_HEIGHT = 0.30
"""Height of the laser's rays above the floor, metres (above the wheels, below any door head)."""

# The base: a 0.40 × 0.34 m box on two 0.08 m-radius wheels, about a Pioneer's footprint.
_BASE_HALF = (0.20, 0.17, 0.06)
_WHEEL_RADIUS = 0.08
_WHEEL_HALF_WIDTH = 0.02
_CASTER_RADIUS = 0.04


def laser_angles(samples: int = LASER_SAMPLES, fov_degrees: float = LASER_FOV) -> list[float]:
    """The ring's ray directions in radians, relative to the robot's heading, clockwise-most first."""
    half = math.radians(fov_degrees) / 2
    return [-half + i * (2 * half) / (samples - 1) for i in range(samples)]


def _assets(root: ET.Element) -> None:
    asset = ET.SubElement(root, "asset")
    ET.SubElement(asset, "texture", name="grid", type="2d", builtin="checker", rgb1=".82 .82 .80",
                  rgb2=".74 .74 .72", width="256", height="256")
    ET.SubElement(asset, "material", name="floor", texture="grid", texrepeat="1 1", texuniform="true")
    ET.SubElement(asset, "material", name="wall", rgba=".93 .91 .86 1")
    ET.SubElement(asset, "material", name="robot", rgba=".85 .25 .15 1")
    ET.SubElement(asset, "material", name="wheel", rgba=".15 .15 .15 1")


def _robot(worldbody: ET.Element, x: float, y: float) -> None:
    hx, hy, hz = _BASE_HALF
    base_z = _WHEEL_RADIUS  # the base's centre sits at axle height
    body = ET.SubElement(worldbody, "body", name="robot", pos=vector(x, y, base_z))
    ET.SubElement(body, "freejoint", name="robot")
    ET.SubElement(body, "geom", name="robot_base", type="box", size=vector(hx, hy, hz), material="robot", mass="8")
    for side, sign in (("left", 1), ("right", -1)):
        wheel = ET.SubElement(body, "body", name=f"{side}_wheel", pos=vector(0, sign * (hy + _WHEEL_HALF_WIDTH + 0.005), 0))
        ET.SubElement(wheel, "joint", name=f"{side}_wheel", type="hinge", axis="0 1 0", damping="0.01")
        ET.SubElement(wheel, "geom", name=f"{side}_wheel", type="cylinder", zaxis="0 1 0",
                      size=vector(_WHEEL_RADIUS, _WHEEL_HALF_WIDTH), material="wheel", mass="0.5")
    # the caster touches the floor at the same height as the wheels
    ET.SubElement(body, "geom", name="caster", type="sphere", size=vector(_CASTER_RADIUS),
                  pos=vector(-hx + _CASTER_RADIUS, 0, _CASTER_RADIUS - _WHEEL_RADIUS),
                  friction="0 0 0", material="wheel", mass="0.2")
    laser_z = LASER_HEIGHT - base_z
    ET.SubElement(body, "site", name="laser", pos=vector(0, 0, laser_z), size="0.03", rgba=".1 .1 .1 1")
    for index, angle in enumerate(laser_angles()):
        ET.SubElement(body, "site", name=f"laser_{index:03d}", pos=vector(0, 0, laser_z), size="0.005",
                      zaxis=vector(math.cos(angle), math.sin(angle), 0), group="4")


def mjcf_tree(layout: Layout, geometry: WallGeometry, *, robot_room: str | None = None, robot: bool = True) -> ET.Element:
    """The MJCF document as an element tree."""
    root = ET.Element("mujoco", model=layout.name)
    ET.SubElement(root, "compiler", angle="radian")
    # implicitfast integrates the wheels' velocity servos stably at a 2 ms step
    ET.SubElement(root, "option", timestep="0.002", integrator="implicitfast")
    x0, y0, x1, y1 = geometry.extent
    cx, cy = geometry.centre
    span = max(x1 - x0, y1 - y0)
    visual = ET.SubElement(root, "visual")
    # the free camera frames the whole building; far clipping covers its diagonal
    ET.SubElement(visual, "global", azimuth="-90", elevation="-60")
    # a soft headlight: the sun alone leaves the walls facing away from it black
    ET.SubElement(visual, "headlight", ambient=".25 .25 .25", diffuse=".35 .35 .35", specular="0 0 0")
    ET.SubElement(visual, "map", znear="0.01", zfar=vector(max(50.0, 4 * span)))
    ET.SubElement(root, "statistic", center=vector(cx, cy, 0), extent=vector(span / 2 + geometry.height))
    _assets(root)
    worldbody = ET.SubElement(root, "worldbody")
    # no shadows: one shadow map stretched over a whole building speckles every floor
    ET.SubElement(worldbody, "light", name="sun", pos=vector(cx, cy, geometry.height + span),
                  dir="0.3 0.2 -1", directional="true", diffuse=".55 .55 .55", castshadow="false")
    ET.SubElement(worldbody, "geom", name="floor", type="plane", material="floor",
                  pos=vector(cx, cy, 0), size=vector((x1 - x0) / 2 + 1, (y1 - y0) / 2 + 1, 0.1))
    half_height = geometry.height / 2
    for index, box in enumerate(geometry.boxes):
        bx, by = box.centre
        sx, sy = box.size
        ET.SubElement(worldbody, "geom", name=f"wall_{index:04d}", type="box", material="wall",
                      pos=vector(bx, by, half_height), size=vector(sx / 2, sy / 2, half_height))
    if robot:
        room = robot_start_room(layout, robot_room)
        _robot(worldbody, *room.centre)
        actuator = ET.SubElement(root, "actuator")
        for side in ("left", "right"):
            ET.SubElement(actuator, "velocity", name=f"{side}_wheel", joint=f"{side}_wheel", kv="1",
                          ctrlrange="-10 10")
        sensor = ET.SubElement(root, "sensor")
        for index in range(LASER_SAMPLES):
            ET.SubElement(sensor, "rangefinder", name=f"laser_{index:03d}", site=f"laser_{index:03d}",
                          cutoff=vector(LASER_RANGE[1]))
    return root


def render_mjcf(layout: Layout, geometry: WallGeometry, *, robot_room: str | None = None, robot: bool = True) -> str:
    """The MJCF text."""
    root = mjcf_tree(layout, geometry, robot_room=robot_room, robot=robot)
    ET.indent(root)
    comment = (
        f"<!-- {_quoted(layout.name)}: generated by layoutdsl. Frame: metres, the layout's origin, z up "
        f"(the Stage world's frame). Walls {vector(geometry.thickness)} m thick, {vector(geometry.height)} m high. -->\n"
    )
    return comment + ET.tostring(root, encoding="unicode") + "\n"


def _quoted(text: str) -> str:
    # "--" may not appear inside an XML comment
    return text.replace("--", "- -")


def render(
    layout: Layout,
    stem: str,
    *,
    robot_room: str | None = None,
    wall_height: float = DEFAULT_WALL_HEIGHT,
    robot: bool = True,
    **_options: object,
) -> dict[str, bytes]:
    """File name -> content: `stem.mjcf.xml`."""
    geometry = wall_geometry(layout, wall_height)
    text = render_mjcf(layout, geometry, robot_room=robot_room, robot=robot)
    return {f"{stem}{SUFFIX}": text.encode("utf-8")}
