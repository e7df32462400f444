"""New arrangements by annealing the rooms in cycles only, with the rooms hanging off them
placed beside their parents after every move (issue 11).

The sequence-pair annealer (layoutdsl.compile.anneal) packs every room of a plan in one
sequence pair. On school_stjoseph_scatholichighschool (105 rooms, 26 independent cycles) its
runs ended 5-90 m from a layout, whatever was tried (bench/results/anneal-align.txt,
anneal-stages.txt). Two things stood in the way, both measured there: rooms hanging off a
corridor that the packing puts between two rooms that need a door (a room *in the way*), and
a packed 2-core that leaves no free wall for the hanging rooms once they come back.

Here the plan is split in two:

- the *core*: the biconnected blocks of generate.CORE_BLOCK_ROOMS rooms or more, the part
  where the large cycles must close. It is a sequence pair, moved and packed as the
  sequence-pair annealer does (anneal._propose, anneal._evaluate);
- the *satellites*: every other room, in breadth-first order from the core, each with the
  room it hangs off (its parent). After each packing of the core they are placed one by one,
  greedily, in free space beside their parent (_place_satellites): on one of its four sides,
  centred, flush with either end (or with the boundary, for a room that must touch it),
  lined up with another door neighbour already placed, or
  (when nothing of that is free) flush against a sibling. A satellite's other doors (it may
  close a small cycle, as a classroom between a corridor and a closet does) add their gaps.

So a satellite is never in the core's way, and the core is scored with its satellites: a
move that closes a cycle but walls in a corridor's rooms costs what they lose. A satellite's
side, place, turn and size are annealed too. The score is the sequence-pair annealer's
violation for the core plus, for each satellite, its overlap with the rooms placed before
it, its extent past the boundary and its doors' gaps (in metres); 0 is a geometry in which
every door is met, no two rooms overlap and all lies inside the boundary.

Measured (bench/results/satellites.txt): on school_stjoseph_scatholichighschool, whose
whole-plan sequence-pair runs never came within 5 m of a layout, 11 of 16 runs of 4M moves
end within 6 m (the repair's reach, construct.ANNEAL_REPAIR_M), 2 of them at 0, once the
satellites' moves start warm (SATELLITES_TEMPERATURE); 3 of 8 of 2M. compile, 60 s, with
both cores on runs of 2M moves (construct._anneal_order "alone", CORE_MOVES_PER_PAIR): the school's
seeds 0-7 constructed 6 of 8, the first layout after 22-37 s (0 of 4 seeds before). Plans
without a block of generate.CORE_BLOCK_ROOMS are not split (see there).

Every run is seeded and its number of moves fixed by the plan's size: the same seed gives
the same geometry. Needs numba, as the sequence-pair annealer does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from layoutdsl.compile.anneal import (
    CANCEL_CHECK,
    COMPACT_WEIGHT,
    END_TEMPERATURE,
    RESIZE_WEIGHT,
    START_TEMPERATURE,
    _Arrays,
    _bounds,
    _drift,
    _evaluate,
    _new_work,
    _propose,
    _resize_into,
    best_of_chains,
)
from layoutdsl.compile.generate import RoomSizes, core_rooms, drawn_sides, room_graph
from layoutdsl.layout.geometry import Rect
from layoutdsl.syntax.ast import Spec

CORE_MOVES_PER_PAIR = 5000
CORE_MAX_MOVES = 1_500_000
SATELLITE_MOVES = 500_000
"""A run's moves: first the core alone, this many per pair of core rooms (a sequence pair
relates every pair), at most CORE_MAX_MOVES; then SATELLITE_MOVES with the satellites placed
after every move and counted. Measured (bench/results/satellites.txt section 5, runs repaired
as compile repairs them): school_stjoseph_scatholichighschool (27 core rooms, 351 pairs) needs
the long core phase, with 1.5M core moves 5 of 10 runs repaired, 1.08M 1 of 10, 0.5M 0 of
10; office_floor-1024x523 (14 core rooms, 91 pairs) does not, about 0.5M core moves
repairing 8-10 of 40 runs (three probes) at 10-13 s a run against 2 of 10 at 13.5 s with 1.5M
(the same 0.5M satellite moves each time): about 3 s less a run. The school's runs are as
before (2M moves, 1.5M of them the core's).

Before: a run of 40000 moves a room, at most 2M, the first 3/4 on the core alone. With the
satellites' moves warm (SATELLITES_TEMPERATURE), 2M moves ended 3 runs of 8 within 6 m on
school_stjoseph_scatholichighschool at 16-23 s a run, 4M 11 of 16 at 27-43 s; in compile the
shorter runs fit two rounds into the construction's 48 s where the longer fit one. Cold runs,
before the reheat: with every move placing the satellites, 1M moves left 3 of 8 within 6 m at
about 20 s a run; with the core alone first, at 15000 moves a room (1.7M) 0.5 alone 4 of 12 at
13 s, 0.7 3 of 12 at 10.4 s, 0.75 6 of 24 at 9.7 s, 0.8 4 of 12 at 8.2 s. While everything
still moves, the satellites' places say little and cost most of the time (the core alone takes
about 3 microseconds a move, with its satellites 20)."""

SATELLITE_SHARE = 0.5
"""Share of the moves that change a satellite (turn it, resize it, or move it to another
side of its parent), times the satellites' share of the rooms."""

CORE_DOOR_WEIGHT = 2.0
"""While the satellites are placed, a metre of the core's own violation (its doors' gaps and
missing wall, its rooms past the boundary) costs this many metres of the satellites' in the
moves' cost; the best state is still the one nearest a layout, unweighted. The core meets its
doors alone, then opens them to make room for its satellites: of 38 office runs that did not
meet every door, 34 had a door between two core rooms open (bench/results/satellites.txt
section 8). Measured with bench/checkpoints.py on fresh runs (kernel seeds 1000-1039, runs
within REACH_M repaired as compile repairs them, section 9): runs that repaired,
office_floor-1024x523 5, 12, 17, 14 and 14 of 40 at weights 1, 1.5, 2, 2.5 and 3;
school_stjoseph_scatholichighschool 4, 7, 15, 10 and 11 of 40. (Ten runs a plan at an earlier
kernel had shown the school worse at 2; the forty fresh ones do not.)"""

SATELLITES_TEMPERATURE = 0.02
"""The temperature (times the boundary's width plus height, as START_TEMPERATURE) at which the
moves with the satellites begin, cooling from there to END_TEMPERATURE. The core-alone moves
end cold (about 0.1 m on the school): carried on from there, a move that lifts a core room
for a satellite by a metre was taken about once in e^10, and the runs froze with satellites
walled in (their overlap most of what was left). Reheated to about 4 m, the core gives way.
Measured with one run a seed (4M moves, two runs at a time, 30-40 s each), runs ending within
6 m of a layout: school_stjoseph_scatholichighschool 0 of 8 as before, 2 of 8 at 0.01, 6 of 8
(then 5 of 8 on seeds 8-15) at 0.02, 2 of 8 at 0.03, 1 of 8 at 0.05;
office_floor-1024x523 (3M moves) 4 of 8 as before, 8 of 8 at 0.02 (bench/results/satellites.txt)."""

REACH_M = 4.0
CHECKPOINT_SHARE = 0.6
"""A run whose best state is still farther than REACH_M (metres) from a layout when
CHECKPOINT_SHARE of its moves with the satellites are made stops there, and a run that ends
farther is not repaired (layoutdsl.compile.anneal_runs drops it; other runs' reach is
construct.ANNEAL_REPAIR_M). Measured (bench/results/satellites.txt section 6, the best at
every 5 % of the moves with the satellites): of 60 runs on office_floor-1024x523 and 20 on
school_stjoseph_scatholichighschool, every run that ended within a metre of a layout, or
repaired, was within 3.4 m of one at 60 %; 32 and 13 of them were farther than 4 m there,
and none of those ended within a metre or repaired. Their last 40 % of the moves with
the satellites was a quarter to a third of each one's time. Of the runs ending 4-6 m from
a layout (13 of the office's, none of the school's), the 7 of seeds 0-19 were each repaired
as compile repairs them: none repaired, each repair taking 1.2-9.5 s of a core."""

PROGRESS_MARKS = 20
"""A run records its best so far at every 1/PROGRESS_MARKS (5 %) of its moves with the
satellites, in the array Satellites.chain is given as `progress` (bench/checkpoints.py reads
it to see where runs stand when a checkpoint would judge them; it changes no run)."""

SETTLED_SHARE = 0.8
"""A run ends, and hands its best state to the repair, when this share of its moves with the
satellites is made: the rest of the cooling no longer changes where a run stands. Measured
(bench/results/satellites.txt section 6's traces, the best at every 5 %): of the 80 runs,
the 25 that ended within 4 m of a layout without meeting every door by 80 % stood within
0.12 m of their end there, but for two (office seeds 15 and 39: 3.66 -> 3.36 and 3.30 ->
2.20 m; none of the office's runs that ended 1.2-3.9 m away repaired, seeds 1, 2, 12, 15
and 18 here and compile seed 0's third and fourth runs). The two that met every
door only after 80 % (office seed 13, school seed 12) were 0.02 m from a layout there, and
school seed 8, which ended at 0.02 m, repaired. What it saves is the last fifth of the
moves with the satellites of every run that does not meet every door (one that does stops
there)."""

INCREMENTAL_PLACEMENT = True
"""After a move, a satellite that nothing near it disturbed keeps its place instead of being
placed again (_undisturbed). The runs are the same, move for move, either way (a test holds
them to it); only faster. Measured on single runs of the full length, one at a time: on
office_floor-1024x523 8.03 -> 8.39 s (seed 8), 8.34 -> 6.31 s (17), 11.29 -> 8.40 s (3); on
school_stjoseph_scatholichighschool 23.68 -> 19.83 s (0), 21.69 -> 18.82 s (2). Most satellites
are free at the place they had and cost one try either way; what it saves is the full search
of a walled-in satellite whose surroundings did not change."""

GRID_CELL = 4.0
GRID_CAPACITY = 96
"""The placement looks for overlaps in a grid of cells this many metres square, each listing
up to GRID_CAPACITY rooms (a fuller cell falls back to looking at every room)."""

MAX_SLIDES = 5 + 2 * 64
"""Places along a parent's side a satellite may take: middle and ends (and both ends of the
boundary, for a room on it), then two for each door neighbour and each sibling placed
before it (beyond 64 of those, the rest are not tried)."""


@dataclass(frozen=True)
class Satellites:
    """A spec split into its core (annealed as a sequence pair) and satellites (placed)."""

    core: _Arrays
    ids: list[str]
    """the core's rooms, then the satellites in placing order"""
    parent: np.ndarray
    """each satellite's parent, an index into ids"""
    need: np.ndarray
    """the wall each satellite must share with its parent (0: no door, beside it anyway)"""
    long_side: np.ndarray
    short_side: np.ndarray
    bounds: np.ndarray
    on_boundary: np.ndarray
    """satellites that must touch the boundary (onB): their distance from it is scored"""
    extra_ptr: np.ndarray
    extra_to: np.ndarray
    extra_need: np.ndarray
    """each satellite's doors to rooms placed before it other than its parent, CSR-style"""
    sibling_ptr: np.ndarray
    sibling_to: np.ndarray
    """each satellite's siblings placed before it, CSR-style"""

    @classmethod
    def of(cls, spec: Spec) -> Satellites | None:
        """The split of `spec` (its L-rooms' arms drawn as rooms), or None when it has no
        cycle block of generate.CORE_BLOCK_ROOMS rooms or no room outside its core."""
        core = core_rooms(spec)
        if core is None:
            return None
        graph = room_graph(spec)
        core_arrays = _Arrays.of(spec.restricted_to(core, f"{spec.name}-core"))
        ids = list(core_arrays.ids)
        index = {room_id: i for i, room_id in enumerate(ids)}
        utilization = spec.settings.door_utilization
        needs = {frozenset((adj.a, adj.b)): adj.door / utilization for adj in spec.adjacencies}
        parent: list[int] = []
        need: list[float] = []
        order: list[str] = []

        def reach(frontier: list[str]) -> None:
            # breadth first from `frontier`: each room's parent is the first placed neighbour
            while frontier:
                following = []
                for room_id in frontier:
                    for other in sorted(graph[room_id]):
                        if other not in index:
                            index[other] = len(ids) + len(order)
                            order.append(other)
                            parent.append(index[room_id])
                            need.append(needs[frozenset((room_id, other))])
                            following.append(other)
                frontier = following

        reach(list(ids))
        for room in spec.rooms:
            if room.id not in index:
                # a part of the plan with no door to the core: its first room beside the
                # core's first, without a door
                index[room.id] = len(ids) + len(order)
                order.append(room.id)
                parent.append(0)
                need.append(0.0)
                reach([room.id])
        extras = [[(index[other], needs[frozenset((room_id, other))]) for other in sorted(graph[room_id])
                   if index[other] < len(ids) + k and index[other] != parent[k]]
                  for k, room_id in enumerate(order)]
        siblings = [[len(ids) + j for j in range(k) if parent[j] == parent[k]] for k in range(len(order))]
        rooms = {room.id: room for room in spec.rooms}
        sides = drawn_sides(spec)
        extra_ptr, extra_to = _csr([[j for j, _ in row] for row in extras])
        sibling_ptr, sibling_to = _csr(siblings)
        return cls(
            core=core_arrays,
            ids=ids + order,
            parent=np.array(parent, dtype=np.int64),
            need=np.array(need, dtype=np.float64),
            long_side=np.array([sides[r][0] for r in order], dtype=np.float64),
            short_side=np.array([sides[r][1] for r in order], dtype=np.float64),
            bounds=np.array([_bounds(RoomSizes.of(rooms[r])) for r in order], dtype=np.float64),
            on_boundary=np.array([rooms[r].on_boundary for r in order], dtype=np.bool_),
            extra_ptr=extra_ptr, extra_to=extra_to,
            extra_need=np.array([n for row in extras for _, n in row], dtype=np.float64),
            sibling_ptr=sibling_ptr, sibling_to=sibling_to)

    def core_moves(self) -> int:
        """Moves on the core alone (CORE_MOVES_PER_PAIR)."""
        rooms = len(self.core.ids)
        return min(CORE_MAX_MOVES, CORE_MOVES_PER_PAIR * rooms * (rooms - 1) // 2)

    def moves(self) -> int:
        return self.core_moves() + SATELLITE_MOVES

    def chain(self, kernel_seed: int, cancel: np.ndarray, progress: np.ndarray | None = None):
        """One run from a random sequence pair of the core (the kernel releases the GIL),
        cut off when cancel[0] is set; geometry() reads its result. `progress`, an array of
        PROGRESS_MARKS, receives the run's best at every mark (NaN for those it stopped
        before)."""
        core = self.core
        core_moves = self.core_moves()
        scale = core.width + core.height
        share = SATELLITE_SHARE * len(self.parent) / len(self.ids)
        return _anneal_satellites(
            core.long_side, core.short_side, core.bounds, core.edge_a, core.edge_b, core.need,
            core.door_ptr, core.door_to, core.on_boundary, core.width, core.height, core.wall,
            kernel_seed, self.moves(), START_TEMPERATURE * scale, END_TEMPERATURE * scale, cancel,
            self.parent, self.need, self.long_side, self.short_side, self.bounds, self.on_boundary, self.extra_ptr,
            self.extra_to, self.extra_need, self.sibling_ptr, self.sibling_to, share,
            core_moves, SATELLITES_TEMPERATURE * scale, core_moves + int(CHECKPOINT_SHARE * SATELLITE_MOVES), REACH_M,
            core_moves + int(SETTLED_SHARE * SATELLITE_MOVES), INCREMENTAL_PLACEMENT,
            np.full(PROGRESS_MARKS, np.nan) if progress is None else progress, CORE_DOOR_WEIGHT)

    @staticmethod
    def repairable(violation: float) -> bool:
        """Whether a run that ended `violation` metres from a layout is worth its repair."""
        return violation <= REACH_M

    def geometry(self, result) -> tuple[dict[str, Rect], float]:
        """The rectangles of a run's best state, and its violation."""
        violation, x, y, w, h, _ = result
        return ({room_id: (float(x[i]), float(y[i]), float(w[i]), float(h[i]))
                 for i, room_id in enumerate(self.ids)}, float(violation))


def satellites_geometry(spec: Spec, seed: int,
                        deadline: float | None = None) -> tuple[dict[str, Rect], float] | None:
    """As layoutdsl.compile.anneal.anneal_geometry, with the core-and-satellites annealer (for
    a spec it splits, Satellites.of)."""
    satellites = Satellites.of(spec)
    assert satellites is not None, "a spec without cycles, or all core: use anneal_geometry"
    return best_of_chains(satellites, seed, deadline)


def _csr(rows: list[list[int]]) -> tuple[np.ndarray, np.ndarray]:
    ptr = np.zeros(len(rows) + 1, dtype=np.int64)
    ptr[1:] = np.cumsum([len(row) for row in rows])
    return ptr, np.array([j for row in rows for j in row], dtype=np.int64)


@njit(cache=True, inline="always")
def _door_gap(ax, ay, aw, ah, bx, by, bw, bh, need, wall):
    """How far two rectangles are from sharing `need` metres of wall one wall apart: along the
    nearer axis, the gap's distance from a wall plus the missing shared length."""
    gap_x = max(bx - ax - aw, ax - bx - bw) - wall
    gap_y = max(by - ay - ah, ay - by - bh) - wall
    shared_y = min(ay + ah, by + bh) - max(ay, by)
    shared_x = min(ax + aw, bx + bw) - max(ax, bx)
    return min(abs(gap_x) + max(0.0, need - shared_y), abs(gap_y) + max(0.0, need - shared_x))


@njit(cache=True, inline="always")
def _cells(low, high, count):
    first = min(max(int(math.floor(low / GRID_CELL)), 0), count - 1)
    last = min(max(int(math.floor(high / GRID_CELL)), 0), count - 1)
    return first, last


@njit(cache=True)
def _grid_add(grid, counts, k, x, y, w, h, wall, columns, rows):
    """Room k into every cell its rectangle (a wall wider all round) touches."""
    i0, i1 = _cells(x - wall, x + w + wall, columns)
    j0, j1 = _cells(y - wall, y + h + wall, rows)
    for j in range(j0, j1 + 1):
        for i in range(i0, i1 + 1):
            c = j * columns + i
            if counts[c] < GRID_CAPACITY:
                grid[c, counts[c]] = k
            counts[c] += 1


@njit(cache=True)
def _crowding(cx, cy, w, h, x, y, rw, rh, placed, width, height, wall, stop, grid, counts, columns, rows,
              stamp, token):
    """A candidate rectangle's extent past the boundary plus, for each of the `placed` rooms
    closer than a wall, the lesser of its two overlaps (a wall added): 0 is a free place.
    Stops counting at `stop`."""
    cost = max(0.0, -cx) + max(0.0, -cy) + max(0.0, cx + w - width) + max(0.0, cy + h - height)
    if cost >= stop:
        return cost
    i0, i1 = _cells(cx, cx + w, columns)
    j0, j1 = _cells(cy, cy + h, rows)
    full = False
    for j in range(j0, j1 + 1):
        for i in range(i0, i1 + 1):
            if counts[j * columns + i] > GRID_CAPACITY:
                full = True
    for j in range(j0, j1 + 1):
        for i in range(i0, i1 + 1):
            c = j * columns + i
            listed = placed if full else counts[c]
            for t in range(listed):
                r = t if full else grid[c, t]
                if stamp[r] == token:
                    continue
                stamp[r] = token
                over_x = min(cx + w, x[r] + rw[r]) - max(cx, x[r]) + wall
                if over_x <= 1e-9:
                    continue
                over_y = min(cy + h, y[r] + rh[r]) - max(cy, y[r]) + wall
                if over_y <= 1e-9:
                    continue
                cost += min(over_x, over_y)
                if cost >= stop:
                    return cost
            if full:
                return cost
    return cost


@njit(cache=True, inline="always")
def _flush_slides(slides, count, rooms, x, y, w, h, wall, sw, sh, along_y):
    """Into slides from `count` on: for each of `rooms` (placed), the two places along the
    slide that put a sw x sh satellite a wall past either end of it; the new count (at most
    MAX_SLIDES)."""
    for j in rooms:
        if count + 2 > MAX_SLIDES:
            break
        slides[count] = y[j] + h[j] + wall if along_y else x[j] + w[j] + wall
        slides[count + 1] = y[j] - wall - sh if along_y else x[j] - wall - sw
        count += 2
    return count


@njit(cache=True, inline="always")
def _moved_from(k, x, y, w, h, placed_x, placed_y, placed_w, placed_h, moved, dirty, nd):
    """Whether room k's rectangle differs from the state moved from; if so its old and new
    rectangles go into `dirty` (x0, y0, x1, y1 rows, from nd on). The new count of rows."""
    moved[k] = x[k] != placed_x[k] or y[k] != placed_y[k] or w[k] != placed_w[k] or h[k] != placed_h[k]
    if moved[k]:
        dirty[nd, 0], dirty[nd, 1] = placed_x[k], placed_y[k]
        dirty[nd, 2], dirty[nd, 3] = placed_x[k] + placed_w[k], placed_y[k] + placed_h[k]
        dirty[nd + 1, 0], dirty[nd + 1, 1], dirty[nd + 1, 2], dirty[nd + 1, 3] = x[k], y[k], x[k] + w[k], y[k] + h[k]
        nd += 2
    return nd


@njit(cache=True, inline="always")
def _slide_range(low, span, size, limit, on_boundary, rooms, pos, ext, wall):
    """The least and greatest start of a size-long satellite along one axis of its parent's
    side (low, span: the parent's), over every place _place_satellites tries there."""
    lo = min(low, low + span - size, low + span / 2 - size / 2)
    hi = max(low, low + span - size, low + span / 2 - size / 2)
    if on_boundary:
        lo = min(lo, 0.0)
        hi = max(hi, limit - size)
    for j in rooms:
        lo = min(lo, pos[j] - wall - size)
        hi = max(hi, pos[j] + ext[j] + wall)
    return lo, hi


@njit(cache=True)
def _undisturbed(s, parent, on_boundary, sw, sh, extra_ptr, extra_to, sibling_ptr, sibling_to, width, height,
                 wall, x, y, w, h, moved, dirty, nd):
    """Whether satellite s, its own state unchanged, would be placed where it was:
    its parent, its door neighbours and its siblings have not moved, and no room that moved
    (old or new rectangle, `dirty`) comes within a wall of any place it may try. Placing
    it again would then give the same place and cost (it first tries the place it had,
    and that place was the best of the same candidates before)."""
    p = parent[s]
    if moved[p]:
        return False
    for e in range(extra_ptr[s], extra_ptr[s + 1]):
        if moved[extra_to[e]]:
            return False
    for e in range(sibling_ptr[s], sibling_ptr[s + 1]):
        if moved[sibling_to[e]]:
            return False
    if nd == 0:
        return True
    extras = extra_to[extra_ptr[s]:extra_ptr[s + 1]]
    siblings = sibling_to[sibling_ptr[s]:sibling_ptr[s + 1]]
    px, py, pw, ph = x[p], y[p], w[p], h[p]
    # left or right of the parent (sliding along y), then below or above it (along x)
    y0, y1 = _slide_range(py, ph, sh, height, on_boundary[s], extras, y, h, wall)
    y2, y3 = _slide_range(py, ph, sh, height, on_boundary[s], siblings, y, h, wall)
    x0, x1 = _slide_range(px, pw, sw, width, on_boundary[s], extras, x, w, wall)
    x2, x3 = _slide_range(px, pw, sw, width, on_boundary[s], siblings, x, w, wall)
    strips = (
        (px - wall - sw, min(y0, y2), px + pw + wall + sw, max(y1, y3) + sh),
        (min(x0, x2), py - wall - sh, max(x1, x3) + sw, py + ph + wall + sh),
    )
    reach = wall + 1e-6
    for a0, b0, a1, b1 in strips:
        for d in range(nd):
            if (dirty[d, 0] < a1 + reach and dirty[d, 2] > a0 - reach
                    and dirty[d, 1] < b1 + reach and dirty[d, 3] > b0 - reach):
                return False
    return True


@njit(cache=True)
def _place_satellites(work, parent, need, on_boundary, long_side, short_side, turned, side_of, slide_of, extra_ptr,
                      extra_to, extra_need, sibling_ptr, sibling_to, width, height, wall, x, y, w, h, cost_of,
                      grid, counts, stamp, budget, first, placed, incremental, changed, moved, dirty):
    """Place the satellites beside their parents, after the core's packing (work): into x, y,
    w, h (core rooms first) and cost_of; each satellite's side and place into side_of,
    slide_of. Returns the satellites' cost (overlap, overflow, doors' gaps), or as soon as it
    passes `budget` (the move is then refused whatever the rest would cost) the cost so far.

    From satellite `first` on: the core and the satellites before it are where `placed` (x, y,
    w, h, cost_of of the state moved from) has them. A move of one satellite changes nothing
    before it, so only it and those after it are placed again.

    A satellite first tries the side and place it had (in a settled plan most keep theirs),
    then its sides from that one round, each at its middle, ends and lined up with its other
    doors' rooms, then the same sides flush against its siblings; the first free place wins,
    else the cheapest.

    `incremental` (`placed` is the state moved from, placed in full; `changed`: the satellite
    whose own state the move changed, or -1): a satellite that nothing near it disturbed
    (_undisturbed) keeps its place and cost from `placed` without trying any. The result is
    the same as placing it again, only faster; `moved` and `dirty` are scratch arrays."""
    nc = work.x.shape[0]
    columns = int(width / GRID_CELL) + 1
    rows = int(height / GRID_CELL) + 1
    counts[:] = 0
    total = 0.0
    placed_x, placed_y, placed_w, placed_h, placed_cost = placed
    if first == 0:
        for i in range(nc):
            x[i] = work.x[i]
            y[i] = work.y[i]
            w[i] = work.w[i]
            h[i] = work.h[i]
    else:
        for i in range(nc + first):
            x[i] = placed_x[i]
            y[i] = placed_y[i]
            w[i] = placed_w[i]
            h[i] = placed_h[i]
        for s in range(first):
            cost_of[s] = placed_cost[s]
            total += placed_cost[s]
    for i in range(nc + first):
        _grid_add(grid, counts, i, x[i], y[i], w[i], h[i], wall, columns, rows)
    nd = 0
    if incremental:
        moved[:nc + first] = False
        if first == 0:
            for i in range(nc):
                nd = _moved_from(i, x, y, w, h, placed_x, placed_y, placed_w, placed_h, moved, dirty, nd)
    slides = np.empty(MAX_SLIDES)
    for s in range(first, parent.shape[0]):
        k = nc + s
        if turned[s]:
            sw, sh = short_side[s], long_side[s]
        else:
            sw, sh = long_side[s], short_side[s]
        if incremental and s != changed and _undisturbed(s, parent, on_boundary, sw, sh, extra_ptr, extra_to,
                                                         sibling_ptr, sibling_to, width, height, wall, x, y, w, h,
                                                         moved, dirty, nd):
            x[k], y[k], w[k], h[k] = placed_x[k], placed_y[k], placed_w[k], placed_h[k]
            moved[k] = False
            _grid_add(grid, counts, k, x[k], y[k], w[k], h[k], wall, columns, rows)
            cost_of[s] = placed_cost[s]
            total += placed_cost[s]
            if total > budget:
                return total
            continue
        p = parent[s]
        px, py, pw, ph = x[p], y[p], w[p], h[p]
        best, best_x, best_y = np.inf, 0.0, 0.0
        best_side, best_slide = side_of[s], slide_of[s]
        for t in range(-1, 8):
            side = side_of[s] if t < 0 else (side_of[s] + t) % 4
            along_y = side < 2  # right (0) or left (1) of the parent: it slides along y
            low, span, size = (py, ph, sh) if along_y else (px, pw, sw)
            slides[0] = low + span / 2 - size / 2
            slides[1] = low
            slides[2] = low + span - size
            count = 3
            if on_boundary[s]:
                # against the boundary across the slide (its other sides: the parent's place)
                slides[3] = 0.0
                slides[4] = (height if along_y else width) - size
                count = 5
            count = _flush_slides(slides, count, extra_to[extra_ptr[s]:extra_ptr[s + 1]], x, y, w, h, wall, sw,
                                  sh, along_y)
            from_slide = 0
            if t >= 4:
                from_slide = count  # the second round: flush against the siblings only
            if t < 0 or t >= 4:
                count = _flush_slides(slides, count, sibling_to[sibling_ptr[s]:sibling_ptr[s + 1]], x, y, w, h,
                                      wall, sw, sh, along_y)
            for u in range(from_slide, count):
                if t < 0 and u != slide_of[s] % count:
                    continue
                if along_y:
                    cx = px + pw + wall if side == 0 else px - wall - sw
                    cy = slides[u]
                else:
                    cy = py + ph + wall if side == 2 else py - wall - sh
                    cx = slides[u]
                cost = 0.0
                if on_boundary[s]:
                    # its distance from the nearest side (past one, the overflow counts)
                    cost += max(0.0, min(min(cx, cy), min(width - cx - sw, height - cy - sh)))
                if need[s] > 0.0:
                    cost += _door_gap(cx, cy, sw, sh, px, py, pw, ph, need[s], wall)
                for e in range(extra_ptr[s], extra_ptr[s + 1]):
                    j = extra_to[e]
                    cost += _door_gap(cx, cy, sw, sh, x[j], y[j], w[j], h[j], extra_need[e], wall)
                if cost >= best:
                    continue
                stamp[0] += 1  # a fresh mark for the rooms this candidate looks at
                cost += _crowding(cx, cy, sw, sh, x, y, w, h, k, width, height, wall, best - cost, grid, counts,
                                  columns, rows, stamp[1:], stamp[0])
                if cost < best:
                    best, best_x, best_y, best_side, best_slide = cost, cx, cy, side, u
                    if cost <= 1e-9:
                        break
            if best <= 1e-9:
                break
        side_of[s] = best_side
        slide_of[s] = best_slide
        x[k], y[k], w[k], h[k] = best_x, best_y, sw, sh
        if incremental:
            nd = _moved_from(k, x, y, w, h, placed_x, placed_y, placed_w, placed_h, moved, dirty, nd)
        _grid_add(grid, counts, k, best_x, best_y, sw, sh, wall, columns, rows)
        cost_of[s] = best
        total += best
        if total > budget:
            return total
    return total


@njit(cache=True)
def _keep(p, q, turned, long_side, short_side, s_turned, s_side, s_slide, s_long, s_short,
          best_p, best_q, best_turned, best_long, best_short, best_s_turned, best_s_side, best_s_slide,
          best_s_long, best_s_short):
    """A state copied into the best state's arrays."""
    best_p[:] = p
    best_q[:] = q
    best_turned[:] = turned
    best_long[:] = long_side
    best_short[:] = short_side
    best_s_turned[:] = s_turned
    best_s_side[:] = s_side
    best_s_slide[:] = s_slide
    best_s_long[:] = s_long
    best_s_short[:] = s_short


@njit(cache=True, nogil=True)
def _anneal_satellites(drawn_long, drawn_short, bounds, edge_a, edge_b, need, door_ptr, door_to, on_boundary,
                       width, height, wall, seed, moves, t_start, t_end, cancel, parent, sat_need,
                       sat_drawn_long, sat_drawn_short, sat_bounds, sat_on_boundary, extra_ptr, extra_to,
                       extra_need,
                       sibling_ptr, sibling_to, satellite_share, core_alone_until, t_satellites, checkpoint,
                       reach, last_step, incremental, progress, core_weight):
    np.random.seed(seed)
    n = drawn_long.shape[0]
    ns = parent.shape[0]
    m = edge_a.shape[0]
    # the state: the core's sequence pair and sides, each satellite's turn, sides and place
    p = np.random.permutation(n)
    q = np.random.permutation(n)
    turned = np.random.random(n) < 0.5
    long_side = drawn_long.copy()
    short_side = drawn_short.copy()
    s_turned = np.random.random(ns) < 0.5
    s_side = np.random.randint(0, 4, ns)
    s_slide = np.zeros(ns, dtype=np.int64)
    s_long = sat_drawn_long.copy()
    s_short = sat_drawn_short.copy()
    # the trial state of a move, and the best state, in arrays made once
    new_p, new_q, new_turned = p.copy(), q.copy(), turned.copy()
    spare_long, spare_short = long_side.copy(), short_side.copy()
    new_s_turned, new_s_side, new_s_slide = s_turned.copy(), s_side.copy(), s_slide.copy()
    new_s_long, new_s_short = s_long.copy(), s_short.copy()
    best_p, best_q, best_turned = p.copy(), q.copy(), turned.copy()
    best_long, best_short = long_side.copy(), short_side.copy()
    best_s_turned, best_s_side, best_s_slide = s_turned.copy(), s_side.copy(), s_slide.copy()
    best_s_long, best_s_short = s_long.copy(), s_short.copy()
    # where the state's rooms are and what each satellite costs (placed), and a move's (x, y, w, h, cost_of)
    x, y, w, h = np.zeros(n + ns), np.zeros(n + ns), np.zeros(n + ns), np.zeros(n + ns)
    cost_of = np.zeros(ns)
    placed = (np.zeros(n + ns), np.zeros(n + ns), np.zeros(n + ns), np.zeros(n + ns), np.zeros(ns))
    grid = np.empty(((int(width / GRID_CELL) + 1) * (int(height / GRID_CELL) + 1), GRID_CAPACITY), dtype=np.int64)
    counts = np.zeros(grid.shape[0], dtype=np.int64)
    stamp = np.zeros(n + ns + 1, dtype=np.int64)
    moved = np.zeros(n + ns, dtype=np.bool_)
    dirty = np.zeros((2 * (n + ns), 4))
    per_edge = np.zeros(m)
    trial_edge = np.zeros(m)
    work = _new_work(n)
    violation, box = _evaluate(p, q, turned, long_side, short_side, bounds, edge_a, edge_b, need,
                               door_ptr, door_to, on_boundary, width, height, wall, per_edge, work)
    core_violation, core_box = violation, box
    violation += _place_satellites(work, parent, sat_need, sat_on_boundary, s_long, s_short, s_turned, s_side,
                                   s_slide, extra_ptr, extra_to, extra_need, sibling_ptr, sibling_to, width, height,
                                   wall, x, y, w, h, cost_of, grid, counts, stamp, np.inf, 0, placed, False, -1,
                                   moved, dirty)
    x, y, w, h, cost_of, placed = placed[0], placed[1], placed[2], placed[3], placed[4], (x, y, w, h, cost_of)
    boundary_area = width * height
    cost = violation + COMPACT_WEIGHT * box / boundary_area
    if core_alone_until > 0:
        cost = core_violation + COMPACT_WEIGHT * box / boundary_area  # the satellites count later
    resized = 0.0
    best_violation = violation
    best_cost = cost
    ratio = t_end / t_start
    made = moves
    # the best so far at every 1/PROGRESS_MARKS of the moves with the satellites
    mark_every = max(1, (moves - core_alone_until) // progress.shape[0])
    progress[:] = np.nan
    mark, next_mark = 0, core_alone_until + mark_every
    for step in range(moves):
        if step == next_mark and mark < progress.shape[0]:
            progress[mark] = best_violation
            mark += 1
            next_mark += mark_every
        if step % CANCEL_CHECK == 0 and cancel[0]:
            made = step
            break
        if best_violation <= 1e-9 and step >= moves // 2:
            made = step
            break  # every door met: the rest would only make it more compact
        if step == checkpoint and best_violation > reach:
            made = step
            break  # still far from a layout: such runs were never repaired (REACH_M)
        if step == last_step:
            made = step
            break  # settled: the best state no longer changes (SETTLED_SHARE)
        core_alone = step < core_alone_until
        if core_alone:
            temperature = t_start * ratio ** (step / moves)
        else:
            temperature = t_satellites * (t_end / t_satellites) ** (
                (step - core_alone_until) / max(1, moves - core_alone_until))
        if step == core_alone_until and step > 0:
            # the satellites count from here on: placed for the state the core has reached,
            # which is the best so far (nothing before was scored with them)
            core_violation, core_box = _evaluate(p, q, turned, long_side, short_side, bounds, edge_a, edge_b, need,
                                                 door_ptr, door_to, on_boundary, width, height, wall, per_edge, work)
            satellites_cost = _place_satellites(work, parent, sat_need, sat_on_boundary, s_long, s_short, s_turned,
                                                s_side, s_slide, extra_ptr, extra_to, extra_need, sibling_ptr,
                                                sibling_to, width, height, wall, x, y, w, h, cost_of, grid, counts,
                                                stamp, np.inf, 0, placed, False, -1, moved, dirty)
            x, y, w, h, cost_of, placed = placed[0], placed[1], placed[2], placed[3], placed[4], (x, y, w, h, cost_of)
            best_violation = core_violation + satellites_cost
            cost = (core_weight * core_violation + satellites_cost + COMPACT_WEIGHT * core_box / boundary_area
                    + RESIZE_WEIGHT * resized)
            best_cost = cost
            _keep(p, q, turned, long_side, short_side, s_turned, s_side, s_slide, s_long, s_short,
                  best_p, best_q, best_turned, best_long, best_short, best_s_turned, best_s_side, best_s_slide,
                  best_s_long, best_s_short)
        new_p[:] = p
        new_q[:] = q
        new_turned[:] = turned
        new_s_turned[:] = s_turned
        new_s_side[:] = s_side
        new_s_slide[:] = s_slide
        new_s_long[:] = s_long
        new_s_short[:] = s_short
        new_long, new_short = long_side, short_side
        new_resized = resized
        resizing = False
        first = 0
        changed = -1
        if not core_alone and np.random.random() < satellite_share:
            s = np.random.randint(ns)
            first = s
            changed = s
            kind = np.random.random()
            if kind < 0.3:
                new_s_turned[s] = not new_s_turned[s]
            elif kind < 0.6:
                _resize_into(s, s_long, s_short, sat_bounds, new_s_long, new_s_short)
                new_resized = resized - _drift(s, s_long, s_short, sat_drawn_long, sat_drawn_short) \
                    + _drift(s, new_s_long, new_s_short, sat_drawn_long, sat_drawn_short)
            else:
                new_s_side[s] = np.random.randint(4)
                new_s_slide[s] = np.random.randint(3)
        else:
            resized_room = _propose(p, q, turned, long_side, short_side, new_p, new_q, new_turned, spare_long,
                                    spare_short, bounds, edge_a, edge_b, per_edge)
            resizing = resized_room >= 0
            if resizing:
                new_long, new_short = spare_long, spare_short
                new_resized = resized - _drift(resized_room, long_side, short_side, drawn_long, drawn_short) \
                    + _drift(resized_room, new_long, new_short, drawn_long, drawn_short)
        # the move is taken iff its cost is at most `limit` (Metropolis, its draw made first):
        # the satellites are placed only as long as that may still hold, which is most of the time
        limit = cost - temperature * math.log(1.0 - np.random.random())
        core_moved = first == 0
        if core_moved:
            new_core, box = _evaluate(new_p, new_q, new_turned, new_long, new_short, bounds, edge_a, edge_b,
                                      need, door_ptr, door_to, on_boundary, width, height, wall, trial_edge, work)
        else:
            new_core, box = core_violation, core_box  # the core is as it was
        # with the satellites, the core's doors weigh CORE_DOOR_WEIGHT in the moves' cost (not in the best's)
        new_cost = (new_core if core_alone else core_weight * new_core) + COMPACT_WEIGHT * box / boundary_area \
            + RESIZE_WEIGHT * new_resized
        if new_cost > limit:
            continue
        new_violation = new_core
        if not core_alone:
            satellites_cost = _place_satellites(work, parent, sat_need, sat_on_boundary, new_s_long, new_s_short,
                                                new_s_turned, new_s_side, new_s_slide, extra_ptr, extra_to,
                                                extra_need, sibling_ptr, sibling_to, width, height, wall, x, y, w, h,
                                                cost_of, grid, counts, stamp, limit - new_cost, first, placed,
                                                incremental, changed, moved, dirty)
            new_violation += satellites_cost
            new_cost += satellites_cost
            if new_cost > limit:
                continue
            x, y, w, h, cost_of, placed = placed[0], placed[1], placed[2], placed[3], placed[4], (x, y, w, h, cost_of)
        # the move is taken (with the core alone, the satellites' arrays trade identical copies)
        core_violation, core_box = new_core, box
        p, new_p = new_p, p
        q, new_q = new_q, q
        turned, new_turned = new_turned, turned
        if resizing:
            long_side, spare_long = spare_long, long_side
            short_side, spare_short = spare_short, short_side
        s_turned, new_s_turned = new_s_turned, s_turned
        s_side, new_s_side = new_s_side, s_side
        s_slide, new_s_slide = new_s_slide, s_slide
        s_long, new_s_long = new_s_long, s_long
        s_short, new_s_short = new_s_short, s_short
        cost, resized = new_cost, new_resized
        if core_moved:
            per_edge[:] = trial_edge
        if core_alone:
            continue  # nothing is scored with its satellites yet
        if new_violation < best_violation - 1e-9 or (
                abs(new_violation - best_violation) <= 1e-9 and new_cost < best_cost):
            _keep(p, q, turned, long_side, short_side, s_turned, s_side, s_slide, s_long, s_short,
                  best_p, best_q, best_turned, best_long, best_short, best_s_turned, best_s_side, best_s_slide,
                  best_s_long, best_s_short)
            best_violation = new_violation
            best_cost = new_cost
    # the best state's rectangles: its satellites each take the place they were scored in
    _evaluate(best_p, best_q, best_turned, best_long, best_short, bounds, edge_a, edge_b, need,
              door_ptr, door_to, on_boundary, width, height, wall, per_edge, work)
    _place_satellites(work, parent, sat_need, sat_on_boundary, best_s_long, best_s_short, best_s_turned,
                      best_s_side, best_s_slide, extra_ptr, extra_to, extra_need, sibling_ptr, sibling_to, width,
                      height, wall, x, y, w, h, cost_of, grid, counts, stamp, np.inf, 0, placed, False, -1, moved,
                      dirty)
    return best_violation, x, y, w, h, made
