"""The drawing as SVG (`--emit svg`): the PNG's primitives (`layoutdsl.emit.png.drawing`) as
vectors, for browsers and docs, so it scales without blurring and its text can be searched.

Every room's rectangles, id, label and area carry a `<title>` (the tooltip a browser shows
on hover) with the room's id, label, size and area; the robot's disc says where it starts.
Pixel coordinates are the PNG's, so the SVG and the PNG of a layout line up exactly. The
text uses the same sizes and anchors; the font is the reader's sans-serif, so glyph widths
differ slightly from Pillow's (the layout of the text never depends on them: see png.py).
"""

from __future__ import annotations

from xml.sax.saxutils import escape, quoteattr

from layoutdsl.emit.png import Circle, Drawing, Line, Polygon, Rect, Text, area_text, drawing, status_text
from layoutdsl.layout import Layout, PlacedRoom

FONT_FAMILY = "Aileron, 'Helvetica Neue', Helvetica, Arial, sans-serif"
"""Aileron is the font Pillow draws the PNG with; the others are close, common fallbacks."""

_HORIZONTAL = {"l": "start", "m": "middle", "r": "end"}
"""Pillow's horizontal anchor letter -> SVG text-anchor."""
_BASELINE_SHIFT = {"m": 0.35, "t": 0.8, "a": 0.8, "s": 0.0, "b": -0.2}
"""Pillow's vertical anchor letter -> where the baseline is below the anchor point, in font
sizes. Written as a plain y rather than `dominant-baseline`, which some renderers (librsvg,
image viewers) ignore and which would then shift every tick label and caption."""


def _n(value: float) -> str:
    """A coordinate with at most two decimals, no trailing zeros, never `-0`."""
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _points(points) -> str:
    return " ".join(f"{_n(x)},{_n(y)}" for x, y in points)


def room_tooltip(room: PlacedRoom) -> str:
    """`R0 · OFFICE`, then its size and area (both rectangles of an L-room)."""
    size = f"{room.w:g} m × {room.h:g} m"
    if room.arm is not None:
        size += f" + arm {room.arm[2]:g} m × {room.arm[3]:g} m"
    return f"{room.id} · {room.label}\n{size}, {area_text(room)}"


def _tooltip(layout: Layout, tag: str, tooltips: dict[str, str]) -> str | None:
    kind, _, name = tag.partition(" ")
    if kind in ("room", "label", "area") and name in tooltips:
        return tooltips[name]
    if kind == "robot":
        x, y = layout.room(name).centre
        return f"robot start (Stage, MuJoCo): room {name}, x {x:g} m, y {y:g} m, heading +x"
    return None


def _element(item, title: str | None) -> str:
    """One primitive as an SVG element (with a <title> child when it has a tooltip)."""
    if isinstance(item, Rect):
        x0, x1 = sorted((item.x0, item.x1))
        y0, y1 = sorted((item.y0, item.y1))
        # crispEdges: two rectangles that meet (an L-room's parts, a room over its walls)
        # show no anti-aliased seam where they touch
        attrs = (f'x="{_n(x0)}" y="{_n(y0)}" width="{_n(x1 - x0)}" height="{_n(y1 - y0)}" '
                 f'fill="{item.fill or "none"}" shape-rendering="crispEdges"')  # fmt: skip
        if item.outline and item.width:
            attrs += f' stroke="{item.outline}" stroke-width="{item.width}"'
        name = "rect"
    elif isinstance(item, Line):
        attrs = f'points="{_points(item.points)}" fill="none" stroke="{item.color}" stroke-width="{item.width}"'
        if item.dash:
            attrs += f' stroke-dasharray="{_n(item.dash[0])} {_n(item.dash[1])}"'
        name = "polyline"
    elif isinstance(item, Circle):
        attrs = f'cx="{_n(item.x)}" cy="{_n(item.y)}" r="{_n(item.r)}" fill="{item.fill}"'
        if item.outline and item.width:
            attrs += f' stroke="{item.outline}" stroke-width="{item.width}"'
        name = "circle"
    elif isinstance(item, Polygon):
        attrs = f'points="{_points(item.points)}" fill="{item.fill}"'
        name = "polygon"
    elif isinstance(item, Text):
        name = "text"
        baseline = item.y + _BASELINE_SHIFT[item.anchor[1]] * item.size
        x, y = item.x, baseline
        if item.angle:
            # the shift runs across the text, which is turned: to the right of the anchor
            x, y = item.x + _BASELINE_SHIFT[item.anchor[1]] * item.size, item.y
        attrs = (f'x="{_n(x)}" y="{_n(y)}" font-size="{item.size}" fill="{item.color}" '
                 f'text-anchor="{_HORIZONTAL[item.anchor[0]]}"')  # fmt: skip
        if item.angle:
            # Pillow turns counter-clockwise; SVG's rotate() turns clockwise (y points down)
            attrs += f' transform="rotate({-item.angle} {_n(x)} {_n(y)})"'
        element = f"<text {attrs}>{escape(item.text)}</text>"
    else:  # pragma: no cover - Primitive is a closed union
        raise TypeError(f"unknown primitive {item!r}")
    if name != "text":
        element = f"<{name} {attrs}/>"
    if title:
        # a group whose first child is its <title>: browsers show it as the tooltip of
        # everything in the group, and the element itself stays as the PNG draws it
        return f"<g><title>{escape(title)}</title>{element}</g>"
    return element


def render_svg(layout: Layout, picture: Drawing) -> str:
    """The SVG text of a layout's drawing."""
    tooltips = {room.id: room_tooltip(room) for room in layout.rooms}
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{picture.width}" height="{picture.height}" '
        f'viewBox="0 0 {picture.width} {picture.height}" font-family={quoteattr(FONT_FAMILY)}>',
        f"<title>{escape(layout.name)} ({escape(status_text(layout))})</title>",
        f'<rect x="0" y="0" width="{picture.width}" height="{picture.height}" fill="{picture.background}"/>',
    ]
    for item in picture.items:
        out.append(_element(item, _tooltip(layout, item.tag, tooltips)))
    out.append("</svg>")
    return "\n".join(out) + "\n"


def render(layout: Layout, stem: str, *, robot_room: str | None = None, **_options: object) -> dict[str, bytes]:
    """File name -> content for the SVG emitter: `stem.svg`."""
    return {f"{stem}.svg": render_svg(layout, drawing(layout, robot_room=robot_room)).encode("utf-8")}
