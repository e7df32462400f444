"""The thesis' MIQP (seed §5.5.1) as a Pyomo model: a pure function of the checked spec.

Every constraint family is one named Block carrying its equation number (`m.eq5_4_min_size`
... `m.eq5_13_cluster`), so the code can be held against the thesis line by line. Nothing
here solves anything: `solve.py` owns SCIP.

Deliberate differences from the equations as printed, each exact or a valid tightening:

* Objective (5.1)-(5.3). Written as printed, one nonconvex quadratic objective made SCIP
  report numerical trouble and abort on large models (see shared/notes/solver-scouting.md).
  We use the equivalent bounded-helper form: a_i <= w_i*h_i (nonconvex, a_i bounded by the
  size bounds), e_w and e_h linear in (w, h, o) as in (5.3), q_i >= e_w^2 + e_h^2 (convex),
  and the linear objective lambda_cover*(W*H - sum rho_cover*a) + lambda_error*sum rho_error*q.
  With rho >= 0 every optimum has a_i = w_i*h_i and q_i = e_w^2 + e_h^2, so the optimal value
  and the optimal layouts are those of (5.1); nothing is convexified.
* Orientation. As in the thesis, o_i = 0 means w_i is the long side: (5.4)/(5.5) give the
  long side the larger of the two minimum (maximum) sizes and (5.6) bounds w/h. (5.3) then
  compares the long side with the larger target and the short side with the smaller one,
  which is the printed (5.3) for rooms listed wide; for rooms listed tall the printed form
  would compare the long side with the short target, contradicting (5.4).
* Adjacency (5.9) as printed guarantees only door - walldim of shared interior wall; here the
  rooms' interiors overlap by at least door / door_utilization along the wall, and the gap
  across the wall is exactly walldim (non-overlap gives >= walldim, adjacency <= walldim).
* Big-M: one constant per constraint, from interval bounds of the variables involved (never
  looser than the boundary allows), unless `Formulation(tight_big_m=False)` asks for the
  thesis' single M.
* Long and short sides (`Formulation.long_short`, on by default): variables long_i, short_i
  equal to (w_i, h_i) when o_i = 0 and (h_i, w_i) when o_i = 1, linked by big-M rows in
  `m.orientation`. (5.4)-(5.6) hold on them too (inside their blocks), and the objective
  uses a_i <= long_i*short_i and the errors long_i - long target, short_i - short target:
  the same values as (5.3) for every o, but with narrow bounds, so SCIP's relaxation of the
  area term is tight (a 5-room spec proves its 1 % gap at the root node instead of >20 s).
* Cheap valid cuts: pairs whose bounds already separate them get no binaries, sides the
  bounds rule out are fixed to 0, interchangeable rooms are ordered by x, and each
  adjacency's α is tied to its pair's ω. `THESIS_AS_WRITTEN` switches all of this off.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import pyomo.environ as pyo

from layoutdsl.syntax.ast import Room, Spec

SIDES = ("left", "right", "below", "above")
"""Where the first room of a pair lies relative to the second (the four ω of (5.8))."""

OPPOSITE_SIDE = {"left": "right", "right": "left", "below": "above", "above": "below"}

BOUNDARY_SIDES = ("left", "right", "bottom", "top")
"""Which side of the boundary an onB room touches (the four β of (5.12))."""

Rect = tuple[float, float, float, float]
"""(x, y, w, h): bottom-left corner and size, metres, boundary frame."""


@dataclass(frozen=True, slots=True)
class Formulation:
    """Which of our improvements over the thesis formulation as written are switched on."""

    tight_big_m: bool = True
    """Per-constraint big-M from variable bounds; False = one global M for every constraint."""
    prune_pairs: bool = True
    """Skip non-overlap binaries for sides that the variable bounds already decide."""
    symmetry_breaking: bool = True
    """Order interchangeable rooms (identical lines and neighbourhoods) by x."""
    adjacency_links: bool = True
    """Tie each adjacency's side binary to the pair's non-overlap binaries (valid cuts)."""
    long_short: bool = True
    """Give each room long and short side variables (w and h swapped by o) and write the
    size bounds, aspect ratio and objective on them: exact, and SCIP's relaxation of the
    area a <= long*short is much tighter than of a <= w*h, whose bounds span both
    orientations."""


THESIS_AS_WRITTEN = Formulation(
    tight_big_m=False, prune_pairs=False, symmetry_breaking=False, adjacency_links=False,
    long_short=False,
)
"""The formulation of §5.5.1 with only the corrections needed for correctness."""


@dataclass(frozen=True, slots=True)
class _Bounds:
    """Interval bounds of one room's variables, derived from the spec alone."""

    w: tuple[float, float]
    h: tuple[float, float]
    x: tuple[float, float]
    y: tuple[float, float]
    limit: tuple[float, float] = (math.inf, math.inf)
    """The boundary's width and height: x + w and y + h never exceed them (5.7)."""

    @property
    def right(self) -> tuple[float, float]:
        """Bounds of x + w."""
        return (self.x[0] + self.w[0], min(self.x[1] + self.w[1], self.limit[0]))

    @property
    def top(self) -> tuple[float, float]:
        """Bounds of y + h."""
        return (self.y[0] + self.h[0], min(self.y[1] + self.h[1], self.limit[1]))


def room_bounds(spec: Spec) -> dict[str, _Bounds]:
    """Interval bounds of x, y, w, h per room, from sizes, boundary, positions and connections."""
    assert spec.boundary is not None, "build_model needs a checked spec with a boundary"
    width, height = spec.boundary.w, spec.boundary.h
    bounds: dict[str, _Bounds] = {}
    for room in spec.rooms:
        w_lo = min(room.min_w, room.min_h)
        w_hi = min(max(room.max_w, room.max_h), width)
        h_lo = min(room.min_w, room.min_h)
        h_hi = min(max(room.max_w, room.max_h), height)
        x_lo, x_hi = 0.0, max(0.0, width - w_lo)
        y_lo, y_hi = 0.0, max(0.0, height - h_lo)
        # points the room must cover pin its corner to within one room size of them
        points = [(p.x, p.y) for p in spec.positions if p.room == room.id]
        for c in spec.connections:
            if c.room == room.id:
                points += [(c.x1, c.y1), (c.x2, c.y2)]
        for px, py in points:
            x_hi = min(x_hi, px)
            x_lo = max(x_lo, px - w_hi)
            y_hi = min(y_hi, py)
            y_lo = max(y_lo, py - h_hi)
        x_lo, y_lo = min(x_lo, x_hi), min(y_lo, y_hi)
        bounds[room.id] = _Bounds((w_lo, w_hi), (h_lo, h_hi), (x_lo, x_hi), (y_lo, y_hi), (width, height))
    return bounds


def orientation_bounds(room: Room, o: int) -> tuple[float, float, float, float]:
    """(min_w, max_w, min_h, max_h) of the placed room for orientation o (0: w is the long side)."""
    lo_short, lo_long = sorted((room.min_w, room.min_h))
    hi_short, hi_long = sorted((room.max_w, room.max_h))
    if o == 0:
        return (lo_long, hi_long, lo_short, hi_short)
    return (lo_short, hi_short, lo_long, hi_long)


def orientation_targets(room: Room, o: int) -> tuple[float, float]:
    """(target w, target h) for orientation o: the long target goes to the long side."""
    short, long = sorted((room.target_w, room.target_h))
    return (long, short) if o == 0 else (short, long)


def _interchangeable_groups(spec: Spec) -> list[list[str]]:
    """Rooms that can swap places in any layout: identical lines, no own geometry constraints,
    and identical neighbourhoods (same neighbours with the same door and kind)."""
    pinned = {p.room for p in spec.positions} | {c.room for c in spec.connections}
    pinned |= {m.room for cl in spec.clusters for m in cl.members}
    neighbours: dict[str, set[tuple[str, float, str]]] = {r.id: set() for r in spec.rooms}
    for adj in spec.adjacencies:
        neighbours[adj.a].add((adj.b, adj.door, adj.kind))
        neighbours[adj.b].add((adj.a, adj.door, adj.kind))

    def signature(room: Room) -> tuple:
        return (
            room.min_w, room.max_w, room.target_w, room.min_h, room.max_h, room.target_h,
            room.min_ar, room.max_ar, room.rtype, room.on_boundary,
            room.rho_cover, room.rho_error,
        )

    groups: list[list[str]] = []
    for room in spec.rooms:
        if room.id in pinned:
            continue
        for group in groups:
            first = spec.room(group[0])
            assert first is not None
            if signature(first) != signature(room):
                continue
            # neighbourhoods compared with the pair itself removed: two identical rooms
            # adjacent to each other are still interchangeable
            mine = {n for n in neighbours[room.id] if n[0] != first.id}
            theirs = {n for n in neighbours[first.id] if n[0] != room.id}
            if mine == theirs:
                group.append(room.id)
                break
        else:
            groups.append([room.id])
    return [g for g in groups if len(g) > 1]


def build_model(
    spec: Spec,
    *,
    fixed_relations: Mapping[tuple[str, str], str] | None = None,
    formulation: Formulation = Formulation(),
) -> pyo.ConcreteModel:
    """The MIQP of seed §5.5.1 for a checked spec (no solving).

    `fixed_relations` maps a pair of room or obstacle ids (a, b) to the side of b on which a
    lies ('left', 'right', 'below', 'above'); those pairs' non-overlap binaries are fixed, so
    a construction that decided the relative positions leaves SCIP an easy model.
    """
    assert spec.boundary is not None, "build_model needs a checked spec with a boundary"
    width, height = float(spec.boundary.w), float(spec.boundary.h)
    wall = float(spec.settings.walldim)
    bounds = room_bounds(spec)
    rooms = {room.id: room for room in spec.rooms}
    obstacles = {ob.id: ob for ob in spec.boundary.obstacles}
    max_ar = max([r.max_ar for r in spec.rooms if not r.is_corridor] + [1.0])
    max_need = max([a.door / spec.settings.door_utilization for a in spec.adjacencies] + [0.0])
    # the thesis' single M: at least every per-constraint value below (aspect ratio needs
    # maxAR times a side, adjacency a side plus the shared wall, non-overlap a side plus a wall)
    global_m = max(width, height) * max(max_ar, 1.0) + max(width, height) + wall + max_need

    def big_m(value: float) -> float:
        return max(value, 0.0) if formulation.tight_big_m else global_m

    m = pyo.ConcreteModel(name=spec.name)
    m.formulation = formulation

    # ----- sets named after DSL concepts -----
    m.rooms = pyo.Set(initialize=[r.id for r in spec.rooms], ordered=True, doc="room ids, spec order")
    m.corridors = pyo.Set(within=m.rooms, initialize=[r.id for r in spec.rooms if r.is_corridor],
                          doc="rooms of type C (no aspect-ratio constraint)")
    m.obstacles = pyo.Set(initialize=list(obstacles), ordered=True, doc="fixed obstacle rectangles")
    m.room_pairs = pyo.Set(
        dimen=2, ordered=True,
        initialize=[(a.id, b.id) for i, a in enumerate(spec.rooms) for b in spec.rooms[i + 1:]],
        doc="unordered room pairs (r1, r2), r1 listed before r2",
    )
    m.room_obstacle_pairs = pyo.Set(
        dimen=2, ordered=True, initialize=[(r.id, o) for r in spec.rooms for o in obstacles],
        doc="(room, obstacle) pairs",
    )
    m.sides = pyo.Set(initialize=SIDES, ordered=True,
                      doc="where the first of a pair lies relative to the second")
    m.adjacencies = pyo.Set(dimen=2, ordered=True,
                            initialize=[(a.a, a.b) for a in spec.adjacencies],
                            doc="adjacent room pairs as written")
    m.positions = pyo.Set(initialize=[p.room for p in spec.positions], ordered=True,
                          doc="rooms that must cover a fixed point")
    m.connections = pyo.Set(initialize=range(len(spec.connections)), ordered=True,
                            doc="connection lines (index into spec.connections)")
    m.onb_rooms = pyo.Set(initialize=[r.id for r in spec.rooms if r.on_boundary], ordered=True,
                          doc="rooms that must touch the boundary (onB)")
    m.boundary_sides = pyo.Set(initialize=BOUNDARY_SIDES, ordered=True, doc="sides of the boundary")
    m.clusters = pyo.Set(initialize=[c.id for c in spec.clusters], ordered=True, doc="cluster ids")
    m.cluster_members = pyo.Set(
        dimen=2, ordered=True,
        initialize=[(c.id, mem.room) for c in spec.clusters for mem in c.members],
        doc="(cluster, room) membership",
    )

    # ----- room variables -----
    m.x = pyo.Var(m.rooms, bounds=lambda _, r: bounds[r].x, doc="left edge (m)")
    m.y = pyo.Var(m.rooms, bounds=lambda _, r: bounds[r].y, doc="bottom edge (m)")
    m.w = pyo.Var(m.rooms, bounds=lambda _, r: bounds[r].w, doc="width along x (m)")
    m.h = pyo.Var(m.rooms, bounds=lambda _, r: bounds[r].h, doc="height along y (m)")
    m.o = pyo.Var(m.rooms, domain=pyo.Binary, doc="orientation: 0 = w is the long side, 1 = h is")
    lo = {r.id: (min(r.min_w, r.min_h), max(r.min_w, r.min_h)) for r in spec.rooms}
    hi = {r.id: (min(r.max_w, r.max_h), max(r.max_w, r.max_h)) for r in spec.rooms}
    long_short = formulation.long_short
    if long_short:
        side_bounds = {r: (min(bounds[r].w[0], bounds[r].h[0]), max(bounds[r].w[1], bounds[r].h[1])) for r in rooms}
        m.long = pyo.Var(m.rooms, bounds=lambda _, r: side_bounds[r], doc="the long side: w when o = 0, h when o = 1")
        m.short = pyo.Var(m.rooms, bounds=lambda _, r: side_bounds[r], doc="the short side: h when o = 0, w when o = 1")
        m.orientation = pyo.Block(doc="o swaps which of w, h is the long side")
        ob = m.orientation

        def swap_rule(_, r, which):
            spread = big_m(side_bounds[r][1] - side_bounds[r][0])
            o = m.o[r]
            return {
                "long_w_lo": m.long[r] >= m.w[r] - spread * o,
                "long_w_hi": m.long[r] <= m.w[r] + spread * o,
                "short_h_lo": m.short[r] >= m.h[r] - spread * o,
                "short_h_hi": m.short[r] <= m.h[r] + spread * o,
                "long_h_lo": m.long[r] >= m.h[r] - spread * (1 - o),
                "long_h_hi": m.long[r] <= m.h[r] + spread * (1 - o),
                "short_w_lo": m.short[r] >= m.w[r] - spread * (1 - o),
                "short_w_hi": m.short[r] <= m.w[r] + spread * (1 - o),
            }[which]

        ob.swap = pyo.Constraint(m.rooms, ["long_w_lo", "long_w_hi", "short_h_lo", "short_h_hi",
                                           "long_h_lo", "long_h_hi", "short_w_lo", "short_w_hi"], rule=swap_rule)

    # ----- (5.4) minimum size: the long side gets the larger minimum -----
    m.eq5_4_min_size = pyo.Block(doc="(5.4) h >= minD + (maxD - minD)*o, w >= minD + (maxD - minD)*(1 - o)")
    b = m.eq5_4_min_size
    b.height = pyo.Constraint(m.rooms, rule=lambda _, r: m.h[r] >= lo[r][0] + (lo[r][1] - lo[r][0]) * m.o[r])
    b.width = pyo.Constraint(m.rooms, rule=lambda _, r: m.w[r] >= lo[r][0] + (lo[r][1] - lo[r][0]) * (1 - m.o[r]))
    if long_short:  # the same minimums on the orientation-free sides
        b.long = pyo.Constraint(m.rooms, rule=lambda _, r: m.long[r] >= lo[r][1])
        b.short = pyo.Constraint(m.rooms, rule=lambda _, r: m.short[r] >= lo[r][0])

    # ----- (5.5) maximum size: the short side gets the smaller maximum -----
    m.eq5_5_max_size = pyo.Block(doc="(5.5) w <= maxD + (minD - maxD)*o, h <= maxD + (minD - maxD)*(1 - o)")
    b = m.eq5_5_max_size
    b.width = pyo.Constraint(m.rooms, rule=lambda _, r: m.w[r] <= hi[r][1] + (hi[r][0] - hi[r][1]) * m.o[r])
    b.height = pyo.Constraint(m.rooms, rule=lambda _, r: m.h[r] <= hi[r][1] + (hi[r][0] - hi[r][1]) * (1 - m.o[r]))
    if long_short:
        b.long = pyo.Constraint(m.rooms, rule=lambda _, r: m.long[r] <= hi[r][1])
        b.short = pyo.Constraint(m.rooms, rule=lambda _, r: m.short[r] <= hi[r][0])

    # ----- (5.6) aspect ratio, not for corridors: o = 0 bounds w/h, o = 1 bounds h/w -----
    m.eq5_6_aspect_ratio = pyo.Block(doc="(5.6) long/short side ratio in [minar, maxar], rooms minus corridors")
    b = m.eq5_6_aspect_ratio
    b.rooms = pyo.Set(initialize=[r.id for r in spec.rooms if not r.is_corridor], ordered=True)

    def _ar(kind: str):
        def rule(_, r):
            room, bd = rooms[r], bounds[r]
            o = m.o[r]
            w_lo, w_hi = bd.w
            h_lo, h_hi = bd.h
            if kind == "w_min":  # minAR*h <= w + M*o
                return room.min_ar * m.h[r] <= m.w[r] + big_m(room.min_ar * h_hi - w_lo) * o
            if kind == "w_max":  # maxAR*h >= w - M*o
                return m.w[r] <= room.max_ar * m.h[r] + big_m(w_hi - room.max_ar * h_lo) * o
            if kind == "h_min":  # minAR*w <= h + M*(1 - o)
                return room.min_ar * m.w[r] <= m.h[r] + big_m(room.min_ar * w_hi - h_lo) * (1 - o)
            return m.h[r] <= room.max_ar * m.w[r] + big_m(h_hi - room.max_ar * w_lo) * (1 - o)
        return rule

    for kind in ("w_min", "w_max", "h_min", "h_max"):
        setattr(b, kind, pyo.Constraint(b.rooms, rule=_ar(kind)))
    if long_short:  # the same ratio on the orientation-free sides: linear, no big-M
        b.long_min = pyo.Constraint(b.rooms, rule=lambda _, r: rooms[r].min_ar * m.short[r] <= m.long[r])
        b.long_max = pyo.Constraint(b.rooms, rule=lambda _, r: m.long[r] <= rooms[r].max_ar * m.short[r])

    # ----- (5.7) inside the boundary -----
    m.eq5_7_inside = pyo.Block(doc="(5.7) every room inside the boundary")
    b = m.eq5_7_inside
    b.right = pyo.Constraint(m.rooms, rule=lambda _, r: m.x[r] + m.w[r] <= width)
    b.top = pyo.Constraint(m.rooms, rule=lambda _, r: m.y[r] + m.h[r] <= height)

    # ----- (5.8) non-overlap with wall thickness: room pairs and room-obstacle pairs -----
    m.eq5_8_non_overlap = pyo.Block(doc="(5.8) rooms and obstacles keep walldim apart; four ω per pair")
    b = m.eq5_8_non_overlap

    def rect_terms(name: str):
        """(x, y, w, h, bounds) of a room (variables) or an obstacle (constants)."""
        if name in rooms:
            return m.x[name], m.y[name], m.w[name], m.h[name], bounds[name]
        ob = obstacles[name]
        fixed = _Bounds((ob.w, ob.w), (ob.h, ob.h), (ob.x, ob.x), (ob.y, ob.y))
        return ob.x, ob.y, ob.w, ob.h, fixed

    def side_slack(a: str, bname: str, side: str) -> float:
        """How much the side's inequality can be violated at worst: its big-M."""
        _, _, _, _, ba = rect_terms(a)
        _, _, _, _, bb = rect_terms(bname)
        if side == "left":  # a.x + a.w + wall <= b.x
            return ba.right[1] + wall - bb.x[0]
        if side == "right":  # b.x + b.w + wall <= a.x
            return bb.right[1] + wall - ba.x[0]
        if side == "below":
            return ba.top[1] + wall - bb.y[0]
        return bb.top[1] + wall - ba.y[0]

    def side_always(a: str, bname: str, side: str) -> bool:
        """The side's inequality holds for every value the bounds allow."""
        return side_slack(a, bname, side) <= 0

    def side_never(a: str, bname: str, side: str) -> bool:
        """The side's inequality holds for no value the bounds allow."""
        _, _, _, _, ba = rect_terms(a)
        _, _, _, _, bb = rect_terms(bname)
        if side == "left":
            return ba.right[0] + wall > bb.x[1] + 1e-9
        if side == "right":
            return bb.right[0] + wall > ba.x[1] + 1e-9
        if side == "below":
            return ba.top[0] + wall > bb.y[1] + 1e-9
        return bb.top[0] + wall > ba.y[1] + 1e-9

    all_pairs = list(m.room_pairs) + list(m.room_obstacle_pairs)
    separated = set()
    if formulation.prune_pairs:
        separated = {p for p in all_pairs if any(side_always(p[0], p[1], s) for s in SIDES)}
    b.pairs = pyo.Set(dimen=2, ordered=True, initialize=[p for p in all_pairs if p not in separated],
                      doc="pairs that need the disjunction (bounds do not already separate them)")
    b.side = pyo.Var(b.pairs, m.sides, domain=pyo.Binary,
                     doc="ω: 1 when the first of the pair lies on this side of the second")

    def sep_rule(_, a, bname, side):
        xa, ya, wa, ha, _ = rect_terms(a)
        xb, yb, wb, hb, _ = rect_terms(bname)
        slack = big_m(side_slack(a, bname, side)) * (1 - b.side[a, bname, side])
        if side == "left":
            return xa + wa + wall <= xb + slack
        if side == "right":
            return xb + wb + wall <= xa + slack
        if side == "below":
            return ya + ha + wall <= yb + slack
        return yb + hb + wall <= ya + slack

    b.separate = pyo.Constraint(b.pairs, m.sides, rule=sep_rule)
    b.one_side = pyo.Constraint(b.pairs, rule=lambda _, a, c: sum(b.side[a, c, s] for s in SIDES) >= 1)
    if formulation.prune_pairs:
        for a, c in b.pairs:
            for s in SIDES:
                if side_never(a, c, s):
                    b.side[a, c, s].fix(0)

    # relations decided by a construction: fix the pair's binaries
    for (first, second), side in (fixed_relations or {}).items():
        if side not in OPPOSITE_SIDE:
            raise ValueError(f"unknown side {side!r} for pair ({first}, {second})")
        key, rel = (first, second), side
        if key not in b.pairs:
            key, rel = (second, first), OPPOSITE_SIDE[side]
        if key not in b.pairs:
            continue  # the bounds already separate this pair
        for s in SIDES:
            b.side[key[0], key[1], s].fix(1 if s == rel else 0)

    # ----- (5.9) adjacency, corrected -----
    m.eq5_9_adjacency = pyo.Block(doc="(5.9) adjacent rooms share >= door/door_utilization of wall, walldim apart")
    b = m.eq5_9_adjacency
    utilization = spec.settings.door_utilization
    min_shared = {(a.a, a.b): a.door / utilization for a in spec.adjacencies}
    b.stacked = pyo.Var(m.adjacencies, domain=pyo.Binary,
                        doc="α: 1 when the rooms are stacked in y (horizontal shared wall)")

    def adj_rule(kind: str):
        def rule(_, r1, r2):
            need = min_shared[r1, r2]
            b1, b2 = bounds[r1], bounds[r2]
            alpha = b.stacked[r1, r2]
            if kind == "x_overlap_lo":  # stacked: r1 starts at least `need` before r2 ends
                return m.x[r1] <= m.x[r2] + m.w[r2] - need + big_m(b1.x[1] - b2.right[0] + need) * (1 - alpha)
            if kind == "x_overlap_hi":
                return m.x[r1] + m.w[r1] >= m.x[r2] + need - big_m(b2.x[1] + need - b1.right[0]) * (1 - alpha)
            if kind == "x_gap_lo":  # side by side: at most walldim apart in x
                return m.x[r1] <= m.x[r2] + m.w[r2] + wall + big_m(b1.x[1] - b2.right[0] - wall) * alpha
            if kind == "x_gap_hi":
                return m.x[r1] + m.w[r1] + wall >= m.x[r2] - big_m(b2.x[1] - b1.right[0] - wall) * alpha
            if kind == "y_overlap_lo":  # side by side: interiors overlap by `need` in y
                return m.y[r1] <= m.y[r2] + m.h[r2] - need + big_m(b1.y[1] - b2.top[0] + need) * alpha
            if kind == "y_overlap_hi":
                return m.y[r1] + m.h[r1] >= m.y[r2] + need - big_m(b2.y[1] + need - b1.top[0]) * alpha
            if kind == "y_gap_lo":  # stacked: at most walldim apart in y
                return m.y[r1] <= m.y[r2] + m.h[r2] + wall + big_m(b1.y[1] - b2.top[0] - wall) * (1 - alpha)
            return m.y[r1] + m.h[r1] + wall >= m.y[r2] - big_m(b2.y[1] - b1.top[0] - wall) * (1 - alpha)
        return rule

    for kind in ("x_overlap_lo", "x_overlap_hi", "x_gap_lo", "x_gap_hi",
                 "y_overlap_lo", "y_overlap_hi", "y_gap_lo", "y_gap_hi"):
        setattr(b, kind, pyo.Constraint(m.adjacencies, rule=adj_rule(kind)))

    if formulation.adjacency_links:
        # Stacked rooms overlap in x, so neither lies left or right of the other, and exactly
        # one lies above the other; the same holds with the axes swapped.
        pairs_set = set(m.eq5_8_non_overlap.pairs)
        omega = m.eq5_8_non_overlap.side

        def link_rule(_, r1, r2, axis):
            if min_shared[r1, r2] <= 0:
                return pyo.Constraint.Skip
            key = (r1, r2) if (r1, r2) in pairs_set else (r2, r1)
            if key not in pairs_set:
                return pyo.Constraint.Skip
            alpha = b.stacked[r1, r2]
            if axis == "y":
                return omega[key + ("below",)] + omega[key + ("above",)] == alpha
            return omega[key + ("left",)] + omega[key + ("right",)] == 1 - alpha

        b.link = pyo.Constraint(m.adjacencies, ["x", "y"], rule=link_rule,
                                doc="α agrees with the pair's ω (valid cut)")

    # ----- (5.10) position -----
    m.eq5_10_position = pyo.Block(doc="(5.10) a room covers its fixed point")
    b = m.eq5_10_position
    points = {p.room: (p.x, p.y) for p in spec.positions}
    b.left = pyo.Constraint(m.positions, rule=lambda _, r: m.x[r] <= points[r][0])
    b.right = pyo.Constraint(m.positions, rule=lambda _, r: m.x[r] + m.w[r] >= points[r][0])
    b.bottom = pyo.Constraint(m.positions, rule=lambda _, r: m.y[r] <= points[r][1])
    b.top = pyo.Constraint(m.positions, rule=lambda _, r: m.y[r] + m.h[r] >= points[r][1])

    # ----- (5.11) connection -----
    m.eq5_11_connection = pyo.Block(doc="(5.11) a room covers both points of each of its connections")
    b = m.eq5_11_connection

    def conn_rule(kind: str):
        def rule(_, k):
            c = spec.connections[k]
            r = c.room
            if kind == "left":
                return m.x[r] <= min(c.x1, c.x2)
            if kind == "right":
                return m.x[r] + m.w[r] >= max(c.x1, c.x2)
            if kind == "bottom":
                return m.y[r] <= min(c.y1, c.y2)
            return m.y[r] + m.h[r] >= max(c.y1, c.y2)
        return rule

    for kind in ("left", "right", "bottom", "top"):
        setattr(b, kind, pyo.Constraint(m.connections, rule=conn_rule(kind)))

    # ----- (5.12) on boundary -----
    m.eq5_12_on_boundary = pyo.Block(doc="(5.12) onB rooms touch at least one side of the boundary")
    b = m.eq5_12_on_boundary
    b.side = pyo.Var(m.onb_rooms, m.boundary_sides, domain=pyo.Binary,
                     doc="β: 1 when the room touches this side of the boundary")

    def onb_rule(_, r, side):
        bd = bounds[r]
        beta = b.side[r, side]
        if side == "left":
            return m.x[r] <= big_m(bd.x[1]) * (1 - beta)
        if side == "right":
            return m.x[r] + m.w[r] >= width - big_m(width - bd.right[0]) * (1 - beta)
        if side == "bottom":
            return m.y[r] <= big_m(bd.y[1]) * (1 - beta)
        return m.y[r] + m.h[r] >= height - big_m(height - bd.top[0]) * (1 - beta)

    b.touch = pyo.Constraint(m.onb_rooms, m.boundary_sides, rule=onb_rule)
    b.one_side = pyo.Constraint(m.onb_rooms, rule=lambda _, r: sum(b.side[r, s] for s in BOUNDARY_SIDES) >= 1)

    # ----- (5.13) cluster -----
    m.eq5_13_cluster = pyo.Block(doc="(5.13) cluster members keep their relative points, within the margin")
    b = m.eq5_13_cluster
    margin = spec.settings.cluster_margin
    frame = {(c.id, mem.room): (mem.x, mem.y) for c in spec.clusters for mem in c.members}

    def offset_bounds(axis: int, limit: float):
        def rule(_, cid):
            coords = [xy[axis] for (c, _r), xy in frame.items() if c == cid]
            return (-max(coords) - margin, limit - min(coords) + margin)
        return rule

    b.offset_x = pyo.Var(m.clusters, bounds=offset_bounds(0, width), doc="x_cluster: the cluster frame's x offset")
    b.offset_y = pyo.Var(m.clusters, bounds=offset_bounds(1, height), doc="y_cluster: the cluster frame's y offset")
    b.left = pyo.Constraint(m.cluster_members, rule=lambda _, c, r: m.x[r] - margin <= frame[c, r][0] + b.offset_x[c])
    b.right = pyo.Constraint(m.cluster_members, rule=lambda _, c, r: m.x[r] + m.w[r] + margin >= frame[c, r][0] + b.offset_x[c])
    b.bottom = pyo.Constraint(m.cluster_members, rule=lambda _, c, r: m.y[r] - margin <= frame[c, r][1] + b.offset_y[c])
    b.top = pyo.Constraint(m.cluster_members, rule=lambda _, c, r: m.y[r] + m.h[r] + margin >= frame[c, r][1] + b.offset_y[c])

    # ----- symmetry breaking among interchangeable rooms -----
    m.symmetry = pyo.Block(doc="interchangeable rooms ordered by x (removes mirror-image search)")
    groups = _interchangeable_groups(spec) if formulation.symmetry_breaking else []
    chain = [(g[i], g[i + 1]) for g in groups for i in range(len(g) - 1)]
    m.symmetry.chain = pyo.Set(dimen=2, ordered=True, initialize=chain)
    m.symmetry.order = pyo.Constraint(m.symmetry.chain, rule=lambda _, a, c: m.x[a] <= m.x[c])
    m.interchangeable_groups = groups

    # ----- objective (5.1)-(5.3), bounded-helper form -----
    m.eq5_2_cover = pyo.Block(doc="(5.2) covered area: a <= w*h, a bounded by the size bounds")
    b = m.eq5_2_cover
    b.area = pyo.Var(m.rooms, bounds=lambda _, r: (lo[r][0] * lo[r][1], min(hi[r][0] * hi[r][1], width * height)),
                     doc="a_i, at most the room's area w*h")
    if long_short:
        b.product = pyo.Constraint(m.rooms, rule=lambda _, r: b.area[r] <= m.long[r] * m.short[r])
    else:
        b.product = pyo.Constraint(m.rooms, rule=lambda _, r: b.area[r] <= m.w[r] * m.h[r])

    m.eq5_3_error = pyo.Block(doc="(5.3) squared size error against the targets, by orientation")
    b = m.eq5_3_error
    # targets as (long, short): o = 0 compares w with the long target (see module docstring)
    target = {r.id: (max(r.target_w, r.target_h), min(r.target_w, r.target_h)) for r in spec.rooms}

    def err_bounds(_, r):
        """A side lies in [0, largest side]; a target in [0, largest target]."""
        return (-target[r][0], max(bounds[r].w[1], bounds[r].h[1]))

    b.err_w = pyo.Var(m.rooms, bounds=err_bounds,
                      doc="e_w = w - (1-o)*w* - o*h* (long side - long target with long_short)")
    b.err_h = pyo.Var(m.rooms, bounds=err_bounds,
                      doc="e_h = h - o*w* - (1-o)*h* (short side - short target with long_short)")
    if long_short:
        # (5.3) with o resolved: the long side is compared with the long target
        b.err_w_def = pyo.Constraint(m.rooms, rule=lambda _, r: b.err_w[r] == m.long[r] - target[r][0])
        b.err_h_def = pyo.Constraint(m.rooms, rule=lambda _, r: b.err_h[r] == m.short[r] - target[r][1])
    else:
        b.err_w_def = pyo.Constraint(m.rooms, rule=lambda _, r: b.err_w[r] == m.w[r] - (1 - m.o[r]) * target[r][0] - m.o[r] * target[r][1])
        b.err_h_def = pyo.Constraint(m.rooms, rule=lambda _, r: b.err_h[r] == m.h[r] - m.o[r] * target[r][0] - (1 - m.o[r]) * target[r][1])

    def sq_bounds(_, r):
        e_lo, e_hi = err_bounds(None, r)
        return (0.0, 2 * max(e_lo**2, e_hi**2))

    b.sq = pyo.Var(m.rooms, bounds=sq_bounds, doc="q_i >= e_w^2 + e_h^2")
    b.sq_def = pyo.Constraint(m.rooms, rule=lambda _, r: b.sq[r] >= b.err_w[r] ** 2 + b.err_h[r] ** 2)

    settings = spec.settings
    m.eq5_1_objective = pyo.Objective(
        expr=settings.lambda_cover * (width * height - sum(rooms[r].rho_cover * m.eq5_2_cover.area[r] for r in m.rooms))
        + settings.lambda_error * sum(rooms[r].rho_error * m.eq5_3_error.sq[r] for r in m.rooms),
        sense=pyo.minimize,
        doc="(5.1) λ_cover·E_cover + λ_error·E_error",
    )
    return m


CONSTRAINT_FAMILIES = (
    "eq5_4_min_size", "eq5_5_max_size", "eq5_6_aspect_ratio", "eq5_7_inside",
    "eq5_8_non_overlap", "eq5_9_adjacency", "eq5_10_position", "eq5_11_connection",
    "eq5_12_on_boundary", "eq5_13_cluster",
)
"""Names of the constraint blocks, one per equation of §5.5.1."""


# ----- reading and writing geometry -----

def rects_from_model(model: pyo.ConcreteModel) -> dict[str, Rect]:
    """The rooms' (x, y, w, h) as currently loaded on the model."""
    return {
        r: (pyo.value(model.x[r]), pyo.value(model.y[r]), pyo.value(model.w[r]), pyo.value(model.h[r]))
        for r in model.rooms
    }


def _size_error(room: Room, w: float, h: float, o: int) -> float:
    tw, th = orientation_targets(room, o)
    return (w - tw) ** 2 + (h - th) ** 2


def _fits(room: Room, w: float, h: float, o: int, tol: float = 1e-6) -> bool:
    """(5.4)-(5.6) hold for this orientation."""
    min_w, max_w, min_h, max_h = orientation_bounds(room, o)
    if not (min_w - tol <= w <= max_w + tol and min_h - tol <= h <= max_h + tol):
        return False
    if room.is_corridor:
        return True
    long, short = (w, h) if o == 0 else (h, w)
    return room.min_ar * short - tol <= long <= room.max_ar * short + tol


def best_orientation(room: Room, w: float, h: float) -> int:
    """o for a placed size: the feasible orientation with the smaller size error (0 if neither fits)."""
    options = [o for o in (0, 1) if _fits(room, w, h, o)]
    if not options:
        return 0
    return min(options, key=lambda o: (_size_error(room, w, h, o), o))


def objective_of_rects(spec: Spec, rects: Mapping[str, Rect],
                       orientations: Mapping[str, int] | None = None) -> float:
    """(5.1) evaluated on plain rectangles (the reported objective, not SCIP's figure)."""
    assert spec.boundary is not None
    s = spec.settings
    cover = spec.boundary.w * spec.boundary.h
    error = 0.0
    for room in spec.rooms:
        _, _, w, h = rects[room.id]
        o = orientations[room.id] if orientations and room.id in orientations else best_orientation(room, w, h)
        cover -= room.rho_cover * w * h
        error += room.rho_error * _size_error(room, w, h, o)
    return s.lambda_cover * cover + s.lambda_error * error


def _relation(a: Rect, b: Rect, wall: float, tol: float = 1e-6) -> list[str]:
    """The sides of b on which a lies with at least `wall` between them."""
    ax, ay, aw, ah = a
    bx, by, bw, bh = b
    sides = []
    if ax + aw + wall <= bx + tol:
        sides.append("left")
    if bx + bw + wall <= ax + tol:
        sides.append("right")
    if ay + ah + wall <= by + tol:
        sides.append("below")
    if by + bh + wall <= ay + tol:
        sides.append("above")
    return sides


def relations_of_rects(spec: Spec, rects: Mapping[str, Rect]) -> dict[tuple[str, str], str]:
    """A side for every room pair (and room-obstacle pair) of a feasible geometry.

    For adjacent pairs it is the side of their shared wall; otherwise the first side that
    holds. Pairs with no valid side (overlapping rectangles) are left out.
    """
    assert spec.boundary is not None
    wall = spec.settings.walldim
    shapes: dict[str, Rect] = dict(rects)
    for ob in spec.boundary.obstacles:
        shapes[ob.id] = (ob.x, ob.y, ob.w, ob.h)
    ids = [r.id for r in spec.rooms]
    pairs = [(a, b) for i, a in enumerate(ids) for b in ids[i + 1:]]
    pairs += [(r, ob.id) for r in ids for ob in spec.boundary.obstacles]
    relations = {}
    for a, b in pairs:
        sides = _relation(shapes[a], shapes[b], wall)
        if sides:
            relations[(a, b)] = sides[0]
    return relations


def warm_start_from_rects(model: pyo.ConcreteModel, spec: Spec, rects: Mapping[str, Rect]) -> list[str]:
    """Set every variable of `model` from a geometry, to hand SCIP as its start.

    Sets x, y, w, h, o, the non-overlap ω of each pair, the adjacency α, the onB β, the
    cluster offsets and the objective helpers. Interchangeable rooms (symmetry breaking)
    swap rectangles so the start respects their x order. Returns the problems found (the
    constraint the geometry violates), empty when the start is consistent.
    """
    problems: list[str] = []
    rects = dict(rects)
    missing = [r for r in model.rooms if r not in rects]
    if missing:
        return [f"no rectangle for rooms {', '.join(missing)}"]
    for group in getattr(model, "interchangeable_groups", []):
        ordered = sorted((rects[r] for r in group), key=lambda t: (t[0], t[1]))
        for room_id, rect in zip(group, ordered):
            rects[room_id] = rect
    rooms = {room.id: room for room in spec.rooms}
    wall = spec.settings.walldim

    def put(var, value: float) -> None:
        if var.fixed:
            if abs(var.value - value) > 1e-6:
                problems.append(f"{var.name} is fixed to {var.value} but the start needs {value}")
            return
        lo, hi = var.bounds
        if lo is not None and value < lo - 1e-6 or hi is not None and value > hi + 1e-6:
            problems.append(f"{var.name} = {value:g} outside its bounds [{lo}, {hi}]")
        var.set_value(value, skip_validation=True)

    orient = {}
    for r in model.rooms:
        x, y, w, h = rects[r]
        put(model.x[r], x)
        put(model.y[r], y)
        put(model.w[r], w)
        put(model.h[r], h)
        o = best_orientation(rooms[r], w, h)
        if not _fits(rooms[r], w, h, o):
            problems.append(f"room {r}: size {w:g} x {h:g} fits neither orientation")
        orient[r] = o
        put(model.o[r], o)
        area = model.eq5_2_cover.area[r]
        put(area, min(w * h, area.ub))
        if hasattr(model, "long"):
            put(model.long[r], w if o == 0 else h)
            put(model.short[r], h if o == 0 else w)
        tw, th = orientation_targets(rooms[r], o)
        err_w, err_h = w - tw, h - th
        if hasattr(model, "long") and o == 1:  # errors of (long, short) = (h, w)
            err_w, err_h = err_h, err_w
        put(model.eq5_3_error.err_w[r], err_w)
        put(model.eq5_3_error.err_h[r], err_h)
        put(model.eq5_3_error.sq[r], err_w**2 + err_h**2)

    shapes: dict[str, Rect] = dict(rects)
    for ob in spec.boundary.obstacles if spec.boundary else ():
        shapes[ob.id] = (ob.x, ob.y, ob.w, ob.h)
    stacked = {}
    for adj in spec.adjacencies:
        a, b = shapes[adj.a], shapes[adj.b]
        y_sep = max(b[1] - (a[1] + a[3]), a[1] - (b[1] + b[3]))
        x_sep = max(b[0] - (a[0] + a[2]), a[0] - (b[0] + b[2]))
        stacked[(adj.a, adj.b)] = 1 if y_sep > x_sep else 0
        put(model.eq5_9_adjacency.stacked[adj.a, adj.b], stacked[(adj.a, adj.b)])

    adjacent_axis = {}
    for (a, b), s in stacked.items():
        adjacent_axis[(a, b)] = adjacent_axis[(b, a)] = ("below", "above") if s else ("left", "right")
    omega = model.eq5_8_non_overlap.side
    for a, b in model.eq5_8_non_overlap.pairs:
        sides = _relation(shapes[a], shapes[b], wall)
        preferred = [s for s in sides if s in adjacent_axis.get((a, b), SIDES)] or sides
        fixed_one = [s for s in SIDES if omega[a, b, s].fixed and omega[a, b, s].value == 1]
        choice = fixed_one[0] if fixed_one else (preferred[0] if preferred else None)
        if choice is None:
            problems.append(f"{a} and {b} are closer than walldim {wall:g} on every side")
            choice = "left"
        elif choice not in sides:
            problems.append(f"{a} is not {choice} of {b} as a fixed relation requires")
        for s in SIDES:
            put(omega[a, b, s], 1 if s == choice else 0)

    if spec.boundary is not None:
        width, height = spec.boundary.w, spec.boundary.h
        for r in model.onb_rooms:
            x, y, w, h = rects[r]
            touching = {
                "left": x <= 1e-6, "right": x + w >= width - 1e-6,
                "bottom": y <= 1e-6, "top": y + h >= height - 1e-6,
            }
            if not any(touching.values()):
                problems.append(f"room {r} touches no side of the boundary")
            first = next((s for s in BOUNDARY_SIDES if touching[s]), "left")
            for s in BOUNDARY_SIDES:
                put(model.eq5_12_on_boundary.side[r, s], 1 if s == first else 0)

    margin = spec.settings.cluster_margin
    for cluster in spec.clusters:
        for axis, var in ((0, model.eq5_13_cluster.offset_x), (1, model.eq5_13_cluster.offset_y)):
            lo, hi = -math.inf, math.inf
            for mem in cluster.members:
                pos = rects[mem.room][axis]
                size = rects[mem.room][axis + 2]
                point = mem.x if axis == 0 else mem.y
                lo = max(lo, pos - margin - point)
                hi = min(hi, pos + size + margin - point)
            if lo > hi + 1e-9:
                problems.append(f"cluster {cluster.id}: members are not within the margin of one frame")
            put(var[cluster.id], (lo + hi) / 2 if lo <= hi else lo)
    return problems
