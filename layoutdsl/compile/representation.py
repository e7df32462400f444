"""The representation: a sequence pair (Murata et al., 1995) and its packing.

A state of the generator is two permutations P and Q of the rooms, each room's orientation
(`turned`: long side along y) and its two sides (`long_side`, `short_side`, within its
bounds). P and Q say, for every pair of rooms at once, how the two lie:

- a before b in P and in Q: a is left of b;
- a after b in P, before b in Q: a is below b.

Every sequence pair is a consistent set of relations (no cycle of "left of"), so every state
is a layout without overlaps; its packing (`pack_state`) is the tightest one, each room as
far left and down as the rooms left of and below it allow, one wall apart (longest paths in
Q's order, O(n log n) with two Fenwick trees), followed by a sweep that pulls (or stretches,
within its bounds) each room towards its door neighbours right of and above it. The moves
(`moves.py`) change a state; the cost (`cost.py`) scores its packing.

Everything here is compiled by numba and allocates nothing per packing: the generator packs
millions of states per compile.
"""

from __future__ import annotations

import heapq
from collections import namedtuple
from collections.abc import Mapping
from dataclasses import dataclass, replace

import numpy as np
from numba import njit

from layoutdsl.compile.cost import distance_to_outside
from layoutdsl.compile.cost import violation as cost_violation
from layoutdsl.layout.geometry import Rect, RoomSizes
from layoutdsl.syntax.ast import ARM_SUFFIX, Spec, arm_id

Work = namedtuple("_Work", "pos_p pos_q w h max_w max_h x y right_edges top_edges left_edges bottom_edges")
"""The arrays one packing works in (_pack_into), made once a chain and reused for every move."""


@njit(cache=True)
def new_work(n):
    return Work(np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64), np.empty(n), np.empty(n),
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
def packed(p, q, turned, long_side, short_side, bounds, wall, door_ptr, door_to):
    """(x, y, w, h) of a state: its rooms' sides, packed (_pack) within their growth limits."""
    work = new_work(p.shape[0])
    pack_state(p, q, turned, long_side, short_side, bounds, wall, door_ptr, door_to, work)
    return work.x, work.y, work.w, work.h


@njit(cache=True)
def pack_state(p, q, turned, long_side, short_side, bounds, wall, door_ptr, door_to, work):
    """_packed into `work`."""
    _sizes_into(long_side, short_side, turned, work.w, work.h)
    _growth_limits_into(long_side, short_side, turned, bounds, work.max_w, work.max_h)
    _positions_into(p, q, work.pos_p, work.pos_q)
    _pack_into(p, q, work, wall, door_ptr, door_to, work.max_w, work.max_h)




def _ordered(before: np.ndarray, key: np.ndarray) -> np.ndarray:
    """A topological order of the graph whose edges are before[a, b] (a before b), the
    lowest key first among the rooms free to come next; should the graph have a cycle, it
    is broken at the lowest key among the rooms with fewest predecessors left."""
    n = len(key)
    waiting = before.sum(axis=0).astype(np.int64)
    ready = [(float(key[i]), i) for i in range(n) if waiting[i] == 0]
    heapq.heapify(ready)
    placed = np.zeros(n, dtype=np.bool_)
    order: list[int] = []
    while len(order) < n:
        if not ready:
            rest = [i for i in range(n) if not placed[i]]
            least = min(waiting[i] for i in rest)
            ready = [min((float(key[i]), i) for i in rest if waiting[i] == least)]
        _key, i = heapq.heappop(ready)
        if placed[i]:
            continue
        placed[i] = True
        order.append(i)
        for j in np.nonzero(before[i])[0]:
            if not placed[j]:
                waiting[j] -= 1
                if waiting[j] == 0:
                    heapq.heappush(ready, (float(key[j]), int(j)))
    return np.array(order, dtype=np.int64)


def _bounds(sizes: RoomSizes) -> tuple[float, ...]:
    """(lo long, hi long, lo short, hi short, min ar, max ar); a corridor's ratio is free."""
    if sizes.corridor:
        return (sizes.lo_long, sizes.hi_long, sizes.lo_short, sizes.hi_short, 1e-9, 1e9)
    return (sizes.lo_long, sizes.hi_long, sizes.lo_short, sizes.hi_short, sizes.min_ar, sizes.max_ar)


def _door_lists(n: int, edges: list[tuple[int, int, float, bool]]) -> tuple[np.ndarray, np.ndarray]:
    """Each room's door neighbours, CSR-style: door_to[door_ptr[i]:door_ptr[i + 1]]."""
    lists: list[list[int]] = [[] for _ in range(n)]
    for a, b, *_ in edges:
        lists[a].append(b)
        lists[b].append(a)
    door_ptr = np.zeros(n + 1, dtype=np.int64)
    door_ptr[1:] = np.cumsum([len(neighbours) for neighbours in lists])
    door_to = np.array([b for neighbours in lists for b in neighbours], dtype=np.int64)
    return door_ptr, door_to


State = tuple
"""(P, Q, turned, long_side, short_side): numpy arrays indexed by room (P and Q by position)."""


@dataclass(frozen=True)
class Rooms:
    """A spec as the compiled code reads it: rooms by index, doors as index pairs, the
    outline (width x height) and whether the spec gave it (else the tool chose it)."""

    ids: list[str]
    target_long: np.ndarray
    target_short: np.ndarray
    bounds: np.ndarray
    edge_a: np.ndarray
    edge_b: np.ndarray
    need: np.ndarray
    join: np.ndarray
    """Per edge: it joins an L-room's box and arm (the cost wants the arm at an end)."""
    group_end: np.ndarray
    """Doors as groups of alternative edges (an L-room's box or arm): edges
    group_end[g - 1]:group_end[g] form door g; the cost counts the best of each."""
    door_ptr: np.ndarray
    door_to: np.ndarray
    on_boundary: np.ndarray
    width: float
    height: float
    wall: float
    outline_given: bool
    partner: np.ndarray
    """Per room: the other rectangle of its L (an L-room's box and arm are packed as two
    rooms) when the L fixes how the two are turned against each other, else -1. Every state
    keeps them so (`state_of`; moves.propose turns both): the sizing stage joins the arm to
    its box in the shape the L has (Arm.crosses), and an arm packed turned the other way is
    moved there, away from the doors the packing met (measured on office_floorplanMAIN,
    seed 0: a violation of 0 left 20 m of stretch to the sizing stage, 21 s)."""
    crosses: np.ndarray
    """Per room with a partner: the arm runs across its box (turned unlike it)."""
    doors: tuple[tuple[str, str], ...] = ()
    """The spec's two rooms of each door (group), in group order."""

    @classmethod
    def of(cls, spec: Spec, sides: dict[str, tuple[float, float]], outline: tuple[float, float],
           outline_given: bool, crossings: Mapping[tuple[str, str], bool] | None = None) -> Rooms:
        """`sides`: each room's (long, short) target as drawn (initial.drawn_sides);
        `crossings`: (L-room, its arm id) -> does the arm run across the box
        (layout.lshape.crossings of the spec before its arms became rooms)."""
        ids = [room.id for room in spec.rooms]
        index = {room_id: i for i, room_id in enumerate(ids)}
        partner = np.full(len(ids), -1, dtype=np.int64)
        crosses = np.zeros(len(ids), dtype=np.bool_)
        for (box, arm), across in (crossings or {}).items():
            if box in index and arm in index:
                partner[index[box]], partner[index[arm]] = index[arm], index[box]
                crosses[index[box]] = crosses[index[arm]] = across
        utilization = spec.settings.door_utilization
        edges, groups = [], []
        door_rooms: list[tuple[str, str]] = []
        for adj in spec.adjacencies:
            if adj.a not in index or adj.b not in index:
                continue
            # a door of an L-room (its box and arm packed as two rooms, layout.lshape
            # .seeds_spec) is met by either of its rectangles: one group of alternatives
            joined = arm_id(adj.a) == adj.b or arm_id(adj.b) == adj.a
            ends_a = [adj.a] + ([arm_id(adj.a)] if not joined and arm_id(adj.a) in index else [])
            ends_b = [adj.b] + ([arm_id(adj.b)] if not joined and arm_id(adj.b) in index else [])
            door = len(set(groups))
            door_rooms.append((adj.a, adj.b))
            for a in ends_a:
                for b in ends_b:
                    edges.append((index[a], index[b], adj.door / utilization, joined))
                    groups.append(door)
        door_ptr, door_to = _door_lists(len(ids), edges)
        return cls(
            ids=ids,
            target_long=np.array([sides[room_id][0] for room_id in ids], dtype=np.float64),
            target_short=np.array([sides[room_id][1] for room_id in ids], dtype=np.float64),
            bounds=np.array([_bounds(RoomSizes.of(room)) for room in spec.rooms], dtype=np.float64),
            edge_a=np.array([e[0] for e in edges], dtype=np.int64),
            edge_b=np.array([e[1] for e in edges], dtype=np.int64),
            need=np.array([e[2] for e in edges], dtype=np.float64),
            join=np.array([e[3] for e in edges], dtype=np.bool_),
            group_end=np.array([k + 1 for k in range(len(edges)) if k + 1 == len(edges) or groups[k + 1] != groups[k]],
                               dtype=np.int64),
            door_ptr=door_ptr, door_to=door_to,
            on_boundary=np.array([room.on_boundary for room in spec.rooms], dtype=np.bool_),
            width=float(outline[0]), height=float(outline[1]), wall=spec.settings.walldim,
            outline_given=outline_given, partner=partner, crosses=crosses, doors=tuple(door_rooms))

    def grown_towards(self, sides: Mapping[str, tuple[float, float]], share: float, floor: float) -> Rooms:
        """These rooms drawn `share` of the way from their drawn sides to `sides` (their
        targets), each side at least `floor` x that size: a state packed with them keeps its
        rooms that large, so its doors can only be met by moving rooms, not shrinking them."""
        long_side = self.target_long + share * (np.array([sides[i][0] for i in self.ids]) - self.target_long)
        short_side = self.target_short + share * (np.array([sides[i][1] for i in self.ids]) - self.target_short)
        bounds = self.bounds.copy()
        bounds[:, 0] = np.minimum(np.maximum(bounds[:, 0], floor * long_side), bounds[:, 1])
        bounds[:, 2] = np.minimum(np.maximum(bounds[:, 2], floor * short_side), bounds[:, 3])
        return replace(self, target_long=long_side, target_short=short_side, bounds=bounds)

    def fitted(self, state: State) -> State:
        """The state with each room's sides raised to its drawn size, within its bounds."""
        p, q, turned, long_side, short_side = state
        return (p, q, turned,
                np.clip(np.maximum(long_side, self.target_long), self.bounds[:, 0], self.bounds[:, 1]),
                np.clip(np.maximum(short_side, self.target_short), self.bounds[:, 2], self.bounds[:, 3]))

    def state_of(self, geometry: Mapping[str, Rect]) -> State:
        """The state of a geometry whose rectangles may overlap: P by x - y of the centres,
        Q by x + y (a room whose centre lies within 45 degrees of straight left of another's
        is left of it, and so on round); sides clamped to the room's bounds."""
        x, y, w, h = self._boxes(geometry)
        cx, cy = x + w / 2, y + h / 2
        p = np.array(sorted(range(len(self.ids)), key=lambda i: (cx[i] - cy[i], i)), dtype=np.int64)
        q = np.array(sorted(range(len(self.ids)), key=lambda i: (cx[i] + cy[i], i)), dtype=np.int64)
        return (p, q, *self._sides(w, h))

    def state_of_layout(self, geometry: Mapping[str, Rect]) -> State:
        """The state of a layout (rectangles that do not overlap) that keeps each pair of
        rooms apart along one axis and overlapping along the other in its relation, so every
        door the layout meets is between rooms in the same relation again. P orders a before
        b when a is left of or above b, Q when a is left of or below b (Murata et al.); those
        pairs are the edges of two graphs, and each order is a topological sort of its graph,
        ties and the pairs apart along both axes by the centre rule of `state_of`. Packing
        puts the rooms left and down, so the doors the layout met by position need a chain
        to meet again."""
        x, y, w, h = self._boxes(geometry)
        # gap_x[a, b]: how far a's right side lies left of b's left side; overlap_y[a, b]:
        # how far their vertical extents overlap (and the same turned)
        gap_x = x[None, :] - (x + w)[:, None]
        gap_y = y[None, :] - (y + h)[:, None]
        overlap_y = np.minimum(y + h, (y + h)[:, None]) - np.maximum(y, y[:, None])
        overlap_x = np.minimum(x + w, (x + w)[:, None]) - np.maximum(x, x[:, None])
        left = (gap_x > -1e-6) & (overlap_y > 1e-6)
        below = (gap_y > -1e-6) & (overlap_x > 1e-6)
        cx, cy = x + w / 2, y + h / 2
        return (_ordered(left | below.T, cx - cy), _ordered(left | below, cx + cy), *self._sides(w, h))

    def _boxes(self, geometry: Mapping[str, Rect]) -> tuple[np.ndarray, ...]:
        """(x, y, w, h) of the rooms' rectangles, in room order."""
        return tuple(np.array([geometry[r][k] for r in self.ids]) for k in range(4))

    def _sides(self, w: np.ndarray, h: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(turned, long side, short side) of rectangles w x h, the sides clamped to the
        rooms' bounds."""
        long_side = np.clip(np.maximum(w, h), self.bounds[:, 0], self.bounds[:, 1])
        short_side = np.minimum(np.clip(np.minimum(w, h), self.bounds[:, 2], self.bounds[:, 3]), long_side)
        turned = h > w
        # an L's arm turned as its shape says against its box (the box, the larger, keeps its way)
        for i in range(len(self.ids)):
            if self.partner[i] >= 0 and self.ids[i].endswith(ARM_SUFFIX):
                turned[i] = turned[self.partner[i]] != self.crosses[i]
        return turned, long_side, short_side

    def unmet_doors(self, state: State) -> list[tuple[str, str, float]]:
        """(room, room, metres) of each door the state's packing does not meet, worst first:
        the metres are the gap between the two rooms plus the shared wall they lack."""
        p, q, turned, long_side, short_side = state
        work = new_work(len(self.ids))
        pack_state(p, q, turned, long_side, short_side, self.bounds, self.wall, self.door_ptr, self.door_to, work)
        per_edge = np.zeros(self.edge_a.shape[0])
        cost_violation(work, self.edge_a, self.edge_b, self.need, self.join, self.group_end, self.on_boundary, self.width,
                       self.height, self.wall, self.outline_given, per_edge)
        unmet, start = [], 0
        for g, end in enumerate(self.group_end):
            metres = float(per_edge[start:end].min())
            if metres > 1e-6 and g < len(self.doors):
                unmet.append((*self.doors[g], round(metres, 2)))
            start = end
        return sorted(unmet, key=lambda door: (-door[2], door[0], door[1]))

    def outside_shortfall(self, state: State) -> tuple[list[tuple[str, float]], tuple[float, float]]:
        """What keeps a state from a layout besides its doors (cost.violation's other two
        terms): each room that must open to the outside (onB) but lies inside, with its
        distance in metres to the outer boundary, furthest first; and (metres, metres) the
        packing sticks out of the outline along x and y (0, 0 for an outline the tool chose,
        which the boundary is drawn round)."""
        geometry = self.geometry(state)
        right = max(x + w for x, _y, w, _h in geometry.values())
        top = max(y + h for _x, y, _w, h in geometry.values())
        outer_w, outer_h = (self.width, self.height) if self.outline_given else (right, top)
        away = []
        for i, room_id in enumerate(self.ids):
            if not self.on_boundary[i]:
                continue
            metres = distance_to_outside(*geometry[room_id], outer_w, outer_h)
            if metres > 1e-6:
                away.append((room_id, round(metres, 2)))
        overflow = ((round(max(0.0, right - self.width), 2), round(max(0.0, top - self.height), 2))
                    if self.outline_given else (0.0, 0.0))
        return sorted(away, key=lambda room: (-room[1], room[0])), overflow

    def geometry(self, state: State) -> dict[str, Rect]:
        """The packed rectangles of a state."""
        p, q, turned, long_side, short_side = state
        x, y, w, h = packed(p, q, turned, long_side, short_side, self.bounds, self.wall,
                            self.door_ptr, self.door_to)
        return {room_id: (float(x[i]), float(y[i]), float(w[i]), float(h[i]))
                for i, room_id in enumerate(self.ids)}
