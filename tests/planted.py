"""Planted specs: build a layout first, derive the spec from it, so feasibility is known.

Rooms hang in two rows off each of a stack of horizontal corridors; corridors are chained by
their end rooms. Sizes get ±`spread` around the planted ones, the boundary `slack` times the
planted extent.
"""

from __future__ import annotations

from layoutdsl.syntax.ast import Adjacency, Boundary, Room, Settings, Spec

Rect = tuple[float, float, float, float]


def planted(rooms_per_row: int, corridors: int, *, spread: float = 0.2, slack: float = 1.15,
            wall: float = 0.2) -> tuple[Spec, dict[str, Rect]]:
    """A feasible spec with 2 * rooms_per_row * corridors rooms plus the corridors, and its layout."""
    room_w, room_h, corridor_h = 3.4, 3.2, 2.0
    length = rooms_per_row * room_w + (rooms_per_row - 1) * wall
    rects: dict[str, Rect] = {}
    adjacencies: list[Adjacency] = []
    y = 0.0
    for c in range(corridors):
        below = [f"R{c}b{i}" for i in range(rooms_per_row)]
        above = [f"R{c}a{i}" for i in range(rooms_per_row)]
        corridor = f"C{c}"
        for i, rid in enumerate(below):
            rects[rid] = (i * (room_w + wall), y, room_w, room_h)
        rects[corridor] = (0.0, y + room_h + wall, length, corridor_h)
        top = y + room_h + wall + corridor_h + wall
        for i, rid in enumerate(above):
            rects[rid] = (i * (room_w + wall), top, room_w, room_h)
        adjacencies += [Adjacency(rid, corridor, 0.9, "e") for rid in below + above]
        if c > 0:  # the previous corridor's first upper room is this one's first lower room's neighbour
            adjacencies.append(Adjacency(f"R{c - 1}a0", below[0], 0.9, "e"))
        y = top + room_h + wall
    rooms = []
    for rid, (_, _, w, h) in rects.items():
        corridor = rid.startswith("C")
        lo, hi = 1 - spread, 1 + spread
        long, short = max(w, h), min(w, h)
        ar = (max(1.0, (long * lo) / (short * hi) * 0.99), (long * hi) / (short * lo) * 1.01)
        rooms.append(Room(rid, w * lo, w * hi, w, h * lo, h * hi, h, ar[0], ar[1] if not corridor else 20.0,
                          "C" if corridor else "R", "CORRIDOR" if corridor else "OFFICE"))
    width = max(x + w for x, _, w, _ in rects.values()) * slack
    height = max(yy + h for _, yy, _, h in rects.values()) * slack
    spec = Spec(f"planted{len(rects)}", tuple(rooms), Boundary(round(width, 3), round(height, 3)),
                tuple(adjacencies), settings=Settings(walldim=wall))
    return spec, rects
