"""The MIQP of the thesis, §5.5.1, one unit per equation: each adds one named Block.

Every unit takes the model and the spec's `ModelData` and adds the components of one
constraint family, named after its equation (`m.eq5_4_min_size` ... `m.eq5_13_cluster`,
the objective `m.eq5_1_objective`), so a reader can hold each function against its
equation. `build_model` runs `UNITS` in order; the order fixes the order of the variables
and constraints SCIP sees, and so the layout a seed gives.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import pyomo.environ as pyo

from layoutdsl.model.formulation import (
    BOUNDARY_SIDES,
    OPPOSITE_SIDE,
    SIDES,
    Bounds,
    ModelData,
    interchangeable_groups,
    target_area,
)

Unit = Callable[[pyo.ConcreteModel, ModelData], None]


def sets(m: pyo.ConcreteModel, d: ModelData) -> None:
    """The index sets, named after DSL concepts."""
    spec = d.spec
    m.rooms = pyo.Set(initialize=[r.id for r in spec.rooms], ordered=True, doc="room ids, spec order")
    m.corridors = pyo.Set(within=m.rooms, initialize=[r.id for r in spec.rooms if r.is_corridor],
                          doc="rooms of type C (no aspect-ratio constraint)")
    m.obstacles = pyo.Set(initialize=list(d.obstacles), ordered=True, doc="fixed obstacle rectangles")
    m.room_pairs = pyo.Set(
        dimen=2, ordered=True,
        initialize=[(a.id, b.id) for i, a in enumerate(spec.rooms) for b in spec.rooms[i + 1:]],
        doc="unordered room pairs (r1, r2), r1 listed before r2",
    )
    m.room_obstacle_pairs = pyo.Set(
        dimen=2, ordered=True, initialize=[(r.id, o) for r in spec.rooms for o in d.obstacles],
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
    )  # fmt: skip


def room_variables(m: pyo.ConcreteModel, d: ModelData) -> None:
    """x, y, w, h and the orientation o of each room, bounded by the spec alone."""
    bounds = d.bounds
    m.x = pyo.Var(m.rooms, bounds=lambda _, r: bounds[r].x, doc="left edge (m)")
    m.y = pyo.Var(m.rooms, bounds=lambda _, r: bounds[r].y, doc="bottom edge (m)")
    m.w = pyo.Var(m.rooms, bounds=lambda _, r: bounds[r].w, doc="width along x (m)")
    m.h = pyo.Var(m.rooms, bounds=lambda _, r: bounds[r].h, doc="height along y (m)")
    m.o = pyo.Var(m.rooms, domain=pyo.Binary, doc="orientation: 0 = w is the long side, 1 = h is")


def long_and_short_sides(m: pyo.ConcreteModel, d: ModelData) -> None:
    """long, short = (w, h) when o = 0 and (h, w) when o = 1 (Formulation.long_short)."""
    if not d.formulation.long_short:
        return
    m.long = pyo.Var(m.rooms, bounds=lambda _, r: d.side_bounds(r), doc="the long side: w when o = 0, h when o = 1")
    m.short = pyo.Var(m.rooms, bounds=lambda _, r: d.side_bounds(r), doc="the short side: h when o = 0, w when o = 1")
    m.orientation = pyo.Block(doc="o swaps which of w, h is the long side")

    def swap_rule(_, r, which):
        low, high = d.side_bounds(r)
        spread = d.big_m(high - low)
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

    m.orientation.swap = pyo.Constraint(m.rooms, ["long_w_lo", "long_w_hi", "short_h_lo", "short_h_hi",
                                                  "long_h_lo", "long_h_hi", "short_w_lo", "short_w_hi"], rule=swap_rule)


def eq5_4_min_size(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.4) minimum size: the long side gets the larger minimum."""
    lo = d.lo
    m.eq5_4_min_size = pyo.Block(doc="(5.4) h >= minD + (maxD - minD)*o, w >= minD + (maxD - minD)*(1 - o)")
    b = m.eq5_4_min_size
    b.height = pyo.Constraint(m.rooms, rule=lambda _, r: m.h[r] >= lo[r][0] + (lo[r][1] - lo[r][0]) * m.o[r])
    b.width = pyo.Constraint(m.rooms, rule=lambda _, r: m.w[r] >= lo[r][0] + (lo[r][1] - lo[r][0]) * (1 - m.o[r]))
    if d.formulation.long_short:  # the same minimums on the orientation-free sides
        b.long = pyo.Constraint(m.rooms, rule=lambda _, r: m.long[r] >= lo[r][1])
        b.short = pyo.Constraint(m.rooms, rule=lambda _, r: m.short[r] >= lo[r][0])


def eq5_5_max_size(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.5) maximum size: the short side gets the smaller maximum."""
    hi = d.hi
    m.eq5_5_max_size = pyo.Block(doc="(5.5) w <= maxD + (minD - maxD)*o, h <= maxD + (minD - maxD)*(1 - o)")
    b = m.eq5_5_max_size
    b.width = pyo.Constraint(m.rooms, rule=lambda _, r: m.w[r] <= hi[r][1] + (hi[r][0] - hi[r][1]) * m.o[r])
    b.height = pyo.Constraint(m.rooms, rule=lambda _, r: m.h[r] <= hi[r][1] + (hi[r][0] - hi[r][1]) * (1 - m.o[r]))
    if d.formulation.long_short:
        b.long = pyo.Constraint(m.rooms, rule=lambda _, r: m.long[r] <= hi[r][1])
        b.short = pyo.Constraint(m.rooms, rule=lambda _, r: m.short[r] <= hi[r][0])


def eq5_6_aspect_ratio(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.6) aspect ratio, not for corridors: o = 0 bounds w/h, o = 1 bounds h/w."""
    rooms, big_m = d.rooms, d.big_m
    m.eq5_6_aspect_ratio = pyo.Block(doc="(5.6) long/short side ratio in [minar, maxar], rooms minus corridors")
    b = m.eq5_6_aspect_ratio
    b.rooms = pyo.Set(initialize=[r.id for r in d.spec.rooms if not r.is_corridor], ordered=True)

    def _ar(kind: str):
        def rule(_, r):
            room, bd = rooms[r], d.bounds[r]
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
    if d.formulation.long_short:  # the same ratio on the orientation-free sides: linear, no big-M
        b.long_min = pyo.Constraint(b.rooms, rule=lambda _, r: rooms[r].min_ar * m.short[r] <= m.long[r])
        b.long_max = pyo.Constraint(b.rooms, rule=lambda _, r: m.long[r] <= rooms[r].max_ar * m.short[r])


def eq5_7_inside(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.7) every room inside the boundary."""
    m.eq5_7_inside = pyo.Block(doc="(5.7) every room inside the boundary")
    b = m.eq5_7_inside
    b.right = pyo.Constraint(m.rooms, rule=lambda _, r: m.x[r] + m.w[r] <= d.width)
    b.top = pyo.Constraint(m.rooms, rule=lambda _, r: m.y[r] + m.h[r] <= d.height)


# ----- (5.8) helpers: a pair's rectangles and how far each side's inequality can fail -----


def _rect_terms(m: pyo.ConcreteModel, d: ModelData, name: str):
    """(x, y, w, h, bounds) of a room (variables) or an obstacle (constants)."""
    if name in d.rooms:
        return m.x[name], m.y[name], m.w[name], m.h[name], d.bounds[name]
    ob = d.obstacles[name]
    fixed = Bounds((ob.w, ob.w), (ob.h, ob.h), (ob.x, ob.x), (ob.y, ob.y))
    return ob.x, ob.y, ob.w, ob.h, fixed


def _side_slack(ba: Bounds, bb: Bounds, side: str, wall: float) -> float:
    """How much the side's inequality can be violated at worst: its big-M."""
    if side == "left":  # a.x + a.w + wall <= b.x
        return ba.right[1] + wall - bb.x[0]
    if side == "right":  # b.x + b.w + wall <= a.x
        return bb.right[1] + wall - ba.x[0]
    if side == "below":
        return ba.top[1] + wall - bb.y[0]
    return bb.top[1] + wall - ba.y[0]


def _side_never(ba: Bounds, bb: Bounds, side: str, wall: float) -> bool:
    """The side's inequality holds for no value the bounds allow."""
    if side == "left":
        return ba.right[0] + wall > bb.x[1] + 1e-9
    if side == "right":
        return bb.right[0] + wall > ba.x[1] + 1e-9
    if side == "below":
        return ba.top[0] + wall > bb.y[1] + 1e-9
    return bb.top[0] + wall > ba.y[1] + 1e-9


def eq5_8_non_overlap(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.8) non-overlap with wall thickness: room pairs and room-obstacle pairs."""
    wall = d.wall
    m.eq5_8_non_overlap = pyo.Block(doc="(5.8) rooms and obstacles keep walldim apart; four ω per pair")
    b = m.eq5_8_non_overlap

    def bounds_of(a: str, c: str) -> tuple[Bounds, Bounds]:
        return _rect_terms(m, d, a)[4], _rect_terms(m, d, c)[4]

    all_pairs = list(m.room_pairs) + list(m.room_obstacle_pairs)
    separated = set()
    if d.formulation.prune_pairs:  # a side that holds for every value the bounds allow
        separated = {p for p in all_pairs if any(_side_slack(*bounds_of(*p), s, wall) <= 0 for s in SIDES)}
    b.pairs = pyo.Set(dimen=2, ordered=True, initialize=[p for p in all_pairs if p not in separated],
                      doc="pairs that need the disjunction (bounds do not already separate them)")
    b.side = pyo.Var(b.pairs, m.sides, domain=pyo.Binary,
                     doc="ω: 1 when the first of the pair lies on this side of the second")

    def sep_rule(_, a, bname, side):
        xa, ya, wa, ha, ba = _rect_terms(m, d, a)
        xb, yb, wb, hb, bb = _rect_terms(m, d, bname)
        slack = d.big_m(_side_slack(ba, bb, side, wall)) * (1 - b.side[a, bname, side])
        if side == "left":
            return xa + wa + wall <= xb + slack
        if side == "right":
            return xb + wb + wall <= xa + slack
        if side == "below":
            return ya + ha + wall <= yb + slack
        return yb + hb + wall <= ya + slack

    if d.formulation.prune_pairs:
        for a, c in b.pairs:
            for s in SIDES:
                if _side_never(*bounds_of(a, c), s, wall):
                    b.side[a, c, s].fix(0)
    b.separation_rule = sep_rule
    b.one_side_rule = lambda _, a, c: sum(b.side[a, c, s] for s in SIDES) >= 1
    if d.defer_separations:
        return  # settle_separations builds what the start's relations need
    b.separate = pyo.Constraint(b.pairs, m.sides, rule=sep_rule)
    b.one_side = pyo.Constraint(b.pairs, rule=b.one_side_rule)


def settle_separations(m: pyo.ConcreteModel) -> None:
    """The (5.8) constraints of a model built with them deferred, for the ω now on it.

    Each pair's ω are fixed at their values (a warm start sets one side to 1) and only that
    side's separation is built: the model is then what polish() solves once it has fixed
    every binary and left out the separations those make idle, without building the three
    of every four that would be left out (measured on school_wilbraham's variant starts: the
    build takes 0.09-0.16 s instead of 0.31-0.41 s). A pair without values on its ω keeps
    its whole disjunction; the pairs of an L-room's join keep none, as join_l_arms leaves
    them. The relations stay fixed: a model settled so is polished, never searched.
    """
    b = m.eq5_8_non_overlap
    joined = set(m.join_l_arms.pairs) if hasattr(m, "join_l_arms") else set()
    sides, open_pairs = [], []
    for a, c in b.pairs:
        if (a, c) in joined or (c, a) in joined:
            continue
        values = [b.side[a, c, s].value for s in SIDES]
        if any(value is None for value in values) or sum(round(value) for value in values) < 1:
            sides += [(a, c, s) for s in SIDES]
            open_pairs.append((a, c))
            continue
        for s, value in zip(SIDES, map(round, values)):
            b.side[a, c, s].fix(value)
            if value == 1:
                sides.append((a, c, s))
    b.settled_sides = pyo.Set(dimen=3, ordered=True, initialize=sides)
    b.separate = pyo.Constraint(b.settled_sides, rule=b.separation_rule)
    b.open_pairs = pyo.Set(dimen=2, ordered=True, initialize=open_pairs)
    b.one_side = pyo.Constraint(b.open_pairs, rule=b.one_side_rule)


def fix_relations(m: pyo.ConcreteModel, fixed_relations: Mapping[tuple[str, str], str]) -> None:
    """Fix the (5.8) ω of pairs whose relative position a construction decided."""
    b = m.eq5_8_non_overlap
    for (first, second), side in fixed_relations.items():
        if side not in OPPOSITE_SIDE:
            raise ValueError(f"unknown side {side!r} for pair ({first}, {second})")
        key, rel = (first, second), side
        if key not in b.pairs:
            key, rel = (second, first), OPPOSITE_SIDE[side]
        if key not in b.pairs:
            continue  # the bounds already separate this pair
        for s in SIDES:
            b.side[key[0], key[1], s].fix(1 if s == rel else 0)


JOIN_SIDES = SIDES
"""A join's side: where the room's box lies relative to its arm, as in (5.8)'s ω."""


def join_l_arms(m: pyo.ConcreteModel, joins: Mapping[tuple[str, str], str],
                crossing: Mapping[tuple[str, str], bool] | None = None) -> None:
    """L-shaped rooms (issue 14): each (room box, arm box) pair of `joins` is one room.

    The model is built on the spec's boxes (an L-room's arm as a room of its own); this
    replaces the pair's (5.8) disjunction, which would keep the two a wall apart, by the
    join its option names (`side:end`, compile.lshape.JOIN_OPTIONS): the box flush on
    `side` of its arm, no wall between, their edges flush at the low or high `end` of the
    side they share, so the union is an L. `crossing[pair]` says whether the arm runs across
    its box (orientations o opposite) or along it (o equal): the L turns as a whole. The pair
    leaves the symmetry chains too (an arm swapped with a look-alike room would break its L).
    """
    b = m.eq5_8_non_overlap
    # sorted: callers build `joins` from sets of pairs, whose order follows Python's string
    # hashing (PYTHONHASHSEED, new in every process), and the order of the flush constraints
    # is the order SCIP sees them in. Unsorted, one spec and seed gave different layouts in
    # different processes (measured on school_Neulengbach1's polish: 1229 and 1180 LP
    # iterations, every room moved, at PYTHONHASHSEED 1 and 2; what looked like machine load)
    joins = dict(sorted(joins.items()))
    m.join_l_arms = pyo.Block(doc="L-rooms: each room's box joined flush to its arm at a corner")
    m.join_l_arms.pairs = pyo.Set(dimen=2, ordered=True, initialize=list(joins))
    flush = []
    for (box, arm), option in joins.items():
        side, end = option.split(":")
        if side not in JOIN_SIDES or end not in ("lo", "hi"):
            raise ValueError(f"unknown join {option!r} for ({box}, {arm})")
        for pair in ((box, arm), (arm, box)):
            if pair in b.pairs and hasattr(b, "separate"):  # deferred: settle_separations skips it
                for s in SIDES:
                    b.separate[pair[0], pair[1], s].deactivate()
                b.one_side[pair].deactivate()
        if side in ("left", "right"):
            first, second = (box, arm) if side == "left" else (arm, box)
            flush.append((m.x[first] + m.w[first], m.x[second]))
            flush.append((m.y[box], m.y[arm]) if end == "lo" else (m.y[box] + m.h[box], m.y[arm] + m.h[arm]))
        else:
            first, second = (box, arm) if side == "below" else (arm, box)
            flush.append((m.y[first] + m.h[first], m.y[second]))
            flush.append((m.x[box], m.x[arm]) if end == "lo" else (m.x[box] + m.w[box], m.x[arm] + m.w[arm]))
    m.join_l_arms.flush = pyo.Constraint(range(len(flush)), rule=lambda _, i: flush[i][0] == flush[i][1])
    turns = [(box, arm, crosses) for (box, arm), crosses in sorted((crossing or {}).items()) if (box, arm) in joins]
    m.join_l_arms.turns = turns  # (box, arm, crosses): a warm start gives the pair orientations that obey them
    m.join_l_arms.turn = pyo.Constraint(
        range(len(turns)),
        rule=lambda _, i: m.o[turns[i][1]] == (1 - m.o[turns[i][0]] if turns[i][2] else m.o[turns[i][0]]),
    )
    joined = {room for pair in joins for room in pair}
    for a, c in list(m.symmetry.chain):
        if a in joined or c in joined:
            m.symmetry.order[a, c].deactivate()
    m.interchangeable_groups = [g for g in m.interchangeable_groups if not joined & set(g)]


def eq5_9_adjacency(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.9) adjacency, corrected: a shared wall of door / door_utilization, walldim apart."""
    bounds, wall, big_m = d.bounds, d.wall, d.big_m
    m.eq5_9_adjacency = pyo.Block(doc="(5.9) adjacent rooms share >= door/door_utilization of wall, walldim apart")
    b = m.eq5_9_adjacency
    utilization = d.spec.settings.door_utilization
    min_shared = {(a.a, a.b): a.door / utilization for a in d.spec.adjacencies}
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
    if d.formulation.adjacency_links:
        _link_adjacency_to_non_overlap(m, min_shared)


def _link_adjacency_to_non_overlap(m: pyo.ConcreteModel, min_shared: Mapping[tuple[str, str], float]) -> None:
    """Valid cuts: stacked rooms overlap in x, so neither lies left or right of the other, and
    exactly one lies above the other; the same holds with the axes swapped."""
    b = m.eq5_9_adjacency
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


def eq5_10_position(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.10) a room covers its fixed point."""
    m.eq5_10_position = pyo.Block(doc="(5.10) a room covers its fixed point")
    b = m.eq5_10_position
    points = {p.room: (p.x, p.y) for p in d.spec.positions}
    b.left = pyo.Constraint(m.positions, rule=lambda _, r: m.x[r] <= points[r][0])
    b.right = pyo.Constraint(m.positions, rule=lambda _, r: m.x[r] + m.w[r] >= points[r][0])
    b.bottom = pyo.Constraint(m.positions, rule=lambda _, r: m.y[r] <= points[r][1])
    b.top = pyo.Constraint(m.positions, rule=lambda _, r: m.y[r] + m.h[r] >= points[r][1])


def eq5_11_connection(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.11) a room covers both points of each of its connections."""
    m.eq5_11_connection = pyo.Block(doc="(5.11) a room covers both points of each of its connections")
    b = m.eq5_11_connection

    def conn_rule(kind: str):
        def rule(_, k):
            c = d.spec.connections[k]
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


def eq5_12_on_boundary(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.12) onB rooms touch at least one side of the boundary."""
    width, height, big_m = d.width, d.height, d.big_m
    m.eq5_12_on_boundary = pyo.Block(doc="(5.12) onB rooms touch at least one side of the boundary")
    b = m.eq5_12_on_boundary
    b.side = pyo.Var(m.onb_rooms, m.boundary_sides, domain=pyo.Binary,
                     doc="β: 1 when the room touches this side of the boundary")

    def onb_rule(_, r, side):
        bd = d.bounds[r]
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


def eq5_13_cluster(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.13) cluster members keep their relative points, within the margin."""
    m.eq5_13_cluster = pyo.Block(doc="(5.13) cluster members keep their relative points, within the margin")
    b = m.eq5_13_cluster
    margin = d.spec.settings.cluster_margin
    frame = {(c.id, mem.room): (mem.x, mem.y) for c in d.spec.clusters for mem in c.members}

    def offset_bounds(axis: int, limit: float):
        def rule(_, cid):
            coords = [xy[axis] for (c, _r), xy in frame.items() if c == cid]
            return (-max(coords) - margin, limit - min(coords) + margin)
        return rule

    b.offset_x = pyo.Var(m.clusters, bounds=offset_bounds(0, d.width), doc="x_cluster: the cluster frame's x offset")
    b.offset_y = pyo.Var(m.clusters, bounds=offset_bounds(1, d.height), doc="y_cluster: the cluster frame's y offset")
    b.left = pyo.Constraint(m.cluster_members, rule=lambda _, c, r: m.x[r] - margin <= frame[c, r][0] + b.offset_x[c])
    b.right = pyo.Constraint(m.cluster_members, rule=lambda _, c, r: m.x[r] + m.w[r] + margin >= frame[c, r][0] + b.offset_x[c])
    b.bottom = pyo.Constraint(m.cluster_members, rule=lambda _, c, r: m.y[r] - margin <= frame[c, r][1] + b.offset_y[c])
    b.top = pyo.Constraint(m.cluster_members, rule=lambda _, c, r: m.y[r] + m.h[r] + margin >= frame[c, r][1] + b.offset_y[c])


def symmetry_breaking(m: pyo.ConcreteModel, d: ModelData) -> None:
    """Interchangeable rooms ordered by x (a valid cut: removes mirror-image search)."""
    m.symmetry = pyo.Block(doc="interchangeable rooms ordered by x (removes mirror-image search)")
    groups = interchangeable_groups(d.spec) if d.formulation.symmetry_breaking else []
    chain = [(g[i], g[i + 1]) for g in groups for i in range(len(g) - 1)]
    m.symmetry.chain = pyo.Set(dimen=2, ordered=True, initialize=chain)
    m.symmetry.order = pyo.Constraint(m.symmetry.chain, rule=lambda _, a, c: m.x[a] <= m.x[c])
    m.interchangeable_groups = groups


def eq5_2_cover(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.2) covered area, bounded-helper form: a <= w*h, a bounded by the size bounds
    (and by the target area with Formulation.cover_up_to_target)."""
    lo, hi = d.lo, d.hi
    m.eq5_2_cover = pyo.Block(doc="(5.2) covered area: a <= w*h, a bounded by the size bounds")
    b = m.eq5_2_cover

    def area_bounds(_, r):
        most = min(hi[r][0] * hi[r][1], d.width * d.height)
        if d.formulation.cover_up_to_target:
            # the target lies within the size bounds, so the lower bound stays below it
            most = min(most, target_area(d.rooms[r]))
        return (lo[r][0] * lo[r][1], most)

    b.area = pyo.Var(m.rooms, bounds=area_bounds, doc="a_i, at most the room's area w*h")
    if d.formulation.long_short:
        b.product = pyo.Constraint(m.rooms, rule=lambda _, r: b.area[r] <= m.long[r] * m.short[r])
    else:
        b.product = pyo.Constraint(m.rooms, rule=lambda _, r: b.area[r] <= m.w[r] * m.h[r])


def eq5_3_error(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.3) squared size error against the targets, by orientation: q >= e_w^2 + e_h^2."""
    m.eq5_3_error = pyo.Block(doc="(5.3) squared size error against the targets, by orientation")
    b = m.eq5_3_error
    # targets as (long, short): o = 0 compares w with the long target (see model/__init__)
    target = {r.id: (max(r.target_w, r.target_h), min(r.target_w, r.target_h)) for r in d.spec.rooms}

    def err_bounds(_, r):
        """A side lies in [0, largest side]; a target in [0, largest target]."""
        return (-target[r][0], max(d.bounds[r].w[1], d.bounds[r].h[1]))

    b.err_w = pyo.Var(m.rooms, bounds=err_bounds,
                      doc="e_w = w - (1-o)*w* - o*h* (long side - long target with long_short)")
    b.err_h = pyo.Var(m.rooms, bounds=err_bounds,
                      doc="e_h = h - o*w* - (1-o)*h* (short side - short target with long_short)")
    if d.formulation.long_short:
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


def eq5_1_objective(m: pyo.ConcreteModel, d: ModelData) -> None:
    """(5.1) minimise λ_cover·E_cover + λ_error·E_error over the helpers of (5.2) and (5.3)."""
    settings, rooms = d.spec.settings, d.rooms
    m.eq5_1_objective = pyo.Objective(
        expr=settings.lambda_cover * (d.width * d.height - sum(rooms[r].rho_cover * m.eq5_2_cover.area[r] for r in m.rooms))
        + settings.lambda_error * sum(rooms[r].rho_error * m.eq5_3_error.sq[r] for r in m.rooms),
        sense=pyo.minimize,
        doc="(5.1) λ_cover·E_cover + λ_error·E_error",
    )


UNITS: tuple[Unit, ...] = (
    sets,
    room_variables,
    long_and_short_sides,
    eq5_4_min_size,
    eq5_5_max_size,
    eq5_6_aspect_ratio,
    eq5_7_inside,
    eq5_8_non_overlap,
    eq5_9_adjacency,
    eq5_10_position,
    eq5_11_connection,
    eq5_12_on_boundary,
    eq5_13_cluster,
    symmetry_breaking,
    eq5_2_cover,
    eq5_3_error,
    eq5_1_objective,
)
"""The model's units in build order."""
