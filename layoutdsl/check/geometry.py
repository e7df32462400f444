"""Checks of sizes and places (E2xx, W303, W304): each room, the boundary, doors, points."""

from __future__ import annotations

import math
from collections.abc import Iterator

from layoutdsl.check.common import diag, node_span, pair_span, rooms_by_id
from layoutdsl.diagnostics import Diagnostic, Severity, register
from layoutdsl.diagnostics.source import Span
from layoutdsl.syntax.ast import Room, Spec
from layoutdsl.syntax.format import format_number as _n

# ===== Codes: E2xx geometry =====

E_MIN_OVER_MAX = register(
    "E201", Severity.ERROR, "minimum larger than maximum",
    "Reports a room whose minimum width (height) exceeds its maximum width (height).",
    "No size satisfies both bounds (5.4, 5.5): the spec is infeasible.",
    "R0 8 4 6 6 10 8 1 1.7 R CLASSROOM    # minw 8 > maxw 4",
)  # fmt: skip
E_TARGET_OUTSIDE = register(
    "E202", Severity.ERROR, "target outside its bounds",
    "Reports a target width (height) outside [min, max].",
    "The objective pulls the room toward a size it may not take; usually a typo or swapped column.",
    "R0 4 8 9 6 10 8 1 1.7 R CLASSROOM    # targetw 9 > maxw 8",
)  # fmt: skip
E_AR_ORDER = register(
    "E203", Severity.ERROR, "minimum aspect ratio larger than maximum",
    "Reports minar > maxar.",
    "No aspect ratio satisfies both bounds (5.6).",
    "R0 4 8 6 6 10 8 2 1.5 R CLASSROOM",
)  # fmt: skip
E_AR_BELOW_ONE = register(
    "E204", Severity.ERROR, "aspect ratio below 1",
    "Reports minar < 1 (or maxar < 1).",
    "The aspect ratio is long side / short side, so it is at least 1; a smaller bound is a mistake.",
    "R0 4 8 6 6 10 8 0.5 1.7 R CLASSROOM",
)  # fmt: skip
E_AR_UNSATISFIABLE = register(
    "E205", Severity.ERROR, "size bounds admit no allowed aspect ratio",
    "Reports a room (not a corridor) whose width and height bounds allow no rectangle with an "
    "aspect ratio in [minar, maxar].",
    "Every constraint is fine alone but together they are infeasible (5.4-5.6).",
    "R0 2 3 2.5 10 12 11 1 1.5 R CLOSET    # at least 10/3 = 3.3 long, maxar 1.5",
)  # fmt: skip
E_ROOM_TOO_BIG = register(
    "E206", Severity.ERROR, "room cannot fit in the boundary",
    "Reports a room whose minimum size does not fit in the boundary in either orientation.",
    "Rooms must lie inside the boundary (5.7).",
    "boundary\n10 10\n... R0 12 14 13 4 6 5 1 3.5 R HALL",
)  # fmt: skip
E_AREA_TOO_BIG = register(
    "E207", Severity.ERROR, "rooms larger than the free boundary area",
    "Reports a spec whose rooms' minimum areas add up to more than the boundary's area minus "
    "its obstacles.",
    "Rooms cannot overlap (5.8), so they cannot all fit.",
    "boundary\n10 10     # but the rooms need at least 120 m²",
)  # fmt: skip
E_DOOR_TOO_WIDE = register(
    "E208", Severity.ERROR, "door cannot fit on either room",
    "Reports an adjacency whose required shared wall (door / door_utilization) is longer than "
    "the longest side one of its rooms can have.",
    "The rooms must share a wall at least that long (5.9), so the spec is infeasible.",
    "adjacencies\nR7 C2 3.5 e     # R7 is at most 3 m long",
)  # fmt: skip
E_POSITION_OUTSIDE = register(
    "E209", Severity.ERROR, "position outside the boundary",
    "Reports a `positions` point outside the boundary.",
    "The room must cover the point (5.10) and lie inside the boundary (5.7): infeasible.",
    "boundary\n20 50\n\npositions\nR0 25 3",
)  # fmt: skip
E_POSITION_IN_OBSTACLE = register(
    "E210", Severity.ERROR, "position inside an obstacle",
    "Reports a `positions` point strictly inside an obstacle.",
    "A room covering the point would overlap the obstacle (5.8, 5.10): infeasible.",
    "boundary\n20 50\nO1 0 0 5 5\n\npositions\nR0 2 2",
)  # fmt: skip
E_CONNECTION_OUTSIDE = register(
    "E211", Severity.ERROR, "connection point outside the boundary",
    "Reports a `connections` point outside the boundary.",
    "The room must cover both points (5.11) inside the boundary: infeasible.",
    "connections\nC3 1 1 1 60     # boundary is 50 m high",
)  # fmt: skip
E_CONNECTION_IN_OBSTACLE = register(
    "E212", Severity.ERROR, "connection point inside an obstacle",
    "Reports a `connections` point strictly inside an obstacle.",
    "A room covering the point would overlap the obstacle: infeasible.",
    "boundary\n20 50\nO1 0 0 5 5\n\nconnections\nC3 2 2 2 20",
)  # fmt: skip
E_OBSTACLE_OUTSIDE = register(
    "E213", Severity.ERROR, "obstacle leaves the boundary",
    "Reports an obstacle that is not entirely inside the boundary.",
    "Obstacles are parts of the floor that rooms avoid; one outside it is almost surely a typo.",
    "boundary\n20 50\nO1 18 0 5 5",
)  # fmt: skip
E_OBSTACLES_OVERLAP = register(
    "E214", Severity.ERROR, "obstacles overlap",
    "Reports two obstacles whose interiors overlap.",
    "Overlapping obstacles usually mean a wrong coordinate, and they make the free area wrong.",
    "boundary\n20 50\nO1 0 0 5 5\nO2 4 4 5 5",
)  # fmt: skip
E_NOT_POSITIVE = register(
    "E216", Severity.ERROR, "size must be positive",
    "Reports a zero or negative length: a room's minimum size, the boundary, an obstacle, a "
    "door or a hint size.",
    "Lengths are metres of real things; zero or less is a typo.",
    "boundary\n0 50",
)  # fmt: skip
E_POINTS_TOO_FAR = register(
    "E217", Severity.ERROR, "connection points farther apart than the room can reach",
    "Reports a connection whose two points cannot both be covered by the room at its maximum size "
    "in either orientation.",
    "The room must cover both points (5.11): infeasible.",
    "connections\nR0 1 1 1 30     # R0 is at most 10 m long",
)  # fmt: skip

E_SHARED_POINT = register(
    "E218", Severity.ERROR, "two rooms must cover the same point",
    "Reports two different rooms whose fixed points (positions or connection points) are "
    "closer than the wall thickness in both x and y.",
    "Rooms are at least `walldim` apart (5.8), so no two rooms can both cover such points.",
    "positions\nR0 3 3\nR1 3.1 3",
)  # fmt: skip
W_HINT_OUTSIDE = register(
    "W303", Severity.WARNING, "hint outside the boundary",
    "Reports a hint rectangle that is not inside the boundary.",
    "Hints only guide the solver, so it is not an error, but such a hint cannot be used as given.",
    "boundary\n20 50\n\nhints\nR0 18 0 5 5",
)  # fmt: skip
W_TARGETS_TOO_BIG = register(
    "W304", Severity.WARNING, "target sizes exceed the free boundary area",
    "Reports a spec whose rooms' target areas add up to more than the boundary's area minus "
    "its obstacles (while their minimum areas still fit).",
    "No layout can reach the targets: every room comes out smaller than asked, and the "
    "solver spends its time trading one room's error against another's.",
    "boundary\n10 10     # but the target rooms cover 120 m²",
)  # fmt: skip


def _room_bounds_ok(room: Room) -> bool:
    """True when the room's own numbers are consistent (what check_room_sizes verifies)."""
    return (
        0 < room.min_w <= room.max_w and 0 < room.min_h <= room.max_h
        and room.min_w <= room.target_w <= room.max_w and room.min_h <= room.target_h <= room.max_h
        and 1 <= room.min_ar <= room.max_ar
    )  # fmt: skip


def reachable_ratios(room: Room) -> tuple[float, float]:
    """The aspect ratios max(w,h)/min(w,h) over w in [minw, maxw], h in [minh, maxh].

    They form an interval: w/h ranges over [minw/maxh, maxw/minh], and the ratio is
    max(w/h, h/w), so the ends come from the rectangle's corners, except that 1 (a square)
    is reachable whenever the two ranges overlap.
    """
    corners = [max(w, h) / min(w, h) for w in (room.min_w, room.max_w) for h in (room.min_h, room.max_h)]
    overlap = max(room.min_w, room.min_h) <= min(room.max_w, room.max_h)
    return (1.0 if overlap else min(corners)), max(corners)


def _aspect_ratio_possible(room: Room) -> bool:
    """Is there w in [minw, maxw], h in [minh, maxh] with max(w,h)/min(w,h) in [minar, maxar]?"""
    lowest, highest = reachable_ratios(room)
    return lowest <= room.max_ar * (1 + 1e-12) and highest >= room.min_ar * (1 - 1e-12)


def check_room_sizes(spec: Spec) -> Iterator[Diagnostic]:
    """E216, E201-E205: each room's sizes and aspect ratios are consistent, and each arm's
    (an L-room's second rectangle is checked as a room of its own)."""
    known = rooms_by_id(spec)
    arms = [arm.as_room(known[arm.room]) for arm in spec.arms if arm.room in known]
    for room in (*spec.rooms, *arms):
        broken = False
        for field, value, name in (("min_w", room.min_w, "minw"), ("min_h", room.min_h, "minh")):
            if value <= 0:
                broken = True
                yield diag(spec, E_NOT_POSITIVE, f"room `{room.id}` has `{name}` {_n(value)}, not positive",
                            node_span(room, field), "must be > 0", "sizes are metres; give a positive minimum")  # fmt: skip
        for axis, lo, hi, target in (("w", room.min_w, room.max_w, room.target_w),
                                     ("h", room.min_h, room.max_h, room.target_h)):  # fmt: skip
            if lo > hi:
                broken = True
                yield diag(spec, E_MIN_OVER_MAX,
                            f"room `{room.id}` has `min{axis}` {_n(lo)} larger than `max{axis}` {_n(hi)}",
                            node_span(room, f"min_{axis}"), f"larger than max{axis}",
                            f"swap min{axis} and max{axis}")  # fmt: skip
            elif not lo <= target <= hi:
                broken = True
                side = "below" if target < lo else "above"
                yield diag(spec, E_TARGET_OUTSIDE,
                            f"room `{room.id}` has `target{axis}` {_n(target)} {side} its bounds [{_n(lo)}, {_n(hi)}]",
                            node_span(room, f"target_{axis}"), f"outside [min{axis}, max{axis}]",
                            f"use a target{axis} between {_n(lo)} and {_n(hi)}")  # fmt: skip
        if room.min_ar < 1 or room.max_ar < 1:
            broken = True
            field = "min_ar" if room.min_ar < 1 else "max_ar"
            value = min(room.min_ar, room.max_ar)
            yield diag(spec, E_AR_BELOW_ONE,
                        f"room `{room.id}` has aspect ratio bound {_n(value)} below 1",
                        node_span(room, field), "must be at least 1",
                        "the aspect ratio is long side / short side; use 1 for a square")  # fmt: skip
        elif room.min_ar > room.max_ar:
            broken = True
            yield diag(spec, E_AR_ORDER,
                        f"room `{room.id}` has `minar` {_n(room.min_ar)} larger than `maxar` {_n(room.max_ar)}",
                        node_span(room, "min_ar"), "larger than maxar", "swap minar and maxar")  # fmt: skip
        if broken or room.is_corridor:
            continue  # corridors have no aspect-ratio constraint (5.6)
        if not _aspect_ratio_possible(room):
            yield diag(spec, E_AR_UNSATISFIABLE,
                        f"room `{room.id}`: no size within its bounds has an aspect ratio in "
                        f"[{_n(room.min_ar)}, {_n(room.max_ar)}]",
                        Span(node_span(room, "min_w").line, node_span(room, "min_w").col,
                             node_span(room, "max_ar").end_line, node_span(room, "max_ar").end_col),
                        "these bounds contradict each other",
                        "widen the aspect-ratio range or the size bounds; "
                        f"sizes allow ratios {_ratio_range(room)}")  # fmt: skip


def _ratio_range(room: Room) -> str:
    lowest, highest = reachable_ratios(room)
    return f"from {lowest:.3g} to {highest:.3g}"


def _obstacle_area_inside(spec: Spec) -> float:
    boundary = spec.boundary
    total = 0.0
    for o in boundary.obstacles:
        w = max(0.0, min(o.x + o.w, boundary.w) - max(o.x, 0.0))
        h = max(0.0, min(o.y + o.h, boundary.h) - max(o.y, 0.0))
        total += w * h
    return total


def check_boundary(spec: Spec) -> Iterator[Diagnostic]:
    """E216, E213, E214: the boundary and its obstacles are sound."""
    boundary = spec.boundary
    if boundary is None:
        return
    for field, value in (("w", boundary.w), ("h", boundary.h)):
        if value <= 0:
            yield diag(spec, E_NOT_POSITIVE, f"boundary {field} is {_n(value)}, not positive",
                        node_span(boundary, field), "must be > 0", "the boundary is `w h` in metres")  # fmt: skip
    valid = []
    for o in boundary.obstacles:
        bad = [f for f, v in (("w", o.w), ("h", o.h)) if v <= 0]
        for field in bad:
            yield diag(spec, E_NOT_POSITIVE, f"obstacle `{o.id}` has {field} {_n(getattr(o, field))}, not positive",
                        node_span(o, field), "must be > 0")  # fmt: skip
        if bad:
            continue
        if boundary.w > 0 and boundary.h > 0 and (
            o.x < 0 or o.y < 0 or o.x + o.w > boundary.w or o.y + o.h > boundary.h
        ):
            yield diag(spec, E_OBSTACLE_OUTSIDE,
                        f"obstacle `{o.id}` ({_n(o.x)}..{_n(o.x + o.w)} x {_n(o.y)}..{_n(o.y + o.h)}) "
                        f"leaves the boundary (0..{_n(boundary.w)} x 0..{_n(boundary.h)})",
                        node_span(o), "not inside the boundary",
                        "x, y are the obstacle's bottom-left corner; x + w and y + h must stay within the boundary")  # fmt: skip
        valid.append(o)
    for index, b in enumerate(valid):
        for a in valid[:index]:
            if a.x < b.x + b.w and b.x < a.x + a.w and a.y < b.y + b.h and b.y < a.y + a.h:
                yield diag(spec, E_OBSTACLES_OVERLAP, f"obstacle `{b.id}` overlaps obstacle `{a.id}`",
                            node_span(b), "overlaps", "merge them into one obstacle or fix a coordinate",
                            (f"`{a.id}` is on line {node_span(a).line}",))  # fmt: skip


def _boundary_ok(spec: Spec) -> bool:
    return spec.boundary is not None and spec.boundary.w > 0 and spec.boundary.h > 0


def check_fit(spec: Spec) -> Iterator[Diagnostic]:
    """E206, E207, W304: each room, and all rooms together, fit in the boundary."""
    if not _boundary_ok(spec):
        return
    bw, bh = spec.boundary.w, spec.boundary.h
    total = 0.0
    counted = True
    known = rooms_by_id(spec)
    # an L-room's arm is a rectangle of its own: it must fit and it takes area too
    arms = [arm.as_room(known[arm.room]) for arm in spec.arms if arm.room in known]
    for room in (*spec.rooms, *arms):
        if not (room.min_w > 0 and room.min_h > 0):
            counted = False
            continue
        total += room.min_w * room.min_h
        a, b = room.min_w, room.min_h
        if not ((a <= bw and b <= bh) or (b <= bw and a <= bh)):
            yield diag(spec, E_ROOM_TOO_BIG,
                        f"room `{room.id}` needs at least {_n(a)} x {_n(b)} m, which does not fit in the "
                        f"{_n(bw)} x {_n(bh)} m boundary",
                        node_span(room, "id"), "too big for the boundary",
                        "lower the room's minimum sizes or enlarge the boundary")  # fmt: skip
    free = bw * bh - _obstacle_area_inside(spec)
    targets = sum(room.target_w * room.target_h for room in (*spec.rooms, *arms))
    if counted and total <= free * (1 + 1e-9) and targets > free * (1 + 1e-9):
        yield diag(spec, W_TARGETS_TOO_BIG,
                    f"the rooms' target sizes cover {targets:.2f} m² but the free boundary area is only {free:.2f} m²",
                    node_span(spec.boundary), "smaller than the target rooms",
                    "enlarge the boundary (imported plans use about 1.3-1.6 times the target area) "
                    "or lower the targets", warning=True)  # fmt: skip
    if counted and total > free * (1 + 1e-9):
        label = "boundary" if not spec.boundary.obstacles else "boundary minus obstacles"
        yield diag(spec, E_AREA_TOO_BIG,
                    f"rooms need at least {total:.2f} m² but the {label} has only {free:.2f} m²",
                    node_span(spec.boundary), "too small for the rooms",
                    f"enlarge the boundary (for example to {_n(round(math.sqrt(total / free) * bw + 0.05, 1))} x "
                    f"{_n(round(math.sqrt(total / free) * bh + 0.05, 1))}) or lower the rooms' minimum sizes")  # fmt: skip


def check_doors(spec: Spec) -> Iterator[Diagnostic]:
    """E216, E208: every door is positive and fits on a side of both of its rooms (5.9)."""
    rooms = rooms_by_id(spec)
    utilization = spec.settings.door_utilization
    for adjacency in spec.adjacencies:
        if adjacency.door <= 0:
            yield diag(spec, E_NOT_POSITIVE, f"door between `{adjacency.a}` and `{adjacency.b}` is "
                        f"{_n(adjacency.door)} m, not positive", node_span(adjacency, "door"), "must be > 0",
                        "`mina` is the door width in metres, usually 0.9")  # fmt: skip
            continue
        if adjacency.a == adjacency.b or utilization <= 0:
            continue
        wall = adjacency.door / utilization
        for room_id in (adjacency.a, adjacency.b):
            room = rooms.get(room_id)
            if room is None or not _room_bounds_ok(room):
                continue
            longest = max(room.max_w, room.max_h)
            if wall > longest * (1 + 1e-12):
                need = (f"a shared wall of {_n(wall)} m (door {_n(adjacency.door)} / door_utilization "
                        f"{_n(utilization)})" if utilization != 1 else f"a shared wall of {_n(wall)} m")  # fmt: skip
                yield diag(spec, E_DOOR_TOO_WIDE,
                            f"door between `{adjacency.a}` and `{adjacency.b}` needs {need}, longer than "
                            f"any side of `{room_id}` (at most {_n(longest)} m)",
                            node_span(adjacency, "door"), "too wide for `" + room_id + "`",
                            f"use a door of at most {_n(round(longest * utilization, 3))} m or let `{room_id}` grow")  # fmt: skip
                break


def _inside(x: float, y: float, w: float, h: float) -> bool:
    return 0 <= x <= w and 0 <= y <= h


def _obstacle_at(spec: Spec, x: float, y: float):
    for o in spec.boundary.obstacles:
        if o.x < x < o.x + o.w and o.y < y < o.y + o.h:
            return o
    return None


def check_points(spec: Spec) -> Iterator[Diagnostic]:
    """E209-E212, E217: positions and connection points are reachable."""
    if not _boundary_ok(spec):
        return
    bw, bh = spec.boundary.w, spec.boundary.h
    extent = f"0..{_n(bw)} x 0..{_n(bh)}"
    for p in spec.positions:
        if not _inside(p.x, p.y, bw, bh):
            yield diag(spec, E_POSITION_OUTSIDE,
                        f"position ({_n(p.x)}, {_n(p.y)}) of `{p.room}` is outside the boundary ({extent})",
                        Span(node_span(p, "x").line, node_span(p, "x").col, node_span(p, "y").end_line, node_span(p, "y").end_col),
                        "outside the boundary", "coordinates are metres from the bottom-left corner, y up")  # fmt: skip
        elif (o := _obstacle_at(spec, p.x, p.y)) is not None:
            yield diag(spec, E_POSITION_IN_OBSTACLE,
                        f"position ({_n(p.x)}, {_n(p.y)}) of `{p.room}` is inside obstacle `{o.id}`",
                        Span(node_span(p, "x").line, node_span(p, "x").col, node_span(p, "y").end_line, node_span(p, "y").end_col),
                        f"inside `{o.id}`", "move the point out of the obstacle")  # fmt: skip
    rooms = rooms_by_id(spec)
    for c in spec.connections:
        reported = False
        for index, (x, y, fx, fy) in enumerate(((c.x1, c.y1, "x1", "y1"), (c.x2, c.y2, "x2", "y2")), start=1):
            span = Span(node_span(c, fx).line, node_span(c, fx).col, node_span(c, fy).end_line, node_span(c, fy).end_col)
            if not _inside(x, y, bw, bh):
                reported = True
                yield diag(spec, E_CONNECTION_OUTSIDE,
                            f"connection point {index} ({_n(x)}, {_n(y)}) of `{c.room}` is outside the boundary ({extent})",
                            span, "outside the boundary", "coordinates are metres from the bottom-left corner, y up")  # fmt: skip
            elif (o := _obstacle_at(spec, x, y)) is not None:
                reported = True
                yield diag(spec, E_CONNECTION_IN_OBSTACLE,
                            f"connection point {index} ({_n(x)}, {_n(y)}) of `{c.room}` is inside obstacle `{o.id}`",
                            span, f"inside `{o.id}`", "move the point out of the obstacle")  # fmt: skip
        room = rooms.get(c.room)
        if reported or room is None or not _room_bounds_ok(room):
            continue
        dx, dy = abs(c.x2 - c.x1), abs(c.y2 - c.y1)
        if not ((dx <= room.max_w and dy <= room.max_h) or (dx <= room.max_h and dy <= room.max_w)):
            yield diag(spec, E_POINTS_TOO_FAR,
                        f"`{c.room}` cannot cover both connection points: they are {_n(dx)} x {_n(dy)} m apart "
                        f"but the room is at most {_n(room.max_w)} x {_n(room.max_h)} m",
                        Span(node_span(c, "x1").line, node_span(c, "x1").col, node_span(c, "y2").end_line, node_span(c, "y2").end_col),
                        "too far apart", f"move the points closer or raise `{c.room}`'s maximum size")  # fmt: skip
    for hint in spec.hints:
        if hint.w <= 0 or hint.h <= 0:
            field = "w" if hint.w <= 0 else "h"
            yield diag(spec, E_NOT_POSITIVE, f"hint for `{hint.room}` has {field} {_n(getattr(hint, field))}, not positive",
                        node_span(hint, field), "must be > 0")  # fmt: skip
        elif hint.x < 0 or hint.y < 0 or hint.x + hint.w > bw or hint.y + hint.h > bh:
            yield diag(spec, W_HINT_OUTSIDE,
                        f"hint for `{hint.room}` ({_n(hint.x)}..{_n(hint.x + hint.w)} x "
                        f"{_n(hint.y)}..{_n(hint.y + hint.h)}) is not inside the boundary ({extent})",
                        node_span(hint), "outside the boundary", "hints are only a starting point; fix or drop it",
                        warning=True)  # fmt: skip


def check_shared_points(spec: Spec) -> Iterator[Diagnostic]:
    """E218: points that different rooms must cover are at least a wall apart."""
    gap = spec.settings.walldim
    points: list[tuple[float, float, str, Span]] = []
    for p in spec.positions:
        points.append((p.x, p.y, p.room, pair_span(p, "x", "y")))
    for c in spec.connections:
        points.append((c.x1, c.y1, c.room, pair_span(c, "x1", "y1")))
        points.append((c.x2, c.y2, c.room, pair_span(c, "x2", "y2")))
    points.sort(key=lambda p: (p[0], p[1]))
    reported: set[frozenset[str]] = set()
    for i, (x, y, room, span) in enumerate(points):
        # sweep along x: only points less than a wall further right can clash
        for x2, y2, room2, span2 in points[i + 1 :]:
            if x2 - x >= gap:
                break
            pair = frozenset((room, room2))
            if room2 != room and abs(y2 - y) < gap and pair not in reported:
                reported.add(pair)
                first, second = sorted(((span, room, x, y), (span2, room2, x2, y2)), key=lambda t: (t[0].line, t[0].col))
                yield diag(spec, E_SHARED_POINT,
                            f"`{first[1]}` and `{second[1]}` must both cover points less than a wall "
                            f"({_n(gap)} m) apart: ({_n(first[2])}, {_n(first[3])}) and ({_n(second[2])}, {_n(second[3])})",
                            second[0], "too close to the other room's point",
                            "move one of the points at least a wall thickness away",
                            (f"`{first[1]}`'s point is on line {first[0].line}",))  # fmt: skip
