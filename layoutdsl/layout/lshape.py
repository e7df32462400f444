"""L-shaped rooms in the construction: each L is two boxes joined flush at a corner.

The relation model of the construction (construct.py) places rectangles. An L-room (a room
with an `arms` line) enters it as two: the room's own box (id `room`) and its arm's
(`arm_id(room)`), sized by their own bounds. Instead of being kept a wall apart like any
other pair, the two are *joined*: flush along one axis, aligned at one end of the other, so
that their union is an L with no wall inside (the thesis' future work, §7: rooms made of
several rectangles). A join's option names where the room's box lies relative to its arm
and which end they align at, e.g. `below:lo` (the box is below the arm, left edges flush).

Which box realises an adjacency of the L is read off each seed geometry, like every other
relation: the box nearer to meeting the neighbour. The generator draws an L-room's arm as a
room of its own hung off the box (`seeds_spec`), so it keeps space for it; `seed_arms` then
joins the arm to the box where it overlaps and misses least, nearest where it was drawn.
"""

from __future__ import annotations

import math
import random
from dataclasses import replace

from layoutdsl.layout.geometry import SIDES, Rect, separations
from layoutdsl.syntax.ast import Adjacency, Hint, Spec, arm_id

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
    """The arm's (w, h) in the orientations its L allows beside `room_box`: its target,
    scaled as the box is against the room's target when the box is drawn smaller (the
    generator draws rooms shrunk to leave the repair space; an arm at full size would take
    the space the shrinking left), never below the arm's minimum sides."""
    scale = min(1.0, math.sqrt(room_box[2] * room_box[3] / max(room.target_w * room.target_h, 1e-9)))
    lo_long, lo_short = max(arm.min_w, arm.min_h), min(arm.min_w, arm.min_h)
    long_side = max(lo_long, scale * max(arm.target_w, arm.target_h))
    short_side = max(lo_short, scale * min(arm.target_w, arm.target_h))
    crosses = arm.crosses(room)
    if crosses is None or long_side == short_side:
        return [(long_side, short_side), (short_side, long_side)]
    box_long_x = room_box[2] >= room_box[3]
    return [(long_side, short_side) if box_long_x != crosses else (short_side, long_side)]


def _drawn_first(sizes: list[tuple[float, float]], drawn: Rect | None) -> list[tuple[float, float]]:
    """The arm's sizes to try: the size the generator drew it at first (it packed the arm
    at that size against its neighbours, so an arm moved at its target size would overlap
    them), when the L allows that orientation."""
    if drawn is None:
        return sizes
    drawn_size = (drawn[2], drawn[3])
    allowed = {size[0] >= size[1] for size in sizes}
    return [drawn_size, *sizes] if (drawn_size[0] >= drawn_size[1]) in allowed else sizes


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
    walldim, utilization = spec.settings.walldim, spec.settings.door_utilization
    adjacencies = tuple(_nearer_boxes(adj, armed, geometry, walldim, adj.door / utilization)
                        for adj in spec.adjacencies)
    joins = frozenset((room_id, arm_id(room_id)) for room_id in armed)
    return replace(spec, rooms=tuple(rooms), adjacencies=adjacencies, arms=()), joins


def seeds_spec(spec: Spec) -> Spec:
    """The spec the seed geometries are drawn for: each L-room's arm a room of its own,
    hung off the room's box by a door as wide as the arm's narrow side at its least.

    So the generator (layoutdsl.compile.generator) packs the arm with the rest, and counts
    its area when it decides how tightly to pack; an arm added afterwards beside a box whose
    sides the neighbours already took overlaps them (measured: most of the extra repair
    rounds of L-specs, issue 14). `seed_arms` then joins each arm to its box nearest where
    it was drawn. With hints, each arm's hint is where `seed_arms` puts it beside its room's
    hint (the arm's place in the original plan is not in the spec).
    """
    rooms_by_id = {room.id: room for room in spec.rooms}
    armed = {arm.room: arm for arm in spec.arms if arm.room in rooms_by_id}
    if not armed:
        return spec
    rooms, joins = [], []
    utilization = spec.settings.door_utilization
    for room in spec.rooms:
        rooms.append(room)
        if room.id in armed:
            arm = armed[room.id]
            rooms.append(arm.as_room(room))
            narrow = min(arm.min_w, arm.min_h)
            joins.append(Adjacency(room.id, arm_id(room.id), utilization * narrow, "i"))
    hints = spec.hints
    hinted = {hint.room: hint for hint in hints}
    if hints and all(room.id in hinted for room in spec.rooms):
        boxes = {h.room: (h.x, h.y, h.w, h.h) for h in hints}
        seeded = seed_arms(spec, boxes, random.Random(0), hints=True)
        hints = hints + tuple(Hint(arm_id(room_id), *seeded[arm_id(room_id)]) for room_id in armed)
    return replace(spec, rooms=tuple(rooms), adjacencies=spec.adjacencies + tuple(joins),
                   hints=hints, arms=())


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


def _nearer_boxes(adj: Adjacency, armed, geometry: dict[str, Rect], walldim: float,
                  wall: float) -> Adjacency:
    """The adjacency between the two boxes of its rooms that come nearest in `geometry` to
    meeting as its door needs (a wall apart, sharing `wall` m), then that lie nearest: a
    box overlapping the neighbour is no nearer to a door than one a wall away."""
    if adj.a not in armed and adj.b not in armed:
        return adj
    choices = [(a, b) for a in _boxes_of(adj.a, armed) for b in _boxes_of(adj.b, armed)
               if a in geometry and b in geometry]
    if not choices:
        return adj

    def key(pair):
        first, second = geometry[pair[0]], geometry[pair[1]]
        return (round(contact_shortfall(first, second, walldim, wall), 6), box_distance(first, second))
    a, b = min(choices, key=key)
    return replace(adj, a=a, b=b)


def box_distance(a: Rect, b: Rect) -> float:
    """How far apart two boxes are (the larger of the x and y gaps; negative: overlapping),
    less a bonus for the length they face each other along, so of two boxes touching a
    neighbour the one sharing more wall wins."""
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    gap_x, gap_y = separations(a, b)
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


def seed_arms(spec: Spec, geometry: dict[str, Rect], rng: random.Random, *,
              hints: bool = False) -> dict[str, Rect]:
    """The geometry with every L-room's arm joined to its box: at the size the geometry drew
    it, if it did, or at its target size (see arm_sizes), in the orientations its L allows,
    where it overlaps the other boxes, leaves the boundary and misses the L-room's
    neighbours least, and lies against other rooms most; of equal places, the one nearest
    where the geometry drew the arm, if it did (the generator draws it as a room of its own,
    seeds_spec, a wall from its box, maybe turned the way the L forbids); then one drawn
    from `rng`.

    Overlap counts as a geometry's rooms meet: in a generated geometry neighbours lie a wall
    apart, so an arm closer than a wall to a room overlaps it; in a hint geometry (`hints`:
    the original plan's boxes) neighbours overlap by about a wall, which is no conflict.
    """
    boundary = spec.boundary
    assert boundary is not None
    walldim = spec.settings.walldim
    # how deep the arm may overlap another box before it is a conflict
    allowance = walldim if hints else -(walldim - 1e-6)
    outside = (-boundary.w, -boundary.h, 3 * boundary.w, 3 * boundary.h)
    inside = (0.0, 0.0, boundary.w, boundary.h)
    seeded = dict(geometry)
    rooms = {room.id: room for room in spec.rooms}
    walls = _walls(spec)
    for arm in spec.arms:
        key = arm_id(arm.room)
        drawn = seeded.pop(key, None)
        if arm.room not in seeded:
            continue
        room_box = seeded[arm.room]
        others = [box for other, box in seeded.items() if other != arm.room]
        # the L-room's neighbours the box does not meet yet: the arm may meet them instead
        # (with hints, the arm's own place in the original plan is where it meets them)
        missed = [(seeded[other], wall) for other, wall in walls.get(arm.room, ())
                  if other in seeded and contact_shortfall(room_box, seeded[other], walldim, wall) > 0]
        best = None
        sizes = _drawn_first(arm_sizes(arm, rooms[arm.room], room_box), drawn)
        for option in JOIN_OPTIONS:
            for size in sizes:
                box = joined_box(room_box, size, option)
                out = _overlap(box, outside) - _overlap(box, inside)
                core = (box[0] + allowance, box[1] + allowance, box[2] - 2 * allowance, box[3] - 2 * allowance)
                score = sum(_overlap(core, other) for other in others) + 2.0 * out
                # lying against other rooms rather than in open space: in a hint geometry,
                # where the arm was in the original plan
                score -= TOUCH_BONUS * sum(_touching(box, other, walldim) for other in others)
                score += CONTACT_COST * sum(
                    min(contact_shortfall(room_box, other, walldim, wall),
                        contact_shortfall(box, other, walldim, wall))
                    for other, wall in missed)
                # an L's arms meet at their ends: the arm's short side on the room's box
                # (a corridor turning a corner), not its long side (a wider corridor)
                shares_long_side = (option.split(":")[0] in ("below", "above")) == (size[0] > size[1])
                score += LONG_SIDE_JOIN_COST * shares_long_side
                if drawn is not None:
                    score += DRAWN_COST * math.dist(_centre(box), _centre(drawn))
                candidate = (round(score, 9), rng.random(), box)
                if best is None or candidate[:2] < best[:2]:
                    best = candidate
        assert best is not None
        seeded[key] = best[2]
    return seeded


CONTACT_COST = 1.0
"""Score (m² of overlap) a seed arm pays per metre an L-room's neighbour is from meeting
the L (neither box touching it with its door's wall)."""


DRAWN_COST = 0.1
"""Score (m² of overlap) a seed arm pays per metre its centre lies from the arm drawn by
the generator: the space kept free for it."""


def _centre(box: Rect) -> tuple[float, float]:
    return (box[0] + box[2] / 2, box[1] + box[3] / 2)


TOUCH_BONUS = 0.05
"""Score (m² of overlap) a seed arm gains per metre of its sides that lie against another
room: less than any real overlap, more than nothing."""


def _touching(a: Rect, b: Rect, walldim: float) -> float:
    """Length along which two boxes lie against each other (a gap of at most a wall and a
    half, or an overlap of at most a wall)."""
    gap_x, gap_y = separations(a, b)
    if -walldim <= gap_x <= 1.5 * walldim and gap_y < 0:
        return -gap_y
    if -walldim <= gap_y <= 1.5 * walldim and gap_x < 0:
        return -gap_x
    return 0.0


def _walls(spec: Spec) -> dict[str, list[tuple[str, float]]]:
    """Room id -> (neighbour, wall length its door needs) for each of its adjacencies."""
    walls: dict[str, list[tuple[str, float]]] = {}
    for adj in spec.adjacencies:
        wall = adj.door / spec.settings.door_utilization
        walls.setdefault(adj.a, []).append((adj.b, wall))
        walls.setdefault(adj.b, []).append((adj.a, wall))
    return walls


def contact_shortfall(a: Rect, b: Rect, walldim: float, wall: float) -> float:
    """Metres two boxes are from touching with one wall between them and `wall` m of it
    shared (0: they do)."""
    gap_x, gap_y = separations(a, b)
    along_x = abs(gap_x - walldim) + max(0.0, wall + gap_y)
    along_y = abs(gap_y - walldim) + max(0.0, wall + gap_x)
    return max(0.0, min(along_x, along_y) - 1e-6)

