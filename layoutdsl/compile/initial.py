"""The initial state: a sequence pair read off an embedding of the room graph.

The schedule does not start from random permutations. The room graph is drawn in the plane
by a force-directed embedding (networkx's spring layout, seeded from the spec's seed and the
restart): rooms that share a door land near each other and the corridors that join many
rooms in the middle. The rectangles of the rooms, at their drawn sides, centred on those
points give the state (representation.Rooms.state_of): most doors start close to met, and
different seeds give different arrangements. Rooms pinned to a point (positions,
connections) start there.

A *pulled* start draws the embedding again with each room that must open outside (onB)
tied to a point of its own on a circle round the building, in the direction the plain
embedding put it (the outside stands in, as a rectangular dual's four exterior vertices
do): a corridor that the other corridors ring starts on the outside when its entrance must.
The schedule alternates the two kinds of start (generator.py says why).

The sides each room is drawn with (`drawn_sides`) are its targets shrunk towards
PACKING_DENSITY of the outline, corridors lengthened for the rooms that hang off them;
a found state is grown back towards the targets (schedule.grown) before it is sized.
"""

from __future__ import annotations

import math

import networkx as nx
import numpy as np

from layoutdsl.compile.graph import room_graph
from layoutdsl.compile.representation import Rooms, State
from layoutdsl.layout.geometry import Rect, RoomSizes
from layoutdsl.syntax.ast import ARM_SUFFIX, Spec, arm_id

PACKING_DENSITY = 0.5
"""Room area the rooms are drawn with per m² of outline: dense plans (real ones fill up to
100 % of their bounding box with target areas) are drawn smaller, so the packing finds room
for every door; the sizing LP grows them back as far as they fit."""

MAX_SHRINK = 0.92
"""Drawn sides are at most this share of their targets."""

OUTSIDE_RADIUS = 2.0
"""Where a room that must open outside is tied to, in the embedding's units (the rooms
spread over about -1..1)."""

SPRING_ITERATIONS = 60
"""Iterations of the spring embedding (networkx's default is 50)."""


def _neighbours(spec: Spec) -> dict[str, list[str]]:
    neighbours: dict[str, list[str]] = {room.id: [] for room in spec.rooms}
    for adj in spec.adjacencies:
        neighbours[adj.a].append(adj.b)
        neighbours[adj.b].append(adj.a)
    return neighbours


def _target_sides(spec: Spec, shrink: float) -> dict[str, tuple[float, float]]:
    """(long, short) side each room is drawn with: its target, shrunk, within its bounds."""
    sides = {}
    for room in spec.rooms:
        sizes = RoomSizes.of(room)
        long_side = min(sizes.hi_long, max(sizes.lo_long, sizes.target_long * shrink))
        short_side = min(sizes.hi_short, max(sizes.lo_short, sizes.target_short * shrink))
        if not sizes.corridor:
            # clamping the two sides separately can break the aspect-ratio bounds: widen
            # the short side (or shorten the long one) back into them
            if long_side > sizes.max_ar * short_side:
                short_side = min(sizes.hi_short, long_side / sizes.max_ar)
                long_side = min(long_side, sizes.max_ar * short_side)
            elif long_side < sizes.min_ar * short_side:
                long_side = min(sizes.hi_long, sizes.min_ar * short_side)
                short_side = min(short_side, long_side / sizes.min_ar)
        sides[room.id] = (long_side, short_side)
    return sides


FRONTAGE_USE = 0.7
"""Share of a corridor's perimeter its rooms can hang on: doors need their wall, and rooms at
a corner or an end take more than their side."""


LENGTHEN_MAX_DENSITY = 0.5
"""Target room area per m² of boundary above which corridors keep their drawn length: a dense
plan has no room to give them. Measured with the construction this generator replaced (seeds
0-2, 45 s): on school_hendersonhighschool (0.44) lengthened corridors construct 3 of 3 in
6-10 s, 1 of 3 without; on office_floorplanLOWER (0.87) lengthened took 4.7-36 s,
unlengthened 0.6-5.3 s; on school_scuolasconosciuta (0.57, L-rooms) lengthened found nothing
in 30 s (seeds 0-1), unlengthened 0.3 s."""


def _corridors_lengthened(spec: Spec, sides: dict[str, tuple[float, float]],
                          neighbours: dict[str, list[str]]) -> dict[str, tuple[float, float]]:
    """Each corridor long enough (within its bounds) for the rooms that hang off it.

    A corridor drawn at its target length can have less perimeter than its neighbours'
    short sides add up to, and they then pile over each other around it.
    """
    lengthened = dict(sides)
    for room in spec.rooms:
        if not room.is_corridor or not neighbours[room.id]:
            continue
        if room.id.endswith(ARM_SUFFIX) or arm_id(room.id) in neighbours:
            # an L-room's box and arm are drawn as two rooms (layout.lshape.seeds_spec)
            # joined later at their target shape: measured on school_hendersonhighschool,
            # whose hub corridor is an L, lengthened they left no seed geometry repairable
            continue
        long_side, short_side = sides[room.id]
        frontage = sum(sides[n][1] for n in neighbours[room.id]) / FRONTAGE_USE
        wanted = frontage / 2 - short_side
        sizes = RoomSizes.of(room)
        wanted = min(wanted, sizes.hi_long, sizes.max_ar * sizes.hi_short)
        if wanted > long_side:
            lengthened[room.id] = (wanted, short_side)
    return lengthened


def drawn_sides(spec: Spec, outline: tuple[float, float],
                shrink: float | None = None) -> dict[str, tuple[float, float]]:
    """(long, short) side each room is drawn with: targets shrunk to PACKING_DENSITY of
    the boundary (or by `shrink`), corridors lengthened for their rooms."""
    width, height = outline
    density = sum(room.target_w * room.target_h for room in spec.rooms) / (width * height)
    if shrink is None:
        shrink = min(MAX_SHRINK, (PACKING_DENSITY / max(density, 1e-9)) ** 0.5)
    sides = _target_sides(spec, shrink)
    if density > LENGTHEN_MAX_DENSITY:
        return sides
    return _corridors_lengthened(spec, sides, _neighbours(spec))





def pinned_points(spec: Spec) -> dict[str, tuple[float, float]]:
    """Room id -> the point it must cover (a position, else a connection's midpoint)."""
    points: dict[str, tuple[float, float]] = {p.room: (p.x, p.y) for p in spec.positions}
    for c in spec.connections:
        points.setdefault(c.room, ((c.x1 + c.x2) / 2, (c.y1 + c.y2) / 2))
    return points


def _embedding(spec: Spec, graph: nx.Graph, seed: int, pulled: bool) -> dict[str, np.ndarray]:
    """The room graph's seeded spring embedding; `pulled`: with each room that must open
    outside (onB) pulled out, tied to a point of its own on a circle round the building in
    the direction the plain embedding put it, and the embedding run again from there."""
    points = nx.spring_layout(graph, seed=seed, iterations=SPRING_ITERATIONS)
    outside = sorted(room.id for room in spec.rooms if room.on_boundary and room.id in graph) if pulled else []
    if not outside:
        return points
    centre = np.mean([points[node] for node in graph], axis=0)
    tied = graph.copy()
    start = dict(points)
    anchors = []
    for room_id in outside:
        direction = points[room_id] - centre
        norm = float(np.hypot(*direction))
        direction = direction / norm if norm > 1e-9 else np.array([1.0, 0.0])
        anchor = ("outside", room_id)
        tied.add_edge(room_id, anchor)
        start[anchor] = centre + OUTSIDE_RADIUS * direction
        anchors.append(anchor)
    drawn_out = nx.spring_layout(tied, pos=start, fixed=anchors, seed=seed,
                                 iterations=SPRING_ITERATIONS, k=1 / math.sqrt(len(graph)))
    # with fixed nodes spring_layout does not rescale: the rooms alone, as a plain one is
    return nx.rescale_layout_dict({node: drawn_out[node] for node in graph})


def initial_geometry(spec: Spec, rooms: Rooms, seed: int, pulled: bool = False) -> dict[str, Rect]:
    """Each room's drawn rectangle centred on its point of a seeded spring embedding of the
    room graph (`pulled`: with the entrances pulled outside), stretched to the outline;
    pinned rooms on their points."""
    graph = room_graph(spec)
    scale = math.sqrt(rooms.width * rooms.height) / 2
    points = _embedding(spec, graph, seed, pulled)
    aspect = math.sqrt(rooms.width / rooms.height)
    pinned = pinned_points(spec)
    rng = np.random.default_rng(seed)
    geometry = {}
    for i, room_id in enumerate(rooms.ids):
        px, py = points[room_id]
        cx = rooms.width / 2 + px * scale * aspect
        cy = rooms.height / 2 + py * scale / aspect
        if room_id in pinned:
            cx, cy = pinned[room_id]
        long_side, short_side = float(rooms.target_long[i]), float(rooms.target_short[i])
        w, h = (long_side, short_side) if rng.random() < 0.5 else (short_side, long_side)
        geometry[room_id] = (cx - w / 2, cy - h / 2, w, h)
    return geometry


def initial_state(spec: Spec, rooms: Rooms, seed: int, pulled: bool = False) -> State:
    """The state the schedule starts a chain from (see the module docstring)."""
    return rooms.state_of(initial_geometry(spec, rooms, seed, pulled))
