"""Corridor ladders drawn outright: two parallel rails joined by rungs (issue 11).

Office and school plans often have a block of the room graph shaped like a ladder: two
long corridors (the rails) joined by several shorter corridors or halls (the rungs), each
with a door to both rails. Every rung must then span the same gap between the rails, so a
layout of the block needs rungs of one common length, within each rung's bounds. The greedy
placement (layoutdsl.compile.generate) sizes rooms one at a time and almost never lands
on that; the repair then stalls on the gap (measured: the 9-room block of
office_OfficePlan found no layout in 10 s for any of 3 seeds).

`ladder_template` finds the ladder in a spec that is one such block (the two corridors, not
sharing a door, with the most common neighbours, three or more) and draws it: rails along x, rungs
across at the gap, in a drawn order and spacing, turned a quarter for half the draws. The
result is a template for the greedy placement: the rest of the block is placed around it.
The construction uses it only when it satisfies every hard constraint among its rooms.
"""

from __future__ import annotations

import random
from collections.abc import Mapping
from itertools import combinations

from layoutdsl.compile.generate import RoomSizes, room_graph
from layoutdsl.layout.geometry import Rect
from layoutdsl.syntax.ast import Spec

MIN_RUNGS = 3
"""Common neighbours two corridors need to be a ladder's rails. Two rungs are any ring of
four rooms, which the repair closes well by itself: drawn as a ladder, the 10-room block of
school_wilbraham (rails C10 and C8, rungs C7 and R32) took its first layout from 0.3 s to
17 s (seed 0)."""

SPACING_ROOMS = 1.0
"""Most room between two rungs, in typical room depths: offices often sit between them."""


def find_ladder(spec: Spec) -> tuple[str, str, list[str]] | None:
    """(rail, rail, rungs): the two corridors without a shared door with the most common
    neighbours (at least MIN_RUNGS), or None."""
    graph = room_graph(spec)
    best = None
    corridors = sorted(room.id for room in spec.rooms if room.is_corridor)
    for a, b in combinations(corridors, 2):
        if graph.has_edge(a, b):
            continue
        rungs = sorted(set(graph[a]) & set(graph[b]))
        if len(rungs) >= MIN_RUNGS and (best is None or len(rungs) > len(best[2])):
            best = (a, b, rungs)
    return best


def _rung_width(sizes: RoomSizes, gap: float, corridor: bool, wall: float) -> float | None:
    """The side of a rung along the rails, for a rung spanning `gap` between them (or None).

    The gap is the rung's long side (its short side runs along the rails) or, for a hall
    wider than the gap, its short side; a room's sides keep their aspect-ratio bounds.
    """
    options = (
        # (the gap's side bounds, the other side's bounds, the other side's ratio range to gap)
        ((sizes.lo_long, sizes.hi_long), (sizes.lo_short, sizes.hi_short),
         (gap / sizes.max_ar, gap / sizes.min_ar), sizes.target_short),
        ((sizes.lo_short, sizes.hi_short), (sizes.lo_long, sizes.hi_long),
         (gap * sizes.min_ar, gap * sizes.max_ar), sizes.target_long),
    )
    for (gap_lo, gap_hi), (lo, hi), (ratio_lo, ratio_hi), target in options:
        if not gap_lo <= gap <= gap_hi:
            continue
        lo = max(lo, wall)
        if not corridor:
            lo, hi = max(lo, ratio_lo), min(hi, ratio_hi)
        if lo <= hi:
            return min(hi, max(lo, target))
    return None


def ladder_template(spec: Spec, rng: random.Random,
                    hanging: Mapping[str, float] | None = None) -> dict[str, Rect] | None:
    """The ladder of the spec drawn as rectangles (its rooms only), or None when the rungs
    allow no common gap or the rails cannot hold them. The caller checks the result against
    the hard constraints among its rooms before using it.

    `hanging`: room -> area of the rooms outside the spec that hang off it. Rooms hanging off
    a rung can only lie between the rails, beside it: the spacing next to a rung gets their
    area over the gap (measured on office_OfficePlan: ten rooms hang off one rung).
    """
    found = find_ladder(spec)
    if found is None or spec.boundary is None:
        return None
    rail_a, rail_b, rungs = found
    rooms = {room.id: room for room in spec.rooms}
    sizes = {room_id: RoomSizes.of(rooms[room_id]) for room_id in (rail_a, rail_b, *rungs)}
    walldim = spec.settings.walldim
    walls = {frozenset((adj.a, adj.b)): adj.door / spec.settings.door_utilization
             for adj in spec.adjacencies}
    # the gap: the rungs' target lengths' median, else the nearest length all rungs allow
    candidates = sorted({v for r in rungs for v in (sizes[r].target_long, sizes[r].lo_long,
                                                    sizes[r].hi_long, sizes[r].target_short,
                                                    sizes[r].lo_short, sizes[r].hi_short)})
    wanted = sorted(sizes[r].target_long for r in rungs)[len(rungs) // 2] * rng.uniform(0.9, 1.1)
    widths = None
    for gap in sorted(candidates + [wanted], key=lambda v: abs(v - wanted)):
        widths = {r: _rung_width(sizes[r], gap, rooms[r].is_corridor,
                                 max(walls[frozenset((r, rail_a))], walls[frozenset((r, rail_b))]))
                  for r in rungs}
        if all(w is not None for w in widths.values()):
            break
        widths = None
    if widths is None:
        return None
    order = list(rungs)
    rng.shuffle(order)
    hanging = hanging or {}
    # the rung with the most rooms hanging off it goes first, the rails flush with its
    # outer side: its rooms take the open end of the ladder, as a hall at the end of two
    # corridors does (office_OfficePlan: six rooms off the hall C8)
    outside = max(order, key=lambda r: hanging.get(r, 0.0)) if hanging else None
    if outside is not None and hanging.get(outside, 0.0) > 0:
        order.remove(outside)
        order.insert(0, outside)
    else:
        outside = None
    depth = sorted(RoomSizes.of(room).target_short for room in spec.rooms)[len(spec.rooms) // 2]
    # each other rung's hanging rooms split over the spacings beside it
    beside = [0.0] * max(0, len(order) - 1)
    for k, r in enumerate(order):
        if r == outside:
            continue
        slots = [j for j in (k - 1, k) if 0 <= j < len(beside)]
        for j in slots:
            beside[j] += hanging.get(r, 0.0) / len(slots) / max(gap, walldim)
    spacings = [walldim + extra + rng.uniform(0, SPACING_ROOMS) * depth for extra in beside]
    rails = {}
    for rail in (rail_a, rail_b):
        span = sum(widths.values()) + sum(spacings)
        if span > sizes[rail].hi_long:
            # the hanging rooms' share as far as the rail allows, nothing drawn beyond
            spare = sizes[rail].hi_long - sum(widths.values()) - walldim * len(spacings)
            scale = min(1.0, max(0.0, spare) / sum(beside)) if sum(beside) > 0 else 0.0
            spacings = [walldim + extra * scale for extra in beside]
            span = sum(widths.values()) + sum(spacings)
        if span > sizes[rail].hi_long:
            return None
        length = min(sizes[rail].hi_long, max(span, sizes[rail].lo_long, sizes[rail].target_long * rng.uniform(0.85, 1.0)))
        rails[rail] = (length, sizes[rail].target_short)
    span = sum(widths.values()) + sum(spacings)
    rects: dict[str, Rect] = {}
    thick_a = min(sizes[rail_a].hi_short, max(sizes[rail_a].lo_short, rails[rail_a][1]))
    def rail_start(rail: str) -> float:
        return 0.0 if outside is not None else -rng.uniform(0, rails[rail][0] - span)

    rects[rail_a] = (rail_start(rail_a), 0.0, rails[rail_a][0], thick_a)
    x = 0.0
    for k, r in enumerate(order):
        rects[r] = (x, thick_a + walldim, widths[r], gap)
        x += widths[r] + (spacings[k] if k < len(spacings) else 0.0)
    thick_b = min(sizes[rail_b].hi_short, max(sizes[rail_b].lo_short, rails[rail_b][1]))
    rects[rail_b] = (rail_start(rail_b), thick_a + 2 * walldim + gap,
                     rails[rail_b][0], thick_b)
    x0 = min(x for x, _, _, _ in rects.values())
    y0 = min(y for _, y, _, _ in rects.values())
    rects = {r: (x - x0, y - y0, w, h) for r, (x, y, w, h) in rects.items()}
    extent = (max(x + w for x, _, w, _ in rects.values()), max(y + h for _, y, _, h in rects.values()))
    # rails along x or, turned a quarter, along y: drawn among the ways the boundary holds
    fits = [turn for turn, (w, h) in ((False, extent), (True, extent[::-1]))
            if w <= spec.boundary.w and h <= spec.boundary.h]
    if fits and fits[rng.randrange(len(fits))]:
        rects = {r: (y, x, h, w) for r, (x, y, w, h) in rects.items()}
    return rects
