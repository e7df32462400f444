"""The SVG output: the PNG's drawing as vectors, with a tooltip on every room."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from _emit_support import CASES, load_case, school_layout
from defusedxml import ElementTree

from layoutdsl.emit import FORMATS, parse_formats, png, render_outputs, svg
from layoutdsl.layout import PlacedRoom

NS = "{http://www.w3.org/2000/svg}"
SMALL = Path(__file__).parent / "small_office"
ELEMENT_OF = {"rect": "rect", "line": "polyline", "text": "text", "circle": "circle", "polygon": "polygon"}


def _parse(text: str):
    return ElementTree.fromstring(text.encode("utf-8"))


def _title(element) -> str | None:
    found = element.find(f"{NS}title")
    return None if found is None else found.text


def _drawn(root) -> list[tuple[object, str | None]]:
    """(element, tooltip) for every drawn element, in order: an element with a tooltip is
    the second child of a <g> whose first child is its <title>."""
    out = []
    for child in root:
        if child.tag == f"{NS}g":
            title, element = list(child)
            assert title.tag == f"{NS}title"
            out.append((element, title.text))
        elif child.tag != f"{NS}title":
            out.append((child, None))
    return out


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_svg_matches_golden(case: Path, golden) -> None:
    layout = load_case(case)
    golden(case / "expected.svg", svg.render(layout, case.name)[f"{case.name}.svg"].decode("utf-8"))


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_the_svg_is_the_png_drawing(case: Path) -> None:
    layout = load_case(case)
    picture = png.drawing(layout)
    root = _parse(svg.render_svg(layout, picture))
    assert root.tag == f"{NS}svg"
    assert (root.get("width"), root.get("height")) == (str(picture.width), str(picture.height))
    drawn = [element for element, _ in _drawn(root)][1:]  # after the background
    assert [child.tag for child in drawn] == [NS + ELEMENT_OF[item.kind] for item in picture.items]
    for element, item in zip(drawn, picture.items):
        if item.kind == "rect":
            assert float(element.get("x")) == pytest.approx(min(item.x0, item.x1), abs=0.006)
            assert float(element.get("width")) == pytest.approx(abs(item.x1 - item.x0), abs=0.011)
        elif item.kind == "text":
            assert element.text == item.text and element.get("font-size") == str(item.size)


def test_every_room_has_its_id_label_and_size_as_a_tooltip() -> None:
    layout = load_case(SMALL)
    root = _parse(svg.render(layout, "office")["office.svg"].decode("utf-8"))
    drawn = _drawn(root)
    rects = {(float(r.get("x")), float(r.get("y"))): title for r, title in drawn if r.tag == f"{NS}rect"}
    picture = png.drawing(layout)
    for room in layout.rooms:
        (box,) = [i for i in picture.items if i.tag == f"room {room.id}"]
        title = rects[(round(box.x0, 2), round(box.y0, 2))]
        assert title == f"{room.id} · {room.label}\n{room.w:g} m × {room.h:g} m, {room.w * room.h:.1f} m²"
    # the text over a room shows the same tooltip, so hovering the label works too
    (label,) = [title for t, title in drawn if t.tag == f"{NS}text" and t.text == "R1"]
    assert label.startswith("R1 · MEETING ROOM\n4.9 m × 1.8 m")


def test_an_l_room_tooltip_gives_both_rectangles() -> None:
    room = PlacedRoom("R9", "HALL", "R", 0, 0, 4, 3, arm=(4, 0, 2, 1.5))
    assert svg.room_tooltip(room) == "R9 · HALL\n4 m × 3 m + arm 2 m × 1.5 m, 15.0 m²"


def test_text_is_escaped_and_reads_back() -> None:
    layout = load_case(Path(__file__).parent / "single_room")
    text = svg.render(layout, "one")["one.svg"].decode("utf-8")
    assert '"A" & <B>' not in text  # escaped in the file...
    root = _parse(text)
    assert 'STUDIO "A" & <B>' in {t.text for t in root.iter(f"{NS}text")}  # ...and read back as written
    assert _title(root) == "single room (seed 3 · status optimal)"


def test_svg_is_a_format_of_emit_and_draws_the_robot_room() -> None:
    assert "svg" in FORMATS and parse_formats("png,svg") == ("png", "svg")
    layout = load_case(SMALL)
    files = render_outputs(layout, "office", "svg", robot_room="R2")
    assert list(files) == ["office.svg"]
    root = _parse(files["office.svg"].decode("utf-8"))
    (robot,) = [title for element, title in _drawn(root) if element.tag == f"{NS}circle" and title]
    assert robot.startswith("robot start (Stage, MuJoCo): room R2, x 7.55 m, y 1.15 m, heading +x")  # x 5.1 + 4.9/2


def test_svg_is_deterministic_and_plain_ascii_numbers() -> None:
    layout = school_layout(2, 3)
    first = svg.render(layout, "s")["s.svg"]
    assert first == svg.render(layout, "s")["s.svg"]
    assert not re.search(rb'[ ",=]-0[ ",]', first)  # no negative zero
    assert not re.search(rb'="[^"#]*\d[eE][-+]?\d', first)  # no exponent notation (colours aside)
