"""New arrangements from the room graph alone: greedy contact placement (issue 11).

The construction's repair (layoutdsl.compile.construct) turns a seed geometry into a verified
layout in well under a second when the geometry already realises nearly every adjacency as
a touching contact with few overlaps; that is why an imported plan's own boxes (its hints)
repair so fast. Spring embeddings of the room graph are a poor seed from ~40 rooms up or
with cycles. This module grows such a near-layout from the room graph and the size bounds
only, so that hints are never the reason a layout is found (the thesis generates from the
graph, §5.5).

Rooms are placed one at a time, each as a rectangle near its target size:

1. order: the corridor backbone first (corridors carry most doors in real schools and
   offices; breadth first over the corridors already placed), then the rooms with the most
   placed neighbours (the rooms that close cycles, which must touch all of them), leaves
   last; ties are broken by degree and by the seeded random generator;
2. candidates: for each placed neighbour, each of its four sides and a few slide offsets
   along it, in both orientations of the new room, the rectangle one wall thickness away
   from that side (a door needs exactly one wall between the rooms);
3. score (numpy, all candidates at once): overlap with placed rooms and obstacles
   (inflated by a wall), area outside the boundary, distance from every other placed
   neighbour (so cycle rooms land where they touch all of them), growth of the bounding
   box (compact buildings, as real ones are), and the boundary for rooms that must touch it;
4. choice: one of the few best candidates, drawn by the seeded random generator, so each
   seed gives another building while every choice stays a good one.

Rooms are drawn a little smaller than their target (SHRINK) to leave the repair room to
separate what the greedy pass could not; the final LP of the construction brings them back
towards their targets. Rooms with a fixed `position` (or `connection`) are placed over
their point first; obstacles are placed from the start. Clusters are left to the repair.
"""

from __future__ import annotations

import random
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import networkx as nx

import numpy as np

from layoutdsl.layout.geometry import Rect
from layoutdsl.syntax.ast import ARM_SUFFIX, Room, Spec, arm_id


@dataclass(frozen=True, slots=True)
class RoomSizes:
    """A room's size bounds in orientation-free form, as (5.4)-(5.6) read them."""

    lo_long: float
    hi_long: float
    lo_short: float
    hi_short: float
    min_ar: float
    max_ar: float
    corridor: bool
    target_long: float
    target_short: float

    @staticmethod
    def of(room: Room) -> RoomSizes:
        """Bounds of the long and the short side, whichever axis the room lies along."""
        return RoomSizes(
            lo_long=max(room.min_w, room.min_h),
            hi_long=max(room.max_w, room.max_h),
            lo_short=min(room.min_w, room.min_h),
            hi_short=min(room.max_w, room.max_h),
            min_ar=room.min_ar,
            max_ar=room.max_ar,
            corridor=room.is_corridor,
            target_long=max(room.target_w, room.target_h),
            target_short=min(room.target_w, room.target_h),
        )

    def bounds(self, long_along_x: bool) -> tuple[float, float, float, float]:
        """(w_lo, w_hi, h_lo, h_hi) for the given orientation."""
        if long_along_x:
            return self.lo_long, self.hi_long, self.lo_short, self.hi_short
        return self.lo_short, self.hi_short, self.lo_long, self.hi_long

    def targets(self, long_along_x: bool) -> tuple[float, float]:
        """(target w, target h) for the given orientation."""
        if long_along_x:
            return self.target_long, self.target_short
        return self.target_short, self.target_long


SLIDES = 7
"""Offsets along a neighbour's side tried for each new room (plus a random one)."""

TOP_CHOICES = 3
"""The new room's place is drawn among this many best-scored candidates."""

CHOICE_SLACK = 0.15
"""...of those, only candidates scoring within this share of the best score's scale."""

OVERLAP_WEIGHT = 8.0
"""Per m² of overlap (or of area outside the boundary): the dominant term."""

HALO_WEIGHT = 1.0
"""Per m² of the band a room's unplaced neighbours need that is taken (see _best_place)."""

CONTACT_WEIGHT = 3.0
"""Per metre a placed neighbour is from touching (cycles), or its wall is short."""

CYCLE_WEIGHT = 2.0
"""Per metre a room lands beyond the reach of a placed room it shares an unplaced
neighbour with (that neighbour closes a cycle and must touch both)."""

COMPACT_WEIGHT = 0.5
"""Per metre the placed rooms' bounding box grows (half perimeter): real buildings are
compact. Perimeter, not area: an area term outweighs small overlaps on large plans."""

BOUNDARY_WEIGHT = 2.0
"""Per metre a room that must touch the boundary (onB) is away from it."""


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
"""Target room area per m² of boundary above which corridors keep their drawn length: a
dense plan has no room to give them. Measured (construct_start, seeds 0-2, 45 s): on
school_hendersonhighschool (0.44) lengthened corridors construct 3 of 3 in 6-10 s, 1 of 3
without; on office_floorplanLOWER (0.87) lengthened took 4.7-36 s, unlengthened 0.6-5.3 s;
on school_scuolasconosciuta (0.57, L-rooms) lengthened found nothing in 30 s (seeds 0-1),
unlengthened 0.3 s."""


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
            # an L-room's box and arm are drawn as two rooms (compile.lshape.seeds_spec)
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


def drawn_sides(spec: Spec, shrink: float | None = None) -> dict[str, tuple[float, float]]:
    """(long, short) side each room is drawn with: targets shrunk to PACKING_DENSITY of
    the boundary (or by `shrink`), corridors lengthened for their rooms."""
    boundary = spec.boundary
    assert boundary is not None
    density = sum(room.target_w * room.target_h for room in spec.rooms) / (boundary.w * boundary.h)
    if shrink is None:
        shrink = min(MAX_SHRINK, (PACKING_DENSITY / max(density, 1e-9)) ** 0.5)
    sides = _target_sides(spec, shrink)
    if density > LENGTHEN_MAX_DENSITY:
        return sides
    return _corridors_lengthened(spec, sides, _neighbours(spec))


def _neighbours(spec: Spec) -> dict[str, list[str]]:
    neighbours: dict[str, list[str]] = {room.id: [] for room in spec.rooms}
    for adj in spec.adjacencies:
        neighbours[adj.a].append(adj.b)
        neighbours[adj.b].append(adj.a)
    return neighbours


def _fixed_points(spec: Spec) -> dict[str, tuple[float, float]]:
    points = {p.room: (p.x, p.y) for p in spec.positions}
    for c in spec.connections:
        points.setdefault(c.room, ((c.x1 + c.x2) / 2, (c.y1 + c.y2) / 2))
    return points


class _Placement:
    """The rectangles placed so far, as numpy arrays for vectorised scoring."""

    def __init__(self, width: float, height: float, walldim: float):
        self.width, self.height, self.walldim = width, height, walldim
        self.ids: list[str] = []
        self.rects = np.zeros((0, 4))
        self.blockers = np.zeros((0, 4))
        """Placed rooms and obstacles: what a new room must not overlap."""

    def add(self, room_id: str | None, rect: Rect) -> None:
        row = np.array([rect], dtype=float)
        self.blockers = np.vstack([self.blockers, row])
        if room_id is not None:
            self.ids.append(room_id)
            self.rects = np.vstack([self.rects, row])

    def bbox(self) -> tuple[float, float, float, float] | None:
        if not len(self.rects):
            return None
        r = self.rects
        return (r[:, 0].min(), r[:, 1].min(), (r[:, 0] + r[:, 2]).max(), (r[:, 1] + r[:, 3]).max())


def _side_candidates(anchor: np.ndarray, w: float, h: float, walldim: float, wall: float,
                     blockers: np.ndarray, rng: random.Random) -> np.ndarray:
    """(x, y, w, h) rows: a w x h room touching the anchor on each side, slid along it.

    The slide offsets are evenly spread, one drawn, and snapped: flush with the anchor's
    ends and one wall away from the edges of the rooms already placed, so that rooms pack
    along a corridor as in bottom-left packing instead of leaving gaps between them.
    """
    ax, ay, aw, ah = anchor
    overlap_w = min(wall, aw, w)
    overlap_h = min(wall, ah, h)
    # the shared wall must be at least the door's wall: y slides over [lo_y, hi_y]
    lo_y, hi_y = ay - h + overlap_h, ay + ah - overlap_h
    lo_x, hi_x = ax - w + overlap_w, ax + aw - overlap_w
    fractions = np.array([i / (SLIDES - 1) for i in range(SLIDES)] + [rng.random()])
    ys = [lo_y + fractions * (hi_y - lo_y), [ay, ay + ah - h]]
    xs = [lo_x + fractions * (hi_x - lo_x), [ax, ax + aw - w]]
    if len(blockers):
        ys += [blockers[:, 1] + blockers[:, 3] + walldim, blockers[:, 1] - h - walldim]
        xs += [blockers[:, 0] + blockers[:, 2] + walldim, blockers[:, 0] - w - walldim]
    ys = np.concatenate([np.asarray(v, dtype=float) for v in ys])
    xs = np.concatenate([np.asarray(v, dtype=float) for v in xs])
    ys = np.unique(ys[(ys >= lo_y - 1e-9) & (ys <= hi_y + 1e-9)])
    xs = np.unique(xs[(xs >= lo_x - 1e-9) & (xs <= hi_x + 1e-9)])
    right = np.column_stack([np.full(len(ys), ax + aw + walldim), ys])
    left = np.column_stack([np.full(len(ys), ax - walldim - w), ys])
    up = np.column_stack([xs, np.full(len(xs), ay + ah + walldim)])
    down = np.column_stack([xs, np.full(len(xs), ay - walldim - h)])
    corners = np.vstack([right, left, up, down])
    return np.column_stack([corners, np.full(len(corners), w), np.full(len(corners), h)])


def _overlap_area(cands: np.ndarray, others: np.ndarray, pad: float) -> np.ndarray:
    """Per candidate: total overlap area with `others`, each side padded by `pad`."""
    if not len(others):
        return np.zeros(len(cands))
    cx0 = cands[:, 0:1] - pad
    cy0 = cands[:, 1:2] - pad
    cx1 = cands[:, 0:1] + cands[:, 2:3] + pad
    cy1 = cands[:, 1:2] + cands[:, 3:4] + pad
    ox = np.minimum(cx1, others[None, :, 0] + others[None, :, 2]) - np.maximum(cx0, others[None, :, 0])
    oy = np.minimum(cy1, others[None, :, 1] + others[None, :, 3]) - np.maximum(cy0, others[None, :, 1])
    return (np.clip(ox, 0, None) * np.clip(oy, 0, None)).sum(axis=1)


def _contact_shortfall(cands: np.ndarray, other: np.ndarray, walldim: float, wall: float) -> np.ndarray:
    """Per candidate: metres from touching `other` with a shared wall of `wall` m."""
    ox, oy, ow, oh = other
    sep_x = np.maximum(ox - cands[:, 0] - cands[:, 2], cands[:, 0] - ox - ow)
    sep_y = np.maximum(oy - cands[:, 1] - cands[:, 3], cands[:, 1] - oy - oh)
    # touching along x: sep_x == walldim and the y-overlap (= -sep_y) >= wall; same for y
    along_x = np.abs(sep_x - walldim) + np.clip(wall + sep_y, 0, None)
    along_y = np.abs(sep_y - walldim) + np.clip(wall + sep_x, 0, None)
    return np.minimum(along_x, along_y)


def _outside_area(cands: np.ndarray, width: float, height: float) -> np.ndarray:
    x0, y0 = cands[:, 0], cands[:, 1]
    x1, y1 = x0 + cands[:, 2], y0 + cands[:, 3]
    inside_w = np.clip(np.minimum(x1, width) - np.maximum(x0, 0), 0, None)
    inside_h = np.clip(np.minimum(y1, height) - np.maximum(y0, 0), 0, None)
    return cands[:, 2] * cands[:, 3] - inside_w * inside_h


def _boundary_distance(cands: np.ndarray, width: float, height: float) -> np.ndarray:
    x0, y0 = cands[:, 0], cands[:, 1]
    x1, y1 = x0 + cands[:, 2], y0 + cands[:, 3]
    return np.clip(np.minimum.reduce([x0, y0, width - x1, height - y1]), 0, None)


def _bbox_growth(cands: np.ndarray, bbox, width: float, height: float) -> np.ndarray:
    """Metres the placed rooms' bounding box grows, each axis weighted by how much of the
    boundary it has: in a long, thin boundary, growing along it is cheap and across it dear,
    so the building takes the boundary's shape instead of a square in its middle."""
    if bbox is None:
        return np.zeros(len(cands))
    bx0, by0, bx1, by1 = bbox
    nx0 = np.minimum(bx0, cands[:, 0])
    ny0 = np.minimum(by0, cands[:, 1])
    nx1 = np.maximum(bx1, cands[:, 0] + cands[:, 2])
    ny1 = np.maximum(by1, cands[:, 1] + cands[:, 3])
    mean = (width + height) / 2
    return ((nx1 - nx0 - bx1 + bx0) * mean / width + (ny1 - ny0 - by1 + by0) * mean / height)


def _orientations(long_side: float, short_side: float, width: float, height: float,
                  rng: random.Random) -> list[tuple[float, float]]:
    """(w, h) of both orientations, those that fit the boundary; random order for ties."""
    both = [(long_side, short_side), (short_side, long_side)]
    if long_side == short_side:
        both = both[:1]
    fitting = [(w, h) for w, h in both if w <= width and h <= height]
    rng.shuffle(fitting)
    return fitting or both[:1]


PACKING_DENSITY = 0.5
"""Room area the greedy pass aims to lay out per m² of boundary: dense plans (real ones
fill up to 100 % of their bounding box with target areas) are drawn smaller, so the greedy
pass finds free sides; the construction's final LP grows them back as far as they fit."""

MAX_SHRINK = 0.92


DRAWS = 3
"""Greedy placements drawn per seed geometry; the one with the fewest defects is kept."""


def generate_geometry(spec: Spec, rng: random.Random, *, shrink: float | None = None,
                      draws: int = DRAWS, templates: Sequence[Mapping[str, Rect]] = (),
                      choices: int = TOP_CHOICES) -> dict[str, Rect]:
    """A seed geometry for the construction's repair, grown from the room graph alone.

    Every adjacency of the spec is, where the greedy choice could manage it, a touching
    contact with one wall thickness between the rooms; overlaps are few. `draws` placements
    are drawn from `rng` and the one with the least overlap and missing contact is kept
    (measured: the repair's time grows with those defects). Different draws of `rng` give
    different arrangements; more `choices` (each room's place drawn among more of its best
    candidates) give arrangements that differ more from one seed to the next.
    """
    best: tuple[float, dict[str, Rect]] | None = None
    for _ in range(max(1, draws)):
        geometry, defect = _draw_geometry(spec, rng, shrink, templates, choices)
        if best is None or defect < best[0]:
            best = (defect, geometry)
    assert best is not None
    return best[1]


def _draw_geometry(spec: Spec, rng: random.Random, shrink: float | None,
                   templates: Sequence[Mapping[str, Rect]] = (),
                   choices: int = TOP_CHOICES) -> tuple[dict[str, Rect], float]:
    """One greedy placement plus rip-up-and-replace: (geometry, its total defect)."""
    boundary = spec.boundary
    assert boundary is not None
    width, height = boundary.w, boundary.h
    walldim = spec.settings.walldim
    door_factor = spec.settings.door_utilization
    walls: dict[frozenset[str], float] = {
        frozenset((adj.a, adj.b)): adj.door / door_factor for adj in spec.adjacencies
    }
    neighbours = _neighbours(spec)
    sides = drawn_sides(spec, shrink)
    corridor = {room.id: room.is_corridor for room in spec.rooms}
    on_boundary = {room.id: room.on_boundary for room in spec.rooms}
    degree = {room_id: len(ns) for room_id, ns in neighbours.items()}
    # the draws from rng stay in this order (tie-breaks, pinned rooms' orientations, then
    # each placement): the same seed gives the same geometry
    tiebreak = {room.id: rng.random() for room in spec.rooms}
    placement = _Placement(width, height, walldim)
    for ob in boundary.obstacles:
        placement.add(None, (ob.x, ob.y, ob.w, ob.h))
    geometry: dict[str, Rect] = {}

    def put(room_id: str, rect: Rect) -> None:
        geometry[room_id] = rect
        placement.add(room_id, rect)

    # rooms pinned to a point are placed over it first: everything else grows around them
    for room_id, (px, py) in _fixed_points(spec).items():
        long_side, short_side = sides[room_id]
        w, h = _orientations(long_side, short_side, width, height, rng)[0]
        x = min(max(0.0, px - w / 2), max(0.0, width - w))
        y = min(max(0.0, py - h / 2), max(0.0, height - h))
        put(room_id, (x, y, w, h))

    unplaced = [room.id for room in spec.rooms if room.id not in geometry]
    dropped: set[int] = set()
    while unplaced:
        room_id = _next_room(unplaced, geometry, neighbours, corridor, degree, sides, tiebreak)
        pending = [t for t in templates if room_id in t and not all(r in geometry for r in t)
                   and id(t) not in dropped]
        if pending:
            # a cycle block: all its rooms at once, as they were solved together
            placed = _place_template(pending[0], room_id, placement, geometry, neighbours, walls, rng,
                                     choices)
            if placed is None:
                # it shares a placed room solved in another shape: its rooms go one by one
                dropped.add(id(pending[0]))
                continue
            for other, rect in placed.items():
                put(other, rect)
                if other in unplaced:
                    unplaced.remove(other)
            continue
        unplaced.remove(room_id)
        own_depth, foreign = _halos(room_id, unplaced, geometry, sides, neighbours, degree)
        partners = _cycle_partners(room_id, geometry, sides, neighbours)
        corridor_anchors = {n for n in neighbours[room_id] if corridor[room_id] and corridor[n]}
        put(room_id, _best_place(room_id, placement, sides[room_id], neighbours[room_id],
                                 walls, geometry, on_boundary[room_id], rng, own_depth,
                                 foreign, partners, corridor_anchors, choices))
    fixed = set(_fixed_points(spec))
    shift_fixed = set(fixed)
    # the rooms of a placed block keep the places they were solved in: moving one alone
    # would only break the contacts that close its cycles
    fixed |= {room_id for t in templates if id(t) not in dropped for room_id in t if room_id in geometry}
    if not shift_fixed and len(placement.rects):
        _centre_in_boundary(geometry, placement, width, height)
    for _ in range(REPLACE_PASSES):
        moved = _replace_worst(geometry, placement, sides, neighbours, walls, on_boundary, fixed)
        placement = _move_subtrees(geometry, placement, neighbours, walls, shift_fixed)
        if not moved:
            break
    return geometry, sum(_room_defects(geometry, placement, neighbours, walls).values())


def _next_room(unplaced: list[str], geometry: dict[str, Rect], neighbours: dict[str, list[str]],
               corridor: dict[str, bool], degree: dict[str, int],
               sides: dict[str, tuple[float, float]], tiebreak: dict[str, float]) -> str:
    """The room the greedy placement takes next."""
    placed_count = {
        r: sum(1 for n in neighbours[r] if n in geometry) for r in unplaced
    }
    frontier = [r for r in unplaced if placed_count[r] > 0]
    if frontier:
        # corridors first, then rooms closing cycles (several placed neighbours), leaves last
        # (bigger rooms before smaller ones: small ones fit in the gaps that are left)
        return max(frontier, key=lambda r: (corridor[r], min(placed_count[r], 2),
                                            degree[r], sides[r][0] * sides[r][1],
                                            tiebreak[r]))
    # a new component (or the first room): its best-connected room, corridor first
    return max(unplaced, key=lambda r: (corridor[r], degree[r], tiebreak[r]))


def _halos(room_id: str, unplaced: list[str], geometry: dict[str, Rect],
           sides: dict[str, tuple[float, float]], neighbours: dict[str, list[str]],
           degree: dict[str, int]) -> tuple[float, np.ndarray]:
    """Space kept free for the rooms still to hang off each placed room (and this one).

    Returns (this room's halo depth, the placed rooms' halos as an (n, 4) array of rects).
    """
    area = {r: sides[r][0] * sides[r][1] / max(1, degree[r]) for r in unplaced}
    own_depth = _halo_depth(sides[room_id], [area[n] for n in neighbours[room_id]
                                             if n in area], sides, neighbours[room_id])
    foreign = []
    for other, rect in geometry.items():
        # neighbours too: a corridor that touches another along its whole side takes
        # the side the other's rooms need; touching at its end costs little of it
        depth = _halo_depth(rect[2:], [area[n] for n in neighbours[other] if n in area],
                            sides, neighbours[other])
        if depth > 0:
            foreign.append(_grow(np.array(rect), depth))
    return own_depth, np.array(foreign).reshape(-1, 4)


def _cycle_partners(room_id: str, geometry: dict[str, Rect], sides: dict[str, tuple[float, float]],
                    neighbours: dict[str, list[str]]) -> dict[str, float]:
    """Placed rooms that share an unplaced neighbour with this one -> that neighbour's short
    side: the neighbour will have to touch both, so this room should land within its reach."""
    partners = {}
    for n in neighbours[room_id]:
        if n in geometry:
            continue
        for p in neighbours[n]:
            if p in geometry:
                partners[p] = max(partners.get(p, 0.0), sides[n][1])
    return partners


def _centre_in_boundary(geometry: dict[str, Rect], placement: _Placement, width: float,
                        height: float) -> None:
    """Shift the placed building, as a whole and in place, to the centre of the boundary.

    It grew from a drawn first room and may stick out on one side, or touch it, while
    there is room on the other; centred, the repair has slack on every side to push
    conflicts out into.
    """
    x0, y0, x1, y1 = placement.bbox()
    dx = (width - x1 - x0) / 2
    dy = (height - y1 - y0) / 2
    if dx or dy:
        shift = np.array([dx, dy, 0.0, 0.0])
        placement.rects += shift
        placement.blockers[len(placement.blockers) - len(placement.rects):] += shift
        for room_id, (x, y, w, h) in geometry.items():
            geometry[room_id] = (x + dx, y + dy, w, h)


def room_graph(spec: Spec) -> nx.Graph:
    """The spec's rooms as nodes (in the spec's order), its adjacencies as edges."""
    graph = nx.Graph()
    graph.add_nodes_from(room.id for room in spec.rooms)
    graph.add_edges_from((adj.a, adj.b) for adj in spec.adjacencies)
    return graph


def cycle_blocks(spec: Spec) -> list[frozenset[str]]:
    """The parts of the room graph where rooms close cycles: its biconnected components of
    three rooms or more, largest first. In real plans they are small (at most 27 of 105
    rooms, mostly 3-11) while the rest of the graph is trees hanging off them."""
    blocks = [frozenset(b) for b in nx.biconnected_components(room_graph(spec)) if len(b) >= 3]
    return sorted(blocks, key=lambda b: (-len(b), sorted(b)))


CORE_BLOCK_ROOMS = 12
"""Biconnected blocks of this many rooms or more form the core of the core-and-satellites
annealer (layoutdsl.compile.satellites); smaller blocks (a classroom and a closet beside a
corridor, say) are placed as satellites, their cycle closed by the
satellite's extra door. On school_stjoseph_scatholichighschool the core is then its 27-room
block: with the whole 54-room 2-core as the core, two runs of 2M moves ended 16 m and 18 m
from a layout, with the 27-room block 0.1 m and 1.9 m at 1M. A plan without such a block is
not split: the 2-core of office_OfficePlan (9 rooms), office_floorplanLOWER and
office_floorplanMAIN as a core left runs 4-40 m from a layout where the sequence pair meets
every door (bench/results/satellites.txt), and compile got slower with them."""


def core_rooms(spec: Spec) -> frozenset[str] | None:
    """The rooms of the spec's cycle blocks of CORE_BLOCK_ROOMS rooms or more (the core that
    layoutdsl.compile.satellites anneals, every other room placed beside it), or None when it
    has no such block or no room outside them."""
    core = frozenset().union(*(block for block in cycle_blocks(spec) if len(block) >= CORE_BLOCK_ROOMS))
    if not core or len(core) == len(spec.rooms):
        return None
    return core


def _mirrored(template: Mapping[str, Rect], flip_x: bool, flip_y: bool,
              turn: bool = False) -> dict[str, Rect]:
    """The template mirrored about its frame's axes (and, with `turn`, about its diagonal:
    x and y swapped): the same contacts, another building."""
    if turn:
        template = {room_id: (y, x, h, w) for room_id, (x, y, w, h) in template.items()}
    return {
        room_id: (-x - w if flip_x else x, -y - h if flip_y else y, w, h)
        for room_id, (x, y, w, h) in template.items()
    }


SHAPE_TOLERANCE = 1e-3
"""Metres two solutions of a room shared by two blocks may differ by and still be one
(the solver leaves its sizes a few micrometres off the bounds they were pinned to)."""

SYMMETRIES = [(flip_x, flip_y, turn) for turn in (False, True) for flip_x in (False, True)
              for flip_y in (False, True)]
"""The 8 images of a template: 4 mirror images, each also turned a quarter."""


def _place_template(template: Mapping[str, Rect], room_id: str, placement: _Placement,
                    geometry: dict[str, Rect], neighbours: dict[str, list[str]],
                    walls: dict[frozenset[str], float], rng: random.Random,
                    choices: int = TOP_CHOICES) -> dict[str, Rect] | None:
    """Where a solved cycle block goes, as a rigid whole: its rooms not yet placed (None
    when it shares a placed room that has another shape there).

    A block with a room already placed (a room two blocks share) is laid over that room, in
    each of its 8 images (mirrored, turned) in which that room has the shape it was placed
    with; otherwise `room_id` is put against the sides of its placed neighbours as a single
    room would be, and the rest of the block follows it. Candidates are scored like single
    rooms: overlap, area outside the boundary, missing contacts with placed rooms outside
    the block, growth of the building.
    """
    width, height, walldim = placement.width, placement.height, placement.walldim
    todo = [r for r in template if r not in geometry]
    anchors = [r for r in template if r in geometry]
    offsets, shapes = [], []
    extent = (max(x + w for x, _, w, _ in template.values()) - min(x for x, _, _, _ in template.values()),
              max(y + h for _, y, _, h in template.values()) - min(y for _, y, _, _ in template.values()))
    # turned a quarter only where the boundary holds the block that way
    turns = [turn for turn, (w, h) in ((False, extent), (True, extent[::-1]))
             if w <= width + 1e-9 and h <= height + 1e-9] or [False, True]
    for flip_x, flip_y, turn in SYMMETRIES:
        if turn not in turns:
            continue
        shape = _mirrored(template, flip_x, flip_y, turn)
        if anchors:
            # laid over the shared room as it was placed, where it has that shape
            ax, ay, aw, ah = geometry[anchors[0]]
            sx, sy, sw, sh = shape[anchors[0]]
            if abs(aw - sw) > SHAPE_TOLERANCE or abs(ah - sh) > SHAPE_TOLERANCE:
                continue
            moves = np.array([[ax - sx, ay - sy]])
        else:
            x, y, w, h = shape[room_id]
            placed = [n for n in neighbours[room_id] if n in geometry]
            blocks = [_side_candidates(np.array(geometry[n]), w, h, walldim, walls[frozenset((room_id, n))],
                                       placement.blockers, rng) for n in placed]
            cands = np.vstack(blocks) if blocks else _free_candidates(placement, w, h, rng)
            moves = cands[:, :2] - np.array([x, y])
        offsets.append(moves)
        shapes.append(np.array([shape[r] for r in todo], dtype=float))
    if not offsets:
        return None
    # every (mirror image, offset) as len(todo) rectangles
    cand_shapes = np.concatenate([np.repeat(shape[None], len(moves), axis=0) for shape, moves in zip(shapes, offsets)])
    moves = np.concatenate(offsets)
    rects = cand_shapes.copy()
    rects[:, :, :2] += moves[:, None, :]
    flat = rects.reshape(-1, 4)
    per_room = OVERLAP_WEIGHT * (_overlap_area(flat, placement.blockers, walldim - 1e-9)
                                 + _outside_area(flat, width, height))
    for k, r in enumerate(todo):
        for n in neighbours[r]:
            if n in geometry and n not in template:
                per_room.reshape(len(moves), len(todo))[:, k] += CONTACT_WEIGHT * _contact_shortfall(
                    rects[:, k], np.array(geometry[n]), walldim, walls[frozenset((r, n))])
    score = per_room.reshape(len(moves), len(todo)).sum(axis=1)
    union = np.column_stack([rects[:, :, 0].min(axis=1), rects[:, :, 1].min(axis=1),
                             (rects[:, :, 0] + rects[:, :, 2]).max(axis=1) - rects[:, :, 0].min(axis=1),
                             (rects[:, :, 1] + rects[:, :, 3]).max(axis=1) - rects[:, :, 1].min(axis=1)])
    score += COMPACT_WEIGHT * _bbox_growth(union, placement.bbox(), width, height)
    order = np.argsort(score, kind="stable")
    best = score[order[0]]
    scale = max(1.0, abs(best))
    good = [int(i) for i in order[:choices] if score[i] <= best + CHOICE_SLACK * scale]
    chosen = rects[good[rng.randrange(len(good))]]
    return {r: tuple(float(v) for v in chosen[k]) for k, r in enumerate(todo)}


REPLACE_PASSES = 4
"""Rip-up-and-replace passes over the rooms the greedy pass left overlapping."""


def _room_defects(geometry: dict[str, Rect], placement: _Placement,
                  neighbours: dict[str, list[str]], walls: dict[frozenset[str], float]) -> dict[str, float]:
    """Per room: its overlap (m², walls included), area outside, and contact shortfalls."""
    rects, blockers = placement.rects, placement.blockers
    pad = placement.walldim - 1e-9
    ox = (np.minimum(rects[:, None, 0] + rects[:, None, 2] + pad, blockers[None, :, 0] + blockers[None, :, 2])
          - np.maximum(rects[:, None, 0] - pad, blockers[None, :, 0]))
    oy = (np.minimum(rects[:, None, 1] + rects[:, None, 3] + pad, blockers[None, :, 1] + blockers[None, :, 3])
          - np.maximum(rects[:, None, 1] - pad, blockers[None, :, 1]))
    overlap = np.clip(ox, 0, None) * np.clip(oy, 0, None)
    own = np.arange(len(rects))
    overlap[own, own + len(blockers) - len(rects)] = 0.0  # a room does not overlap itself
    values = OVERLAP_WEIGHT * (overlap.sum(axis=1)
                               + _outside_area(rects, placement.width, placement.height))
    index = {room_id: i for i, room_id in enumerate(placement.ids)}
    for pair, wall in walls.items():
        a, b = tuple(pair)
        shortfall = CONTACT_WEIGHT * _contact_shortfall(
            rects[index[a]:index[a] + 1], rects[index[b]], placement.walldim, wall)[0]
        values[index[a]] += shortfall
        values[index[b]] += shortfall
    return {room_id: float(values[i]) for room_id, i in index.items()}


SUBTREE_GAIN = 1e-3
"""Least drop of the total defect for which a subtree is moved."""


def _move_subtrees(geometry: dict[str, Rect], placement: _Placement,
                   neighbours: dict[str, list[str]], walls: dict[frozenset[str], float],
                   pinned: set[str]) -> _Placement:
    """Move, as rigid wholes, the parts of the building hanging off a door that is not
    realised, so that door's rooms touch; returns the placement (rebuilt when one moved).

    Most of a real room graph is trees hanging off the corridors: when the door on which
    such a tree hangs (a bridge of the graph) is missing, moving its room alone, as
    `_replace_worst` does, breaks every door further down the tree, and the repair stalls
    on the same defect (measured on school_wilbraham: an entrance hanging between a
    corridor and a four-room wing 5 m away stalled every repair round). Moved whole, in
    any of its four mirror images, the tree keeps its own doors.
    """
    graph = nx.Graph()
    graph.add_nodes_from(geometry)
    graph.add_edges_from((a, b) for a in neighbours for b in neighbours[a] if a < b)
    # the total defect, kept up to date as trees move: each bridge compares against it
    total = sum(_room_defects(geometry, placement, neighbours, walls).values())
    for u, v in sorted(nx.bridges(graph)):
        shortfall = _contact_shortfall(np.array([geometry[u]]), np.array(geometry[v]),
                                       placement.walldim, walls[frozenset((u, v))])[0]
        if shortfall <= 1e-6:
            continue
        graph.remove_edge(u, v)
        side_u, side_v = nx.node_connected_component(graph, u), nx.node_connected_component(graph, v)
        graph.add_edge(u, v)
        if len(side_u) < len(side_v):
            u, v, side_v = v, u, side_u
        if side_v & pinned:
            continue
        rest = {room_id: rect for room_id, rect in geometry.items() if room_id not in side_v}
        others = _placement_of(rest, placement)
        template = {room_id: geometry[room_id] for room_id in geometry if room_id in side_v}
        moved = _place_template(template, v, others, rest, neighbours, walls, _NO_DRAW)
        if moved is None:
            continue
        trial = {room_id: moved.get(room_id, rect) for room_id, rect in geometry.items()}
        trial_placement = _placement_of(trial, placement)
        trial_total = sum(_room_defects(trial, trial_placement, neighbours, walls).values())
        if trial_total < total - SUBTREE_GAIN:
            geometry.update(trial)
            placement, total = trial_placement, trial_total
    return placement


def _placement_of(geometry: dict[str, Rect], like: _Placement) -> _Placement:
    """A placement of these rooms, with the obstacles of `like`."""
    placement = _Placement(like.width, like.height, like.walldim)
    for row in like.blockers[:len(like.blockers) - len(like.rects)]:
        placement.add(None, tuple(float(v) for v in row))
    for room_id, rect in geometry.items():
        placement.add(room_id, rect)
    return placement


def _blocker_index(placement: _Placement, room_index: int) -> int:
    """Row of the room in placement.blockers (obstacles come first there)."""
    return len(placement.blockers) - len(placement.rects) + room_index


def _replace_worst(geometry, placement: _Placement, sides, neighbours, walls, on_boundary,
                   fixed: set[str]) -> bool:
    """Take out each room with a defect, worst first, and put it back where it scores best
    with all its neighbours placed (either orientation, any neighbour's side); True when
    some room moved. The greedy pass placed it knowing only the rooms before it."""
    defects = _room_defects(geometry, placement, neighbours, walls)
    moved = False
    for room_id in sorted(defects, key=lambda r: -defects[r]):
        if defects[room_id] <= 1e-6 or room_id in fixed:
            continue
        index = placement.ids.index(room_id)
        row = _blocker_index(placement, index)
        others = np.delete(placement.blockers, row, axis=0)
        long_side, short_side = sides[room_id]
        blocks = [placement.rects[index:index + 1]]
        for w, h in ((long_side, short_side), (short_side, long_side)):
            for n in neighbours[room_id]:
                blocks.append(_side_candidates(np.array(geometry[n]), w, h, placement.walldim,
                                               walls[frozenset((room_id, n))], others, _NO_DRAW))
        cands = np.vstack(blocks)
        score = OVERLAP_WEIGHT * (_overlap_area(cands, others, placement.walldim - 1e-9)
                                  + _outside_area(cands, placement.width, placement.height))
        for n in neighbours[room_id]:
            score += CONTACT_WEIGHT * _contact_shortfall(
                cands, np.array(geometry[n]), placement.walldim, walls[frozenset((room_id, n))])
        if on_boundary[room_id]:
            score += BOUNDARY_WEIGHT * _boundary_distance(cands, placement.width, placement.height)
        best = int(np.argmin(score))
        if best == 0 or score[best] >= score[0] - 1e-6:
            continue
        rect = tuple(float(v) for v in cands[best])
        geometry[room_id] = rect
        placement.rects[index] = rect
        placement.blockers[row] = rect
        moved = True
    return moved


class _MidDraw:
    """A stand-in for the random generator where the choice must not depend on the seed."""

    @staticmethod
    def random() -> float:
        return 0.5

    @staticmethod
    def randrange(stop: int) -> int:
        return 0


_NO_DRAW = _MidDraw()


def _halo_depth(size, pending_areas: list[float], sides, room_neighbours) -> float:
    """How deep a band around a room its unplaced neighbours need: their area over its
    perimeter, at most the longest side among them (they hang off it, they don't stack)."""
    if not pending_areas:
        return 0.0
    perimeter = 2 * (size[0] + size[1])
    deepest = max(sides[n][0] for n in room_neighbours)
    return min(deepest, sum(pending_areas) / perimeter)


def _grow(rects: np.ndarray, depth: float) -> np.ndarray:
    """Rectangles (x, y, w, h) grown by `depth` on every side."""
    grown = np.array(rects, dtype=float, copy=True)
    grown[..., 0] -= depth
    grown[..., 1] -= depth
    grown[..., 2] += 2 * depth
    grown[..., 3] += 2 * depth
    return grown


def _best_place(room_id: str, placement: _Placement, sides: tuple[float, float],
                room_neighbours: list[str], walls: dict[frozenset[str], float],
                geometry: dict[str, Rect], on_boundary: bool, rng: random.Random,
                own_depth: float, foreign_halos: np.ndarray,
                partners: dict[str, float] | None = None,
                corridor_anchors: set[str] = frozenset(), choices: int = TOP_CHOICES) -> Rect:
    """Where the room goes: the seeded pick among the best-scored candidate rectangles.

    Besides overlaps, a candidate pays (at HALO_WEIGHT) for the band of `own_depth` around
    it that its own unplaced neighbours will need, where placed rooms or the boundary take
    it, and for taking the bands `foreign_halos` other placed rooms keep for theirs: a
    corridor backbone placed first then leaves room for the rooms that hang off it.
    """
    width, height, walldim = placement.width, placement.height, placement.walldim
    placed_neighbours = [n for n in room_neighbours if n in geometry]
    blocks = []
    for w, h in _orientations(*sides, width, height, rng):
        if placed_neighbours:
            for n in placed_neighbours:
                wall = walls[frozenset((room_id, n))]
                blocks.append(_side_candidates(np.array(geometry[n]), w, h, walldim, wall,
                                               placement.blockers, rng))
        else:
            blocks.append(_free_candidates(placement, w, h, rng))
    cands = np.vstack(blocks)
    score = OVERLAP_WEIGHT * (_overlap_area(cands, placement.blockers, walldim - 1e-9)
                              + _outside_area(cands, width, height))
    if own_depth > 0:
        halo = _grow(cands, own_depth)
        others = placement.rects[[i for i, r in enumerate(placement.ids) if r not in room_neighbours]]
        score += HALO_WEIGHT * (_overlap_area(halo, others, 0.0) + _outside_area(halo, width, height))
    score += HALO_WEIGHT * _overlap_area(cands, foreign_halos, 0.0)
    for n in placed_neighbours:
        wall = walls[frozenset((room_id, n))]
        score += CONTACT_WEIGHT * _contact_shortfall(cands, np.array(geometry[n]), walldim, wall)
        if n in corridor_anchors:
            score += SIDE_BY_SIDE_WEIGHT * _side_by_side(cands, np.array(geometry[n]), walldim)
    score += COMPACT_WEIGHT * _bbox_growth(cands, placement.bbox(), width, height)
    if on_boundary:
        score += BOUNDARY_WEIGHT * _boundary_distance(cands, width, height)
    for partner, reach in (partners or {}).items():
        px, py, pw, ph = geometry[partner]
        gap = np.maximum(np.maximum(px - cands[:, 0] - cands[:, 2], cands[:, 0] - px - pw),
                         np.maximum(py - cands[:, 1] - cands[:, 3], cands[:, 1] - py - ph))
        score += CYCLE_WEIGHT * np.clip(gap - reach - 2 * walldim, 0, None)
    order = np.argsort(score, kind="stable")
    best = score[order[0]]
    scale = max(1.0, abs(best), (sides[0] + sides[1]) * COMPACT_WEIGHT)
    good = [int(i) for i in order[:choices] if score[i] <= best + CHOICE_SLACK * scale]
    x, y, w, h = cands[good[rng.randrange(len(good))]]
    return (float(x), float(y), float(w), float(h))


SIDE_BY_SIDE_WEIGHT = 4.0
"""Per m² of the strip two corridors sharing a door would take from each other's rooms
when they lie side by side (see _side_by_side)."""


def _side_by_side(cands: np.ndarray, corridor: np.ndarray, walldim: float) -> np.ndarray:
    """Per candidate corridor touching `corridor`: the length of wall they share beyond the
    candidate's end, times the candidate's width.

    Real corridors meet end to end or in a T, one's end against the other's side. Two laid
    side by side along their length take each other's sides, where their rooms must hang:
    measured on office_floorplanLOWER, two 30 m corridors placed so left their 16 rooms
    piling over one another and no geometry repaired.
    """
    ox, oy, ow, oh = corridor
    shared_y = np.clip(np.minimum(cands[:, 1] + cands[:, 3], oy + oh) - np.maximum(cands[:, 1], oy), 0, None)
    shared_x = np.clip(np.minimum(cands[:, 0] + cands[:, 2], ox + ow) - np.maximum(cands[:, 0], ox), 0, None)
    beside_x = (np.abs(cands[:, 0] - ox - ow - walldim) < 1e-6) | (np.abs(ox - cands[:, 0] - cands[:, 2] - walldim) < 1e-6)
    beside_y = (np.abs(cands[:, 1] - oy - oh - walldim) < 1e-6) | (np.abs(oy - cands[:, 1] - cands[:, 3] - walldim) < 1e-6)
    width = np.minimum(cands[:, 2], cands[:, 3])
    excess = np.where(beside_x, np.clip(shared_y - width, 0, None), 0.0)
    excess += np.where(beside_y, np.clip(shared_x - width, 0, None), 0.0)
    return excess * width


def _free_candidates(placement: _Placement, w: float, h: float, rng: random.Random) -> np.ndarray:
    """Places for a room with no placed neighbour: a grid over the boundary, plus jitter.

    The very first room goes anywhere the grid offers (the draw makes buildings differ);
    the first room of a further component prefers to sit close to, not on, the others.
    """
    width, height = placement.width, placement.height
    steps = 9
    xs = [(width - w) * (i + rng.random() * 0.5) / steps for i in range(steps)]
    ys = [(height - h) * (j + rng.random() * 0.5) / steps for j in range(steps)]
    rows = [(max(0.0, x), max(0.0, y), w, h) for x in xs for y in ys]
    if not len(placement.rects):
        # the first room: somewhere in the middle third of the boundary, drawn
        cx = width * (1 / 3 + rng.random() / 3)
        cy = height * (1 / 3 + rng.random() / 3)
        rows = [(min(max(0.0, cx - w / 2), max(0.0, width - w)),
                 min(max(0.0, cy - h / 2), max(0.0, height - h)), w, h)]
    return np.array(rows, dtype=float)

