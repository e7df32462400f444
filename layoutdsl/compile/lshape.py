"""L-shaped rooms in the construction: each L is two boxes joined flush at a corner.

The relation model of the construction (construct.py) places rectangles. An L-room (a room
with an `arms` line) enters it as two: the room's own box (id `room`) and its arm's
(`arm_id(room)`), sized by their own bounds. Instead of being kept a wall apart like any
other pair, the two are *joined*: flush along one axis, aligned at one end of the other, so
that their union is an L with no wall inside (the thesis' future work, §7: rooms made of
several rectangles). A join's option names where the room's box lies relative to its arm
and which end they align at, e.g. `below:lo` (the box is below the arm, left edges flush).

Which box realises an adjacency of the L is read off each seed geometry, like every other
relation: the box nearer the neighbour. The generator sizes and places an L-room by its
first box; `seed_arms` then puts the arm beside it where it overlaps least.
"""

from __future__ import annotations

import random
from dataclasses import replace

from layoutdsl.layout.geometry import SIDES, Rect
from layoutdsl.syntax.ast import Adjacency, Spec, arm_id

ENDS = ("lo", "hi")
"""Which ends of the shared side are flush: the low ones (left or bottom edges) or the high."""

JOIN_OPTIONS = tuple(f"{side}:{end}" for side in SIDES for end in ENDS)
"""Every way two boxes can form an L: the room's box on `side` of its arm, flush at `end`."""


LONG_SIDE_JOIN_COST = 0.5
"""Score (m² of overlap) a seed arm pays for meeting the room's box with its long side."""


def crossings(spec: Spec) -> dict[tuple[str, str], bool]:
    """(room box, arm box) -> does the arm run across the box (Arm.crosses), for the L-rooms
    whose lines say so."""
    rooms = {room.id: room for room in spec.rooms}
    found = {}
    for arm in spec.arms:
        if arm.room in rooms and (crosses := arm.crosses(rooms[arm.room])) is not None:
            found[(arm.room, arm_id(arm.room))] = crosses
    return found


def arm_sizes(arm, room, room_box: Rect) -> list[tuple[float, float]]:
    """The arm's target (w, h) in the orientations its L allows beside `room_box`."""
    long_side, short_side = max(arm.target_w, arm.target_h), min(arm.target_w, arm.target_h)
    crosses = arm.crosses(room)
    if crosses is None or long_side == short_side:
        return [(long_side, short_side), (short_side, long_side)]
    box_long_x = room_box[2] >= room_box[3]
    return [(long_side, short_side) if box_long_x != crosses else (short_side, long_side)]


def rooms_only(spec: Spec, rects: dict[str, Rect]) -> dict[str, Rect]:
    """The rectangles of the rooms themselves, without the L-rooms' arms."""
    arms = {arm_id(arm.room) for arm in spec.arms}
    return {key: rect for key, rect in rects.items() if key not in arms} if arms else rects


def boxes_spec(spec: Spec, geometry: dict[str, Rect]) -> tuple[Spec, frozenset[tuple[str, str]]]:
    """The spec as the relation model sees it: one room per box, and the joined pairs.

    Each L-room's arm becomes a room of its own (right after its room, so the pair keeps
    spec order); each adjacency of an L-room goes to its box nearer the other room in
    `geometry`. Positions, connections and clusters stay on the room's own box.
    """
    rooms_by_id = {room.id: room for room in spec.rooms}
    armed = {arm.room: arm for arm in spec.arms if arm.room in rooms_by_id}
    rooms = []
    for room in spec.rooms:
        rooms.append(room)
        if room.id in armed:
            rooms.append(armed[room.id].as_room(room))
    adjacencies = tuple(_nearer_boxes(adj, armed, geometry) for adj in spec.adjacencies)
    joins = frozenset((room_id, arm_id(room_id)) for room_id in armed)
    return replace(spec, rooms=tuple(rooms), adjacencies=adjacencies, arms=()), joins


def beside_pairs(boxes: Spec, joins) -> frozenset[frozenset[str]]:
    """Pairs of boxes of two adjacent rooms, one of them an L, other than the pair that
    realises the adjacency: that pair lies exactly a wall apart, and an L's other box may lie
    on the same line (its outer faces are flush), so it must be kept a wall away exactly,
    not a hair more."""
    partner = {}
    for box, arm in joins:
        partner[box], partner[arm] = arm, box
    def group(box: str) -> tuple[str, ...]:
        return (box, partner[box]) if box in partner else (box,)

    found = set()
    for adj in boxes.adjacencies:
        for first in group(adj.a):
            for second in group(adj.b):
                if (first, second) != (adj.a, adj.b) and first != second:
                    found.add(frozenset((first, second)))
    return frozenset(found)


def _boxes_of(room_id: str, armed) -> tuple[str, ...]:
    return (room_id, arm_id(room_id)) if room_id in armed else (room_id,)


def _nearer_boxes(adj: Adjacency, armed, geometry: dict[str, Rect]) -> Adjacency:
    """The adjacency between the two boxes of its rooms that lie nearest in `geometry`."""
    if adj.a not in armed and adj.b not in armed:
        return adj
    choices = [(a, b) for a in _boxes_of(adj.a, armed) for b in _boxes_of(adj.b, armed)
               if a in geometry and b in geometry]
    if not choices:
        return adj
    a, b = min(choices, key=lambda pair: box_distance(geometry[pair[0]], geometry[pair[1]]))
    return replace(adj, a=a, b=b)


def box_distance(a: Rect, b: Rect) -> float:
    """How far apart two boxes are (the larger of the x and y gaps; negative: overlapping),
    less a bonus for the length they face each other along, so of two boxes touching a
    neighbour the one sharing more wall wins."""
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    gap_x = max(bx - ax - aw, ax - bx - bw)
    gap_y = max(by - ay - ah, ay - by - bh)
    facing = min(ax + aw, bx + bw) - max(ax, bx) if gap_y >= gap_x else min(ay + ah, by + bh) - max(ay, by)
    return max(gap_x, gap_y) - 0.01 * max(0.0, facing)


def join_option(room_box: Rect, arm_box: Rect) -> str:
    """The join option closest to how two boxes lie: the side of the clearer separation,
    the end whose edges are nearer flush."""
    rx, ry, rw, rh = room_box
    ax, ay, aw, ah = arm_box
    gap_x = max(ax - rx - rw, rx - ax - aw)
    gap_y = max(ay - ry - rh, ry - ay - ah)
    if gap_x >= gap_y:
        side = "left" if rx + rw / 2 <= ax + aw / 2 else "right"
        end = "lo" if abs(ry - ay) <= abs(ry + rh - ay - ah) else "hi"
    else:
        side = "below" if ry + rh / 2 <= ay + ah / 2 else "above"
        end = "lo" if abs(rx - ax) <= abs(rx + rw - ax - aw) else "hi"
    return f"{side}:{end}"


def joined_box(room_box: Rect, size: tuple[float, float], option: str) -> Rect:
    """Where an arm of `size` (w, h) lies when joined to the room's box by `option`."""
    x, y, w, h = room_box
    aw, ah = size
    side, end = option.split(":")
    if side in ("left", "right"):
        ax = x + w if side == "left" else x - aw
        ay = y if end == "lo" else y + h - ah
    else:
        ay = y + h if side == "below" else y - ah
        ax = x if end == "lo" else x + w - aw
    return (ax, ay, aw, ah)


def _overlap(a: Rect, b: Rect) -> float:
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    return max(0.0, min(ax + aw, bx + bw) - max(ax, bx)) * max(0.0, min(ay + ah, by + bh) - max(ay, by))


def seed_arms(spec: Spec, geometry: dict[str, Rect], rng: random.Random) -> dict[str, Rect]:
    """The geometry with an arm for every L-room that has none yet: its target size, in
    either orientation, joined to the room's box where it overlaps the other boxes and
    leaves the boundary least (ties drawn from `rng`)."""
    boundary = spec.boundary
    assert boundary is not None
    outside = (-boundary.w, -boundary.h, 3 * boundary.w, 3 * boundary.h)
    inside = (0.0, 0.0, boundary.w, boundary.h)
    seeded = dict(geometry)
    rooms = {room.id: room for room in spec.rooms}
    for arm in spec.arms:
        key = arm_id(arm.room)
        if key in seeded or arm.room not in seeded:
            continue
        room_box = seeded[arm.room]
        others = [box for other, box in seeded.items() if other != arm.room]
        best = None
        for option in JOIN_OPTIONS:
            for size in arm_sizes(arm, rooms[arm.room], room_box):
                box = joined_box(room_box, size, option)
                out = _overlap(box, outside) - _overlap(box, inside)
                score = sum(_overlap(box, other) for other in others) + 2.0 * out
                # an L's arms meet at their ends: the arm's short side on the room's box
                # (a corridor turning a corner), not its long side (a wider corridor)
                shares_long_side = (option.split(":")[0] in ("below", "above")) == (size[0] > size[1])
                score += LONG_SIDE_JOIN_COST * shares_long_side
                candidate = (round(score, 9), rng.random(), box)
                if best is None or candidate[:2] < best[:2]:
                    best = candidate
        assert best is not None
        seeded[key] = best[2]
    return seeded
