"""New arrangements by simulated annealing over sequence pairs (issue 11, groundwork).

The greedy contact placement (layoutdsl.compile.generate) places one room at a time and
cannot take a choice back; on dense plans with cycles (office_OfficePlan's ladder of
corridors, school_stjoseph_scatholichighschool's 26 independent cycles) its geometries
leave conflicts the repair cannot clear. VLSI floorplanning solves the same problem - many
rectangles, a fixed outline, wanted contacts - by searching a discrete representation of
the whole arrangement: the *sequence pair* (Murata et al., 1995). Two permutations P and Q
of the rooms say, for every pair at once, how the two lie:

- a before b in P and in Q: a is left of b;
- a after b in P, before b in Q: a is below b.

Every sequence pair is a consistent set of relations (no cycle of "left of"). Its packing
(`_pack`) is the tightest one, each room as far left and down as the rooms left of and
below it allow (longest paths in Q's order), followed by a sweep that pulls each room
towards the door neighbours right of and above it: O(n^2), microseconds with numba.

The annealer moves through sequence pairs, orientations and room sides (within the room's
bounds and aspect ratio), and scores each packing by what a layout must not have: extent
beyond the boundary, and for each door the gap between its rooms plus the shortfall of their
shared wall; onB rooms add their distance from the boundary; distance from the drawn sides
and the bounding box's area are small tie-breakers. Besides the classic moves (swap in P, in
Q, in both; turn a room; resize a side), one move takes a room whose door is unmet and puts
it right beside its neighbour, on a random side. A violation of 0 is a packing that meets
every door inside the boundary: the relation LP of the construction's repair
(layoutdsl.compile.construct) is then feasible from its first round.

Status (bench/anneal.py, bench/results/anneal.txt, generation-60s.txt): from a random sequence
pair the annealer reaches 0 on most plans without cycles in seconds; on the dense plans with
cycles it was built for, where a run ends depends mostly on its seed (office_OfficePlan, 12
runs: 1.7 m to 26.7 m after ~10 s). Started from a greedy placement the construction's repair
gave up on, a short cool run untangles it far more often (FROM_GEOMETRY_TEMPERATURE). So
`compile` anneals every plan with cycles beside its greedy placement
(layoutdsl.compile.construct.Annealing): runs go on the cores the repairs leave
(layoutdsl.compile.anneal_runs), and a run that ends within a few metres of a layout is
repaired next. That constructs
office_OfficePlan at seeds 0-3 and school_RomainRolland1 in ~5 s (38 s greedy alone);
office_floor-1024x523 at three of seeds 0-3 (18-32 s, each from a random start that met
every door), school_stjoseph_scatholichighschool not at all: its runs ended 5-90 m from a
layout. The core-and-satellites annealer (layoutdsl.compile.satellites), which packs only the
rooms in its large cycle blocks as a sequence pair, constructs it; compile runs both kinds.

The number of moves is fixed by the spec's size, never by the clock, and each chain is
seeded: the same seed gives the same geometry. Needs numba (`pip install
'layoutdsl[anneal]'`).
"""

from __future__ import annotations

import math
import random
import threading
import time
from collections import namedtuple
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from numba import njit

from layoutdsl.compile.generate import RoomSizes, drawn_sides
from layoutdsl.layout.geometry import Rect
from layoutdsl.syntax.ast import Spec

MOVES_PER_ROOM = 50000
"""Annealing moves per room (n rooms: n x this many moves, at most MAX_MOVES). Measured
(bench/results/anneal-moves.txt, random starts, seeds 1000-1009, two runs side by side on 2
cores): on office_floorplanLOWER, 25000 met every door in 1 run of 10 at 10.2 s a run, 50000 in
5 at 15.0 s (a run that meets them stops after half its moves), 100000 in 5 at 20.0 s; on
office_floor-1024x523, 25000 in none of 8, 50000 in 2 of 8 at 21.3 s."""

MAX_MOVES = 4_000_000
"""...so office_floor-1024x523 (76 rooms) gets its 50000 a room; the 105-room school, whose
random starts end 20-50 m from a layout either way, is held to about 30 s a run."""

CHAINS = 2
"""Annealing chains run side by side (one per core of the machine the issue measures on);
the geometry with the least violation is kept."""

GIVE_UP_AT = 0.6
GIVE_UP_M = 5.0
"""A run from a random sequence pair still more than GIVE_UP_M metres from a layout after
GIVE_UP_AT of its moves stops there: it would not have met every door. Traced at 50000 moves a
room (bench/results/anneal-moves.txt, seeds 1000-1009): on office_floorplanLOWER and
office_floor-1024x523, the 7 runs that met every door were at most 4.7 m from it at 60 %, and
the 11 of 13 others above 5 m ended 4.5-11.5 m away (a repair rarely finishes those). Their
last 40 % are better spent on the next run: the worker starts one."""

FROM_GEOMETRY_MOVES_PER_ROOM = 10000
FROM_GEOMETRY_TEMPERATURE = 0.03
"""A run from a given geometry (a greedy placement the repair could not finish) is shorter
and cooler than one from a random sequence pair: it only has to untangle what is there.
Measured on office_OfficePlan (8 greedy geometries, about 3.5 s a run): 0.0-14.7 m left
unmet, two at 0; eight runs from random sequence pairs with the same moves and temperature
left 15-48 m, and full-length ones (25000 moves a room, 0.1) 8.7-18 m in ~10 s. Cooler
(0.003) or longer (20000) runs did no better."""

CANCEL_CHECK = 2048
"""Moves between two looks at the cancel flag (a few milliseconds)."""

ADJACENCY_WEIGHT = 1.0
"""Per metre of gap between a door's rooms, or of missing shared wall."""

OVERFLOW_WEIGHT = 2.0
"""Per metre the packing sticks out of the boundary."""

BOUNDARY_WEIGHT = 1.0
"""Per metre an onB room is from the boundary."""

COMPACT_WEIGHT = 0.02
"""Per (bounding box area / boundary area): a tie-breaker for compact buildings."""

RESIZE_SHARE = 0.15
"""Share of the moves that lengthen or shorten one side of one room."""

RESIZE_STEP = 0.15
"""Spread of a resize: the side is multiplied by exp(this x a standard normal draw)."""

RESIZE_WEIGHT = 0.05
"""Per metre a side is from its drawn length: rooms stay near their targets."""

START_TEMPERATURE = 0.1
"""...times (W + H): the temperature of the first moves, in metres of violation."""

END_TEMPERATURE = 0.0001
"""...times (W + H): the temperature of the last moves."""


@dataclass(frozen=True)
class _Arrays:
    """A spec as the kernel reads it: rooms by index, doors as index pairs."""

    ids: list[str]
    long_side: np.ndarray
    short_side: np.ndarray
    bounds: np.ndarray
    edge_a: np.ndarray
    edge_b: np.ndarray
    need: np.ndarray
    door_ptr: np.ndarray
    door_to: np.ndarray
    on_boundary: np.ndarray
    width: float
    height: float
    wall: float

    @classmethod
    def of(cls, spec: Spec) -> _Arrays:
        boundary = spec.boundary
        assert boundary is not None
        ids = [room.id for room in spec.rooms]
        index = {room_id: i for i, room_id in enumerate(ids)}
        sides = drawn_sides(spec)
        utilization = spec.settings.door_utilization
        edges = [(index[adj.a], index[adj.b], adj.door / utilization) for adj in spec.adjacencies
                 if adj.a in index and adj.b in index]
        door_ptr, door_to = _door_lists(len(ids), edges)
        return cls(
            ids=ids,
            long_side=np.array([sides[room_id][0] for room_id in ids], dtype=np.float64),
            short_side=np.array([sides[room_id][1] for room_id in ids], dtype=np.float64),
            bounds=np.array([_bounds(RoomSizes.of(room)) for room in spec.rooms], dtype=np.float64),
            edge_a=np.array([e[0] for e in edges], dtype=np.int64),
            edge_b=np.array([e[1] for e in edges], dtype=np.int64),
            need=np.array([e[2] for e in edges], dtype=np.float64),
            door_ptr=door_ptr, door_to=door_to,
            on_boundary=np.array([room.on_boundary for room in spec.rooms], dtype=np.bool_),
            width=boundary.w, height=boundary.h, wall=spec.settings.walldim)

    def chain(self, kernel_seed: int, cancel: np.ndarray, start: dict[str, Rect] | None = None):
        """One annealing chain (the kernel releases the GIL), cut off when cancel[0] is set:
        from a random sequence pair, or from `start` (FROM_GEOMETRY_*)."""
        return self.chain_from(kernel_seed, cancel, None if start is None else self._state_of(start))

    def chain_from(self, kernel_seed: int, cancel: np.ndarray, state=None):
        """chain() from a state (P, Q, turned, long, short; _state_of) instead of a geometry:
        bench/anneal_stages.py builds one from a smaller plan's sequence pair."""
        scale = self.width + self.height
        if state is None:
            moves = min(MAX_MOVES, MOVES_PER_ROOM * len(self.ids))
            temperature, give_up_step = START_TEMPERATURE, int(GIVE_UP_AT * moves)
            empty = np.zeros(0, dtype=np.int64)
            state = (empty, empty, np.zeros(0, dtype=np.bool_), np.zeros(0), np.zeros(0))
        else:
            # a cool run from a geometry is short already and is never given up
            moves = min(MAX_MOVES, FROM_GEOMETRY_MOVES_PER_ROOM * len(self.ids))
            temperature, give_up_step = FROM_GEOMETRY_TEMPERATURE, moves
        return _anneal(self.long_side, self.short_side, self.bounds, self.edge_a, self.edge_b,
                       self.need, self.door_ptr, self.door_to, self.on_boundary, self.width,
                       self.height, self.wall, kernel_seed, moves, temperature * scale,
                       END_TEMPERATURE * scale, give_up_step, GIVE_UP_M, cancel, *state)

    def _state_of(self, geometry: dict[str, Rect]):
        """(P, Q, turned, long, short) of a geometry whose rectangles may overlap.

        The sequence pair follows the centres: P by x - y, Q by x + y, so a room whose
        centre lies within 45 degrees of straight left of another's is left of it, and so
        on round; sides are clamped to the room's bounds.
        """
        ids = self.ids
        cx = np.array([geometry[r][0] + geometry[r][2] / 2 for r in ids])
        cy = np.array([geometry[r][1] + geometry[r][3] / 2 for r in ids])
        w = np.array([geometry[r][2] for r in ids])
        h = np.array([geometry[r][3] for r in ids])
        p = np.array(sorted(range(len(ids)), key=lambda i: (cx[i] - cy[i], i)), dtype=np.int64)
        q = np.array(sorted(range(len(ids)), key=lambda i: (cx[i] + cy[i], i)), dtype=np.int64)
        long_side = np.clip(np.maximum(w, h), self.bounds[:, 0], self.bounds[:, 1])
        short_side = np.minimum(np.clip(np.minimum(w, h), self.bounds[:, 2], self.bounds[:, 3]), long_side)
        return p, q, h > w, long_side, short_side

    def geometry(self, result) -> tuple[dict[str, Rect], float]:
        """The packed rectangles of a chain's best state, and its violation."""
        p, q, turned, long_side, short_side, violation = result
        x, y, w, h = _packed(p, q, turned, long_side, short_side, self.bounds, self.wall,
                             self.door_ptr, self.door_to)
        return ({room_id: (float(x[i]), float(y[i]), float(w[i]), float(h[i]))
                 for i, room_id in enumerate(self.ids)}, float(violation))


def _cancel_at(deadline: float | None, cancel: np.ndarray) -> threading.Timer | None:
    """A timer that sets cancel[0] at `deadline`: the kernel cannot read the clock, the
    chains look at the flag every CANCEL_CHECK moves and give up."""
    if deadline is None:
        return None
    timer = threading.Timer(max(0.0, deadline - time.monotonic()), cancel.fill, (1,))
    timer.daemon = True
    timer.start()
    return timer


def anneal_geometry(spec: Spec, seed: int,
                    deadline: float | None = None) -> tuple[dict[str, Rect], float] | None:
    """(a seed geometry grown by annealing a sequence pair, its violation in metres), or None
    when `deadline` (a time.monotonic() instant) came first.

    A violation of 0 means the rectangles are inside the boundary, apart, and every door's
    rooms touch along at least the door's wall. The deadline only ever cuts a run off, it
    never shortens one: a geometry returned is the same with or without it.
    """
    return best_of_chains(_Arrays.of(spec), seed, deadline)


def best_of_chains(kernel, seed: int,
                   deadline: float | None = None) -> tuple[dict[str, Rect], float] | None:
    """(geometry, violation) of the best of CHAINS runs of `kernel` side by side, or None when
    `deadline` came first. `kernel` is an annealer's spec as its runs read it: `_Arrays`, or
    layoutdsl.compile.satellites.Satellites (chain(kernel_seed, cancel), geometry(result))."""
    # the numba generator is seeded inside each chain; draw their seeds from the spec's seed
    # through Python's generator so nearby seeds start far apart
    draw = random.Random(seed)
    kernel_seeds = [draw.randrange(2**31) for _ in range(CHAINS)]
    cancel = np.zeros(1, dtype=np.int64)
    timer = _cancel_at(deadline, cancel)
    # the chains run on the cores side by side, each with its own seed (numba's generator is
    # per thread), and the least violation wins (the first chain on a tie), so the result
    # does not depend on which thread finishes first
    try:
        with ThreadPoolExecutor(max_workers=CHAINS) as pool:
            results = list(pool.map(lambda kernel_seed: kernel.chain(kernel_seed, cancel), kernel_seeds))
    finally:
        if timer is not None:
            timer.cancel()
    if cancel[0]:
        return None
    return min((kernel.geometry(result) for result in results), key=lambda found: found[1])


def _bounds(sizes: RoomSizes) -> tuple[float, ...]:
    """(lo long, hi long, lo short, hi short, min ar, max ar); a corridor's ratio is free."""
    if sizes.corridor:
        return (sizes.lo_long, sizes.hi_long, sizes.lo_short, sizes.hi_short, 1e-9, 1e9)
    return (sizes.lo_long, sizes.hi_long, sizes.lo_short, sizes.hi_short, sizes.min_ar, sizes.max_ar)


def _door_lists(n: int, edges: list[tuple[int, int, float]]) -> tuple[np.ndarray, np.ndarray]:
    """Each room's door neighbours, CSR-style: door_to[door_ptr[i]:door_ptr[i + 1]]."""
    lists: list[list[int]] = [[] for _ in range(n)]
    for a, b, _ in edges:
        lists[a].append(b)
        lists[b].append(a)
    door_ptr = np.zeros(n + 1, dtype=np.int64)
    door_ptr[1:] = np.cumsum([len(neighbours) for neighbours in lists])
    door_to = np.array([b for neighbours in lists for b in neighbours], dtype=np.int64)
    return door_ptr, door_to


_Work = namedtuple("_Work", "pos_p pos_q w h max_w max_h x y right_edges top_edges left_edges bottom_edges")
"""The arrays one packing works in (_pack_into), made once a chain and reused for every move."""


@njit(cache=True)
def _new_work(n):
    return _Work(np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64), np.empty(n), np.empty(n),
                 np.empty(n), np.empty(n), np.zeros(n), np.zeros(n), np.empty(n + 1), np.empty(n + 1),
                 np.empty(n + 1), np.empty(n + 1))


@njit(cache=True)
def _sizes_into(long_side, short_side, turned, w, h):
    for i in range(long_side.shape[0]):
        if turned[i]:
            w[i] = short_side[i]
            h[i] = long_side[i]
        else:
            w[i] = long_side[i]
            h[i] = short_side[i]


@njit(cache=True)
def _positions_into(p, q, pos_p, pos_q):
    """Each room's index in P and in Q."""
    for k in range(p.shape[0]):
        pos_p[p[k]] = k
        pos_q[q[k]] = k


@njit(cache=True)
def _growth_limits_into(long_side, short_side, turned, bounds, max_w, max_h):
    """The widest and tallest each room may become (into max_w, max_h) with its other side
    as it is, within its bounds and aspect ratio; the short side stays the short one."""
    for i in range(long_side.shape[0]):
        hi_long = bounds[i, 1]
        hi_short = bounds[i, 3]
        min_ar = bounds[i, 4]
        max_ar = bounds[i, 5]
        grow_long = max(long_side[i], min(hi_long, max_ar * short_side[i]))
        grow_short = max(short_side[i], min(hi_short, long_side[i], long_side[i] / min_ar))
        if turned[i]:
            max_w[i] = grow_short
            max_h[i] = grow_long
        else:
            max_w[i] = grow_long
            max_h[i] = grow_short


@njit(cache=True)
def _touches_before(a, k, x, y, w, h, wall, pos_p, pos_q, door_ptr, door_to, along_x):
    """Whether a door neighbour of `a` placed before it in Q (left of it when along_x,
    else below it) already touches it."""
    for e in range(door_ptr[a], door_ptr[a + 1]):
        c = door_to[e]
        if pos_q[c] >= k:
            continue
        if along_x and pos_p[c] < pos_p[a]:
            if x[c] + w[c] + wall >= x[a] - 1e-9 and min(y[a] + h[a], y[c] + h[c]) > max(y[a], y[c]):
                return True
        elif not along_x and pos_p[c] > pos_p[a]:
            if y[c] + h[c] + wall >= y[a] - 1e-9 and min(x[a] + w[a], x[c] + w[c]) > max(x[a], x[c]):
                return True
    return False


@njit(cache=True)
def _pack(p, q, w, h, wall, door_ptr, door_to, max_w, max_h):
    """(x, y, w, h) of a sequence pair (_pack_into, on arrays of its own)."""
    n = p.shape[0]
    work = _new_work(n)
    work.w[:] = w
    work.h[:] = h
    _positions_into(p, q, work.pos_p, work.pos_q)
    _pack_into(p, q, work, wall, door_ptr, door_to, max_w, max_h)
    return work.x, work.y, work.w, work.h


@njit(cache=True)
def _pack_into(p, q, work, wall, door_ptr, door_to, max_w, max_h):
    """A sequence pair's tightest packing, then each room stretched or pulled towards the
    rooms it has a door to: into work.x, work.y, work.w, work.h (the rooms' sides on entry;
    work.pos_p and work.pos_q hold p's and q's positions).

    The tightest packing puts each room as far left and down as the rooms left of and below
    it allow, one wall apart (longest paths in Q's order). That alone realises a door only
    where the room is pushed by its door's neighbour: of the rooms hanging below a corridor,
    only the tallest would touch it. So a second sweep, in reverse Q order, closes each
    room's gap to the door neighbours right of (above) it, as far as the rooms right of
    (above) it allow. A room that already meets a door neighbour on its other side grows
    towards them (up to max_w, max_h: its bounds) and keeps that door; the rest of the gap,
    or all of it for a room with no such door, is closed by moving the room. A rung between
    two rails of corridors is thus lengthened to meet both rails, as the repair's LP would.
    No sweep moves or grows a room into another, so the packing stays one. The annealer
    packs millions of times a run: nothing here allocates (measured on office_floor-1024x523, 76
    rooms: 7.3 us a move when each packing made its arrays, 5.2 us now).
    """
    n = p.shape[0]
    w, h, x, y = work.w, work.h, work.x, work.y
    pos_p, pos_q = work.pos_p, work.pos_q
    # the rooms left of b come before it in P, those below it after it in P: with the rooms
    # placed so far in two prefix-maximum trees over P's positions (one of them reversed),
    # each room's place is two O(log n) queries instead of a scan of all rooms before it
    right_edges = work.right_edges  # over P positions: x + w + wall
    top_edges = work.top_edges  # over reversed P positions: y + h + wall
    left_edges = work.left_edges  # over reversed P positions: -(x - wall)
    bottom_edges = work.bottom_edges  # over P positions: -(y - wall)
    for k in range(n + 1):
        right_edges[k] = 0.0
        top_edges[k] = 0.0
        left_edges[k] = -np.inf
        bottom_edges[k] = -np.inf
    for k in range(n):
        b = q[k]
        i = pos_p[b]
        x[b] = _prefix_max(right_edges, i, 0.0)
        y[b] = _prefix_max(top_edges, n - 1 - i, 0.0)
        _raise(right_edges, i, x[b] + w[b] + wall)
        _raise(top_edges, n - 1 - i, y[b] + h[b] + wall)
    for k in range(n - 1, -1, -1):
        a = q[k]
        i = pos_p[a]
        # the furthest right (up) a's far side may go: the rooms after it in Q are right of
        # it (after it in P) or above it (before it in P)
        limit_x = -_prefix_max(left_edges, n - 1 - i, -np.inf)
        limit_y = -_prefix_max(bottom_edges, i, -np.inf)
        want_x = np.inf
        want_y = np.inf
        for e in range(door_ptr[a], door_ptr[a + 1]):
            b = door_to[e]
            if pos_q[b] < k:
                continue
            if pos_p[a] < pos_p[b]:
                want_x = min(want_x, x[b] - wall)
            else:
                want_y = min(want_y, y[b] - wall)
        if want_x < np.inf and want_x > x[a] + w[a]:
            edge = min(want_x, limit_x)
            if _touches_before(a, k, x, y, w, h, wall, pos_p, pos_q, door_ptr, door_to, True):
                w[a] = max(w[a], min(max_w[a], edge - x[a]))
            x[a] = max(x[a], edge - w[a])
        if want_y < np.inf and want_y > y[a] + h[a]:
            edge = min(want_y, limit_y)
            if _touches_before(a, k, x, y, w, h, wall, pos_p, pos_q, door_ptr, door_to, False):
                h[a] = max(h[a], min(max_h[a], edge - y[a]))
            y[a] = max(y[a], edge - h[a])
        _raise(left_edges, n - 1 - i, -(x[a] - wall))
        _raise(bottom_edges, i, -(y[a] - wall))


# A Fenwick tree over positions 0..n-1 (tree[1..n]): the largest value set at a position
# below i (or `floor`), and setting one. A position is set once, before it is asked. The
# packing's minima are maxima of negated values, which is exact in floating point.

@njit(cache=True, inline="always")
def _prefix_max(tree, i, floor):
    best = floor
    while i > 0:
        best = max(best, tree[i])
        i -= i & -i
    return best


@njit(cache=True, inline="always")
def _raise(tree, i, value):
    i += 1
    while i < tree.shape[0]:
        tree[i] = max(tree[i], value)
        i += i & -i


@njit(cache=True)
def _violation(work, edge_a, edge_b, need, on_boundary, width, height, wall, per_edge):
    """(violation in metres, bounding box area) of a packing (_pack_into's work): extent
    past the boundary, each door's gap and missing wall (per_edge[k] gets door k's: the
    directed move picks unmet doors), onB rooms' distance from the boundary."""
    n = work.x.shape[0]
    pos_p, pos_q = work.pos_p, work.pos_q
    x, y, w, h = work.x, work.y, work.w, work.h
    right = 0.0
    top = 0.0
    for i in range(n):
        right = max(right, x[i] + w[i])
        top = max(top, y[i] + h[i])
    for k in range(edge_a.shape[0]):
        a = edge_a[k]
        b = edge_b[k]
        if pos_q[a] > pos_q[b]:
            a, b = b, a
        # now a comes first in Q: a is left of b or below it
        if pos_p[a] < pos_p[b]:
            gap = x[b] - (x[a] + w[a] + wall)
            overlap = min(y[a] + h[a], y[b] + h[b]) - max(y[a], y[b])
        else:
            gap = y[b] - (y[a] + h[a] + wall)
            overlap = min(x[a] + w[a], x[b] + w[b]) - max(x[a], x[b])
        per_edge[k] = abs(gap) + max(0.0, need[k] - overlap)
    away = 0.0
    for i in range(n):
        if on_boundary[i]:
            away += min(min(x[i], y[i]), min(max(0.0, width - x[i] - w[i]), max(0.0, height - y[i] - h[i])))
    overflow = max(0.0, right - width) + max(0.0, top - height)
    return (OVERFLOW_WEIGHT * overflow + ADJACENCY_WEIGHT * per_edge.sum() + BOUNDARY_WEIGHT * away,
            right * top)


@njit(cache=True)
def _packed(p, q, turned, long_side, short_side, bounds, wall, door_ptr, door_to):
    """(x, y, w, h) of a state: its rooms' sides, packed (_pack) within their growth limits."""
    work = _new_work(p.shape[0])
    _pack_state(p, q, turned, long_side, short_side, bounds, wall, door_ptr, door_to, work)
    return work.x, work.y, work.w, work.h


@njit(cache=True)
def _pack_state(p, q, turned, long_side, short_side, bounds, wall, door_ptr, door_to, work):
    """_packed into `work`."""
    _sizes_into(long_side, short_side, turned, work.w, work.h)
    _growth_limits_into(long_side, short_side, turned, bounds, work.max_w, work.max_h)
    _positions_into(p, q, work.pos_p, work.pos_q)
    _pack_into(p, q, work, wall, door_ptr, door_to, work.max_w, work.max_h)


@njit(cache=True)
def _evaluate(p, q, turned, long_side, short_side, bounds, edge_a, edge_b, need, door_ptr, door_to,
              on_boundary, width, height, wall, per_edge, work):
    """(violation, bounding box area) of a state; per_edge as in _violation."""
    _pack_state(p, q, turned, long_side, short_side, bounds, wall, door_ptr, door_to, work)
    return _violation(work, edge_a, edge_b, need, on_boundary, width, height, wall, per_edge)


@njit(cache=True)
def _move_beside(seq, room, anchor, after, out):
    """Into `out`: the permutation `seq` with `room` taken out and put just after (or
    before) `anchor`."""
    n = seq.shape[0]
    k = 0
    for i in range(n):
        r = seq[i]
        if r == room:
            continue
        if r == anchor and not after:
            out[k] = room
            k += 1
        out[k] = r
        k += 1
        if r == anchor and after:
            out[k] = room
            k += 1


@njit(cache=True)
def _resize_into(i, long_side, short_side, bounds, new_long, new_short):
    """One side of room i longer or shorter (into new_long or new_short, copies of the
    sides), within its bounds and aspect ratio."""
    factor = math.exp(RESIZE_STEP * np.random.standard_normal())
    lo_long, hi_long, lo_short, hi_short, min_ar, max_ar = bounds[i]
    if np.random.random() < 0.5:
        lo = max(lo_long, min_ar * short_side[i], short_side[i])
        hi = min(hi_long, max_ar * short_side[i])
        new_long[i] = min(hi, max(lo, long_side[i] * factor))
    else:
        lo = max(lo_short, long_side[i] / max_ar)
        hi = min(hi_short, long_side[i] / min_ar, long_side[i])
        new_short[i] = min(hi, max(lo, short_side[i] * factor))


@njit(cache=True, inline="always")
def _drift(i, long_side, short_side, drawn_long, drawn_short):
    """How far room i's sides are from their drawn lengths (RESIZE_WEIGHT), in metres."""
    return abs(long_side[i] - drawn_long[i]) + abs(short_side[i] - drawn_short[i])


@njit(cache=True)
def _propose(p, q, turned, long_side, short_side, new_p, new_q, new_turned, spare_long, spare_short,
             bounds, edge_a, edge_b, per_edge):
    """One random move of a sequence-pair state, into new_p, new_q, new_turned (copies of p,
    q, turned on entry) or, for a resize, into spare_long and spare_short: the resized room,
    or -1 for any other move. per_edge (each door's violation) steers the move beside a
    neighbour towards unmet doors."""
    n = p.shape[0]
    m = edge_a.shape[0]
    kind = np.random.random()
    if kind < RESIZE_SHARE:
        # one side of one room longer or shorter, within its bounds and aspect ratio
        i = np.random.randint(n)
        spare_long[:] = long_side
        spare_short[:] = short_side
        _resize_into(i, long_side, short_side, bounds, spare_long, spare_short)
        return i
    if kind < RESIZE_SHARE + 0.3 and m > 0:
        # a door's room beside its neighbour, on a random side; unmet doors first
        k = np.random.randint(m)
        for _ in range(8):
            if per_edge[k] > 0.0:
                break
            k = np.random.randint(m)
        a = edge_a[k]
        b = edge_b[k]
        if np.random.random() < 0.5:
            a, b = b, a
        side = np.random.randint(4)
        # b right of a: after in both; left: before in both;
        # above: before in P, after in Q; below: after in P, before in Q
        _move_beside(p, b, a, side == 0 or side == 3, new_p)
        _move_beside(q, b, a, side == 0 or side == 2, new_q)
        if np.random.random() < 0.3:
            new_turned[b] = not new_turned[b]
    elif kind < 0.55:
        i = np.random.randint(n)
        j = np.random.randint(n)
        new_p[i], new_p[j] = new_p[j], new_p[i]
    elif kind < 0.65:
        i = np.random.randint(n)
        j = np.random.randint(n)
        new_q[i], new_q[j] = new_q[j], new_q[i]
    elif kind < 0.85:
        # two rooms trade places: swap them in both sequences
        a = np.random.randint(n)
        b = np.random.randint(n)
        for k in range(n):
            if new_p[k] == a:
                new_p[k] = b
            elif new_p[k] == b:
                new_p[k] = a
            if new_q[k] == a:
                new_q[k] = b
            elif new_q[k] == b:
                new_q[k] = a
    else:
        i = np.random.randint(n)
        new_turned[i] = not new_turned[i]
    return -1


@njit(cache=True, nogil=True)
def _anneal(drawn_long, drawn_short, bounds, edge_a, edge_b, need, door_ptr, door_to, on_boundary,
            width, height, wall, seed, moves, t_start, t_end, give_up_step, give_up_m, cancel,
            start_p, start_q, start_turned, start_long, start_short):
    np.random.seed(seed)
    n = drawn_long.shape[0]
    m = edge_a.shape[0]
    if start_p.shape[0] == n:
        p, q, turned = start_p.copy(), start_q.copy(), start_turned.copy()
        long_side, short_side = start_long.copy(), start_short.copy()
    else:
        p = np.random.permutation(n)
        q = np.random.permutation(n)
        turned = np.random.random(n) < 0.5
        long_side = drawn_long.copy()
        short_side = drawn_short.copy()
    per_edge = np.zeros(m)
    # every array a move needs is made here, once: a move's trial state is written over the
    # spare arrays, which trade places with the state's when the move is taken
    work = _new_work(n)
    violation, box = _evaluate(p, q, turned, long_side, short_side, bounds, edge_a, edge_b, need,
                               door_ptr, door_to, on_boundary, width, height, wall, per_edge, work)
    boundary_area = width * height
    cost = violation + COMPACT_WEIGHT * box / boundary_area
    resized = 0.0
    best_p, best_q, best_turned = p.copy(), q.copy(), turned.copy()
    best_long, best_short = long_side.copy(), short_side.copy()
    best_violation = violation
    best_cost = cost
    ratio = t_end / t_start
    trial_edge = np.zeros(m)
    new_p, new_q, new_turned = p.copy(), q.copy(), turned.copy()
    spare_long, spare_short = long_side.copy(), short_side.copy()
    for step in range(moves):
        if step % CANCEL_CHECK == 0 and cancel[0]:
            break
        if step == give_up_step and best_violation > give_up_m:
            break  # GIVE_UP_AT
        temperature = t_start * ratio ** (step / moves)
        new_p[:] = p
        new_q[:] = q
        new_turned[:] = turned
        new_long = long_side
        new_short = short_side
        new_resized = resized
        resized_room = _propose(p, q, turned, long_side, short_side, new_p, new_q, new_turned, spare_long,
                                spare_short, bounds, edge_a, edge_b, per_edge)
        resizing = resized_room >= 0
        if resizing:
            new_long = spare_long
            new_short = spare_short
            new_resized = resized - _drift(resized_room, long_side, short_side, drawn_long, drawn_short) \
                + _drift(resized_room, new_long, new_short, drawn_long, drawn_short)
        new_violation, box = _evaluate(new_p, new_q, new_turned, new_long, new_short, bounds, edge_a,
                                       edge_b, need, door_ptr, door_to, on_boundary, width, height, wall,
                                       trial_edge, work)
        new_cost = new_violation + COMPACT_WEIGHT * box / boundary_area + RESIZE_WEIGHT * new_resized
        delta = new_cost - cost
        if delta <= 0.0 or np.random.random() < math.exp(-delta / temperature):
            p, new_p = new_p, p
            q, new_q = new_q, q
            turned, new_turned = new_turned, turned
            if resizing:
                long_side, spare_long = spare_long, long_side
                short_side, spare_short = spare_short, short_side
            cost, resized = new_cost, new_resized
            per_edge[:] = trial_edge
            if new_violation < best_violation - 1e-9 or (
                    abs(new_violation - best_violation) <= 1e-9 and new_cost < best_cost):
                best_p[:] = p
                best_q[:] = q
                best_turned[:] = turned
                best_long[:] = long_side
                best_short[:] = short_side
                best_violation = new_violation
                best_cost = new_cost
        if best_violation <= 1e-9 and step >= moves // 2:
            # a packing with every door met: the rest would only make it more compact
            break
    return best_p, best_q, best_turned, best_long, best_short, best_violation
