"""The drawing (the thesis, §5.6): walls, tinted rooms with their id, label and area, doors,
implicit portals, obstacles, coordinate ticks in metres along the boundary, the robot's start
pose, the seed and solve status, a scale bar and a legend.

Two steps, so the drawing can be golden-tested without comparing pixels:
`drawing(layout)` computes a `Drawing` (a list of primitives in pixel coordinates, plain
data), and `render_png(drawing)` paints it with Pillow. Text sizes are chosen from an
estimate of the font's advance width, not from Pillow's measurements, so the primitive
list does not depend on the installed font.

Conventions: rooms are tinted by type as in the thesis' Figure 4.3c (corridors red,
entrances yellow, other rooms blue, pale so that the text stays readable); walls are dark
and as thick as `walldim`; an explicit portal (a door) is an opening in the wall with jamb
ticks; an implicit portal (no barrier) is an opening crossed by a dashed line; obstacles
are grey and hatched. Positions, connections and hints in a spec are coordinates in the
boundary's frame (origin at its bottom-left corner, x right, y up), so the ticks along the
bottom and left of the plan read in that frame. The robot's start pose is the one the Stage
and MuJoCo worlds use (`layoutdsl.emit.stage.robot_start_room`: the `--robot-room`, else the
first entrance, else the first room; at its centre, heading along +x), drawn as a disc with a
heading arrow.

`layoutdsl.emit.svg` writes the same `Drawing` as vectors.
"""

from __future__ import annotations

import io
import math
import textwrap
from collections.abc import Callable
from dataclasses import asdict, dataclass, field, replace
from functools import cache

from PIL import Image, ImageDraw, ImageFont

from layoutdsl.emit.stage import robot_start_room
from layoutdsl.layout import Layout, PlacedRoom, Portal, facing_parts
from layoutdsl.syntax.ast import ROOM_TYPE_NAMES, ROOM_TYPES

BACKGROUND = "#ffffff"
WALL = "#2b2b2b"
TEXT = "#111111"
ROOM_TINTS = {"R": "#d6e4f7", "C": "#f8d7d7", "E": "#fcf3c7"}
"""Pale blue rooms, red corridors, yellow entrances (Figure 4.3c)."""
OPENING = "#ffffff"
IMPLICIT = "#555555"
OBSTACLE_FILL = "#c8c8c8"
OBSTACLE_HATCH = "#7a7a7a"
BOUNDARY = "#9a9a9a"
AXIS = "#555555"
ROBOT_FILL = "#2e7d32"
"""A green robot: no room tint or wall colour is green, so it stands out on any room."""
ROBOT_OUTLINE = "#ffffff"

ROBOT_RADIUS_M = 0.26
"""Half the diagonal of the MuJoCo robot's 0.40 m × 0.34 m base (layoutdsl.emit.mjcf): the
disc covers the robot whatever its heading."""
TICK_SPACING_PX = 70.0
"""Coordinate ticks are a 1-2-5 number of metres apart, at least this many pixels."""

TARGET_PLAN_PIXELS = 2400
"""The plan's longer side aims at this many pixels (a 100-room plan stays readable)."""
MIN_PX_PER_M = 20.0
MAX_PX_PER_M = 100.0
MIN_FONT = 9
CHAR_WIDTH = 0.6
"""Estimated advance width of a character, in font sizes (generous for Pillow's default)."""
LINE_HEIGHT = 1.2


# ----------------------------------------------------------------------------- primitives


@dataclass(frozen=True, slots=True)
class Rect:
    """An axis-aligned rectangle (x0, y0) top-left to (x1, y1) bottom-right."""

    x0: float
    y0: float
    x1: float
    y1: float
    fill: str | None
    outline: str | None = None
    width: int = 0
    tag: str = ""
    """What the primitive shows (`room R0`, `wall R0`, `door C0-R0`, `legend`, ...)."""
    kind: str = "rect"


@dataclass(frozen=True, slots=True)
class Line:
    """A polyline; `dash` is (on, off) in pixels, or None for a solid line."""

    points: tuple[tuple[float, float], ...]
    color: str
    width: int
    dash: tuple[float, float] | None = None
    tag: str = ""
    kind: str = "line"


@dataclass(frozen=True, slots=True)
class Text:
    """Text centred on (x, y) unless `anchor` says otherwise (Pillow anchors)."""

    x: float
    y: float
    text: str
    size: int
    color: str = TEXT
    anchor: str = "mm"
    angle: int = 0
    """Counter-clockwise rotation in degrees (0 or 90), about (x, y)."""
    tag: str = ""
    kind: str = "text"


@dataclass(frozen=True, slots=True)
class Circle:
    """A disc of radius `r` centred on (x, y)."""

    x: float
    y: float
    r: float
    fill: str
    outline: str | None = None
    width: int = 0
    tag: str = ""
    kind: str = "circle"


@dataclass(frozen=True, slots=True)
class Polygon:
    """A filled closed polygon."""

    points: tuple[tuple[float, float], ...]
    fill: str
    tag: str = ""
    kind: str = "polygon"


Primitive = Rect | Line | Text | Circle | Polygon


@dataclass(frozen=True, slots=True)
class Drawing:
    """Everything `render_png` paints, in order, on a `width` × `height` canvas."""

    width: int
    height: int
    background: str
    px_per_m: float
    items: tuple[Primitive, ...] = field(default=())

    def to_data(self) -> dict:
        """Plain data (for JSON goldens), numbers rounded to 0.01 px."""

        def clean(value):
            if isinstance(value, float):
                return round(value, 2) + 0.0  # + 0.0 turns -0.0 into 0.0
            if isinstance(value, (list, tuple)):
                return [clean(v) for v in value]
            if isinstance(value, dict):
                return {k: clean(v) for k, v in value.items()}
            return value

        return clean(
            {
                "width": self.width,
                "height": self.height,
                "background": self.background,
                "px_per_m": self.px_per_m,
                "items": [asdict(item) for item in self.items],
            }
        )


# ----------------------------------------------------------------------------- geometry


def text_width(text: str, size: float) -> float:
    """Estimated width in pixels of `text` at font `size`."""
    return len(text) * size * CHAR_WIDTH


def choose_scale(layout: Layout) -> float:
    """Pixels per metre: the plan's longer side near TARGET_PLAN_PIXELS, within bounds."""
    longest = max(layout.width, layout.height, 1.0)
    return min(MAX_PX_PER_M, max(MIN_PX_PER_M, math.floor(TARGET_PLAN_PIXELS / longest)))


def _nice_length(max_metres: float) -> float:
    """The longest 1-2-5 × 10^k length not above `max_metres` (for the scale bar)."""
    if max_metres <= 0:
        return 1.0
    exponent = math.floor(math.log10(max_metres))
    best = 10.0**exponent
    for mantissa in (1, 2, 5, 10):
        if mantissa * 10.0**exponent <= max_metres:
            best = mantissa * 10.0**exponent
    return best


def _fit_label(room: PlacedRoom, box_w: float, box_h: float, base: int) -> tuple[int, list[str], bool]:
    """The largest font size (≤ base) and lines (id, then the wrapped label) fitting the box.

    Returns (size, lines, rotated). A tall, narrow room (a corridor running up the page)
    gets its text turned 90° when that allows a larger size.
    """
    upright = _fit_in(room, box_w, box_h, base)
    if box_h > box_w:
        turned = _fit_in(room, box_h, box_w, base)
        if turned is not None and (upright is None or (turned[0], len(turned[1]) > 1) > (upright[0], len(upright[1]) > 1)):
            return turned[0], turned[1], True
    if upright is not None:
        return upright[0], upright[1], False
    # Too small for the label: keep the id, which a reader needs most.
    return MIN_FONT, [room.id], False


def _fit_in(room: PlacedRoom, box_w: float, box_h: float, base: int) -> tuple[int, list[str]] | None:
    """The largest size whose lines fit a box (text running along its width), if any."""
    avail_w, avail_h = box_w * 0.92, box_h * 0.92
    for size in range(base, MIN_FONT - 1, -1):
        max_chars = max(1, int(avail_w / (size * CHAR_WIDTH)))
        label_lines = textwrap.wrap(room.label, max_chars, break_long_words=False) if room.label else []
        for lines in ([room.id, *label_lines], [room.id]):
            widest = max(text_width(line, size) for line in lines)
            if widest <= avail_w and len(lines) * size * LINE_HEIGHT <= avail_h:
                if len(lines) > 1 or not room.label or size == MIN_FONT:
                    return size, lines
                break  # the id alone fits but the label does not: try a smaller size first
    return None


class _Frame:
    """Maps the layout's metres (y up) to image pixels (y down); the plan's top-left corner
    (walls included) is at (left, top)."""

    def __init__(self, layout: Layout, scale: float, left: float, top: float) -> None:
        pad = layout.walldim
        self.x_min = min([0.0, *(r.x for r in layout.parts())]) - pad
        self.x_max = max([layout.width, *(r.x2 for r in layout.parts())]) + pad
        self.y_min = min([0.0, *(r.y for r in layout.parts())]) - pad
        self.y_max = max([layout.height, *(r.y2 for r in layout.parts())]) + pad
        self.scale = scale
        self.left = left
        self.top = top

    def px(self, x: float, y: float) -> tuple[float, float]:
        return (self.left + (x - self.x_min) * self.scale, self.top + (self.y_max - y) * self.scale)

    def rect(self, x0: float, y0: float, x1: float, y1: float, **style) -> Rect:
        left, top = self.px(x0, y1)
        right, bottom = self.px(x1, y0)
        return Rect(left, top, right, bottom, **style)


def _portal_primitives(layout: Layout, portal: Portal, frame: _Frame, wall_px: int) -> list[Primitive]:
    """The opening of a portal and its marks (jamb ticks for doors, a dashed line otherwise)."""
    # an L-room's door is in the wall of its arm that faces the other room
    a, b = facing_parts(layout.room(portal.a), layout.room(portal.b))
    half = portal.width / 2
    cx, cy = portal.centre
    items: list[Primitive] = []
    tick_px = max(1, wall_px // 2)
    # a dashed line across the opening: no barrier, yet two spaces (the thesis, §5.2)
    dash_px = max(1, wall_px // 3)
    tag = f"{'door' if portal.kind == 'e' else 'implicit portal'} {portal.a}-{portal.b}"
    if portal.vertical:
        left, right = (a, b) if a.x < b.x else (b, a)
        lo, hi = max(cy - half, a.y, b.y), min(cy + half, a.y2, b.y2)
        items.append(frame.rect(left.x2, lo, right.x, hi, fill=OPENING, tag=tag))
        if portal.kind == "e":
            for y in (lo, hi):
                items.append(Line((frame.px(left.x2, y), frame.px(right.x, y)), WALL, tick_px, tag=tag))
        else:
            items.append(Line((frame.px(cx, lo), frame.px(cx, hi)), IMPLICIT, dash_px, (6.0, 4.0), tag=tag))
    else:
        low, high = (a, b) if a.y < b.y else (b, a)
        lo, hi = max(cx - half, a.x, b.x), min(cx + half, a.x2, b.x2)
        items.append(frame.rect(lo, low.y2, hi, high.y, fill=OPENING, tag=tag))
        if portal.kind == "e":
            for x in (lo, hi):
                items.append(Line((frame.px(x, low.y2), frame.px(x, high.y)), WALL, tick_px, tag=tag))
        else:
            items.append(Line((frame.px(lo, cy), frame.px(hi, cy)), IMPLICIT, dash_px, (6.0, 4.0), tag=tag))
    return items


def _hatch(rect: Rect, spacing: float, tag: str = "") -> list[Line]:
    """45° hatch lines clipped to a rectangle."""
    lines: list[Line] = []
    w, h = rect.x1 - rect.x0, rect.y1 - rect.y0
    # lines x - y = c for c from -h to w, each clipped to the box
    c = -h + spacing / 2
    while c < w:
        start = (rect.x0 + max(0.0, c), rect.y0 + max(0.0, -c))
        end_t = min(w - c, h)
        end = (rect.x0 + c + end_t, rect.y0 + end_t)
        lines.append(Line((start, end), OBSTACLE_HATCH, 1, tag=tag))
        c += spacing
    return lines


def _legend(layout: Layout, x0: float, y0: float, font: int, scale: float, max_width: float) -> tuple[list[Primitive], float, float]:
    """Legend and scale bar below the plan; returns primitives, width and height used."""
    swatch = font * 1.4
    gap = font * 1.2
    row_h = swatch + font * 0.8
    entries: list[tuple[str, Callable[[float, float], list[Primitive]]]] = []

    def place(label: str, make: Callable[[float, float], list[Primitive]]) -> None:
        entries.append((label, make))

    for rtype in ROOM_TYPES:
        place(ROOM_TYPE_NAMES[rtype], lambda x, y, t=rtype: [Rect(x, y, x + swatch, y + swatch, ROOM_TINTS[t], WALL, 1)])
    place(
        "door (explicit portal)",
        lambda x, y: [
            Rect(x, y + swatch * 0.35, x + swatch, y + swatch * 0.65, WALL),
            Rect(x + swatch * 0.3, y + swatch * 0.35, x + swatch * 0.7, y + swatch * 0.65, OPENING),
        ],
    )
    place(
        "implicit portal",
        lambda x, y: [
            Rect(x, y + swatch * 0.35, x + swatch, y + swatch * 0.65, WALL),
            Rect(x + swatch * 0.2, y + swatch * 0.35, x + swatch * 0.8, y + swatch * 0.65, OPENING),
            Line(((x + swatch * 0.2, y + swatch * 0.5), (x + swatch * 0.8, y + swatch * 0.5)), IMPLICIT, 1, (3.0, 2.0)),
        ],
    )
    place("robot start (Stage, MuJoCo)", lambda x, y: _robot(x + swatch * 0.3, y + swatch / 2, swatch * 0.3, ""))
    if layout.obstacles:

        def obstacle_swatch(x: float, y: float) -> list[Primitive]:
            box = Rect(x, y, x + swatch, y + swatch, OBSTACLE_FILL, WALL, 1)
            return [box, *_hatch(box, swatch / 3)]

        place("obstacle", obstacle_swatch)

    items: list[Primitive] = []
    x, y = x0, y0
    used_w = 0.0
    for label, make in entries:
        entry_w = swatch + font * 0.5 + text_width(label, font)
        if x > x0 and x + entry_w > x0 + max_width:
            x, y = x0, y + row_h
        items.extend(make(x, y))
        items.append(Text(x + swatch + font * 0.5, y + swatch / 2, label, font, TEXT, "lm"))
        x += entry_w + gap
        used_w = max(used_w, x - gap - x0)

    # scale bar: a 1-2-5 length of at most a quarter of the plan (and at least a metre)
    bar_m = _nice_length(max(1.0, min(max_width / scale / 4, layout.width / 2)))
    bar_px = bar_m * scale
    caption = f"{bar_m:g} m"
    if x > x0 and x + bar_px + text_width(caption, font) + font > x0 + max_width:
        x, y = x0, y + row_h
    bar_y = y + swatch / 2
    items.append(Rect(x, bar_y - 3, x + bar_px, bar_y + 3, WALL))
    items.append(Rect(x + bar_px / 2, bar_y - 3, x + bar_px, bar_y + 3, BACKGROUND, WALL, 1))
    items.append(Text(x, bar_y + 5, "0", max(MIN_FONT, font - 2), TEXT, "mt"))
    items.append(Text(x + bar_px, bar_y + 5, caption, max(MIN_FONT, font - 2), TEXT, "mt"))
    x += bar_px + text_width(caption, font) / 2 + font
    used_w = max(used_w, x - x0)
    height = (y - y0) + row_h + font
    return [replace(item, tag="legend") for item in items], used_w, height


def _nice_step(min_metres: float) -> float:
    """The shortest 1-2-5 × 10^k length of at least `min_metres` (tick spacing)."""
    exponent = math.floor(math.log10(max(min_metres, 1e-9)))
    for power in (exponent, exponent + 1):
        for mantissa in (1, 2, 5):
            if mantissa * 10.0**power >= min_metres:
                return mantissa * 10.0**power
    return 10.0 ** (exponent + 2)


def _tick_values(low: float, high: float, step: float) -> list[float]:
    """Multiples of `step` from `low` to `high` (inclusive, with a rounding tolerance)."""
    first = math.ceil(low / step - 1e-9)
    last = math.floor(high / step + 1e-9)
    return [round(k * step, 6) + 0.0 for k in range(first, last + 1)]


def _axis_label_width(frame: _Frame, step: float, font: int) -> float:
    values = _tick_values(frame.y_min, frame.y_max, step)
    return max(text_width(f"{v:g}", font) for v in values) if values else 0.0


def _axes(frame: _Frame, step: float, font: int, tick: float) -> list[Primitive]:
    """Ticks every `step` metres under the plan (x) and left of it (y), labelled in metres of
    the boundary's frame, the frame positions, connections and hints are written in."""
    left, bottom = frame.px(frame.x_min, frame.y_min)
    right, top = frame.px(frame.x_max, frame.y_max)
    gap = max(2.0, tick / 2)
    base_y, base_x = bottom + gap, left - gap
    items: list[Primitive] = [
        Line(((left, base_y), (right, base_y)), AXIS, 1, tag="axis x"),
        Line(((base_x, top), (base_x, bottom)), AXIS, 1, tag="axis y"),
    ]
    for value in _tick_values(frame.x_min, frame.x_max, step):
        x, _ = frame.px(value, 0.0)
        items.append(Line(((x, base_y), (x, base_y + tick)), AXIS, 1, tag="axis x"))
        items.append(Text(x, base_y + tick + 2, f"{value:g}", font, AXIS, "mt", tag="axis x"))
    for value in _tick_values(frame.y_min, frame.y_max, step):
        _, y = frame.px(0.0, value)
        items.append(Line(((base_x - tick, y), (base_x, y)), AXIS, 1, tag="axis y"))
        items.append(Text(base_x - tick - 2, y, f"{value:g}", font, AXIS, "rm", tag="axis y"))
    items.append(Text(right, base_y + tick + 2 + font * LINE_HEIGHT, "x (m)", font, AXIS, "rt", tag="axis x"))
    caption_x = base_x - tick - 2 - _axis_label_width(frame, step, font) - font * 0.8
    items.append(Text(caption_x, (top + bottom) / 2, "y (m)", font, AXIS, "mm", angle=90, tag="axis y"))
    return items


def _robot(x: float, y: float, radius: float, tag: str) -> list[Primitive]:
    """A disc at the robot's position with an arrow along its heading (+x: Stage's and
    MuJoCo's yaw 0), long enough to stick out of the disc."""
    tip = x + radius * 1.9
    return [
        Circle(x, y, radius, ROBOT_FILL, ROBOT_OUTLINE, max(1, round(radius / 6)), tag=tag),
        Line(((x, y), (tip - radius * 0.5, y)), ROBOT_FILL, max(2, round(radius / 3)), tag=tag),
        Polygon(((tip, y), (tip - radius * 0.7, y - radius * 0.45), (tip - radius * 0.7, y + radius * 0.45)),
                ROBOT_FILL, tag=tag),
    ]  # fmt: skip


def area_text(room: PlacedRoom) -> str:
    """A room's floor area as the drawing writes it (both rectangles of an L-room)."""
    return f"{room.area:.1f} m²"


def status_text(layout: Layout) -> str:
    """The seed and solve status the layout records (`solve` in layout.json)."""
    if layout.solve is None:
        return "no solve record (seed and status unknown)"
    return f"seed {layout.solve.seed} · status {layout.solve.status}"


def drawing(layout: Layout, px_per_m: float | None = None, robot_room: str | None = None) -> Drawing:
    """The drawing's primitives for a layout (pixel coordinates, y down); `robot_room` is
    where the simulated robot starts, as for the Stage and MuJoCo emitters."""
    scale = float(px_per_m) if px_per_m else float(choose_scale(layout))
    base_font = int(max(MIN_FONT + 2, min(28, scale * 0.45)))
    margin = float(base_font * 2)
    tick_font = max(MIN_FONT, base_font - 3)
    tick = max(4.0, tick_font * 0.5)
    step = _nice_step(TICK_SPACING_PX / scale)
    # room on the left for the y ticks' numbers, below the plan for the x ticks'
    probe = _Frame(layout, scale, 0.0, 0.0)
    axis_w = tick * 1.5 + 4 + _axis_label_width(probe, step, tick_font) + tick_font * 1.6
    axis_h = tick * 1.5 + 4 + tick_font * LINE_HEIGHT * 2
    frame = _Frame(layout, scale, margin + axis_w, margin)
    wall = max(layout.walldim, 0.05)
    wall_px = max(2, round(wall * scale))
    plan_w = (frame.x_max - frame.x_min) * scale
    plan_h = (frame.y_max - frame.y_min) * scale

    items: list[Primitive] = []
    title_font = base_font + 2
    items.append(Text(margin, margin / 2, layout.name, title_font, TEXT, "lm", tag="title"))
    # the seed and status on the title's line, flush with the plan's right edge when the
    # title leaves room for it
    status = status_text(layout)
    plan_right = frame.left + (frame.x_max - frame.x_min) * scale
    status_right = max(plan_right, margin + text_width(layout.name, title_font) + base_font + text_width(status, base_font))
    items.append(Text(status_right, margin / 2, status, base_font, AXIS, "rm", tag="status"))
    # the boundary the rooms had to fit in, dashed: empty space inside it is not a room
    bx0, by0 = frame.px(0.0, layout.height)
    bx1, by1 = frame.px(layout.width, 0.0)
    items.append(Line(((bx0, by0), (bx1, by0), (bx1, by1), (bx0, by1), (bx0, by0)), BOUNDARY, 1, (8.0, 6.0), tag="boundary"))
    # walls: each room grown by a wall thickness, then the interiors painted over them, so
    # shared walls are exactly the gap between rooms and outer walls are one wall thick; an
    # L-room is its two rectangles, painted over each other's walls, so no wall is inside it
    for room in layout.parts():
        items.append(frame.rect(room.x - wall, room.y - wall, room.x2 + wall, room.y2 + wall, fill=WALL, tag=f"wall {room.id}"))
    for room in layout.parts():
        items.append(frame.rect(room.x, room.y, room.x2, room.y2, fill=ROOM_TINTS.get(room.rtype, ROOM_TINTS["R"]), tag=f"room {room.id}"))
    for obstacle in layout.obstacles:
        tag = f"obstacle {obstacle.id}"
        box = frame.rect(obstacle.x, obstacle.y, obstacle.x + obstacle.w, obstacle.y + obstacle.h, fill=OBSTACLE_FILL, outline=WALL, width=1, tag=tag)
        items.append(box)
        items.extend(_hatch(box, max(6.0, scale * 0.3), tag))
    for portal in layout.portals:
        items.extend(_portal_primitives(layout, portal, frame, wall_px))
    items.extend(_axes(frame, step, tick_font, tick))

    start = robot_start_room(layout, robot_room)
    robot_x, robot_y = frame.px(*start.centre)
    robot_r = max(5.0, ROBOT_RADIUS_M * scale)
    for placed in layout.rooms:
        # the label goes in the larger rectangle, the one whose centre PlacedRoom.centre (and
        # so the robot's start) is: the same tie-break when both are as large
        room = max(placed.parts, key=lambda part: (part.w * part.h, -part.x, -part.y))
        left, top = frame.px(room.x, room.y2)
        right, bottom = frame.px(room.x2, room.y)
        below: tuple[float, float] | None = None
        if placed.id == start.id:
            # the robot stands at the centre of this rectangle: the text goes above it, and
            # the area below it when it does not fit above
            gap = base_font * 0.3
            above = robot_y - robot_r - gap - top
            if above >= MIN_FONT * LINE_HEIGHT * 2:
                below = (robot_y + robot_r + gap, bottom)
                bottom = top + above
        size, lines, rotated = _fit_label(room, right - left, bottom - top, base_font)
        area = area_text(placed)
        has_area = _fits([*lines, area], size, right - left, bottom - top, rotated)
        if has_area:
            lines = [*lines, area]
        elif below is not None and _fits([area], size, right - left, below[1] - below[0], False):
            items.append(Text((left + right) / 2, (below[0] + below[1]) / 2, area, size, tag=f"area {room.id}"))
        cx, cy = (left + right) / 2, (top + bottom) / 2
        line_h = size * LINE_HEIGHT
        first = -line_h * (len(lines) - 1) / 2
        for index, line in enumerate(lines):
            offset = first + index * line_h
            tag = f"area {room.id}" if has_area and index == len(lines) - 1 else f"label {room.id}"
            if rotated:  # reading upwards, so the first line is the leftmost
                items.append(Text(cx + offset, cy, line, size, angle=90, tag=tag))
            else:
                items.append(Text(cx, cy + offset, line, size, tag=tag))
    items.extend(_robot(robot_x, robot_y, robot_r, f"robot {start.id}"))

    legend_top = frame.top + plan_h + axis_h
    legend_items, legend_w, legend_h = _legend(layout, margin, legend_top, base_font, scale, max(plan_w + axis_w, 600.0))
    items.extend(legend_items)
    width = math.ceil(max(margin + axis_w + plan_w, margin + legend_w, status_right) + margin)
    height = math.ceil(legend_top + legend_h + margin / 2)
    return Drawing(width=width, height=height, background=BACKGROUND, px_per_m=scale, items=tuple(items))


def _fits(lines: list[str], size: int, box_w: float, box_h: float, rotated: bool) -> bool:
    """Do these lines fit the box at this size (as `_fit_in` measures), turned or not?"""
    along, across = (box_h, box_w) if rotated else (box_w, box_h)
    widest = max(text_width(line, size) for line in lines)
    return widest <= along * 0.92 and len(lines) * size * LINE_HEIGHT <= across * 0.92


# ----------------------------------------------------------------------------- rendering


@cache
def _font(size: int) -> ImageFont.ImageFont | ImageFont.FreeTypeFont:
    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow < 10.1 has only the fixed bitmap font
        return ImageFont.load_default()


def _dashed(points: tuple[tuple[float, float], ...], on: float, off: float) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    """Split a polyline into its dash segments."""
    dashes = []
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        length = math.hypot(x1 - x0, y1 - y0)
        if length == 0:
            continue
        ux, uy = (x1 - x0) / length, (y1 - y0) / length
        t = 0.0
        while t < length:
            end = min(length, t + on)
            dashes.append(((x0 + ux * t, y0 + uy * t), (x0 + ux * end, y0 + uy * end)))
            t = end + off
    return dashes


SUPERSCRIPT_TWO = "²"


def _text(draw: ImageDraw.ImageDraw, xy: tuple[float, float], text: str, size: int, color: str, anchor: str) -> None:
    """Draw text; a final `²` (areas: `m²`), which Pillow's default font has no glyph for,
    is drawn as a smaller raised `2`."""
    font = _font(size)
    if not text.endswith(SUPERSCRIPT_TWO):
        draw.text(xy, text, fill=color, font=font, anchor=anchor)
        return
    body, small = text[:-1], _font(max(6, round(size * 0.65)))
    body_w, two_w = font.getlength(body), small.getlength("2")
    x, y = xy
    # where the whole text's left edge and middle line are, from its anchor
    left = {"l": x, "m": x - (body_w + two_w) / 2, "r": x - body_w - two_w}[anchor[0]]
    middle = {"m": y, "t": y + size / 2, "b": y - size / 2, "s": y - size * 0.35}.get(anchor[1], y)
    draw.text((left, middle), body, fill=color, font=font, anchor="lm")
    draw.text((left + body_w, middle - size * 0.3), "2", fill=color, font=small, anchor="lm")


def _draw_turned_text(image: Image.Image, item: Text) -> None:
    """Draw rotated text: render it upright on a transparent tile, turn it, paste it."""
    font = _font(item.size)
    left, top, right, bottom = font.getbbox(item.text, anchor="mm")
    pad = 2
    tile = Image.new("RGBA", (int(right - left) + 2 * pad, int(bottom - top) + 2 * pad), (0, 0, 0, 0))
    _text(ImageDraw.Draw(tile), (tile.width / 2, tile.height / 2), item.text, item.size, item.color, "mm")
    turned = tile.rotate(item.angle, expand=True)
    image.paste(turned, (round(item.x - turned.width / 2), round(item.y - turned.height / 2)), turned)


def render_png(picture: Drawing) -> bytes:
    """Paint a drawing with Pillow and return PNG bytes."""
    image = Image.new("RGB", (picture.width, picture.height), picture.background)
    draw = ImageDraw.Draw(image)
    for item in picture.items:
        if isinstance(item, Rect):
            box = (min(item.x0, item.x1), min(item.y0, item.y1), max(item.x0, item.x1), max(item.y0, item.y1))
            draw.rectangle(box, fill=item.fill, outline=item.outline, width=item.width)
        elif isinstance(item, Circle):
            box = (item.x - item.r, item.y - item.r, item.x + item.r, item.y + item.r)
            draw.ellipse(box, fill=item.fill, outline=item.outline, width=item.width)
        elif isinstance(item, Polygon):
            draw.polygon(list(item.points), fill=item.fill)
        elif isinstance(item, Line):
            if item.dash is None:
                draw.line(list(item.points), fill=item.color, width=item.width)
            else:
                for start, end in _dashed(item.points, *item.dash):
                    draw.line([start, end], fill=item.color, width=item.width)
        elif item.angle == 0:
            _text(draw, (item.x, item.y), item.text, item.size, item.color, item.anchor)
        else:
            _draw_turned_text(image, item)
    buffer = io.BytesIO()
    image.save(buffer, format="PNG", optimize=False)
    return buffer.getvalue()


def render(layout: Layout, stem: str, *, robot_room: str | None = None, **_options: object) -> dict[str, bytes]:
    """File name -> content for the PNG emitter: `stem.png`."""
    return {f"{stem}.png": render_png(drawing(layout, robot_room=robot_room))}
