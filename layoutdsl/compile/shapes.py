"""How a room becomes an L: the arm compile gives a corridor-like room.

Two callers: `structure.with_l_rooms` gives one corridor-like room of every four rooms
joined pairwise an L before the generator runs (structure.py says why), and the generator
turns a corridor of each door between two corridors that its best arrangement still leaves
unmet (`with_turns`, `turned_geometry`): on school graphs such corridors are mostly kept
apart by a row of rooms, which a corridor that turns a corner reaches round. Either way the
room's area is shared between its box (BOX_SHARE of its long side) and an arm across it
(ARM_SHARE).
"""

from __future__ import annotations

from dataclasses import replace

from layoutdsl.compile.graph import room_graph
from layoutdsl.layout.geometry import Rect, RoomSizes
from layoutdsl.syntax.ast import ARM_SUFFIX, Arm, Room, Spec, arm_id

BOX_SHARE = 0.7
ARM_SHARE = 0.4
"""Shares of a corridor-like room's long side (targets and bounds) its box keeps and its
new arm gets when it becomes an L: 110 % of its length in all."""


def with_turns(spec: Spec, doors) -> tuple[Spec, list[str]]:
    """The spec with, for each of `doors` (room, room; an arm by its arm id) between two
    corridor-like rooms neither of which is L-shaped yet, one of them made an L, and the
    rooms made so (`with_corridor_arms`). A door with a room that is no corridor turns
    nothing: the room can move to its corridor; two corridors may need a turn."""
    pairs = [(a.removesuffix(ARM_SUFFIX), b.removesuffix(ARM_SUFFIX)) for a, b in doors]
    return with_corridor_arms(spec, pairs, corridors_needed=2)


def with_corridor_arms(spec: Spec, groups, corridors_needed: int = 1,
                       longest: bool = False) -> tuple[Spec, list[str]]:
    """The spec with, for each group of rooms none of which is L-shaped yet (nor made so for
    an earlier group) and at least `corridors_needed` of which are corridor-like, one of its
    corridor-like rooms made an L: the one with the most doors (`longest`: the one with the
    longest target side first), then the first in spec order. Also the rooms made so."""
    graph = room_graph(spec)
    rooms = {room.id: room for room in spec.rooms}
    order = {room_id: index for index, room_id in enumerate(rooms)}
    armed = {arm.room for arm in spec.arms}
    made: list[str] = []
    for group in groups:
        if armed & set(group):
            continue  # an earlier group's L already covers this one
        corridors = [r for r in group if r in rooms and rooms[r].rtype == "C"]
        if len(corridors) < max(1, corridors_needed):
            continue
        chosen = max(corridors, key=lambda r: (RoomSizes.of(rooms[r]).target_long if longest else 0.0,
                                               graph.degree(r), -order[r]))
        armed.add(chosen)
        made.append(chosen)
    return with_arms(spec, made), made


def turned_geometry(geometry: dict[str, Rect], made: list[str], doors) -> dict[str, Rect]:
    """The geometry (of a drawn spec) with each room of `made` split into an L: its box
    BOX_SHARE of its long side, at the end nearer the room of its first door in `doors`
    ((room, room, metres)), and an arm ARM_SHARE long across that end, towards that room."""
    turned = dict(geometry)
    for room_id in made:
        x, y, w, h = geometry[room_id]
        other = next((b if a == room_id else a for a, b, _m in doors if room_id in (a, b)), None)
        other = other.removesuffix(ARM_SUFFIX) if other is not None else None
        towards_x, towards_y = x + w / 2, y + h / 2
        if other in geometry:
            ox, oy, ow, oh = geometry[other]
            towards_x, towards_y = ox + ow / 2, oy + oh / 2
        if w >= h:
            box_w, arm_long = w * BOX_SHARE, w * ARM_SHARE
            at_right = towards_x >= x + w / 2
            box_x = x if at_right else x + w - box_w
            turned[room_id] = (box_x, y, box_w, h)
            turned[arm_id(room_id)] = (box_x + box_w - h if at_right else box_x,
                                       y + h if towards_y >= y + h / 2 else y - arm_long, h, arm_long)
        else:
            box_h, arm_long = h * BOX_SHARE, h * ARM_SHARE
            at_top = towards_y >= y + h / 2
            box_y = y if at_top else y + h - box_h
            turned[room_id] = (x, box_y, w, box_h)
            turned[arm_id(room_id)] = (x + w if towards_x >= x + w / 2 else x - arm_long,
                                       box_y + box_h - w if at_top else box_y, arm_long, w)
    return turned


def with_arms(spec: Spec, made) -> Spec:
    """The spec with each of the rooms `made` (corridor-like, not L-shaped yet) an L."""
    if not made:
        return spec
    new_rooms, arms = [], list(spec.arms)
    for room in spec.rooms:
        if room.id in made:
            box, arm = _split_into_l(room)
            new_rooms.append(box)
            arms.append(arm)
        else:
            new_rooms.append(room)
    return replace(spec, rooms=tuple(new_rooms), arms=tuple(arms))


def _split_into_l(room: Room) -> tuple[Room, Arm]:
    """The room's box (its long side shortened to BOX_SHARE) and an arm across it, as wide
    as the room and ARM_SHARE of its long side long."""
    wide = room.target_w >= room.target_h
    if wide:
        box = replace(room, min_w=room.min_w * BOX_SHARE, max_w=room.max_w * BOX_SHARE,
                      target_w=room.target_w * BOX_SHARE)
        arm = Arm(room.id, room.min_h, room.max_h, room.target_h, room.min_w * ARM_SHARE,
                  room.max_w * ARM_SHARE, room.target_w * ARM_SHARE, 1.0, 1e3)
    else:
        box = replace(room, min_h=room.min_h * BOX_SHARE, max_h=room.max_h * BOX_SHARE,
                      target_h=room.target_h * BOX_SHARE)
        arm = Arm(room.id, room.min_h * ARM_SHARE, room.max_h * ARM_SHARE, room.target_h * ARM_SHARE,
                  room.min_w, room.max_w, room.target_w, 1.0, 1e3)
    return box, arm
