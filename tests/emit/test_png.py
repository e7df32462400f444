"""The drawing: computed primitives (what a reader sees) and their Pillow rendering."""

from __future__ import annotations

import io
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
    (caption,) = [t for t in _texts(picture) if t.text.endswith(" m")]
    metres = float(caption.text[:-2])
    (zero,) = [t for t in _texts(picture) if t.text == "0"]
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
