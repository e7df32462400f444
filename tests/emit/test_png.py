"""The drawing: computed primitives (what a reader sees) and their Pillow rendering."""

from __future__ import annotations

import io
from dataclasses import replace
from pathlib import Path

import pytest
from _emit_support import CASES, load_case, school_layout
from PIL import Image

from layoutdsl.emit import png
from layoutdsl.emit.png import Line, Rect, Text, drawing, render_png, text_width
from layoutdsl.layout import Layout

SMALL = Path(__file__).parent / "small_office"


def _tagged(picture: png.Drawing, tag: str) -> list:
    return [i for i in picture.items if i.tag == tag]


def _texts(picture: png.Drawing) -> list[Text]:
    return [i for i in picture.items if isinstance(i, Text)]


def _assert_labels_fit(layout: Layout, picture: png.Drawing, require_label: bool) -> None:
    for room in layout.rooms:
        lines = _tagged(picture, f"label {room.id}")
        (box,) = _tagged(picture, f"room {room.id}")
        assert lines[0].text == room.id and lines[0].size >= png.MIN_FONT
        if require_label:
            assert " ".join(t.text for t in lines[1:]) == room.label
        for text in lines:
            # centred text stays inside the room's rectangle, turned or not
            along, across = text_width(text.text, text.size) / 2, text.size / 2
            half_w, half_h = (along, across) if text.angle == 0 else (across, along)
            assert box.x0 <= text.x - half_w and text.x + half_w <= box.x1
            assert box.y0 <= text.y - half_h and text.y + half_h <= box.y1


def test_every_room_shows_its_id_and_label_inside_it() -> None:
    layout = load_case(SMALL)
    _assert_labels_fit(layout, drawing(layout), require_label=True)


def test_rooms_are_tinted_by_type() -> None:
    layout = load_case(SMALL)
    fills = [i.fill for i in drawing(layout).items if isinstance(i, Rect)]
    for rtype in ("R", "C", "E"):
        assert png.ROOM_TINTS[rtype] in fills
    assert len(set(png.ROOM_TINTS.values())) == 3


def test_implicit_portals_are_dashed_and_doors_are_not() -> None:
    layout = load_case(SMALL)
    picture = drawing(layout)
    for portal in layout.portals:
        kind = "door" if portal.kind == "e" else "implicit portal"
        items = _tagged(picture, f"{kind} {portal.a}-{portal.b}")
        openings = [i for i in items if isinstance(i, Rect) and i.fill == png.OPENING]
        dashed = [i for i in items if isinstance(i, Line) and i.dash]
        assert len(openings) == 1  # an opening in the wall either way
        assert len(dashed) == (1 if portal.kind == "i" else 0)
        # the opening is as wide as the door
        box = openings[0]
        long_side = max(box.x1 - box.x0, box.y1 - box.y0)
        assert long_side == pytest.approx(portal.width * picture.px_per_m, abs=0.5)


def test_obstacles_are_grey_and_hatched() -> None:
    layout = load_case(SMALL)
    picture = drawing(layout)
    items = _tagged(picture, "obstacle O0")
    (box,) = [i for i in items if isinstance(i, Rect)]
    assert box.fill == png.OBSTACLE_FILL
    hatch = [i for i in items if isinstance(i, Line)]
    assert len(hatch) >= 3
    for line in hatch:
        assert all(box.x0 - 0.01 <= x <= box.x1 + 0.01 and box.y0 - 0.01 <= y <= box.y1 + 0.01 for x, y in line.points)


def test_legend_and_scale_bar() -> None:
    layout = load_case(SMALL)
    picture = drawing(layout)
    words = {t.text for t in _texts(picture)}
    assert {"room", "corridor", "entrance", "door (explicit portal)", "implicit portal", "obstacle"} <= words
    legend = [t for t in _texts(picture) if t.tag == "legend"]
    assert "robot start (Stage, MuJoCo)" in {t.text for t in legend}
    (caption,) = [t for t in legend if t.text.endswith(" m")]
    metres = float(caption.text[:-2])
    (zero,) = [t for t in legend if t.text == "0"]
    assert caption.x - zero.x == pytest.approx(metres * picture.px_per_m)


def test_a_hundred_room_plan_stays_legible() -> None:
    layout = school_layout()
    assert len(layout.rooms) > 100
    picture = drawing(layout)
    assert max(picture.width, picture.height) <= 4000
    # every room of this school is big enough for its id and its (wrapped) label
    _assert_labels_fit(layout, picture, require_label=True)


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_rendered_png_has_the_drawing_size_and_paints_rooms(case: Path) -> None:
    layout = load_case(case)
    picture = drawing(layout)
    image = Image.open(io.BytesIO(render_png(picture)))
    assert image.size == (picture.width, picture.height) and image.format == "PNG"
    room = layout.rooms[0]
    tint = png.ROOM_TINTS[room.rtype]
    (box,) = _tagged(picture, f"room {room.id}")
    pixel = image.convert("RGB").getpixel((int(box.x0) + 3, int(box.y0) + 3))
    assert "#%02x%02x%02x" % pixel == tint


def test_drawing_is_deterministic() -> None:
    layout = school_layout(2, 3)
    assert drawing(layout).to_data() == drawing(layout).to_data()


def test_a_tall_narrow_corridor_gets_its_label_turned() -> None:
    layout = school_layout()
    picture = drawing(layout)
    spine = _tagged(picture, "label C0")  # 2 m wide, 53 m tall
    assert [t.text for t in spine] == ["C0", "CORRIDOR"] and {t.angle for t in spine} == {90}
    assert {t.angle for t in _tagged(picture, "label C1")} == {0}  # a corridor running across
    _assert_labels_fit(layout, picture, require_label=True)
    image = Image.open(io.BytesIO(render_png(picture)))
    assert image.size == (picture.width, picture.height)


# ----------------------------------------------------------------------------- issue 42's additions


def _metres_to_px(picture: png.Drawing, layout: Layout) -> tuple:
    """The drawing's metre -> pixel map, recovered from room rectangles alone (independent of
    the code under test): x_px = ax + s x, y_px = ay - s y."""
    room = layout.rooms[0]
    (box,) = _tagged(picture, f"room {room.id}")
    s = picture.px_per_m
    return box.x0 - s * room.x, box.y1 + s * room.y, s


def test_every_room_shows_its_area() -> None:
    layout = load_case(SMALL)
    picture = drawing(layout)
    for room in layout.rooms:
        (area,) = _tagged(picture, f"area {room.id}")
        assert area.text == f"{room.w * room.h:.1f} m²"
        # below the label, inside the room
        assert area.y > max(t.y for t in _tagged(picture, f"label {room.id}"))
        (box,) = _tagged(picture, f"room {room.id}")
        assert box.x0 < area.x < box.x1 and box.y0 < area.y < box.y1
    assert _tagged(picture, "area R1")[0].text == "8.8 m²"  # 4.9 m × 1.8 m


def test_the_area_of_an_l_room_counts_both_rectangles() -> None:
    layout = school_layout(1, 2)
    room = layout.rooms[1]
    l_room = replace(room, arm=(room.x, room.y2 + 0.2, room.w / 2, 1.0))
    assert png.area_text(l_room) == f"{room.w * room.h + room.w / 2:.1f} m²"


def test_coordinate_ticks_read_in_the_boundary_frame() -> None:
    layout = load_case(SMALL)
    picture = drawing(layout)
    ax, ay, s = _metres_to_px(picture, layout)
    x_ticks = [t for t in _tagged(picture, "axis x") if isinstance(t, Text) and t.text != "x (m)"]
    y_ticks = [t for t in _tagged(picture, "axis y") if isinstance(t, Text) and t.text != "y (m)"]
    assert [t.text for t in x_ticks] == [str(v) for v in range(0, 13)]  # the 12 m boundary, every metre
    assert [t.text for t in y_ticks] == [str(v) for v in range(0, 7)]
    for t in x_ticks:
        assert t.x == pytest.approx(ax + s * float(t.text), abs=0.01)
    for t in y_ticks:
        assert t.y == pytest.approx(ay - s * float(t.text), abs=0.01)
    # the ticks sit outside the plan: under it and left of it
    walls = [i for i in picture.items if isinstance(i, Rect) and i.tag.startswith("wall ")]
    assert min(t.y for t in x_ticks) > max(w.y1 for w in walls)
    assert max(t.x for t in y_ticks) < min(w.x0 for w in walls)


def test_ticks_stay_readable_on_a_large_plan() -> None:
    layout = school_layout()
    picture = drawing(layout)
    values = [float(t.text) for t in _tagged(picture, "axis x") if isinstance(t, Text) and t.text != "x (m)"]
    step = values[1] - values[0]
    assert step * picture.px_per_m >= png.TICK_SPACING_PX and step in (1, 2, 5, 10, 20, 50)
    assert values[0] <= 0 and values[-1] >= layout.width - step


def test_the_robot_starts_where_stage_and_mujoco_put_it() -> None:
    layout = load_case(SMALL)
    ax, ay, s = _metres_to_px(drawing(layout), layout)
    # by default: the first entrance, at the centre of its rectangle, heading along +x
    entrance = next(room for room in layout.rooms if room.rtype == "E")
    for robot_room, room in ((None, entrance), ("R2", layout.room("R2"))):
        picture = drawing(layout, robot_room=robot_room)
        (disc,) = [i for i in picture.items if isinstance(i, png.Circle) and i.tag.startswith("robot")]
        assert disc.tag == f"robot {room.id}"
        assert (disc.x, disc.y) == pytest.approx((ax + s * (room.x + room.w / 2), ay - s * (room.y + room.h / 2)))
        (arrow,) = [i for i in picture.items if isinstance(i, png.Polygon) and i.tag == disc.tag]
        tip = max(arrow.points)
        assert tip[1] == pytest.approx(disc.y) and tip[0] > disc.x + disc.r  # points along +x
        # the room's id stays readable: no text of the room under the disc
        for text in _tagged(picture, f"label {room.id}") + _tagged(picture, f"area {room.id}"):
            assert text.y + text.size / 2 <= disc.y - disc.r or text.y - text.size / 2 >= disc.y + disc.r


def test_the_robot_pose_matches_the_stage_world() -> None:
    from layoutdsl.emit import stage
    from layoutdsl.emit.raster import rasterize_layout

    layout = load_case(SMALL)
    world = stage.world_model(layout, rasterize_layout(layout), "x", "R1")
    picture = drawing(layout, robot_room="R1")
    ax, ay, s = _metres_to_px(picture, layout)
    (disc,) = [i for i in picture.items if isinstance(i, png.Circle) and i.tag == "robot R1"]
    assert ((disc.x - ax) / s, (ay - disc.y) / s) == pytest.approx(world.robot_pose[:2])
    assert world.robot_pose[3] == 0  # yaw 0: the arrow's +x


def test_the_seed_and_status_are_printed() -> None:
    solved = load_case(Path(__file__).parent / "single_room")
    assert solved.solve is not None
    (status,) = _tagged(drawing(solved), "status")
    assert status.text == f"seed {solved.solve.seed} · status {solved.solve.status}" == "seed 3 · status optimal"
    (unknown,) = _tagged(drawing(load_case(SMALL)), "status")
    assert "unknown" in unknown.text


def test_the_png_emitter_draws_the_robot_room_it_is_given(tmp_path: Path) -> None:
    from layoutdsl.emit import render_outputs

    layout = load_case(SMALL)
    files = render_outputs(layout, "office", ["png"], robot_room="R2")
    assert files["office.png"] == render_png(drawing(layout, robot_room="R2"))
    assert files["office.png"] != render_png(drawing(layout))


def test_the_area_unit_is_painted_as_a_raised_two() -> None:
    # Pillow's default font has no `²`: the renderer draws a small raised `2` instead of a box
    from PIL import ImageChops

    picture = png.Drawing(200, 60, "#ffffff", 20.0, (Text(100, 30, "8.8 m²", 24),))
    painted = Image.open(io.BytesIO(render_png(picture))).convert("L")
    plain = Image.open(io.BytesIO(render_png(replace(picture, items=(Text(100, 30, "8.8 m2", 24),))))).convert("L")
    assert ImageChops.difference(painted, plain).getbbox() is not None
    dark_rows = [y for y in range(60) if any(painted.getpixel((x, y)) < 128 for x in range(130, 200))]
    digits_rows = [y for y in range(60) if any(painted.getpixel((x, y)) < 128 for x in range(60, 100))]
    assert min(dark_rows) < min(digits_rows)  # the `2` is raised above the digits' top


def test_the_robot_room_label_sits_in_the_rectangle_the_robot_stands_in() -> None:
    # an L-room whose two rectangles are as large: the label and the robot pick the same one
    from layoutdsl.layout import PlacedRoom

    base = load_case(SMALL)
    l_room = PlacedRoom("E9", "HALL", "E", 4.0, 0.0, 4.0, 2.3, arm=(0.0, 0.0, 4.0, 2.3))  # the arm on the left
    layout = replace(base, rooms=(l_room,), portals=(), obstacles=())
    picture = drawing(layout)
    (disc,) = [i for i in picture.items if isinstance(i, png.Circle) and i.tag == "robot E9"]
    boxes = [i for i in picture.items if i.tag == "room E9"]
    (home,) = [b for b in boxes if b.x0 < disc.x < b.x1]
    for text in _tagged(picture, "label E9"):
        assert home.x0 < text.x < home.x1
