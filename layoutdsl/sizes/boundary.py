"""The boundary the tool chooses when a spec gives none (the thesis' boundary is required,
§5.4; layoutdsl lets a spec or a room graph leave it out).

The rule: the rooms' target areas add up to A; the boundary's area is A / FILL, its sides
in the ratio ASPECT : 1 (wide). Each side is then lengthened, if needed, so that every room
fits at its target size in some orientation (the longest target side fits the long side,
the longest short target side fits the short side), and both are rounded up to 10 cm.
FILL 0.6 and ASPECT 1.6 leave the generator room to arrange a graph it was never tuned on:
real plans fill 44-100 % of their bounding box (median 0.77) at aspect ratios 1.2-3.8
(median 1.6), and at 0.6 the layouts of issue 40's measurement were found. `compile` may
grow a chosen boundary when it finds no layout in it (the generator's page says how).
"""

from __future__ import annotations

import math
from collections.abc import Iterable

FILL = 0.6
"""Share of the chosen boundary that the rooms' target areas cover."""

ASPECT = 1.6
"""Long side / short side of the chosen boundary."""

STEP = 0.1
"""Sides are rounded up to a multiple of this (metres)."""


def choose_boundary(rooms: Iterable, arms: Iterable = (), *, fill: float = FILL,
                    aspect: float = ASPECT, contains: Iterable[tuple[float, float]] = ()) -> tuple[float, float]:  # fmt: skip
    """(w, h) in metres for rooms (anything with target_w, target_h) and the second
    rectangles of L-rooms (`arms`, the same attributes); w >= h unless points of `contains`
    (the spec's positions, connections and hints, in the boundary's frame) need a side
    longer. Raises ValueError for no rooms or a size that is not a positive finite number."""
    if not 0 < fill <= 1:
        raise ValueError(f"fill must be in (0, 1], got {fill!r}")
    if not aspect >= 1:
        raise ValueError(f"aspect must be >= 1, got {aspect!r}")
    rects = [(r.target_w, r.target_h) for r in rooms]
    if not rects:
        raise ValueError("no rooms: no boundary to choose")
    extra = [(a.target_w, a.target_h) for a in arms]
    for w, h in rects + extra:
        if not (math.isfinite(w) and math.isfinite(h) and w > 0 and h > 0):
            raise ValueError(f"a room's target size {w!r} x {h!r} is not a positive number")
    area = sum(w * h for w, h in rects + extra) / fill
    long_side = math.sqrt(area * aspect)
    short_side = area / long_side
    long_side = max(long_side, max(max(w, h) for w, h in rects))
    short_side = max(short_side, max(min(w, h) for w, h in rects))
    points = list(contains)
    if points:  # every point the spec places must lie inside, with a step to spare
        long_side = max(long_side, max(x for x, _ in points) + STEP)
        short_side = max(short_side, max(y for _, y in points) + STEP)
    return _round_up(long_side), _round_up(short_side)


def _round_up(value: float) -> float:
    steps = math.ceil(value / STEP - 1e-9)
    return round(steps * STEP, 6)
