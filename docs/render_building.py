"""Render docs/building-3d.png: the MuJoCo scene of a compiled real plan, seen from above.

Headless, through MuJoCo's OSMesa backend (Debian: `apt-get install libosmesa6`):

    MUJOCO_GL=osmesa PYOPENGL_PLATFORM=osmesa python docs/render_building.py

The layout is the compiled 55-room office plan of tests/fixtures/layouts; the red box in
its entrance room is the robot, where the Stage robot starts.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import mujoco  # noqa: E402
from PIL import Image  # noqa: E402

from layoutdsl.emit import mjcf  # noqa: E402
from layoutdsl.emit.walls import wall_geometry  # noqa: E402
from layoutdsl.layout import Layout  # noqa: E402

LAYOUT = ROOT / "tests" / "fixtures" / "layouts" / "office_floorplanLOWER.layout.json"
OUT = ROOT / "docs" / "building-3d.png"


def _content_box(picture: Image.Image, margin: int) -> tuple[int, int, int, int]:
    """The bounding box of the non-black pixels (the empty sky is black), plus a margin."""
    left, top, right, bottom = picture.convert("L").point(lambda v: 255 if v > 8 else 0).getbbox()
    width, height = picture.size
    return (max(0, left - margin), max(0, top - margin), min(width, right + margin), min(height, bottom + margin))


def main() -> int:
    layout = Layout.from_json(LAYOUT.read_text())
    text = mjcf.render(layout, "plan")["plan.mjcf.xml"].decode()
    model = mujoco.MjModel.from_xml_string(text)
    model.vis.global_.offwidth, model.vis.global_.offheight = 1600, 1000
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    geometry = wall_geometry(layout)
    x0, y0, x1, y1 = geometry.extent
    camera = mujoco.MjvCamera()
    camera.type = mujoco.mjtCamera.mjCAMERA_FREE
    camera.lookat[:] = ((x0 + x1) / 2, (y0 + y1) / 2 + 0.08 * (y1 - y0), 0)
    camera.distance = 1.6 * max(x1 - x0, y1 - y0)
    camera.azimuth, camera.elevation = -75, -58
    options = mujoco.MjvOption()
    options.flags[mujoco.mjtVisFlag.mjVIS_RANGEFINDER] = False  # 271 yellow rays would hide the room
    renderer = mujoco.Renderer(model, 1000, 1600)
    try:
        renderer.update_scene(data, camera, options)
        pixels = renderer.render()
    finally:
        renderer.close()
    picture = Image.fromarray(pixels)
    picture = picture.crop(_content_box(picture, margin=20))
    picture.save(OUT, optimize=True)
    print(f"wrote {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
