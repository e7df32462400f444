"""The independent verifier: does a Layout satisfy its Spec?

This module reads only the Spec and the plain numbers of a Layout; it shares no code with
the optimisation model on purpose, so a modelling mistake cannot hide itself. Every layout
is verified before anything is written; a layout with violations is an error, never an
output.

Rules (the thesis, §5.5.1, with the adjacency rule corrected as the scouting notes require):
- every spec room is placed exactly once, with finite numbers, its type and label;
- inside the boundary (5.7);
- sizes within bounds in one of the two orientations (5.4, 5.5): the thesis enforces the
  larger of the two minimum (maximum) sizes on the longer side, so a room may be rotated;
- aspect ratio within [minar, maxar] for every room but corridors (5.6), in the same
  orientation as the sizes;
- no two rooms, and no room and obstacle, closer than the wall thickness (5.8);
- each adjacency: the rooms face each other across exactly one wall thickness, and the
  interiors face each other along at least door / door_utilization (5.9);
- positions and connection points covered (5.10, 5.11), onB rooms touch the boundary (5.12);
- each cluster admits one offset that keeps every member within the margin (5.13);
- portals: exactly one per adjacency, `width` = the door, centred on the shared wall.

L-shaped rooms (an `arms` line): the room is placed with its arm, each of its two
rectangles within its own bounds; the two are flush along a full edge at a corner of the
shared side (their union is an L, with no wall inside); every rule above that concerns the
room's place holds for the union: inside, apart from the others, onB, covering points. An
adjacency is met when either rectangle faces the other room across one wall.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from layoutdsl.syntax.ast import Spec
from layoutdsl.layout import Layout, PlacedRoom, shared_wall
from layoutdsl.diagnostics.source import Span

TOLERANCE = 1e-6
"""Metres. Solutions must meet every rule to within this absolute tolerance."""

USABLE_WIDTH = 0.6
"""Metres: a gap between rooms wider than a wall but narrower than this is a sliver, not a
space (layout.realism measures with the same width)."""

SLIVER_TOLERANCE = 1e-3
"""Metres: a gap counts as a sliver only when it is this much wider than a wall and
narrower than a usable space (the realism measure, layout.realism.find_slivers, uses the
same)."""


@dataclass(frozen=True, slots=True)
class Violation:
    """One broken rule: what, which rooms, and the spec line it comes from (if any)."""

    rule: str
    """'missing', 'extra', 'not-finite', 'type', 'inside', 'size', 'aspect-ratio', 'overlap',
    'obstacle', 'adjacency', 'position', 'connection', 'on-boundary', 'cluster', 'portal',
    'shape' (an L-room placed without its arm, or the other way round), 'join' (the arms of an
    L do not form an L); 'sliver' from `slivers` only."""
    rooms: tuple[str, ...]
    message: str
    span: Span | None = None


def verify(spec: Spec, layout: Layout, tol: float = TOLERANCE) -> list[Violation]:
    """All violations of the spec's hard constraints by the layout (empty = valid)."""
    placed = {room.id: room for room in layout.rooms}
    violations = list(_check_room_set(spec, layout, tol))
    if violations:
        # Geometry checks below assume every room is present and finite.
        return violations
    violations += _check_rooms(spec, placed, tol)
    violations += _check_non_overlap(spec, layout, tol)
    violations += _check_adjacencies(spec, placed, tol)
    violations += _check_points(spec, placed, tol)
    violations += _check_clusters(spec, placed, tol)
    violations += _check_portals(spec, layout, placed, tol)
    return violations


def slivers(spec: Spec, layout: Layout, usable_width: float = USABLE_WIDTH,
            tol: float = SLIVER_TOLERANCE) -> list[Violation]:
    """Gaps between two rooms' facing walls wider than a wall and narrower than
    `usable_width`, along more than a wall's thickness: too narrow to walk or furnish, yet
    free space to a robot's laser. Not a hard constraint of the spec (the thesis' model does
    not rule them out, so `verify` leaves them alone); compile's generator promises a wall
    or a usable space instead (issue 40) and checks every layout it writes with this. The
    geometry is this module's own, not layout.realism.find_slivers: the sliver pass finds
    the gaps it mends with that one, so a mistake there cannot hide itself here."""
    wall = spec.settings.walldim
    parts = [part for room in layout.rooms for part in _parts(room)]
    found: dict[tuple[str, str], tuple[float, float]] = {}
    for i, a in enumerate(parts):
        for b in parts[i + 1:]:
            if a.id == b.id:
                continue
            for gap, along in ((_separation(a.x, a.w, b.x, b.w), min(a.y2, b.y2) - max(a.y, b.y)),
                               (_separation(a.y, a.h, b.y, b.h), min(a.x2, b.x2) - max(a.x, b.x))):
                if wall + tol < gap < usable_width - tol and along > wall + tol:
                    key = (a.id, b.id) if a.id < b.id else (b.id, a.id)
                    if key not in found or found[key][1] < along:
                        found[key] = (gap, along)
    return [Violation("sliver", key, f"rooms `{key[0]}` and `{key[1]}` face each other {gap:.3g} m "
                      f"apart along {along:.3g} m: more than a wall ({wall:g} m) and less than a "
                      f"usable space ({usable_width:g} m)")
            for key, (gap, along) in sorted(found.items())]


def drawn_boundary(spec: Spec, layout: Layout) -> Spec:
    """The spec with the boundary its layout was drawn in, where the tool may draw its own:
    a boundary the tool chose (no `boundary` section) is fitted to the building compile
    draws, and `--grow-boundary` may grow a given one (the layout reports it). Verifying a
    written layout against its spec goes through here; a boundary the user set stays."""
    boundary = spec.boundary
    grown = layout.solve is not None and layout.solve.grown_boundary is not None
    if boundary is None or not (boundary.chosen or grown):
        return spec
    return replace(spec, boundary=replace(boundary, w=layout.width, h=layout.height))


def _check_room_set(spec: Spec, layout: Layout, tol: float):
    wanted = {room.id: room for room in spec.rooms}
    seen: set[str] = set()
    for room in layout.rooms:
        if room.id not in wanted:
            yield Violation("extra", (room.id,), f"room `{room.id}` is not in the spec")
            continue
        if room.id in seen:
            yield Violation("extra", (room.id,), f"room `{room.id}` is placed twice")
        seen.add(room.id)
        numbers = (room.x, room.y, room.w, room.h, *(room.arm or ()))
        if (spec.arm(room.id) is not None) != (room.arm is not None):
            shape = "an L (it has an arm)" if spec.arm(room.id) else "a rectangle"
            yield Violation("shape", (room.id,), f"room `{room.id}` is {shape} in the spec, not in the layout",
                            wanted[room.id].span)
        elif room.arm is not None and len(room.arm) != 4:
            yield Violation("shape", (room.id,), f"room `{room.id}`'s arm is not one rectangle (x, y, w, h)")
        if not all(math.isfinite(v) for v in numbers):
            yield Violation("not-finite", (room.id,), f"room `{room.id}` has a non-finite coordinate")
        spec_room = wanted[room.id]
        if (room.rtype, room.label) != (spec_room.rtype, spec_room.label):
            yield Violation(
                "type",
                (room.id,),
                f"room `{room.id}` is {room.rtype} `{room.label}`, spec says "
                f"{spec_room.rtype} `{spec_room.label}`",
                spec_room.span,
            )
    for room_id, room in wanted.items():
        if room_id not in seen:
            yield Violation("missing", (room_id,), f"room `{room_id}` is not placed", room.span)
    if spec.boundary is None:
        yield Violation("inside", (), "the spec has no boundary")
    elif not math.isclose(layout.width, spec.boundary.w, abs_tol=tol) or not math.isclose(
        layout.height, spec.boundary.h, abs_tol=tol
    ):
        yield Violation(
            "inside",
            (),
            f"layout boundary {layout.width} x {layout.height} differs from the spec's "
            f"{spec.boundary.w} x {spec.boundary.h}",
            spec.boundary.span,
        )


def _fits_orientation(
    long_side: float, short_side: float, room, tol: float, *, aspect: bool = True
) -> bool:
    """Sizes (5.4, 5.5) and, if `aspect`, aspect ratio (5.6), `long_side` taking the larger bounds."""
    min_long, min_short = max(room.min_w, room.min_h), min(room.min_w, room.min_h)
    max_long, max_short = max(room.max_w, room.max_h), min(room.max_w, room.max_h)
    if not (min_long - tol <= long_side <= max_long + tol):
        return False
    if not (min_short - tol <= short_side <= max_short + tol):
        return False
    if room.is_corridor or not aspect:
        return True
    # min_ar * short <= long <= max_ar * short, tolerance scaled like a length.
    return room.min_ar * short_side <= long_side + tol and long_side <= room.max_ar * short_side + tol


def _parts(room: PlacedRoom) -> list[PlacedRoom]:
    """A room's rectangles, each as a one-rectangle PlacedRoom: itself, or an L's two arms."""
    if room.arm is None:
        return [room]
    x, y, w, h = room.arm
    first = PlacedRoom(room.id, room.label, room.rtype, room.x, room.y, room.w, room.h)
    return [first, PlacedRoom(room.id, room.label, room.rtype, x, y, w, h)]


def _check_rooms(spec: Spec, placed: dict[str, PlacedRoom], tol: float):
    width, height = spec.boundary.w, spec.boundary.h
    for room in spec.rooms:
        p = placed[room.id]
        parts = _parts(p)
        for part in parts:
            if part.x < -tol or part.y < -tol or part.x2 > width + tol or part.y2 > height + tol:
                yield Violation(
                    "inside",
                    (room.id,),
                    f"room `{room.id}` ({_rect(part)}) leaves the {width:g} x {height:g} boundary",
                    room.span,
                )
        arm = spec.arm(room.id)
        bounds = [room] if arm is None else [room, arm.as_room(room)]
        for part, bound in zip(parts, bounds):
            yield from _check_size(room.id, part, bound, tol)
        if len(parts) == 2:
            yield from _check_join(room, *parts, tol)
            yield from _check_turn(room, arm, *parts, tol)
        if room.on_boundary and not any(
            part.x <= tol or part.y <= tol or part.x2 >= width - tol or part.y2 >= height - tol
            for part in parts
        ):
            yield Violation(
                "on-boundary",
                (room.id,),
                f"room `{room.id}` is marked onB but touches no side of the boundary",
                room.spans.get("on_boundary", room.span),
            )


def _check_size(room_id: str, p: PlacedRoom, room, tol: float):
    """One rectangle of a room against its bounds (the room line's, or its arm's)."""
    what = f"room `{room_id}`" if room.id == room_id else f"the arm of room `{room_id}`"
    # The thesis' orientation o decides which side gets the larger bounds; o = 0 gives
    # the larger minimum/maximum to w, o = 1 to h. Either orientation may be chosen.
    fits = _fits_orientation(p.w, p.h, room, tol) or _fits_orientation(p.h, p.w, room, tol)
    if fits:
        return
    sizes_ok = _fits_orientation(p.w, p.h, room, tol, aspect=False) or _fits_orientation(
        p.h, p.w, room, tol, aspect=False
    )
    if sizes_ok:
        ratio = max(p.w, p.h) / max(min(p.w, p.h), 1e-12)
        yield Violation(
            "aspect-ratio",
            (room_id,),
            f"{what} has aspect ratio {ratio:.6g}, outside [{room.min_ar:g}, {room.max_ar:g}]",
            room.span,
        )
    else:
        yield Violation(
            "size",
            (room_id,),
            f"{what} is {p.w:.6g} x {p.h:.6g}, outside its size bounds "
            f"w [{room.min_w:g}, {room.max_w:g}], h [{room.min_h:g}, {room.max_h:g}] "
            "in either orientation",
            room.span,
        )


def _check_join(room, a: PlacedRoom, b: PlacedRoom, tol: float):
    """The two arms of an L touch along a full edge of one of them, at a corner: flush on
    one axis, overlapping on the other, and aligned at one end of that overlap."""

    def close(u: float, v: float) -> bool:
        return abs(u - v) <= tol

    side_by_side = close(a.x2, b.x) or close(b.x2, a.x)
    stacked = close(a.y2, b.y) or close(b.y2, a.y)
    if side_by_side and not stacked:
        overlap = min(a.y2, b.y2) - max(a.y, b.y)
        aligned = close(a.y, b.y) or close(a.y2, b.y2)
    elif stacked and not side_by_side:
        overlap = min(a.x2, b.x2) - max(a.x, b.x)
        aligned = close(a.x, b.x) or close(a.x2, b.x2)
    else:
        overlap, aligned = 0.0, False
    if overlap <= tol or not aligned:
        yield Violation(
            "join",
            (room.id,),
            f"the arms of room `{room.id}` ({_rect(a)}; {_rect(b)}) do not form an L: they must "
            "touch along a full edge, flush at a corner",
            room.span,
        )


def _check_turn(room, arm, a: PlacedRoom, b: PlacedRoom, tol: float):
    """The L keeps the shape its lines give: when both lines' bounds decide which side is
    long, the arm runs across the first rectangle if one line is wide and the other tall,
    along it otherwise."""
    room_wide, arm_wide = room.target_w - room.target_h, arm.target_w - arm.target_h
    if room_wide == 0 or arm_wide == 0:
        return
    # the longest short side is shorter than the shortest long side
    decided = all(min(r.max_w, r.max_h) < max(r.min_w, r.min_h) for r in (room, arm))
    if not decided:
        return  # a rectangle whose bounds allow a square may lie either way
    crosses = (room_wide > 0) != (arm_wide > 0)
    if ((a.w > a.h) != (b.w > b.h)) != crosses:
        yield Violation(
            "join",
            (room.id,),
            f"the arm of room `{room.id}` runs {'along' if crosses else 'across'} its first rectangle; "
            f"its lines say {'across' if crosses else 'along'}",
            arm.span or room.span,
        )


def _separation(ax: float, aw: float, bx: float, bw: float) -> float:
    """Signed distance between two intervals (negative when they overlap)."""
    return max(bx - (ax + aw), ax - (bx + bw))


def _check_non_overlap(spec: Spec, layout: Layout, tol: float):
    wall = spec.settings.walldim
    parts = sorted((part for room in layout.rooms for part in _parts(room)), key=lambda r: (r.x, r.id))
    reported: set[tuple[str, str]] = set()
    # Sweep along x: only rectangles whose x-ranges come within a wall thickness can clash.
    # The two arms of one L are checked by _check_join instead.
    for i, a in enumerate(parts):
        for b in parts[i + 1 :]:
            if b.x >= a.x2 + wall - tol:
                break
            if a.id == b.id:
                continue
            gap_x = _separation(a.x, a.w, b.x, b.w)
            gap_y = _separation(a.y, a.h, b.y, b.h)
            separation = max(gap_x, gap_y)
            first, second = sorted((a.id, b.id))
            if separation < wall - tol and (first, second) not in reported:
                reported.add((first, second))
                how = "overlap" if separation < 0 else f"are only {separation:.6g} m apart"
                yield Violation(
                    "overlap",
                    (first, second),
                    f"rooms `{first}` and `{second}` {how}; walls need {wall:g} m between rooms",
                )
    if spec.boundary is None:
        return
    for obstacle in spec.boundary.obstacles:
        for room in layout.rooms:
            for part in _parts(room):
                gap_x = _separation(part.x, part.w, obstacle.x, obstacle.w)
                gap_y = _separation(part.y, part.h, obstacle.y, obstacle.h)
                if max(gap_x, gap_y) < wall - tol:
                    yield Violation(
                        "obstacle",
                        (room.id,),
                        f"room `{room.id}` comes within {max(gap_x, gap_y):.6g} m of obstacle "
                        f"`{obstacle.id}` (wall thickness {wall:g})",
                        obstacle.span,
                    )
                    break


def _check_adjacencies(spec: Spec, placed: dict[str, PlacedRoom], tol: float):
    wall = spec.settings.walldim
    for adjacency in spec.adjacencies:
        a, b = placed[adjacency.a], placed[adjacency.b]
        needed = adjacency.door / spec.settings.door_utilization
        # an L-room's adjacency is met by either arm: judge the best pair of rectangles
        facings = [f for pa in _parts(a) for pb in _parts(b) if (f := _facing(pa, pb)) is not None]
        met = [f for f in facings if f[0] <= wall + tol and f[1] >= needed - tol]
        if met:
            continue
        if not facings:
            yield Violation(
                "adjacency",
                (a.id, b.id),
                f"rooms `{a.id}` and `{b.id}` are adjacent in the spec but face no common wall",
                adjacency.span,
            )
            continue
        gap, shared = min(facings, key=lambda f: (f[0] > wall + tol, -f[1]))
        if gap > wall + tol:
            yield Violation(
                "adjacency",
                (a.id, b.id),
                f"rooms `{a.id}` and `{b.id}` are {gap:.6g} m apart; adjacent rooms must be "
                f"exactly one wall ({wall:g} m) apart",
                adjacency.span,
            )
        else:
            yield Violation(
                "adjacency",
                (a.id, b.id),
                f"rooms `{a.id}` and `{b.id}` share {shared:.6g} m of wall, less than the "
                f"{needed:.6g} m the door needs",
                adjacency.span,
            )


def _facing(a: PlacedRoom, b: PlacedRoom) -> tuple[float, float] | None:
    """(gap across the wall, length the interiors face each other) for the closer axis."""
    gap_x = _separation(a.x, a.w, b.x, b.w)
    gap_y = _separation(a.y, a.h, b.y, b.h)
    if gap_x >= gap_y:
        shared = min(a.y2, b.y2) - max(a.y, b.y)
        gap = gap_x
    else:
        shared = min(a.x2, b.x2) - max(a.x, b.x)
        gap = gap_y
    if shared <= 0:
        return None
    return gap, shared


def _covers(room: PlacedRoom, x: float, y: float, tol: float) -> bool:
    return any(p.x - tol <= x <= p.x2 + tol and p.y - tol <= y <= p.y2 + tol for p in _parts(room))


def _check_points(spec: Spec, placed: dict[str, PlacedRoom], tol: float):
    for position in spec.positions:
        room = placed.get(position.room)
        if room is not None and not _covers(room, position.x, position.y, tol):
            yield Violation(
                "position",
                (room.id,),
                f"room `{room.id}` ({_rect(room)}) does not cover its position "
                f"({position.x:g}, {position.y:g})",
                position.span,
            )
    for connection in spec.connections:
        room = placed.get(connection.room)
        if room is None:
            continue
        for x, y in ((connection.x1, connection.y1), (connection.x2, connection.y2)):
            if not _covers(room, x, y, tol):
                yield Violation(
                    "connection",
                    (room.id,),
                    f"room `{room.id}` ({_rect(room)}) does not cover the connection point "
                    f"({x:g}, {y:g})",
                    connection.span,
                )


def _check_clusters(spec: Spec, placed: dict[str, PlacedRoom], tol: float):
    margin = spec.settings.cluster_margin
    for cluster in spec.clusters:
        # (5.13): x_i - margin <= xf + cx <= x_i + w_i + margin for every member, so cx must
        # lie in the intersection of the members' intervals (likewise cy). An L-room's
        # interval is its union's extent.
        lo_x = lo_y = -math.inf
        hi_x = hi_y = math.inf
        for member in cluster.members:
            room = placed.get(member.room)
            if room is None:
                continue
            parts = _parts(room)
            x1, y1 = min(p.x for p in parts), min(p.y for p in parts)
            x2, y2 = max(p.x2 for p in parts), max(p.y2 for p in parts)
            lo_x = max(lo_x, x1 - margin - member.x)
            hi_x = min(hi_x, x2 + margin - member.x)
            lo_y = max(lo_y, y1 - margin - member.y)
            hi_y = min(hi_y, y2 + margin - member.y)
        if lo_x > hi_x + tol or lo_y > hi_y + tol:
            yield Violation(
                "cluster",
                tuple(m.room for m in cluster.members),
                f"no placement of cluster `{cluster.id}` keeps every member within "
                f"{margin:g} m of its cluster point",
                cluster.span,
            )


def _check_portals(spec: Spec, layout: Layout, placed: dict[str, PlacedRoom], tol: float):
    wanted = {frozenset((adj.a, adj.b)): adj for adj in spec.adjacencies}
    seen: set[frozenset[str]] = set()
    for portal in layout.portals:
        key = frozenset((portal.a, portal.b))
        adjacency = wanted.get(key)
        if adjacency is None:
            yield Violation(
                "portal",
                (portal.a, portal.b),
                f"portal between `{portal.a}` and `{portal.b}`, which the spec does not make adjacent",
            )
            continue
        if key in seen:
            yield Violation(
                "portal", (portal.a, portal.b), f"two portals between `{portal.a}` and `{portal.b}`"
            )
        seen.add(key)
        if portal.kind != adjacency.kind or not math.isclose(portal.width, adjacency.door, abs_tol=tol):
            yield Violation(
                "portal",
                (portal.a, portal.b),
                f"portal `{portal.a}`-`{portal.b}` is {portal.kind} {portal.width:g} m, the spec "
                f"says {adjacency.kind} {adjacency.door:g} m",
                adjacency.span,
            )
        length = math.hypot(portal.x2 - portal.x1, portal.y2 - portal.y1)
        wall = shared_wall(placed[portal.a], placed[portal.b])
        if wall is None or not math.isclose(length, portal.width, abs_tol=tol):
            yield Violation(
                "portal",
                (portal.a, portal.b),
                f"portal `{portal.a}`-`{portal.b}` is not a door of its width on a shared wall",
                adjacency.span,
            )
            continue
        axis, middle, lo, hi = wall
        along = (portal.y1, portal.y2) if axis == "x" else (portal.x1, portal.x2)
        across = (portal.x1, portal.x2) if axis == "x" else (portal.y1, portal.y2)
        centred = math.isclose(sum(along) / 2, (lo + hi) / 2, abs_tol=tol)
        on_wall = all(math.isclose(c, middle, abs_tol=tol) for c in across)
        within = min(along) >= lo - tol and max(along) <= hi + tol
        if not (centred and on_wall and within):
            yield Violation(
                "portal",
                (portal.a, portal.b),
                f"portal `{portal.a}`-`{portal.b}` is not centred on the wall the rooms share",
                adjacency.span,
            )
    for key, adjacency in wanted.items():
        if key not in seen:
            yield Violation(
                "portal",
                (adjacency.a, adjacency.b),
                f"no portal between adjacent rooms `{adjacency.a}` and `{adjacency.b}`",
                adjacency.span,
            )


def _rect(room: PlacedRoom) -> str:
    text = f"x {room.x:.6g}, y {room.y:.6g}, w {room.w:.6g}, h {room.h:.6g}"
    if room.arm is not None:
        x, y, w, h = room.arm
        text += f"; arm x {x:.6g}, y {y:.6g}, w {w:.6g}, h {h:.6g}"
    return text
