"""First feasible layout, built fast and without relying on SCIP's luck (issue 6).

The thesis' model (§5.5.1) is hard for SCIP because of its four non-overlap binaries
per room pair: from ~25 rooms up SCIP finds no feasible layout at all, while from a feasible
start it polishes well. So we construct the start ourselves:

1. A *seed geometry*: one rectangle per room, allowed to overlap. For an imported spec it
   is the original plan (the `hints`); otherwise a placement grown from the room graph
   (`construct_geometry`), randomised for variants.
2. From the geometry, each pair of rooms (and room and obstacle) gets its *relation*: the
   direction along the axis that separates them most, in the geometry's centre order, so
   the "left of" and "below" relations are acyclic. Each room's orientation follows its
   seed rectangle. With every relation fixed the model is an LP.
3. Repair, round by round: the LP is solved *elastically* (each pair's constraints may be
   stretched at a cost, everything else - sizes, aspect ratios, boundary, onB, positions,
   connections, clusters - stays hard). The pairs it had to stretch, and the pairs near
   their rooms, get more freedom for the next round: one binary (either axis), then all
   four directions, and after a stall the rooms' graph neighbours join in. Each round is a
   small MIP warm-started from the previous solution, stopped at zero stretch. From the
   hints (close to a layout already) the rounds are local: each room moves a few metres at
   most, and pairs of rooms too far apart to meet are left out of the model until a
   solution brings them together (`_solve_model`).
4. With zero stretch the relations are final: one more LP brings the sizes to their
   targets, and the rectangles are checked against every hard constraint (our own check,
   then `layoutdsl.layout.verify`) before they are returned.

Measured on the 24 real plans (hints from the importer): all 24 construct, median 0.1 s,
at most ~15 s (school_wilbraham); see bench/bench.py.
"""

from __future__ import annotations

import importlib.util
import math
import os
import random
import sys
import threading
import time
from dataclasses import dataclass, replace
from collections.abc import Callable, Mapping

from layoutdsl.layout.geometry import SIDES, Rect, layout_from_rects, separations
from layoutdsl.compile import lshape
from layoutdsl.compile.generate import (TOP_CHOICES, RoomSizes, core_rooms, cycle_blocks, drawn_sides,
                                        generate_geometry, room_graph)
from layoutdsl.compile.ladders import find_ladder, ladder_template
from layoutdsl.syntax.ast import Room, Spec


_LOADED = time.monotonic()


def _debug(message: str) -> None:
    if os.environ.get("LAYOUTDSL_DEBUG_CONSTRUCT"):
        print(f"{time.monotonic() - _LOADED:7.2f}s {message}", file=sys.stderr, flush=True)


SAFETY = 1e-6
"""Metres added to every strict inequality so SCIP's feasibility tolerance cannot make the
verifier (tolerance ~1e-6) see a violation."""



# ---------------------------------------------------------------------------------------
# Relations between pairs, read off a seed geometry
# ---------------------------------------------------------------------------------------

DIRECTIONS = SIDES
"""Where the first thing of a pair lies relative to the second (layout.geometry.SIDES)."""

Pair = tuple[str, str]
"""(room, room) or (room, obstacle), rooms in spec order."""


def _centre(rect: Rect) -> tuple[float, float]:
    x, y, w, h = rect
    return (x + w / 2, y + h / 2)


def _ordered_directions(a: Rect, b: Rect, index_a: int, index_b: int) -> tuple[str, str]:
    """The x-side and the y-side of a relative to b that follow the centre order.

    Ties are broken by the pair's indices, so the induced orders are strict and total:
    whatever axis each pair uses, no chain of "left of" or "below" constraints can close
    into a cycle, which keeps the relation system satisfiable in a large enough boundary.
    """
    (acx, acy), (bcx, bcy) = _centre(a), _centre(b)
    right = (bcx, index_b) > (acx, index_a)
    up = (bcy, index_b) > (acy, index_a)
    return ("left" if right else "right", "below" if up else "above")


@dataclass(frozen=True, slots=True)
class _Problem:
    """What the relation models of one spec share, computed once."""

    spec: Spec
    width: float
    height: float
    walldim: float
    walls: dict[frozenset[str], float]
    """Adjacent room pair -> shared wall length it needs."""
    obstacles: dict[str, Rect]
    pairs: tuple[Pair, ...]
    order: dict[str, int]
    big_m: float
    joins: frozenset[Pair] = frozenset()
    """The pairs of boxes that form one L-shaped room (lshape.py): joined, not apart."""
    checked: Spec | None = None
    """The spec a result is checked against, when `spec` is its boxes (lshape.boxes_spec)."""
    crossing: dict[Pair, bool] | None = None
    """Joined pairs whose arm runs across (True) or along (False) the box (lshape.crossings):
    the two turn together."""
    exact_walls: frozenset[frozenset[str]] = frozenset()
    """Pairs kept exactly a wall apart, without SAFETY (lshape.beside_pairs)."""

    @staticmethod
    def of(spec: Spec, joins: frozenset[Pair] = frozenset(), checked: Spec | None = None,
           crossing: dict[Pair, bool] | None = None) -> _Problem:
        """Precompute the pairs and constants of the spec."""
        boundary = spec.boundary
        assert boundary is not None
        settings = spec.settings
        walls = {
            frozenset((adj.a, adj.b)): adj.door / settings.door_utilization + SAFETY
            for adj in spec.adjacencies
        }
        obstacles = {ob.id: (ob.x, ob.y, ob.w, ob.h) for ob in boundary.obstacles}
        ids = [room.id for room in spec.rooms]
        order = {room_id: index for index, room_id in enumerate(ids)}
        for index, ob_id in enumerate(obstacles):
            order[ob_id] = len(ids) + index
        pairs = [(a, b) for i, a in enumerate(ids) for b in ids[i + 1:]]
        pairs += [(a, ob_id) for a in ids for ob_id in obstacles]
        longest_wall = max(walls.values(), default=0.0)
        return _Problem(
            spec=spec,
            width=boundary.w,
            height=boundary.h,
            walldim=settings.walldim,
            walls=walls,
            obstacles=obstacles,
            pairs=tuple(pairs),
            order=order,
            big_m=max(boundary.w, boundary.h) + settings.walldim + longest_wall + 1.0,
            joins=joins,
            checked=checked,
            crossing=crossing,
            exact_walls=lshape.beside_pairs(spec, joins) if joins else frozenset(),
        )

    def rect(self, geometry: dict[str, Rect], thing: str) -> Rect:
        return self.obstacles[thing] if thing in self.obstacles else geometry[thing]

    def axis_choices(self, geometry: dict[str, Rect], pair: Pair) -> tuple[str, str]:
        """The pair's two centre-ordered directions, the geometry's clearer one first."""
        a, b = pair
        ra, rb = self.rect(geometry, a), self.rect(geometry, b)
        sep_x, sep_y = separations(ra, rb)
        dir_x, dir_y = _ordered_directions(ra, rb, self.order[a], self.order[b])
        return (dir_x, dir_y) if sep_x >= sep_y else (dir_y, dir_x)

    def gap(self, pair: Pair) -> float:
        """Least distance between a pair that shares no door: a wall, plus SAFETY unless
        the pair is kept exactly a wall apart (exact_walls)."""
        return self.walldim + (0.0 if frozenset(pair) in self.exact_walls else SAFETY)

    def distance(self, geometry: dict[str, Rect], pair: Pair) -> float:
        a, b = pair
        return max(separations(self.rect(geometry, a), self.rect(geometry, b)))


# ---------------------------------------------------------------------------------------
# The relation model, solved with SCIP
# ---------------------------------------------------------------------------------------


class _Box:
    """A rectangle of the model: SCIP variables for a room, constants for an obstacle."""

    __slots__ = ("x", "y", "w", "h")

    def __init__(self, x, y, w, h):
        self.x, self.y, self.w, self.h = x, y, w, h


def _excess(a: _Box, b: _Box, direction: str, gap: float):
    """How far a is from lying on the `direction` side of b with `gap` between them (at most
    0: it does); a and b hold SCIP variables (an expression) or numbers (a number)."""
    if direction == "left":
        return a.x + a.w + gap - b.x
    if direction == "right":
        return b.x + b.w + gap - a.x
    if direction == "below":
        return a.y + a.h + gap - b.y
    return b.y + b.h + gap - a.y


def _add_direction(model, a: _Box, b: _Box, direction: str, gap: float, slack) -> None:
    """a lies on the `direction` side of b with at least `gap` between them, up to `slack`."""
    model.addCons(_excess(a, b, direction, gap) <= slack)


def _add_adjacent(model, a: _Box, b: _Box, direction: str, walldim: float, wall: float,
                  slack) -> None:
    """a touches b on its `direction` side: exactly one wall between, `wall` m shared."""
    if direction in ("left", "right"):
        first, second = (a, b) if direction == "left" else (b, a)
        model.addCons(first.x + first.w + walldim - second.x <= slack)
        model.addCons(second.x - first.x - first.w - walldim <= slack)
        model.addCons(a.y + wall - b.y - b.h <= slack)
        model.addCons(b.y + wall - a.y - a.h <= slack)
    else:
        first, second = (a, b) if direction == "below" else (b, a)
        model.addCons(first.y + first.h + walldim - second.y <= slack)
        model.addCons(second.y - first.y - first.h - walldim <= slack)
        model.addCons(a.x + wall - b.x - b.w <= slack)
        model.addCons(b.x + wall - a.x - a.w <= slack)


def _add_join(model, a: _Box, b: _Box, option: str, slack) -> None:
    """a and b form one L-shaped room (lshape.JOIN_OPTIONS): a flush on `side` of b, no
    wall between them, their edges flush at the `end` of the side they share."""
    side, end = option.split(":")
    if side in ("left", "right"):
        first, second = (a, b) if side == "left" else (b, a)
        flush = [first.x + first.w - second.x]
        flush.append((a.y - b.y) if end == "lo" else (a.y + a.h - b.y - b.h))
    else:
        first, second = (a, b) if side == "below" else (b, a)
        flush = [first.y + first.h - second.y]
        flush.append((a.x - b.x) if end == "lo" else (a.x + a.w - b.x - b.w))
    for difference in flush:
        model.addCons(difference <= slack)
        model.addCons(-difference <= slack)


FINAL_STRETCH_COST = 1e4
"""Per metre of stretch in the final LP: far above any size deviation it could buy."""

ADJACENCY_STRETCH_WEIGHT = 4.0
"""Stretching an adjacency costs more than stretching a separation, so the repair model
blames (and the next round frees) the separations that keep adjacent rooms apart."""


@dataclass
class _Outcome:
    """A solved relation model: rectangles, the direction each pair took, what it stretched."""

    rects: dict[str, Rect]
    chosen: dict[Pair, str]
    stretched: dict[Pair, float]
    values: dict[str, float]
    """Every variable's value by name, to warm-start the next, wider model."""
    orientations: dict[str, bool]
    """Room id -> True when the room's long side lies along x."""


def _solve_model(
    problem: _Problem,
    geometry: dict[str, Rect],
    options: dict[Pair, tuple[str, ...]],
    *,
    mode: str,
    seconds: float,
    seed: int,
    orientations: dict[str, bool],
    turnable: frozenset[str] = frozenset(),
    start: _Outcome | None = None,
    feasibility_emphasis: bool = False,
    local: bool = False,
) -> _Outcome | None:
    """Solve the rooms' LP/MIP under the allowed pair directions; None without a solution.

    mode "repair": each pair's constraints may be stretched at a cost; the objective is the
    total stretch and SCIP stops as soon as it reaches zero. mode "final": the same, but a
    stretch costs so much that only the linear deviation of the sizes from their targets is
    left to minimise (elastic rather than hard, so SCIP's tolerances cannot make it fail).

    `local` (a geometry close to a layout, such as the hints): a repair round moves each
    room at most its reach (`_reach`), and pairs of rooms far apart in the round's
    starting rectangles (`start`, else `geometry`) enter the model only once a solution
    brings them closer than their relation allows (`_near_options`); the model is then
    solved again, from that solution.
    """
    if mode not in ("repair", "final"):
        raise ValueError(f"unknown mode {mode!r}")
    deadline = time.monotonic() + seconds
    current = start.rects if start is not None else geometry
    # a repair round keeps each room near where it starts; the final LP (relations fixed)
    # may move rooms as far as their sizes need
    reach = _reach(start) if mode == "repair" and local else None
    active = _near_options(problem, current, options, reach) if local else dict(options)
    while True:
        outcome = _solve_active(problem, active, mode=mode, seconds=max(0.05, deadline - time.monotonic()),
                                seed=seed, orientations=orientations, turnable=turnable, start=start,
                                feasibility_emphasis=feasibility_emphasis, within=(current, reach))
        if outcome is None:
            return None
        left_out = {pair: _least_stretch(problem, outcome.rects, pair, allowed)
                    for pair, allowed in options.items() if pair not in active}
        completed = _completed(outcome, left_out)
        entering = {pair: options[pair] for pair, (_direction, need) in left_out.items() if need > LAZY_TOLERANCE}
        if not entering or deadline - time.monotonic() <= 0.05:
            return completed
        _debug(f"    {len(entering)} far pairs enter the model")
        start = completed
        active.update(entering)


REACH_M = 3.5
"""Metres each side of a room's box may move in one local repair round (`_add_reach`),
plus REACH_PER_STRETCH of the previous round's largest stretch; a room whose sides differ
by more than twice that cannot turn in the round.

Local rounds are for the hints (the original plan's boxes), which are close to a layout:
school_stjoseph_scatholichighschool with hints and its L-rooms then constructs in 4-9 s,
against none in 60 s when a round's MIP holds all 6328 pairs and may carry rooms across
the plan (its rounds ran out of time at 8 s with the stretch stuck at 29 m). Generated
geometries are not: their conflicts need long moves. Measured with local rounds for them
too (bench/generation.py, 60 s): school_rockislandsecondfloor and
school_hendersonhighschool no longer constructed, office_OfficePlan did for some seeds
and not others; so they keep rounds over every pair, free to move anywhere."""

REACH_PER_STRETCH = 0.5

LAZY_RADIUS = 8.0
"""Metres apart (along their clearer axis) beyond which a pair of rooms that share no
door starts outside a round's model, at least: further when the rooms' reach needs it.
On school_stjoseph_scatholichighschool (113 boxes with the L-rooms' arms, 6328 pairs) a
round's model then holds about 600-800 pairs, and SCIP's rounds run several times faster."""

LAZY_MARGIN = 0.5
"""Metres added to the two rooms' reaches and the wall thickness for the radius."""

LAZY_TOLERANCE = 1e-9
"""Metres a far pair may violate its relation by before it enters the model."""


def _reach(start: _Outcome | None) -> float:
    """Metres each side of a room's box may move this round: REACH_M, plus
    REACH_PER_STRETCH of the previous round's largest stretch."""
    if start is None:
        return REACH_M
    return REACH_M + REACH_PER_STRETCH * max(start.stretched.values(), default=0.0)


def _add_reach(model, boxes: dict[str, _Box], rects: dict[str, Rect], reach: float) -> None:
    """Each side of each room's box within `reach` of where it is in `rects`.

    Two rooms further apart than twice that and a wall cannot then collide, which is what
    lets `_near_options` leave them out of the model. Both ways, not only outwards: when
    local rounds were tried on generated geometries too, rooms that could also shrink
    freely made office_OfficePlan construct for 2 of 4 seeds instead of 4 (45 s each)."""
    for room_id, (x, y, w, h) in rects.items():
        box = boxes.get(room_id)
        if box is None:
            continue
        for side, at in ((box.x, x), (box.y, y), (box.x + box.w, x + w), (box.y + box.h, y + h)):
            model.addCons(side >= at - reach)
            model.addCons(side <= at + reach)


def _near_options(problem: _Problem, rects: dict[str, Rect], options: dict[Pair, tuple[str, ...]],
                  reach: float | None) -> dict[Pair, tuple[str, ...]]:
    """The options of the pairs a round's model starts with: every door and every L's two
    boxes, and the pairs near each other in `rects`: within LAZY_RADIUS, or within the two
    rooms' reach and a wall when that is further."""
    radius = LAZY_RADIUS
    if reach is not None:
        radius = max(LAZY_RADIUS, 2 * reach + problem.walldim + LAZY_MARGIN)
    return {
        pair: allowed for pair, allowed in options.items()
        if frozenset(pair) in problem.walls or pair in problem.joins
        or problem.distance(rects, pair) <= radius
    }


def _least_stretch(problem: _Problem, rects: dict[str, Rect], pair: Pair,
                   allowed: tuple[str, ...]) -> tuple[str, float]:
    """(direction, metres) of the allowed direction the pair's rooms (not sharing a door,
    not one L) violate least in `rects`, and by how much (0: satisfied, with SAFETY)."""
    a, b = (_Box(*problem.rect(rects, thing)) for thing in pair)
    needs = {direction: _excess(a, b, direction, problem.gap(pair)) for direction in allowed}
    direction = min(allowed, key=needs.__getitem__)
    return direction, max(0.0, needs[direction])


def _completed(outcome: _Outcome, left_out: dict[Pair, tuple[str, float]]) -> _Outcome:
    """The outcome with the pairs left out of its model (pair -> (least-violated direction,
    by how much), _least_stretch): each in that direction and stretched by what it violates
    (zero once no far pair does), with that stretch as its value for warm-starting a model
    it enters."""
    chosen = dict(outcome.chosen)
    stretched = dict(outcome.stretched)
    values = dict(outcome.values)
    for pair, (direction, need) in left_out.items():
        chosen[pair] = direction
        if need > LAZY_TOLERANCE:
            stretched[pair] = need
            values[f"s_{pair[0]}_{pair[1]}"] = need
    return replace(outcome, chosen=chosen, stretched=stretched, values=values)


def _solve_active(
    problem: _Problem,
    options: dict[Pair, tuple[str, ...]],
    *,
    mode: str,
    seconds: float,
    seed: int,
    orientations: dict[str, bool],
    turnable: frozenset[str],
    start: _Outcome | None,
    feasibility_emphasis: bool,
    within: tuple[dict[str, Rect], float | None],
) -> _Outcome | None:
    """One SCIP solve of the model with the pairs of `options`, each room within a reach of
    its rectangle (`within`: rectangles, reach; None: anywhere); see _solve_model."""
    repair = mode == "repair"
    from pyscipopt import quicksum

    # the variables and constraints are added in one fixed order (rooms, boundary sides,
    # points, clusters, pairs): SCIP's search, and so the layout, depends on that order
    model = _scip_model(repair, seconds, seed, feasibility_emphasis)
    rooms = _add_rooms(model, problem, orientations, turnable, with_deviation=not repair)
    if within[1] is not None:
        _add_reach(model, rooms.boxes, *within)
    _add_on_boundary(model, problem, rooms.boxes)
    _add_covered_points(model, problem.spec, rooms.boxes)
    _add_clusters(model, problem, rooms.boxes)
    pairs = _add_pair_relations(model, problem, rooms.boxes, options)

    if repair:
        model.setObjective(quicksum(pairs.penalty), "minimize")
    else:
        model.setObjective(quicksum(rooms.deviation) + FINAL_STRETCH_COST * quicksum(pairs.penalty),
                           "minimize")
    if start is not None:
        _add_start(model, start, options)
    # without the GIL: an annealing run beside the construction (Annealing) needs it to
    # enter and leave its kernel, and SCIP would otherwise hold it for the whole solve
    model.optimizeNogil()
    status = model.getStatus()
    _debug(f"    {mode} model: {status} in "
           f"{model.getSolvingTime():.2f}s, {model.getNTotalNodes()} nodes, {model.getNLPIterations()} LP "
           f"iterations, {len(options)} pairs, {len(pairs.binaries)} free, {model.getNSols()} sols")
    if model.getNSols() == 0:
        return None
    return _read_outcome(model, problem.spec, options, rooms, pairs, orientations)


def _scip_model(repair: bool, seconds: float, seed: int, feasibility_emphasis: bool):
    """An empty, quiet SCIP model with the relation model's limits and tolerances."""
    from pyscipopt import Model

    model = Model("construct")
    model.hideOutput()
    model.setParam("display/verblevel", 0)
    model.setParam("limits/time", max(0.05, seconds))
    model.setParam("randomization/randomseedshift", seed % 2**31)
    model.setParam("numerics/feastol", 1e-9)
    if repair:
        model.setParam("limits/primal", 1e-7)
        if feasibility_emphasis:
            # measured on the real plans: a stalled repair (school_wilbraham) gets out in
            # 5 s with SCIP's feasibility emphasis and not in 60 s with the defaults, while
            # the defaults are faster on the easy first rounds
            from pyscipopt import SCIP_PARAMEMPHASIS

            model.setEmphasis(SCIP_PARAMEMPHASIS.FEASIBILITY)
    else:
        model.setParam("limits/gap", 1e-4)
    return model


@dataclass
class _RoomVars:
    """What `_add_rooms` put into a model: every room's and obstacle's box, and more."""

    boxes: dict[str, _Box]
    deviation: list
    """rho_error-weighted deviations of the sizes from their targets (final mode only)."""
    orientation_vars: dict[str, object]
    """Room id -> the binary o of a turnable room (1: its long side lies along x)."""


def _add_rooms(model, problem: _Problem, orientations: dict[str, bool], turnable: frozenset[str],
               *, with_deviation: bool) -> _RoomVars:
    """Each room's box inside the boundary, with its size and aspect-ratio bounds."""
    width, height = problem.width, problem.height
    rooms = _RoomVars({}, [], {})
    for room in problem.spec.rooms:
        sizes = RoomSizes.of(room)
        long_x = orientations[room.id]
        x = model.addVar(f"x_{room.id}", lb=0.0, ub=width)
        y = model.addVar(f"y_{room.id}", lb=0.0, ub=height)
        if room.id in turnable:
            w, h, targets = _turnable_sizes(model, room, sizes)
            rooms.orientation_vars[room.id] = targets[2]
            targets = targets[:2]
        else:
            w, h, targets = _fixed_orientation_sizes(model, room, sizes, long_x)
        model.addCons(x + w <= width - SAFETY)
        model.addCons(y + h <= height - SAFETY)
        rooms.boxes[room.id] = _Box(x, y, w, h)
        if with_deviation:
            for var, target in zip((w, h), targets):
                dev = model.addVar(f"d_{var.name}", lb=0.0)
                model.addCons(dev >= var - target)
                model.addCons(dev >= target - var)
                rooms.deviation.append(room.rho_error * dev)
    for ob_id, (ox, oy, ow, oh) in problem.obstacles.items():
        rooms.boxes[ob_id] = _Box(ox, oy, ow, oh)
    for (box, arm), crosses in (problem.crossing or {}).items():
        # an L turns as a whole: its arm keeps running across (or along) its box
        o_box, o_arm = rooms.orientation_vars.get(box), rooms.orientation_vars.get(arm)
        if o_box is not None and o_arm is not None:
            model.addCons(o_arm == (1 - o_box if crosses else o_box))
    return rooms


def _fixed_orientation_sizes(model, room: Room, sizes: RoomSizes, long_x: bool):
    """w, h and (target w, target h) of a room whose long side stays along x (long_x) or y."""
    w_lo, w_hi, h_lo, h_hi = sizes.bounds(long_x)
    w_lo, h_lo = w_lo + SAFETY, h_lo + SAFETY
    w_hi, h_hi = max(w_lo, w_hi - SAFETY), max(h_lo, h_hi - SAFETY)
    w = model.addVar(f"w_{room.id}", lb=w_lo, ub=w_hi)
    h = model.addVar(f"h_{room.id}", lb=h_lo, ub=h_hi)
    if not sizes.corridor:
        long_side, short_side = (w, h) if long_x else (h, w)
        model.addCons(sizes.min_ar * short_side + SAFETY <= long_side)
        model.addCons(long_side <= sizes.max_ar * short_side - SAFETY)
    return w, h, sizes.targets(long_x)


def _add_on_boundary(model, problem: _Problem, boxes: dict[str, _Box]) -> None:
    """An onB room touches at least one side of the boundary (one binary per side)."""
    from pyscipopt import quicksum

    width, height, big_m = problem.width, problem.height, problem.big_m
    for room in problem.spec.rooms:
        if not room.on_boundary:
            continue
        box = boxes[room.id]
        sides = [model.addVar(f"onb_{room.id}_{side}", vtype="B") for side in "lrdu"]
        model.addCons(box.x <= big_m * (1 - sides[0]))
        model.addCons(box.x + box.w >= width - SAFETY - big_m * (1 - sides[1]))
        model.addCons(box.y <= big_m * (1 - sides[2]))
        model.addCons(box.y + box.h >= height - SAFETY - big_m * (1 - sides[3]))
        model.addCons(quicksum(sides) >= 1)


def _add_covered_points(model, spec: Spec, boxes: dict[str, _Box]) -> None:
    """A room covers its fixed positions and both ends of its connections, strictly."""
    points = [(p.room, p.x, p.y) for p in spec.positions]
    for c in spec.connections:
        points += [(c.room, c.x1, c.y1), (c.room, c.x2, c.y2)]
    for room_id, px, py in points:
        box = boxes[room_id]
        model.addCons(box.x <= px - SAFETY)
        model.addCons(box.x + box.w >= px + SAFETY)
        model.addCons(box.y <= py - SAFETY)
        model.addCons(box.y + box.h >= py + SAFETY)


def _add_clusters(model, problem: _Problem, boxes: dict[str, _Box]) -> None:
    """Each cluster's members keep their relative points within the margin of a free origin."""
    margin = problem.spec.settings.cluster_margin
    reach = 2 * max(problem.width, problem.height) + 10.0
    for cluster in problem.spec.clusters:
        cx = model.addVar(f"cx_{cluster.id}", lb=-reach, ub=reach)
        cy = model.addVar(f"cy_{cluster.id}", lb=-reach, ub=reach)
        for member in cluster.members:
            box = boxes[member.room]
            model.addCons(box.x - margin + SAFETY <= member.x + cx)
            model.addCons(box.x + box.w + margin - SAFETY >= member.x + cx)
            model.addCons(box.y - margin + SAFETY <= member.y + cy)
            model.addCons(box.y + box.h + margin - SAFETY >= member.y + cy)


@dataclass
class _PairVars:
    """What `_add_pair_relations` put into a model, by pair."""

    binaries: dict[Pair, list]
    """The direction switches of each pair with more than one allowed direction."""
    stretches: dict[Pair, object]
    penalty: list
    """Each pair's stretch, adjacencies weighted by ADJACENCY_STRETCH_WEIGHT."""


def _add_pair_relations(model, problem: _Problem, boxes: dict[str, _Box],
                        options: dict[Pair, tuple[str, ...]]) -> _PairVars:
    """Each pair lies in one of its allowed directions (apart, or adjacent along a wall),
    up to a stretch variable that the objective prices."""
    from pyscipopt import quicksum

    pairs = _PairVars({}, {}, [])
    for pair, allowed in options.items():
        a, b = pair
        wall = problem.walls.get(frozenset(pair))
        stretch = model.addVar(f"s_{a}_{b}", lb=0.0)
        pairs.stretches[pair] = stretch
        joined = pair in problem.joins
        pairs.penalty.append((ADJACENCY_STRETCH_WEIGHT if wall or joined else 1.0) * stretch)
        if len(allowed) == 1:
            switches = [None]
        else:
            switches = [model.addVar(f"z_{a}_{b}_{d}", vtype="B") for d in allowed]
            pairs.binaries[pair] = switches
            model.addCons(quicksum(switches) >= 1)
        for direction, on in zip(allowed, switches):
            slack = stretch if on is None else stretch + problem.big_m * (1 - on)
            if joined:
                _add_join(model, boxes[a], boxes[b], direction, slack)
            elif wall is None:
                _add_direction(model, boxes[a], boxes[b], direction, problem.gap(pair), slack)
            else:
                _add_adjacent(model, boxes[a], boxes[b], direction, problem.walldim, wall, slack)
    return pairs


def _read_outcome(model, spec: Spec, options: dict[Pair, tuple[str, ...]], rooms: _RoomVars,
                  pairs: _PairVars, orientations: dict[str, bool]) -> _Outcome:
    """The best solution of a solved model as rectangles, chosen directions and stretches."""
    solution = model.getBestSol()
    chosen: dict[Pair, str] = {}
    for pair, allowed in options.items():
        switches = pairs.binaries.get(pair)
        if switches is None:
            chosen[pair] = allowed[0]
        else:
            values = [solution[on] for on in switches]
            chosen[pair] = allowed[max(range(len(allowed)), key=lambda i: values[i])]
    stretches = pairs.stretches
    stretched = {pair: solution[var] for pair, var in stretches.items() if solution[var] > 1e-6}
    _debug(f"    max stretch {max((solution[v] for v in stretches.values()), default=0):.3g}")
    boxes = rooms.boxes
    rects = {
        room.id: (solution[boxes[room.id].x], solution[boxes[room.id].y],
                  solution[boxes[room.id].w], solution[boxes[room.id].h])
        for room in spec.rooms
    }
    values = {var.name: solution[var] for var in model.getVars()}
    turned = dict(orientations)
    for room_id, var in rooms.orientation_vars.items():
        turned[room_id] = solution[var] > 0.5
    return _Outcome(rects, chosen, stretched, values, turned)


def _turnable_sizes(model, room: Room, sizes: RoomSizes):
    """w, h and (target w, target h, o) of a room free to lie along x (o = 1) or y (o = 0)."""
    o = model.addVar(f"o_{room.id}", vtype="B")
    w = model.addVar(f"w_{room.id}", lb=sizes.lo_short + SAFETY, ub=sizes.hi_long - SAFETY)
    h = model.addVar(f"h_{room.id}", lb=sizes.lo_short + SAFETY, ub=sizes.hi_long - SAFETY)
    spread_lo = sizes.lo_long - sizes.lo_short
    spread_hi = sizes.hi_long - sizes.hi_short
    model.addCons(w >= sizes.lo_short + SAFETY + spread_lo * o)
    model.addCons(w <= sizes.hi_short - SAFETY + spread_hi * o)
    model.addCons(h >= sizes.lo_long + SAFETY - spread_lo * o)
    model.addCons(h <= sizes.hi_long - SAFETY - spread_hi * o)
    if not sizes.corridor:
        big = sizes.max_ar * sizes.hi_long + 1.0
        model.addCons(sizes.min_ar * h + SAFETY - w <= big * (1 - o))
        model.addCons(w - sizes.max_ar * h + SAFETY <= big * (1 - o))
        model.addCons(sizes.min_ar * w + SAFETY - h <= big * o)
        model.addCons(h - sizes.max_ar * w + SAFETY <= big * o)
    spread_target = sizes.target_long - sizes.target_short
    target_w = sizes.target_short + spread_target * o
    target_h = sizes.target_long - spread_target * o
    return w, h, (target_w, target_h, o)


def _add_start(model, start: _Outcome, options: dict[Pair, tuple[str, ...]]) -> None:
    """Offer the previous round's solution to SCIP: it stays feasible in a wider model."""
    solution = model.createSol()
    by_name = {var.name: var for var in model.getVars()}
    for var in by_name.values():
        name = var.name
        if name.startswith("z_"):
            continue
        if name in start.values:
            model.setSolVal(solution, var, start.values[name])
        elif name.startswith("o_"):
            model.setSolVal(solution, var, float(start.orientations[name[2:]]))
    for pair, allowed in options.items():
        if len(allowed) == 1:
            continue
        picked = start.chosen.get(pair, allowed[0])
        for direction in allowed:
            var_name = f"z_{pair[0]}_{pair[1]}_{direction}"
            model.setSolVal(solution, by_name[var_name], float(direction == picked))
    model.addSol(solution, free=True)
# ---------------------------------------------------------------------------------------
# Checking rectangles against the spec's hard constraints
# ---------------------------------------------------------------------------------------

TOLERANCE = 1e-6


def hard_violations(spec: Spec, rects: dict[str, Rect]) -> list[str]:
    """Every hard constraint of the spec the rectangles break, in words (empty: feasible).

    Mirrors the verifier's rules so construction can judge its own candidates cheaply;
    `check_start` additionally runs the project's verifier when it is available.
    """
    tol = TOLERANCE
    problems: list[str] = []
    boundary = spec.boundary
    assert boundary is not None
    walldim = spec.settings.walldim
    for room in spec.rooms:
        if room.id not in rects:
            problems.append(f"{room.id}: not placed")
            continue
        x, y, w, h = rects[room.id]
        if x < -tol or y < -tol or x + w > boundary.w + tol or y + h > boundary.h + tol:
            problems.append(f"{room.id}: outside the boundary")
        sizes = RoomSizes.of(room)
        w_lo, w_hi, h_lo, h_hi = sizes.bounds(w >= h)
        if not (w_lo - tol <= w <= w_hi + tol and h_lo - tol <= h <= h_hi + tol):
            problems.append(f"{room.id}: size {w:.3f} x {h:.3f} out of bounds")
        if not room.is_corridor:
            ratio = max(w, h) / min(w, h)
            if not room.min_ar - tol <= ratio <= room.max_ar + tol:
                problems.append(f"{room.id}: aspect ratio {ratio:.3f} out of bounds")
        if room.on_boundary and not (
            x <= tol or y <= tol or x + w >= boundary.w - tol or y + h >= boundary.h - tol
        ):
            problems.append(f"{room.id}: not on the boundary")
    if problems:
        return problems
    things = [(room.id, rects[room.id]) for room in spec.rooms] + [
        (ob.id, (ob.x, ob.y, ob.w, ob.h)) for ob in boundary.obstacles
    ]
    for i, (a, ra) in enumerate(things):
        for b, rb in things[i + 1:]:
            sep_x, sep_y = separations(ra, rb)
            if max(sep_x, sep_y) < walldim - tol:
                problems.append(f"{a} and {b} overlap or lack a wall between them")
    door_factor = spec.settings.door_utilization
    for adj in spec.adjacencies:
        sep_x, sep_y = separations(rects[adj.a], rects[adj.b])
        need = adj.door / door_factor - tol
        touching = (abs(sep_x - walldim) <= tol and -sep_y >= need) or (
            abs(sep_y - walldim) <= tol and -sep_x >= need
        )
        if not touching:
            problems.append(f"{adj.a} and {adj.b} share no wall of {adj.door:.2f} m")
    for position in spec.positions:
        if not _covers(rects[position.room], position.x, position.y):
            problems.append(f"{position.room}: does not cover its position")
    for connection in spec.connections:
        rect = rects[connection.room]
        if not (_covers(rect, connection.x1, connection.y1)
                and _covers(rect, connection.x2, connection.y2)):
            problems.append(f"{connection.room}: does not cover its connection")
    margin = spec.settings.cluster_margin
    for cluster in spec.clusters:
        lo_x = lo_y = -math.inf
        hi_x = hi_y = math.inf
        for member in cluster.members:
            x, y, w, h = rects[member.room]
            lo_x, hi_x = max(lo_x, x - margin - member.x), min(hi_x, x + w + margin - member.x)
            lo_y, hi_y = max(lo_y, y - margin - member.y), min(hi_y, y + h + margin - member.y)
        if lo_x > hi_x + tol or lo_y > hi_y + tol:
            problems.append(f"cluster {cluster.id}: members moved apart beyond the margin")
    return problems


def _covers(rect: Rect, px: float, py: float) -> bool:
    x, y, w, h = rect
    return x - TOLERANCE <= px <= x + w + TOLERANCE and y - TOLERANCE <= py <= y + h + TOLERANCE


def rects_to_layout(spec: Spec, rects: dict[str, Rect]):
    """A Layout (with portals) of the rectangles, for the verifier and the emitters."""
    # the compiler's conversion, so a start is judged exactly as a compiled layout is
    return layout_from_rects(spec, rects)


def check_start(spec: Spec, rects: dict[str, Rect]) -> list[str]:
    """Violations of the rectangles: our own check, then the project's verifier."""
    # our own check knows rectangles only; an L-room is judged by the verifier alone
    problems = hard_violations(spec, rects) if not spec.arms else []
    if problems:
        return problems
    from layoutdsl.layout.verify import verify

    return [violation.message for violation in verify(spec, rects_to_layout(spec, rects))]


# ---------------------------------------------------------------------------------------
# Seed geometries
# ---------------------------------------------------------------------------------------


def hint_geometry(spec: Spec, shrink: bool | float = True) -> dict[str, Rect] | None:
    """The hints as rectangles, or (`shrink`) each shrunk to its target size in its centre.

    An imported room's hint is its original bounding box; the target is that box scaled by
    sqrt(polygon / box area). Measured on the 24 real plans, the boxes themselves are the
    better seed (all 24 repaired, median 0.1 s); the shrunk ones are the fallback.
    None unless every room has a hint.
    """
    hints = {hint.room: hint for hint in spec.hints}
    if any(room.id not in hints for room in spec.rooms):
        return None
    geometry: dict[str, Rect] = {}
    for room in spec.rooms:
        hint = hints[room.id]
        sizes = RoomSizes.of(room)
        w, h = sizes.targets(hint.w >= hint.h)
        fill = (w * h) / max(hint.w * hint.h, 1e-9)
        if shrink is False or (shrink is not True and fill >= shrink):
            w, h = hint.w, hint.h
        cx, cy = hint.x + hint.w / 2, hint.y + hint.h / 2
        geometry[room.id] = (cx - w / 2, cy - h / 2, w, h)
    return geometry


DEFAULT_SECONDS = 60.0

MAX_STALLS = 3
"""Rounds without progress after which a seed geometry is given up."""

FREE_RADII = (1.0, 3.0, 6.0, 12.0, 25.0)
"""Metres around a conflict within which pairs get their relation freed, round by round."""


def _repair(
    problem: _Problem,
    geometry: dict[str, Rect],
    deadline: float,
    seed: int,
    max_stalls: int = MAX_STALLS,
    free_defects: bool = False,
    local: bool = False,
    give_way: Callable[[], bool] | None = None,
    quick: bool = False,
    rebox: Callable[[dict[str, Rect]], _Problem] | None = None,
    max_rounds: int | None = None,
    round_seconds: float | None = None,
) -> dict[str, Rect] | None:
    """Relations from the geometry, repaired round by round until they admit a layout.

    Each round solves the elastic model; the pairs it had to stretch, and the pairs close to
    their rooms, get more freedom (one axis -> either axis -> any direction) for the next
    round, which starts from the previous solution. Zero stretch ends the repair; a final
    LP with those relations then brings the sizes towards their targets. `local`: the
    geometry is close to a layout (the hints), and each round's moves stay local
    (_solve_model). `give_way`, asked before each round: a better geometry is waiting, and
    this repair gives up for it. `quick`: give the geometry up as soon as it looks like one
    that never repairs (QUICK_FIRST_STRETCH_M, QUICK_ROUNDS), for another seed geometry.
    `rebox` (hint geometries of a spec with L-rooms): the problem with each L-room's doors on
    its boxes nearest their neighbours in the given rectangles; after each stretched round, a
    door the round brought nearer the L's other box moves to it (_reboxed). `max_rounds`:
    give the geometry up when this many rounds left pairs stretched (ANNEALED_ROUNDS).
    `round_seconds`: each round's MIP stops after this long (ANNEALED_ROUND_SECONDS).
    """
    options = _first_options(problem, geometry, free_defects)
    start: _Outcome | None = None
    neighbours = _adjacency_neighbours(problem.spec)
    best_total = math.inf
    stalls = 0
    orientations = {
        room_id: rect[2] >= rect[3] for room_id, rect in geometry.items()
    }
    turnable: set[str] = set()
    if quick:
        max_rounds = min(max_rounds or QUICK_ROUNDS, QUICK_ROUNDS)
    for round_index in range(len(FREE_RADII) * 3):
        left = deadline - time.monotonic()
        if left <= 0.05:
            return None
        if give_way is not None and give_way():
            _debug("  gives way to an annealed geometry")
            return None
        seconds = min(left, 1.0 + 0.25 * left)
        if quick:
            seconds = min(seconds, QUICK_ROUND_SECONDS)
        if round_seconds is not None:
            seconds = min(seconds, round_seconds)
        outcome = _solve_model(problem, geometry, options, mode="repair", seconds=seconds, seed=seed,
                               orientations=orientations, turnable=frozenset(turnable),
                               start=start, feasibility_emphasis=stalls > 0, local=local)
        if outcome is None:
            return None
        if max(outcome.stretched.values(), default=0.0) < STRETCH_NOISE_M:
            # none stretched, or a micrometre short: the SAFETY margins of a tight chain of
            # rooms, not a conflict (then, if the final model rejects it, the repair goes on)
            rects = _final_layout(problem, geometry, outcome, deadline, seed, local)
            if rects is not None or not outcome.stretched:
                return rects
        _debug(f"  round {round_index}: {len(outcome.stretched)} stretched, "
               f"total {sum(outcome.stretched.values()):.2f} m: "
               + ", ".join(f"{a}-{b} {options[(a, b)]} {v:.2f}"
                           for (a, b), v in sorted(outcome.stretched.items())))
        total = sum(outcome.stretched.values())
        if quick and round_index == 0 and total > QUICK_FIRST_STRETCH_M:
            _debug("  given up (quick)")
            return None
        if max_rounds is not None and round_index + 1 >= max_rounds and (quick or total >= NEAR_DONE_M):
            # within a metre of a layout, a round limit's geometry gets the patience of the
            # stalls below (an annealed one that met every door was given up at 0.004 m)
            _debug(f"  given up after {max_rounds} rounds")
            return None
        stalled = total > 0.95 * best_total
        best_total = min(best_total, total)
        if stalled:
            stalls += 1
            # a geometry within a metre of a layout is worth the patience hints get
            patience = MAX_STALLS if total < NEAR_DONE_M else max_stalls
            if stalls > patience:
                # a local minimum of the stretch: another seed geometry does better than
                # ever wider (and slower) MIPs around this one
                return None
        radius = FREE_RADII[min(round_index + stalls, len(FREE_RADII) - 1)]
        blamed = {thing for pair in outcome.stretched for thing in pair}
        if stalls:
            # no progress: the blamed rooms may need to turn, and the conflict's cause may
            # lie further out, so look a step further each time
            turnable |= blamed & set(orientations)
            # the two boxes of an L turn together
            turnable |= {other for pair in (problem.crossing or {}) if turnable & set(pair) for other in pair}
        for _ in range(stalls):
            blamed |= {n for thing in blamed for n in neighbours.get(thing, ())}
        orientations = dict(outcome.orientations)
        _free_blamed_pairs(problem, geometry, options, outcome, blamed, radius, stalls)
        if rebox is not None:
            problem = _reboxed(problem, rebox(outcome.rects), geometry, options)
        start = outcome
    return None


def _reboxed(problem: _Problem, nearer: _Problem, geometry: dict[str, Rect],
             options: dict[Pair, tuple[str, ...]]) -> _Problem:
    """`nearer` where it moves an L-room's door to its other box (else `problem`), with the
    pairs whose door moved given both axes in `options` (in place).

    Which box of an L meets which neighbour is read off the seed geometry (lshape.boxes_spec);
    in a hint geometry the arm's place is a guess (the spec holds the room's box, seed_arms
    adds the arm beside it). Measured on school_stjoseph_scatholichighschool with hints and
    L-rooms: the original boxes' repair, stuck at 7.5 m from its fourth round on and given up
    after 24 s (no layout in 60 s), reached a layout in its fourth round (12.9 s) with doors
    moving. Generated geometries do without: on office_floorplanMAIN's quick tries (seeds
    0-29) 16 constructed with it against 19 without, on school_wilbraham 22 either way."""
    if nearer.walls == problem.walls:
        return problem
    for pair in nearer.pairs:
        key = frozenset(pair)
        if (key in nearer.walls) != (key in problem.walls) and len(options[pair]) == 1:
            options[pair] = _widen(nearer, geometry, pair, options[pair])
    _debug(f"    doors moved between boxes: "
           + ", ".join("-".join(sorted(k)) for k in set(nearer.walls) - set(problem.walls)))
    return nearer


QUICK_FIRST_STRETCH_M = 6.0
"""A quick repair gives its geometry up when the first round stretches more than this in all.
Measured on generated geometries (quick tries, seeds 0-29): of office_floorplanMAIN's 50, none
of the 22 from 6 m up repaired, and 20 of the 28 below did; of school_wilbraham's 42, none of
the 15 from 6 m up, 22 of the 27 below."""

QUICK_ROUND_SECONDS = 1.0
"""...and each of its rounds' MIPs stops after this long. In the same runs (2.5 s per geometry,
so about 1.6 s for the second round's MIP) the second rounds that repaired took 0.05-0.8 s
but for 4 of office_floorplanMAIN's 16 (1.15-1.37 s); of the 50 that did not, 44 ran into the
time limit."""

QUICK_ROUNDS = 2
"""...and when it has stretched pairs after this many rounds. In the same runs every geometry
that repaired did so in its first round or its second (the first freed its stretched pairs),
none later: the later rounds of a quick try were time spent on geometries that stay stuck."""


def _first_options(problem: _Problem, geometry: dict[str, Rect],
                   free_defects: bool) -> dict[Pair, tuple[str, ...]]:
    """Each pair's allowed directions in the first round: the geometry's clearer one."""
    options: dict[Pair, tuple[str, ...]] = {
        pair: problem.axis_choices(geometry, pair)[:1] for pair in problem.pairs
    }
    for pair in problem.joins:
        options[pair] = (lshape.join_option(geometry[pair[0]], geometry[pair[1]]),)
    if free_defects:
        # where the geometry is wrong (rooms overlap, or a door's rooms do not touch) its
        # relation is a guess: let the first round choose the axis (measured on generated
        # geometries: fewer stalled rounds)
        for pair in problem.pairs:
            if pair in problem.joins:
                continue  # an L's two boxes touch by design
            distance = problem.distance(geometry, pair)
            wall = problem.walls.get(frozenset(pair))
            if distance < problem.walldim - 1e-6 or (wall and distance > problem.walldim + 1e-3):
                options[pair] = _widen(problem, geometry, pair, options[pair])
    return options


def _adjacency_neighbours(spec: Spec) -> dict[str, set[str]]:
    """Room id -> the rooms it shares a door with."""
    neighbours: dict[str, set[str]] = {}
    for adj in spec.adjacencies:
        neighbours.setdefault(adj.a, set()).add(adj.b)
        neighbours.setdefault(adj.b, set()).add(adj.a)
    return neighbours


def _final_layout(problem: _Problem, geometry: dict[str, Rect], outcome: _Outcome,
                  deadline: float, seed: int, local: bool = False) -> dict[str, Rect] | None:
    """The relations of a zero-stretch round with the sizes brought towards their targets
    (else that round's own rectangles), if they pass `check_start`; None otherwise."""
    final_options = {pair: (direction,) for pair, direction in outcome.chosen.items()}
    final = _solve_model(problem, geometry, final_options, mode="final",
                         seconds=max(0.5, min(5.0, deadline - time.monotonic())),
                         seed=seed, orientations=outcome.orientations, local=local)
    for rects in (final.rects if final else None, outcome.rects):
        if rects is None:
            continue
        problems = check_start(problem.checked or problem.spec, rects)
        if not problems:
            return rects
        _debug(f"    rejected: {problems[:3]}")
    return None


def _free_blamed_pairs(problem: _Problem, geometry: dict[str, Rect],
                       options: dict[Pair, tuple[str, ...]], outcome: _Outcome,
                       blamed: set[str], radius: float, stalls: int) -> None:
    """Widen, in place, the options of the stretched pairs and of the blamed rooms' pairs
    within `radius` (after a stall, every pair of two blamed rooms)."""
    for pair in outcome.stretched:
        options[pair] = _widen(problem, geometry, pair, options[pair])
    for pair in problem.pairs:
        a, b = pair
        if not (a in blamed or b in blamed):
            continue
        if len(options[pair]) == 1 and problem.distance(geometry, pair) <= radius:
            options[pair] = _widen(problem, geometry, pair, options[pair])
        elif stalls and a in blamed and b in blamed:
            options[pair] = _widen(problem, geometry, pair, options[pair])


def _widen(problem: _Problem, geometry: dict[str, Rect], pair: Pair,
           allowed: tuple[str, ...]) -> tuple[str, ...]:
    """One more degree of freedom: one direction -> both axes -> all four directions (for
    the boxes of an L: one join -> every join)."""
    if pair in problem.joins:
        return allowed + tuple(o for o in lshape.JOIN_OPTIONS if o not in allowed)
    if len(allowed) == 1:
        both = problem.axis_choices(geometry, pair)
        return (allowed[0],) + tuple(d for d in both if d != allowed[0])
    if len(allowed) == 2:
        return allowed + tuple(d for d in DIRECTIONS if d not in allowed)
    return allowed


def construct_start(
    spec: Spec,
    *,
    seed: int = 0,
    deadline: float | None = None,
    randomize: bool = False,
    use_hints: bool = True,
    hanging: Mapping[str, float] | None = None,
    anneal: bool = True,
    spare_cores: bool = True,
    max_geometries: int | None = None,
    try_seconds: float | None = None,
    choices: int = TOP_CHOICES,
    quick: bool = False,
    annealing: Annealing | None = None,
) -> dict[str, Rect] | None:
    """Rectangles (x, y, w, h) satisfying every hard constraint of the spec, or None.

    `deadline` is a `time.monotonic()` instant (default: 60 s from now). Seed geometries are
    tried in turn, each with a share of the time left: the hints' boxes and the hints shrunk
    to the target sizes (when the spec has hints and `use_hints`), then geometries grown
    from the room graph (layoutdsl.compile.generate), then spring embeddings. `randomize` (hint-based
    variants) perturbs the hints from `seed`; the graph geometries are always drawn from it.
    `hanging` (a part of a larger spec, such as a cycle block) is the area of the rooms that
    hang off each room outside the part: the part leaves them space. `anneal`: a spec with
    cycles also tries annealed geometries, computed beside the others (Annealing); a cycle
    block solved as a template does without, its greedy tries and ladder drawing being
    quicker for a few rooms. `spare_cores` off (every core already runs a construction, as
    `compile --variants` does): only the plans the greedy placement never constructs anneal.
    `max_geometries`: give up after repairing this many seed geometries (a variant's
    quick try, layoutdsl.compile.variants.QUICK_GEOMETRIES), else only at the deadline;
    `try_seconds`: the most any one geometry's repair may take (else a share of the time left).
    `choices`: the greedy placement's choices per room (layoutdsl.compile.generate.TOP_CHOICES).
    `quick`: each generated geometry's repair gives up early when it looks stuck (_repair).
    `annealing`: this construction's annealing, started earlier (start_annealing); the
    construction takes it over and closes it.
    """
    if spec.boundary is None or not spec.rooms:
        if annealing is not None:
            annealing.close()
        return None
    if deadline is None:
        deadline = time.monotonic() + DEFAULT_SECONDS
    problem = _Problem.of(spec)
    rng = random.Random(seed)
    # an L-room's arm is drawn as a room of its own (lshape.seeds_spec)
    drawn = lshape.seeds_spec(spec)
    has_hints = use_hints and hint_geometry(drawn) is not None
    # the graph geometries that follow the hints' get the cycle blocks solved too (lazily:
    # not at all when a hint geometry constructs)
    templates = _TemplateSets(drawn, seed, deadline, hanging or {})
    order = _construction_order(drawn, has_hints, anneal, spare_cores)
    if annealing is not None and (annealing.order != order or annealing.seed != seed):
        annealing.close()  # started for another construction than this one
        annealing = None
    if annealing is not None:
        annealing.deadline = deadline
    elif order:
        annealing = Annealing(drawn, seed, deadline, order)
    candidates = _seed_geometries(drawn, rng, randomize, use_hints, templates, choices)
    try:
        return _first_repaired(spec, problem, candidates, deadline, seed, rng, annealing, max_geometries,
                               try_seconds, quick)
    finally:
        if annealing is not None:
            annealing.close()


def boxed_problem(spec: Spec, rects: dict[str, Rect], crossing=None) -> _Problem:
    """The repair's problem for a spec with L-rooms, each L drawn as its two boxes, with each
    of its doors on the box nearest the neighbour in `rects`; `crossing`:
    lshape.crossings(spec), computed once by a caller that reboxes often."""
    boxes, joins = lshape.boxes_spec(spec, rects)
    return _Problem.of(boxes, joins=joins, checked=spec,
                       crossing=lshape.crossings(spec) if crossing is None else crossing)


def _first_repaired(spec: Spec, problem: _Problem, candidates, deadline: float, seed: int,
                    rng: random.Random, annealing: Annealing | None,
                    max_geometries: int | None = None,
                    try_seconds: float | None = None,
                    quick: bool = False) -> dict[str, Rect] | None:
    """The first seed geometry the repair turns into a layout, or None: `candidates` in turn,
    with each annealed geometry tried as soon as its run is done (_in_turn), at most
    `max_geometries` of them, each repaired for at most `try_seconds`."""
    crossing = lshape.crossings(spec) if spec.arms else None

    def rebox(rects: dict[str, Rect]) -> _Problem:
        return boxed_problem(spec, rects, crossing)

    repaired = 0
    for index, (kind, make_geometry, last) in enumerate(_in_turn(candidates, annealing)):
        if max_geometries is not None and repaired >= max_geometries:
            return None
        left = deadline - time.monotonic()
        if left <= 0.05:
            return None
        made = make_geometry()
        if made is None:
            continue  # an annealed geometry too far from a layout to repair, or out of time
        geometry = _cover_points(spec, made)
        # making it may have taken a while (solving the cycle blocks): the repair's share
        # is of the time left now, so the construction keeps its deadline
        left = deadline - time.monotonic()
        if left <= 0.05:
            return None
        candidate_problem = problem
        if spec.arms:
            # each seed geometry says which box of an L-room meets which neighbour
            geometry = lshape.seed_arms(spec, geometry, rng, hints=kind == "hints")
            candidate_problem = rebox(geometry)
        # a hint geometry is the likeliest and is worth a long repair; graph geometries are
        # many short tries (measured: a fresh draw beats a long repair of a stuck one)
        if last:
            share = left
        elif kind in ("hints", "annealed"):
            share = 0.5 * left
        elif kind == "generated":
            share = min(left, max(GENERATED_TRY_SECONDS, GENERATED_TRY_SHARE * left))
        else:
            share = min(left, max(GRAPH_TRY_SECONDS, 0.15 * left))
        if try_seconds is not None:
            share = min(share, try_seconds)
        _debug(f"geometry {index} ({kind}): {share:.1f}s")
        repaired += 1
        # an annealed geometry of a plan whose runs take every core, with more coming
        runs_alone = kind == "annealed" and annealing is not None and annealing.order == "alone"
        # a stalled graph geometry is given up sooner: a fresh draw is cheaper (measured)
        rects = _repair(candidate_problem, geometry, time.monotonic() + share, seed,
                        max_stalls=MAX_STALLS if kind in ("hints", "annealed") else GRAPH_MAX_STALLS,
                        free_defects=kind == "generated", local=kind == "hints",
                        give_way=_give_way(annealing, kind), quick=quick and kind == "generated",
                        rebox=rebox if spec.arms and kind == "hints" else None,
                        max_rounds=ANNEALED_ROUNDS if runs_alone else None,
                        round_seconds=ANNEALED_ROUND_SECONDS if runs_alone else None)
        if rects is not None:
            return rects
        if annealing is not None and kind in ("generated", "graph"):
            # annealing untangles what the repair could not (office_OfficePlan: see
            # layoutdsl.compile.anneal.FROM_GEOMETRY_TEMPERATURE)
            annealing.anneal_from(made)
    return None


def _give_way(annealing: Annealing | None, kind: str) -> Callable[[], bool] | None:
    """When the repair of a `kind` geometry gives up for an annealed one that is done: a
    greedy one for any close enough to a layout, an annealed one for one far nearer (the
    hints never)."""
    if annealing is None:
        return None
    if kind in ("generated", "graph"):
        return annealing.promising
    if kind == "annealed":
        nearer_than = FAR_BETTER * annealing.taken_violation
        return lambda: annealing.promising(nearer_than)
    return None


def _in_turn(candidates: list, annealing: Annealing | None):
    """(kind, maker, last) of each seed geometry to try: an annealed geometry whenever a run
    close enough to a layout is done, else the next of `candidates`; when those are used up,
    or for an annealing "alone" (_anneal_order), annealed geometries as they come. The hints'
    geometries come first all the same: a spec with hints asks for its own arrangement.

    Which geometry comes next thus depends on how fast the annealing runs, as the repairs'
    outcomes depend on their time limits. A spec without cycles never starts a run, and a
    "beside" spec (_anneal_order) whose first geometry constructs within ANNEAL_DELAY never
    looks at one.
    """
    tried = 0
    next_candidate = 0
    while True:
        if annealing is not None and tried >= 1:
            # the first geometry failed: annealing runs on the spare cores from now on
            annealing.start()
        hints_next = next_candidate < len(candidates) and candidates[next_candidate][0] == "hints"
        if annealing is not None and annealing.order == "alone" and not hints_next:
            # both cores anneal: see _anneal_order
            yield "annealed", annealing.wait, False
        elif annealing is not None and not hints_next and annealing.promising():
            yield "annealed", annealing.take, False
        elif next_candidate < len(candidates):
            kind, make_geometry = candidates[next_candidate]
            next_candidate += 1
            yield kind, make_geometry, next_candidate == len(candidates) and annealing is None
        elif annealing is not None:
            yield "annealed", annealing.wait, False
        else:
            return
        tried += 1


SHRINK_ORDER: tuple[bool | float, ...] = (False, True)
"""Hint geometries in the order tried: the original boxes, then boxes shrunk to target."""


ANNEALED_ROUND_SECONDS = 1.5
"""...and each of its rounds' MIPs stops after this long. Measured on the annealed geometries
within satellites.REACH_M of a layout of seeds 0-19 (office_floor-1024x523) and 0-11
(school_stjoseph_scatholichighschool), each repaired alone as compile repairs it: the 8 that
repaired did so in rounds of 0.13-0.54 s, while the 4 that did not held the construction for
0.9-4.1 s, their second round 0.8-3.8 s. In compile those rounds run beside two annealing
runs, and every second they take slows the runs that come next."""

ANNEALED_ROUNDS = 2
"""Rounds after which the repair of an annealed geometry of a split plan (_anneal_order
"alone", where more runs keep coming) gives it up when pairs are still stretched. Measured
on satellites runs' geometries (seeds 0-9, at the committed kernel and at trial weights of
the core's doors, 70 runs), each repaired alone for up to 15 s: the 23 that repaired (10 on
school_stjoseph_scatholichighschool, 13 on office_floor-1024x523) all did so within 2.4 s,
and with this limit the same 23 repair; the others ran 12-16 s before failing, and now
0.7-5.3 s. In compile those long repairs held a core while two runs went on, which then
took 17-19 s where they take 12-13 s alone (bench/results/satellites.txt, section 4).
A geometry whose rounds stretch less than NEAR_DONE_M in all is not given up by this limit:
compiling office_floor-1024x523 at seed 0, a run that met every door was given up after two
rounds that each stretched one pair by a few millimetres; and of 20 runs' geometries (seeds
0-19, section 5) one at 0.66 m repaired in its third round."""

GRAPH_MAX_STALLS = 1
"""Rounds without progress after which a generated or spring geometry is given up."""

STRETCH_NOISE_M = 1e-4
"""A round whose every stretch is below this (0.1 mm) goes to the final model and check_start
as if it had none; only if they reject it does the repair go on. Measured on
office_floor-1024x523 without hints (seed 0): an annealed geometry that met every door came
out of its first round with one pair stretched by 2e-06 m (the SAFETY margins of a chain of
rooms packed edge to edge), took a 1.6 s second round in one compile, and in another was given
up after its round limit, leaving the compile with no layout in 60 s."""

NEAR_DONE_M = 1.0
"""Total stretch (metres) below which a stalled graph geometry still gets MAX_STALLS rounds:
measured on office_floorplanLOWER, generated geometries stalled at 0.34 m and were dropped."""

GENERATED_TRIES = 24
"""Greedy contact placements (layoutdsl.compile.generate) tried after the hint geometries."""

GENERATED_TRY_SECONDS = 2.5
"""Least time the repair of one generated geometry gets."""

GENERATED_TRY_SHARE = 0.1
"""Share of the time left the repair of one generated geometry gets, when that is more."""

GRAPH_TRIES = 12
"""Spring-embedded seed geometries, tried in turn with the generated ones."""

SPRING_ROOMS = 30
"""Plans of this many rooms or more get fewer spring-embedded tries (SPRING_EVERY)."""

SPRING_EVERY = 4
"""...one per this many generated tries."""

GRAPH_TRY_SECONDS = 1.5
"""Least time a graph geometry's repair gets (more when much time is left)."""


BLOCK_SHARE = 0.3
"""Share of the construction's time the cycle blocks may take to solve (block_templates)."""

BLOCK_MIN_SECONDS = 1.5
"""Least time one cycle block gets, as long as the construction keeps twice that for itself."""


def block_spec(spec: Spec, block: frozenset[str]) -> Spec:
    """The spec of one cycle block alone: its rooms and the constraints among them."""
    return spec.restricted_to(block, f"{spec.name}-block")


def block_templates(spec: Spec, seed: int, deadline: float,
                    hanging: Mapping[str, float] | None = None) -> list[dict[str, Rect]]:
    """Each cycle block of the room graph solved on its own: rooms placed so that every
    adjacency among them is a door (a verified layout of the block alone).

    Greedy placement realises tree-like parts of a building well but rarely closes a cycle
    of rooms placed one by one; the repair then stalls (measured: 11 of the 24 real plans,
    all with cycles, found nothing in 60 s). The blocks are small, so the construction solves
    each fast, and the generator places it as a rigid whole (the thesis' cycle decomposition,
    §5.5.3, applied to generation). A spec that is one block itself gets no templates.
    """
    blocks = [b for b in cycle_blocks(spec) if len(b) < len(spec.rooms)]
    if not blocks:
        # a block itself: its ladder of corridors, if it has one, drawn outright
        ladder = ladder_template(spec, random.Random(seed), hanging)
        if ladder is None or hard_violations(spec.restricted_to(frozenset(ladder), spec.name), ladder):
            return []
        return [ladder]
    # blocks that share rooms are solved together; where that fails, one by one
    todo = [(group, [b for b in blocks if b <= group]) for group in _joined_blocks(blocks)]
    if any(len(group) == len(spec.rooms) for group, _ in todo):
        todo = [(block, [block]) for block in blocks]
    budget_end = time.monotonic() + BLOCK_SHARE * max(0.0, deadline - time.monotonic())
    total = sum(len(b) for b in blocks)
    templates = []
    solved: dict[str, Rect] = {}
    sides = drawn_sides(spec)
    lengths = {room_id: long_side for room_id, (long_side, _) in sides.items()}
    while todo:
        block, parts = todo.pop(0)
        left = budget_end - time.monotonic()
        # a block's first repair rounds take about a second: less than BLOCK_MIN_SECONDS
        # solves nothing (measured: every 5-room block of rockislandsecondfloor failed with
        # 0.4 s each and all solved with 1.3 s), so small budgets borrow from the rest
        share = max(BLOCK_MIN_SECONDS, left * len(block) / max(total, 1))
        if deadline - time.monotonic() < 2 * share:
            break
        # a room two blocks share keeps the shape the first block gave it, so the second
        # can be laid over it (measured on school_hendersonhighschool: a hall solved in
        # two shapes left the gym of the second block 7.7 m from it)
        shared = {room_id: solved[room_id][2:] for room_id in block if room_id in solved}
        alone = block_spec(spec, block)
        # a ladder's rungs must span one common gap: only its rails are lengthened
        ladder = find_ladder(alone)
        rungs = set(ladder[2]) if ladder else set()
        alone = _with_long_sides(alone, {r: v for r, v in lengths.items() if r not in rungs})
        rects = construct_start(_with_shapes(alone, shared), seed=seed,
                                use_hints=False, deadline=time.monotonic() + share, anneal=False,
                                hanging=_hanging_areas(spec, block, hanging or {}, sides))
        _debug(f"block of {len(block)} rooms: {'solved' if rects else 'not solved'}")
        if rects is None and len(parts) > 1:
            todo[:0] = [(part, [part]) for part in parts]
            continue
        total -= len(block)
        if rects is not None:
            # the generator places rooms; an L-room's arm is seeded again beside its box
            rects = lshape.rooms_only(spec, rects)
            templates.append(rects)
            solved.update(rects)
    return templates


JOINED_MAX_ROOMS = 24
"""Largest set of joined blocks solved together: school_stjoseph_scatholichighschool's
blocks would join into one of 54 rooms, as hard to solve as a whole plan."""


def _hanging_areas(spec: Spec, part: frozenset[str], outer: Mapping[str, float],
                   sides: Mapping[str, tuple[float, float]]) -> dict[str, float]:
    """Room of `part` -> drawn area (`sides`: generate.drawn_sides of the spec) of the
    rooms outside it that hang off that room.

    A cycle block meets the rest of the graph only at its cut rooms, so each connected
    piece of the rest hangs off exactly one room of the block. `outer`: the same for the
    spec itself, when it is a part of a larger one.
    """
    import networkx as nx

    graph = room_graph(spec)
    hanging = {room_id: outer.get(room_id, 0.0) for room_id in part}
    for piece in nx.connected_components(graph.subgraph(set(graph) - part)):
        roots = {n for r in piece for n in graph[r] if n in part}
        area = sum(sides[r][0] * sides[r][1] + outer.get(r, 0.0) for r in piece)
        for root in roots:
            hanging[root] += area / len(roots)
    return hanging


def _joined_blocks(blocks: list[frozenset[str]]) -> list[frozenset[str]]:
    """Blocks that share a room, joined into one, largest first.

    Two blocks solved apart and laid over their shared room collide around it: measured on
    school_hendersonhighschool, whose corridor C9 is in two blocks and its hall R35 in two,
    no full geometry repaired. Solved together (the construction of the joined rooms,
    which solves each block first and then places them), they fit around the shared room.
    """
    groups: list[set[str]] = []
    for block in blocks:
        touching = [g for g in groups if g & block]
        merged = set(block).union(*touching)
        if len(merged) > JOINED_MAX_ROOMS:
            groups.append(set(block))
            continue
        groups = [g for g in groups if not g & block] + [merged]
    return sorted((frozenset(g) for g in groups), key=lambda g: (-len(g), sorted(g)))


PIN_SLACK = 1e-4
"""Metres a shared room's pinned sides may vary by (below generate.SHAPE_TOLERANCE)."""


def _with_long_sides(spec: Spec, lengths: dict[str, float]) -> Spec:
    """The spec with each corridor's long side at least its drawn length (within bounds).

    A block solved alone packs its corridors tight against each other, leaving no side
    free for the rooms that hang off them outside the block (measured on
    school_hendersonhighschool: three 9-door corridors of one block, 30 rooms piled over
    them). Drawn lengths give each corridor the perimeter its rooms need.
    """
    rooms = []
    for room in spec.rooms:
        if room.is_corridor and room.id in lengths:
            long_is_w = room.target_w >= room.target_h
            hi = room.max_w if long_is_w else room.max_h
            # within the aspect ratio the short side's bounds allow
            hi = min(hi, room.max_ar * (room.max_h if long_is_w else room.max_w))
            want = min(hi, lengths[room.id])
            if long_is_w and want > room.min_w:
                room = replace(room, min_w=want, target_w=max(room.target_w, want))
            elif not long_is_w and want > room.min_h:
                room = replace(room, min_h=want, target_h=max(room.target_h, want))
        rooms.append(room)
    return replace(spec, rooms=tuple(rooms))


def _with_shapes(spec: Spec, shapes: dict[str, tuple[float, float]]) -> Spec:
    """The spec with these rooms' sides fixed to (w, h), either way round."""
    if not shapes:
        return spec
    rooms = []
    for room in spec.rooms:
        if room.id in shapes:
            w, h = shapes[room.id]
            # a hair of slack: bounds pinned exactly leave the solver's safety margins
            # (SAFETY) no room, and the verifier then rejects the block by a micrometre
            room = replace(room, min_w=w - PIN_SLACK, max_w=w + PIN_SLACK, target_w=w,
                           min_h=h - PIN_SLACK, max_h=h + PIN_SLACK, target_h=h)
        rooms.append(room)
    return replace(spec, rooms=tuple(rooms))


class _TemplateSets:
    """Solved cycle blocks for each generated geometry: a fresh set per try.

    How a block was solved decides whether the rest of the building can hang off it: one
    set of templates can leave no room for a block room's outside doors. Measured on
    school_wilbraham (seed 3): 0 of 8 generated geometries repaired with the blocks solved
    from seed 3, 8 of 8 with those solved from seed 0. So try k gets the blocks solved
    from its own seed (seed + k * TEMPLATE_SEED_STEP), the first set with BLOCK_SHARE of
    the time, later ones with at most TEMPLATE_RESOLVE_FACTOR times what the first took.
    """

    def __init__(self, spec: Spec, seed: int, deadline: float, hanging: Mapping[str, float] | None = None):
        self.spec, self.seed, self.deadline, self.hanging = spec, seed, deadline, hanging or {}
        self.sets: list[list[dict[str, Rect]]] = []
        self.first_seconds = 0.0

    def get(self, index: int) -> list[dict[str, Rect]]:
        # the first set is solved when the first greedy geometry needs it (annealed
        # geometries, which may come first, need none), with BLOCK_SHARE of the time left
        if not self.sets:
            began = time.monotonic()
            self.sets.append(block_templates(self.spec, self.seed, self.deadline, self.hanging))
            self.first_seconds = time.monotonic() - began
        while len(self.sets) <= index:
            budget = BLOCK_MIN_SECONDS + TEMPLATE_RESOLVE_FACTOR * self.first_seconds
            deadline = min(self.deadline, time.monotonic() + budget / BLOCK_SHARE)
            self.sets.append(block_templates(self.spec, self.seed + len(self.sets) * TEMPLATE_SEED_STEP,
                                             deadline, self.hanging))
        return self.sets[index]


TEMPLATE_SEED_STEP = 7919
"""Seed distance between the template sets of one construction (a prime, so the sets of
neighbouring construction seeds do not coincide)."""

TEMPLATE_RESOLVE_FACTOR = 2.0


def _seed_geometries(spec: Spec, rng: random.Random, randomize: bool, use_hints: bool = True,
                     templates: _TemplateSets | None = None, choices: int = TOP_CHOICES):
    """(kind, maker) of each seed geometry to try, best first; each is built when needed.
    Annealed geometries (Annealing) join them as they come (_in_turn)."""
    has_hints = use_hints and hint_geometry(spec) is not None
    makers = []
    if has_hints and randomize:
        makers.append(("hints", lambda: perturbed_hint_geometry(spec, rng)))
    if has_hints:
        # for variants too: a variant that cannot keep a perturbed geometry still differs
        # by its seed and its entrance, and the plain hints repair far more reliably than
        # graph geometries on large plans
        makers += [("hints", lambda shrink=shrink: hint_geometry(spec, shrink=shrink))
                   for shrink in SHRINK_ORDER]
    # one generator shared by the makers, called in order: the same seed, the same sequence
    # the two graph families alternate: measured on the real plans (machine shared), each
    # finds layouts the other misses (greedy placements: large plans; spring embeddings:
    # some 28-36-room plans with cycles), so neither may starve the other of time
    # from SPRING_ROOMS rooms up, spring embeddings get one try in SPRING_EVERY: measured
    # (seeds 0-1, 45 s) on floorplanLOWER, floorplanMAIN and rockislandsecondfloor (38-55
    # rooms): 3 of 6 constructed alternating one to one, 4 of 6 without any spring try
    every = 1 if len(spec.rooms) < SPRING_ROOMS else SPRING_EVERY
    graph_tries = 0
    for index in range(GENERATED_TRIES):
        makers.append(("generated", lambda index=index: generate_geometry(
            spec, rng, templates=templates.get(index) if templates else (), choices=choices)))
        if index % every == every - 1 and graph_tries < GRAPH_TRIES:
            graph_tries += 1
            makers.append(("graph", lambda: construct_geometry(spec, rng)))
    return makers


ANNEAL_BLOCK_ROOMS = 12
"""Rooms in the largest cycle block from which the annealing starts at once, on two workers
(as it does for a block with a ladder of corridors, layoutdsl.compile.ladders): "first" in
_anneal_order.

The greedy placement and its cycle-block templates construct every real plan whose blocks
have at most 11 rooms and no ladder, most within a second or two (school_wilbraham, a 10-room
block: 0.4 s greedy, 12 s annealed). It constructs none of office_OfficePlan (a 9-room
ladder), office_floor-1024x523 (a 14-room block) and school_stjoseph_scatholichighschool (27)
in 60 s."""

ANNEAL_REPAIR_M = 6.0
"""Violation (metres, layoutdsl.compile.anneal) up to which an annealed geometry is worth
its repair. Measured on office_OfficePlan: annealed geometries 2.2 m from a layout
repaired in 0.5 s, 13.4 m stalled for 34 s; office_floor-1024x523 repaired from 2.3 m (by
whole-plan runs; the core-and-satellites runs of a split plan have a nearer reach of their
own, satellites.REACH_M, and runs beyond it never come here)."""


def _anneal_order(spec: Spec) -> str | None:
    """Where annealed geometries go among the graph geometries of this spec: "alone" for a
    plan the core-and-satellites annealer splits (a cycle block of generate.CORE_BLOCK_ROOMS
    and rooms outside it), "first" for a cycle block of ANNEAL_BLOCK_ROOMS or a ladder,
    "beside" for smaller cycles, None for a spec without cycles (the greedy placement
    constructs those fast), without the annealer installed, or that the annealer does not
    handle (annealable).

    "alone": after its hints, the construction repairs annealed geometries only and leaves
    both cores to the runs. The greedy placement never constructed
    school_stjoseph_scatholichighschool, and its repairs and cycle-block solves halved the
    runs' speed (a 4M-move run took about 37 s beside them, 20-30 s without): measured with
    `bench/generation.py --seeds 4`, 3 of 4 seeds constructed, 0 of 4 beside the greedy
    placement (layoutdsl.compile.anneal_runs); with runs of 2M moves, 6 of seeds 0-7
    (satellites.CORE_MOVES_PER_PAIR)."""
    blocks = cycle_blocks(spec)
    # numba is an optional dependency ('layoutdsl[anneal]'), looked for but not imported
    # here: importing it takes ~0.7 s, a share of a small variant's time limit (measured:
    # `compile --variants 2` of a 3-room spec at 3 s each found nothing on a busy machine
    # when every construction imported it); the annealing imports it when it starts
    if not blocks or not annealable(spec) or importlib.util.find_spec("numba") is None:
        return None
    if core_rooms(spec) is not None:
        return "alone"
    if (max(map(len, blocks)) >= ANNEAL_BLOCK_ROOMS
            or any(find_ladder(block_spec(spec, block)) for block in blocks)):
        return "first"
    return "beside"


def annealable(spec: Spec) -> bool:
    """Specs the annealer (layoutdsl.compile.anneal) handles: rooms, doors, a boundary and
    onB, nothing pinned.

    Obstacles, fixed positions, connection points and clusters pin rooms to places that a
    packing into the bottom-left corner does not know about: those specs keep the greedy
    placement, which places pinned rooms first.
    """
    boundary = spec.boundary
    return (boundary is not None and len(spec.rooms) >= 2 and not boundary.obstacles
            and not spec.positions and not spec.connections and not spec.clusters)


AT_ONCE_ORDERS = ("first", "alone")
"""The orders (_anneal_order) whose annealing starts at once, on two workers; with hints, a
spec of these orders anneals "beside" them instead."""

ANNEAL_DELAY = 2.0
"""Seconds after which a construction of a spec with small cycle blocks starts annealing
(at once if its first geometry fails sooner): school_wilbraham's variants mostly construct
from their first greedy geometry in 1-2 s, and annealing beside them on the same cores
would slow them down."""


def _construction_order(drawn: Spec, has_hints: bool, anneal: bool = True, spare_cores: bool = True) -> str | None:
    """Where a construction of `drawn` (lshape.seeds_spec) puts its annealed geometries:
    _anneal_order, as construct_start's arguments and the spec's hints leave it."""
    order = _anneal_order(drawn) if anneal else None
    if order in AT_ONCE_ORDERS and has_hints:
        # the hints construct most plans in well under a second: no core is taken from them
        # before ANNEAL_DELAY or their first failure
        order = "beside"
    if order == "beside" and not spare_cores:
        # measured on school_wilbraham, `--throughput` with 2 workers on 2 cores: 10
        # variants a minute annealing beside the repairs, 14 without
        order = None
    return order


def start_annealing(spec: Spec, seed: int, deadline: float) -> Annealing | None:
    """The annealing that construct_start(spec, seed=seed) would start at once (a plan of an
    AT_ONCE_ORDERS order without hints), started now, for a caller with other work to do
    first: the compile pipeline builds and probes the thesis' model (1-2 s on a 76-room plan)
    meanwhile. Its runs are those the construction would start, only sooner. None for any
    other spec. Hand it to construct_start, or close it."""
    if spec.boundary is None or not spec.rooms:
        return None
    drawn = lshape.seeds_spec(spec)
    order = _construction_order(drawn, has_hints=hint_geometry(drawn) is not None)
    return Annealing(drawn, seed, deadline, order) if order in AT_ONCE_ORDERS else None


class Annealing:
    """Annealed seed geometries for one construction, computed on the spare cores.

    Greedy geometries are repaired on one core while SCIP holds it; an annealing chain runs
    without the GIL on another. Measured (no hints, seed 0): annealed geometries alone
    construct school_RomainRolland1 in 4 s where the greedy ones take 38 s, while the greedy
    ones construct office_floorplanLOWER and the annealed ones do not. So both run. Every
    greedy geometry the repair gives up on is annealed (`anneal_from`), and a worker with
    nothing to do anneals from scratch (layoutdsl.compile.anneal_runs.AnnealingRuns).

    The annealing starts at once, on two workers, for the plans the greedy placement alone
    has never constructed ("first", and "alone", where the construction waits for it and
    tries no greedy geometry); for the others ("beside"), on one worker, after ANNEAL_DELAY
    or once the first geometry has failed.
    """

    def __init__(self, spec: Spec, seed: int, deadline: float, order: str):
        self.spec, self.seed, self.deadline, self.order = spec, seed, deadline, order
        self.runs = None
        self.closed = False
        self.taken_violation = math.inf
        """The violation of the annealed geometry taken last."""
        self.lock = threading.Lock()
        self.timer = threading.Timer(0.0 if order in AT_ONCE_ORDERS else ANNEAL_DELAY, self.start)
        self.timer.daemon = True
        self.timer.start()

    def start(self) -> None:
        with self.lock:
            if self.runs is None and not self.closed:
                from layoutdsl.compile.anneal_runs import AnnealingRuns

                self.runs = AnnealingRuns(self.spec, self.seed, self.deadline,
                                          workers=2 if self.order in AT_ONCE_ORDERS else 1, log=_debug)

    def anneal_from(self, geometry: dict[str, Rect]) -> None:
        """Anneal from a seed geometry (of the drawn spec) the repair gave up on."""
        self.start()
        self.runs.submit(geometry)

    def promising(self, nearer_than: float = math.inf) -> bool:
        """Whether a finished run is close enough to a layout to repair (and less than
        `nearer_than` metres from one)."""
        return self.runs is not None and self.runs.has_done(
            lambda violation: _repairable(violation) and violation < nearer_than)

    def take(self) -> dict[str, Rect] | None:
        """The finished run nearest a layout, if close enough to repair, or None."""
        return self._chosen(self.runs.pop_done(_repairable) if self.runs is not None else None)

    def wait(self) -> dict[str, Rect] | None:
        """take(), waiting for runs to finish until the deadline."""
        self.start()
        return self._chosen(self.runs.wait(_repairable, self.deadline))

    def _chosen(self, run) -> dict[str, Rect] | None:
        if run is None:
            _debug("annealed geometry: none close enough")
            return None
        geometry, violation, from_geometry = run
        self.taken_violation = violation
        _debug(f"annealed geometry ({'from a greedy one' if from_geometry else 'random start'}): "
               f"{violation:.2f} m from a layout")
        return geometry

    def close(self) -> None:
        with self.lock:
            self.closed = True
            self.timer.cancel()
            if self.runs is not None:
                self.runs.close()


FAR_BETTER = 0.5
"""An annealed geometry's repair gives way to a finished run with less than this share of
its violation (a packing that meets every door, against one 2 m from it, say)."""


def _repairable(violation: float) -> bool:
    return violation <= ANNEAL_REPAIR_M


def _cover_points(spec: Spec, geometry: dict[str, Rect]) -> dict[str, Rect]:
    """Move each room with a position (or connection) so its seed rectangle covers the point.

    The relations then already put the room where the hard constraint wants it, instead of
    leaving the repair to discover that the whole neighbourhood must move.
    """
    points: dict[str, tuple[float, float]] = {p.room: (p.x, p.y) for p in spec.positions}
    for c in spec.connections:
        points.setdefault(c.room, ((c.x1 + c.x2) / 2, (c.y1 + c.y2) / 2))
    if not points:
        return geometry
    moved = dict(geometry)
    for room_id, (px, py) in points.items():
        if room_id in moved:
            x, y, w, h = moved[room_id]
            moved[room_id] = (px - w / 2, py - h / 2, w, h)
    return moved


PERTURBATION = 0.25
"""Largest move of a hint box in a variant's seed geometry, as a fraction of its size."""


def perturbed_hint_geometry(spec: Spec, rng: random.Random) -> dict[str, Rect]:
    """The hints' boxes, each moved by up to PERTURBATION of its size: a variant's seed.

    Rooms that were side by side may now be one above the other, so the repair settles on
    other relations and the variant differs, while the plan's overall shape stays.
    Measured on school_hendersonhighschool (62 rooms): moves of half a room size left the
    repair stuck for every seed; a quarter repairs in < 1 s for most seeds.
    """
    geometry = hint_geometry(spec, shrink=False)
    assert geometry is not None
    moved: dict[str, Rect] = {}
    for room_id, (x, y, w, h) in geometry.items():
        dx = rng.uniform(-PERTURBATION, PERTURBATION) * w
        dy = rng.uniform(-PERTURBATION, PERTURBATION) * h
        moved[room_id] = (x + dx, y + dy, w, h)
    return moved


def construct_geometry(spec: Spec, rng: random.Random) -> dict[str, Rect]:
    """A seed geometry grown from the room graph alone (no hints needed).

    A spring embedding of the adjacency graph (seeded from `rng`) spread over the boundary,
    each room a rectangle of its target size at its node, lying along its longer target
    side or, with probability 1/2, turned. Adjacent rooms end up near each other, which is
    what the relations need; the repair fixes the rest.
    """
    import networkx as nx

    boundary = spec.boundary
    assert boundary is not None
    graph = room_graph(spec)
    fixed_points = {p.room: (p.x, p.y) for p in spec.positions}
    for c in spec.connections:
        fixed_points.setdefault(c.room, ((c.x1 + c.x2) / 2, (c.y1 + c.y2) / 2))
    positions = nx.spring_layout(graph, seed=rng.randrange(2**31), iterations=100)
    xs = [p[0] for p in positions.values()]
    ys = [p[1] for p in positions.values()]
    span_x = (max(xs) - min(xs)) or 1.0
    span_y = (max(ys) - min(ys)) or 1.0
    geometry: dict[str, Rect] = {}
    for room in spec.rooms:
        sizes = RoomSizes.of(room)
        turned = rng.random() < 0.5
        w, h = sizes.targets(not turned)
        if room.id in fixed_points:
            cx, cy = fixed_points[room.id]
        else:
            px, py = positions[room.id]
            cx = w / 2 + (px - min(xs)) / span_x * max(0.0, boundary.w - w)
            cy = h / 2 + (py - min(ys)) / span_y * max(0.0, boundary.h - h)
        geometry[room.id] = (cx - w / 2, cy - h / 2, w, h)
    return spread_apart(geometry, boundary.w, boundary.h, spec.settings.walldim,
                        fixed=set(fixed_points))


def spread_apart(
    geometry: dict[str, Rect],
    width: float,
    height: float,
    walldim: float,
    *,
    fixed: set[str] = frozenset(),
    iterations: int = 300,
) -> dict[str, Rect]:
    """Push overlapping rectangles apart (each along its shallower overlap), inside the box.

    A spring embedding ignores the rooms' sizes, so its rectangles pile up; relations read
    off such a pile are mostly arbitrary. A few hundred rounds of pairwise pushes (numpy,
    O(n^2) per round: fine for a few hundred rooms) leave a geometry whose relations are
    nearly right, so the repair has little left to do. Rooms in `fixed` do not move.
    """
    import numpy as np

    ids = list(geometry)
    if len(ids) < 2:
        return dict(geometry)
    rects = np.array([geometry[i] for i in ids], dtype=float)
    half_w, half_h = rects[:, 2] / 2, rects[:, 3] / 2
    cx, cy = rects[:, 0] + half_w, rects[:, 1] + half_h
    movable = np.array([0.0 if i in fixed else 1.0 for i in ids])
    need_x = half_w[:, None] + half_w[None, :] + walldim
    need_y = half_h[:, None] + half_h[None, :] + walldim
    upper = np.triu(np.ones((len(ids), len(ids)), dtype=bool), 1)
    for _ in range(iterations):
        dx = cx[None, :] - cx[:, None]
        dy = cy[None, :] - cy[:, None]
        over_x = need_x - np.abs(dx)
        over_y = need_y - np.abs(dy)
        clash = (over_x > 0) & (over_y > 0) & upper
        if not clash.any():
            break
        along_x = clash & (over_x <= over_y)
        along_y = clash & ~along_x
        # ties (same centre) are pushed by index order, so the result stays deterministic
        sign_x = np.where(dx >= 0, 1.0, -1.0)
        sign_y = np.where(dy >= 0, 1.0, -1.0)
        push_x = np.where(along_x, over_x * sign_x / 2, 0.0)
        push_y = np.where(along_y, over_y * sign_y / 2, 0.0)
        cx += (push_x.sum(axis=0) - push_x.sum(axis=1)) * movable * 0.5
        cy += (push_y.sum(axis=0) - push_y.sum(axis=1)) * movable * 0.5
        cx = np.clip(cx, half_w, np.maximum(half_w, width - half_w))
        cy = np.clip(cy, half_h, np.maximum(half_h, height - half_h))
    return {
        room_id: (float(cx[k] - half_w[k]), float(cy[k] - half_h[k]),
                  float(rects[k, 2]), float(rects[k, 3]))
        for k, room_id in enumerate(ids)
    }
