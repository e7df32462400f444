"""The relation model: rooms with their pairwise relations fixed (or nearly), solved by SCIP.

The generator (layoutdsl.compile) hands over a geometry: rectangles that may overlap or miss
a door by a few metres. From it each pair of rooms (and room and obstacle) gets its
*relation*: the direction along the axis that separates them most, in the geometry's centre
order, so the "left of" and "below" relations are acyclic; each room's orientation follows
its rectangle. With every relation fixed the model is an LP.

`repair` then works round by round: the LP is solved *elastically* (each pair's constraints
may be stretched at a cost; sizes, aspect ratios, boundary, onB, positions, connections and
clusters stay hard). The pairs it had to stretch, and the pairs near their rooms, get more
freedom for the next round: one binary (either axis), then all four directions, and after a
stall the rooms' graph neighbours join in. Each round is a small MIP warm-started from the
previous solution, stopped at zero stretch. With zero stretch the relations are final: one
more LP brings the sizes to their targets (the *sizing*), and the rectangles are checked
against every hard constraint before they are returned.

Every MIP stops at a node limit the caller gives (work, not time): the same geometry gives
the same rectangles on any machine. The deadline is only an outer cap.
"""

from __future__ import annotations

import math
import os
import random
import sys
import time
from dataclasses import dataclass, replace
from collections.abc import Callable

from layoutdsl.layout import lshape
from layoutdsl.layout.geometry import SIDES, Rect, RoomSizes, gap_between, layout_from_rects, rooms_between, separations
from layoutdsl.solve.quiet import native_output_silenced
from layoutdsl.syntax.ast import Room, Spec


_LOADED = time.monotonic()


def _debug(message: str) -> None:
    if os.environ.get("LAYOUTDSL_DEBUG_REPAIR"):
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


def _add_wall_or_space(model, problem: _Problem, boxes: dict[str, _Box], pair: Pair, direction: str,
                       width: float):
    """The gap between the pair (a on the `direction` side of b) is a wall exactly, or at
    least `width`: one binary chooses, and is returned (1: opened)."""
    a, b = pair
    gap = -_excess(boxes[a], boxes[b], direction, 0.0)
    space = model.addVar(f"u_{a}_{b}", vtype="B")
    big = problem.big_m
    model.addCons(gap <= problem.gap(pair) + SAFETY + big * space)
    model.addCons(gap >= width + SAFETY - big * (1 - space))
    return space


OPEN_GAP_COST = 0.5
"""Objective (metres of size deviation) an opened gap costs against a shut one: a space
between rooms no door leads to is a void, so a wall is preferred when the sizes allow."""


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
    deadline: float,
    nodes: int,
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
    current = start.rects if start is not None else geometry
    # a repair round keeps each room near where it starts; the final LP (relations fixed)
    # may move rooms as far as their sizes need
    reach = _reach(start) if mode == "repair" and local else None
    active = _near_options(problem, current, options, reach) if local else dict(options)
    while True:
        outcome = _solve_active(problem, active, mode=mode, seconds=max(0.05, deadline - time.monotonic()),
                                nodes=nodes, seed=seed, orientations=orientations, turnable=turnable, start=start,
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
    nodes: int,
    seed: int,
    orientations: dict[str, bool],
    turnable: frozenset[str],
    start: _Outcome | None,
    feasibility_emphasis: bool,
    within: tuple[dict[str, Rect], float | None],
    gaps: dict[Pair, float] | None = None,
    pulls: dict[Pair, float] | None = None,
) -> _Outcome | None:
    """One SCIP solve of the model with the pairs of `options`, each room within a reach of
    its rectangle (`within`: rectangles, reach; None: anywhere); see _solve_model. `gaps`:
    pairs whose gap must be a wall or at least the given width (`without_slivers`);
    `pulls`: pairs whose gap costs the given weight per metre (`compacted`)."""
    repair = mode == "repair"
    from pyscipopt import quicksum

    # the variables and constraints are added in one fixed order (rooms, boundary sides,
    # points, clusters, pairs): SCIP's search, and so the layout, depends on that order
    model = _scip_model(repair, seconds, nodes, seed, feasibility_emphasis)
    rooms = _add_rooms(model, problem, orientations, turnable, with_deviation=not repair)
    if within[1] is not None:
        _add_reach(model, rooms.boxes, *within)
    _add_on_boundary(model, problem, rooms.boxes)
    _add_covered_points(model, problem.spec, rooms.boxes)
    _add_clusters(model, problem, rooms.boxes)
    pairs = _add_pair_relations(model, problem, rooms.boxes, options)
    opened = [_add_wall_or_space(model, problem, rooms.boxes, pair, options[pair][0], width)
              for pair, width in (gaps or {}).items()]

    if repair:
        model.setObjective(quicksum(pairs.penalty), "minimize")
    else:
        pulled = [weight * -_excess(rooms.boxes[a], rooms.boxes[b], options[(a, b)][0], 0.0)
                  for (a, b), weight in (pulls or {}).items()]
        model.setObjective(quicksum(rooms.deviation) + FINAL_STRETCH_COST * quicksum(pairs.penalty)
                           + OPEN_GAP_COST * quicksum(opened) + quicksum(pulled), "minimize")
    if start is not None:
        _add_start(model, start, options)
    # without the GIL: the generator's annealing chains may run beside it; SoPlex's warnings
    # (written from C) stay off the terminal for every caller, not only compile's
    with native_output_silenced():
        model.optimizeNogil()
    status = model.getStatus()
    _debug(f"    {mode} model: {status} in "
           f"{model.getSolvingTime():.2f}s, {model.getNTotalNodes()} nodes, {model.getNLPIterations()} LP "
           f"iterations, {len(options)} pairs, {len(pairs.binaries)} free, {model.getNSols()} sols")
    if model.getNSols() == 0:
        return None
    return _read_outcome(model, problem.spec, options, rooms, pairs, orientations)


def _scip_model(repair: bool, seconds: float, nodes: int, seed: int, feasibility_emphasis: bool):
    """An empty, quiet SCIP model with the relation model's limits and tolerances: `nodes`
    decides where it stops, `seconds` (the time left to the compile's deadline) is only the
    outer cap."""
    from pyscipopt import Model

    model = Model("relations")
    model.hideOutput()
    model.setParam("display/verblevel", 0)
    model.setParam("limits/time", max(0.05, seconds))
    model.setParam("limits/nodes", max(1, nodes))
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
        # inside up to the boundary itself: an onB room's far side must reach it, and the
        # verifier's tolerance (1e-6 m) covers SCIP's on the outside
        model.addCons(x + w <= width)
        model.addCons(y + h <= height)
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
        model.addCons(box.x + box.w >= width - big_m * (1 - sides[1]))
        model.addCons(box.y <= big_m * (1 - sides[2]))
        model.addCons(box.y + box.h >= height - big_m * (1 - sides[3]))
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


MAX_STALLS = 3
"""Rounds without progress after which a seed geometry is given up."""

FREE_RADII = (1.0, 3.0, 6.0, 12.0, 25.0)
"""Metres around a conflict within which pairs get their relation freed, round by round."""


STRETCH_NOISE_M = 1e-4
"""Stretch (metres) below which a round counts as unstretched: the SAFETY margins of a tight
chain of rooms, not a conflict."""

NEAR_DONE_M = 1.0
"""A geometry within this many metres of a layout gets the patience of MAX_STALLS stalls."""


@dataclass(frozen=True)
class RepairLimits:
    """The work a repair may do: nodes of each round's MIP, of the final sizing MIP, and
    stalled rounds before the geometry is given up; `deadline` (time.monotonic()) is only
    the outer cap."""

    deadline: float
    round_nodes: int
    final_nodes: int
    max_stalls: int = MAX_STALLS
    max_rounds: int = len(FREE_RADII) * 3


def repair(
    problem: _Problem,
    geometry: dict[str, Rect],
    limits: RepairLimits,
    seed: int,
    *,
    free_defects: bool = False,
    local: bool = False,
    rebox: Callable[[dict[str, Rect]], _Problem] | None = None,
) -> dict[str, Rect] | None:
    """Relations from the geometry, repaired round by round until they admit a layout, then
    sized: rectangles that pass `check_start`, or None.

    Each round solves the elastic model; the pairs it had to stretch, and the pairs close to
    their rooms, get more freedom (one axis -> either axis -> any direction) for the next
    round, which starts from the previous solution. Zero stretch ends the repair; a final
    LP with those relations then brings the sizes towards their targets. `free_defects`:
    where the geometry has rooms overlapping or doors unmet, the first round may already
    choose the axis. `local`: the geometry is close to a layout (the hints), and each
    round's moves stay local (_solve_model). `rebox` (hint geometries of a spec with
    L-rooms): the problem with each L-room's doors on its boxes nearest their neighbours in
    the given rectangles (_reboxed).
    """
    options = _first_options(problem, geometry, free_defects)
    start: _Outcome | None = None
    neighbours = problem.spec.door_neighbours()
    best_total = math.inf
    stalls = 0
    orientations = {
        room_id: rect[2] >= rect[3] for room_id, rect in geometry.items()
    }
    turnable: set[str] = set()
    for round_index in range(limits.max_rounds):
        if limits.deadline - time.monotonic() <= 0.05:
            return None
        outcome = _solve_model(problem, geometry, options, mode="repair", deadline=limits.deadline,
                               nodes=limits.round_nodes, seed=seed,
                               orientations=orientations, turnable=frozenset(turnable),
                               start=start, feasibility_emphasis=stalls > 0, local=local)
        if outcome is None:
            return None
        if max(outcome.stretched.values(), default=0.0) < STRETCH_NOISE_M:
            rects = _final_layout(problem, geometry, outcome, limits, seed, local)
            if rects is not None or not outcome.stretched:
                return rects
        _debug(f"  round {round_index}: {len(outcome.stretched)} stretched, "
               f"total {sum(outcome.stretched.values()):.2f} m: "
               + ", ".join(f"{a}-{b} {options[(a, b)]} {v:.2f}"
                           for (a, b), v in sorted(outcome.stretched.items())))
        total = sum(outcome.stretched.values())
        stalled = total > 0.95 * best_total
        best_total = min(best_total, total)
        if stalled:
            stalls += 1
            # a geometry within a metre of a layout is worth the most patience
            patience = MAX_STALLS if total < NEAR_DONE_M else limits.max_stalls
            if stalls > patience:
                # a local minimum of the stretch: another geometry does better than ever
                # wider (and slower) MIPs around this one
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


def _final_layout(problem: _Problem, geometry: dict[str, Rect], outcome: _Outcome,
                  limits: RepairLimits, seed: int, local: bool = False) -> dict[str, Rect] | None:
    """The relations of a zero-stretch round with the sizes brought towards their targets
    (else that round's own rectangles), if they pass `check_start`; None otherwise."""
    final_options = _without_implied(problem, {pair: (direction,) for pair, direction in outcome.chosen.items()},
                                     keep=set())
    final = _solve_model(problem, geometry, final_options, mode="final",
                         deadline=limits.deadline, nodes=limits.final_nodes,
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


# ---------------------------------------------------------------------------------------
# Slivers: gaps between rooms that are neither wall nor space
# ---------------------------------------------------------------------------------------

SLIVER_ROUNDS = 4
"""Solves of `without_slivers`: each adds the pairs the last one left a sliver between."""

SLIVER_MARGIN = 0.5
"""Metres beyond usable width within which facing pairs get their binary from the first
solve on (measured on cml_new_58: adding only the slivers found, one new sliver appeared
per solve and four solves were not enough)."""


def without_slivers(spec: Spec, rects: dict[str, Rect], *, usable_width: float, deadline: float,
                    nodes: int, seed: int) -> dict[str, Rect] | None:
    """The rectangles (a layout of the spec; an L-room's box and arm by their own ids) with
    every gap between two rooms' facing walls a wall exactly or at least `usable_width`
    wide, the sizes as near the rectangles' own as that allows; None when the rectangles
    have no sliver, or when their relations do not allow it within SLIVER_ROUNDS solves.

    Every pair keeps its relation (the LP of the final sizing); each pair that faces the
    other across a sliver gets one binary: shut to a wall, or open to usable width. Closing
    one sliver can open another between rooms that moved, so the pairs add up over rounds.
    """
    from layoutdsl.layout.realism import facing_gaps, find_slivers

    # the sizes the layout has are the targets: whatever chose them (the thesis' objective,
    # polished by SCIP) keeps its say, and rooms move and resize only as the gaps need
    problem, geometry, options, orientations = _relations_fixed(
        spec, rects, lambda room, rect: replace(room, target_w=rect[2], target_h=rect[3]))
    joined = {frozenset(pair) for pair in problem.joins}
    gaps: dict[Pair, float] = {}
    current = geometry
    for round_index in range(SLIVER_ROUNDS + 1):
        spaces = _box_spaces(current)
        found = [sliver for sliver in find_slivers(spaces, problem.walldim, usable_width)
                 if frozenset((sliver.a, sliver.b)) not in joined]
        if not found:
            return None if current is geometry else current
        if round_index == 0:
            # the pairs that face each other nearly a usable width apart or closer: shutting
            # one sliver moves rooms, and these are the gaps that become the next ones
            found += [gap for gap in facing_gaps(spaces, problem.walldim, usable_width + SLIVER_MARGIN)
                      if frozenset((gap.a, gap.b)) not in joined and gap not in found]
        if len(gaps) and all(_ordered(problem, s.a, s.b) in gaps for s in found):
            return None  # the binaries allowed it and SCIP's tolerance did not: give up
        for sliver in found:
            gaps[_ordered(problem, sliver.a, sliver.b)] = usable_width
        if deadline - time.monotonic() <= 0.05:
            return None
        current = _sized_again(problem, options, orientations, current, deadline=deadline, nodes=nodes, seed=seed,
                               gaps=gaps)
        if current is None:
            return None
    return None


def _sized_again(problem: _Problem, options: dict[Pair, tuple[str, ...]], orientations: dict[str, bool],
                 current: dict[str, Rect], *, deadline: float, nodes: int, seed: int,
                 gaps: dict[Pair, float] | None = None,
                 pulls: dict[Pair, float] | None = None) -> dict[str, Rect] | None:
    """One final-mode solve of a layout's relations fixed (_relations_fixed), with `gaps` or
    `pulls` (_solve_active); None unless it needs no stretch and its rectangles pass
    check_start against the spec the problem is checked against."""
    options = _without_implied(problem, options, keep=set(gaps or ()) | set(pulls or ()))
    outcome = _solve_active(problem, options, mode="final", seconds=max(0.05, deadline - time.monotonic()),
                            nodes=nodes, seed=seed, orientations=orientations, turnable=frozenset(),
                            start=None, feasibility_emphasis=False, within=(current, None), gaps=gaps, pulls=pulls)
    if outcome is None or max(outcome.stretched.values(), default=0.0) > STRETCH_NOISE_M:
        return None
    if check_start(problem.checked or problem.spec, outcome.rects):
        return None
    return outcome.rects


def _without_implied(problem: _Problem, options: dict[Pair, tuple[str, ...]],
                     keep: set[Pair]) -> dict[Pair, tuple[str, ...]]:
    """`options` of fixed relations without the pairs whose relation the others imply.

    With every relation fixed, a left of b and b left of c put a left of c, a wall and b's
    width apart: the row for (a, c) only repeats what the rows for (a, b) and (b, c) say.
    Such a pair is left out when a chain of two or more other fixed room-room relations
    along the same axis leads from one to the other (the transitive reduction of each
    axis' order); doors, the two boxes of an L, obstacles and the pairs in `keep` always
    stay. A layout of rooms side by side keeps a few pairs per room instead of all of them
    (office_floorplanMAIN, 55 boxes: 1485 pairs -> about 245), so the final sizing and each
    realism pass solve an LP a sixth of the size with the same feasible layouts (a variant's
    compile after its first layout, seed 0: 6.3 -> 3.7 s). Elastic (repair) rounds keep
    every pair: there a stretched relation would let an implied one break unpriced."""
    import networkx as nx

    axes = {"x": nx.DiGraph(), "y": nx.DiGraph()}
    for pair, allowed in options.items():
        if len(allowed) != 1 or pair in problem.joins or any(t in problem.obstacles for t in pair):
            continue
        a, b = pair
        direction = allowed[0]
        axis = "x" if direction in ("left", "right") else "y"
        first, second = (a, b) if direction in ("left", "below") else (b, a)
        axes[axis].add_edge(first, second)
    needed: set[tuple[str, str]] = set()
    for graph in axes.values():
        if not nx.is_directed_acyclic_graph(graph):
            return options
        needed |= set(nx.transitive_reduction(graph).edges)
    return {pair: allowed for pair, allowed in options.items()
            if len(allowed) != 1 or pair in problem.joins or pair in keep
            or frozenset(pair) in problem.walls or any(t in problem.obstacles for t in pair)
            or pair in needed or pair[::-1] in needed}


def _box_spaces(rects: dict[str, Rect]) -> list:
    """The rectangles as layout.realism spaces (one box each, id = the rectangle's)."""
    from layoutdsl.layout.realism import Space

    return [Space(room_id, "", "R", ((x, y, x + w, y + h),)) for room_id, (x, y, w, h) in rects.items()]


def _relations_fixed(spec: Spec, rects: dict[str, Rect], anchor: Callable[[Room, Rect], Room]):
    """(problem, geometry, options, orientations) for sizing a layout again with every pair's
    relation and every room's orientation as the rectangles have them: the rectangles (an
    L-room's box and arm by their own ids) of the problem's rooms, each room replaced by
    anchor(room, its rectangle); results are checked against `spec` itself."""
    problem = boxed_problem(spec, rects) if spec.arms else problem_of(spec)
    geometry = {room.id: rects[room.id] for room in problem.spec.rooms}
    anchored = replace(problem.spec, rooms=tuple(anchor(room, geometry[room.id]) for room in problem.spec.rooms))
    problem = replace(problem, spec=anchored, checked=problem.checked or spec)
    options: dict[Pair, tuple[str, ...]] = {
        pair: problem.axis_choices(geometry, pair)[:1] for pair in problem.pairs
    }
    for pair in problem.joins:
        options[pair] = (lshape.join_option(geometry[pair[0]], geometry[pair[1]]),)
    orientations = {room_id: rect[2] >= rect[3] for room_id, rect in geometry.items()}
    return problem, geometry, options, orientations


def _ordered(problem: _Problem, a: str, b: str) -> Pair:
    return (a, b) if problem.order[a] < problem.order[b] else (b, a)


def problem_of(spec: Spec) -> _Problem:
    """The repair's problem for a spec of rectangular rooms."""
    return _Problem.of(spec)


def boxed_problem(spec: Spec, rects: dict[str, Rect], crossing=None) -> _Problem:
    """The repair's problem for a spec with L-rooms, each L drawn as its two boxes, with each
    of its doors on the box nearest the neighbour in `rects`; `crossing`:
    lshape.crossings(spec), computed once by a caller that reboxes often."""
    boxes, joins = lshape.boxes_spec(spec, rects)
    return _Problem.of(boxes, joins=joins, checked=spec,
                       crossing=lshape.crossings(spec) if crossing is None else crossing)


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


PULL_WEIGHT = 1.0
"""Objective per m² of gap across an enclosed void between two rooms that face each other
(gap x facing length), against 1 per metre (x rho_error) a side moves from its size: rooms
move to close a void, and grow into it where their bounds allow (never shrink: compacted).
Measured (seed 0, first layouts, pulling across every void at once): 0.2 and 1.0 gave
about the same voids on school_Neulengbach1 (39 -> 19 % of room area) and school_wilbraham
(12 -> 8 / 7 %); 1.0 grew the rooms more (room area 0.88 -> 0.96 / 0.89 -> 0.94 of the
original's)."""

PULL_RADIUS = 30.0
"""Metres apart beyond which two facing rooms do not pull on each other."""

COMPACT_SOLVES = 6
"""Solves of compacted at most, each pulling across one more void (or the same one again:
a closed void can leave a smaller one between rooms that moved)."""


def compacted(spec: Spec, rects: dict[str, Rect], *, usable_width: float, deadline: float, nodes: int,
              seed: int) -> dict[str, Rect] | None:
    """The rectangles with the rooms that face each other across an enclosed void pulled
    together as far as the relations allow (linear programs: the relations fixed, no room
    smaller than its rectangle); None when that leaves no less void. A sliver that pulling
    opens is shut or opened (without_slivers); where it cannot be, the solve is not kept."""
    from layoutdsl.layout.realism import facing_gaps, void_area, voids_at

    # the sizes the layout has are the least each room keeps: closing a void by shrinking
    # the rooms around it would only trade the void for smaller rooms
    problem, geometry, options, orientations = _relations_fixed(spec, rects, _least_kept)
    joined = {frozenset(pair) for pair in problem.joins}
    void_before = void_area(_box_spaces(geometry))

    def pulled_together(all_first: bool) -> tuple[float, dict[str, Rect]]:
        current, void = geometry, void_before
        pulls: dict[Pair, float] = {}
        solves = 0
        while void > 0.0 and solves < COMPACT_SOLVES and deadline - time.monotonic() > 0.05:
            spaces = _box_spaces(current)
            gaps = [gap for gap in facing_gaps(spaces, problem.walldim, PULL_RADIUS)
                    if frozenset((gap.a, gap.b)) not in joined and gap.width > problem.walldim + 1e-3
                    and not rooms_between(current, gap.a, gap.b)]
            centres = [_gap_centre(current[gap.a], current[gap.b]) for gap in gaps]
            across: dict[tuple[float, int], dict[Pair, float]] = {}
            for gap, (label, area) in zip(gaps, voids_at(spaces, centres)):
                if label:
                    across.setdefault((-area, label), {})[_ordered(problem, gap.a, gap.b)] = PULL_WEIGHT * gap.length
            every = {pair: weight for key in sorted(across) for pair, weight in across[key].items()}
            each = [across[key] for key in sorted(across)] if len(across) > 1 else []
            kept = False
            for added in ([every] + each) if all_first else (each + [every]):
                if not set(added) - set(pulls) or solves >= COMPACT_SOLVES:
                    continue
                solves += 1
                pulled = _pulled(problem, options, orientations, {**pulls, **added}, current, spec, joined,
                                 usable_width, deadline, nodes, seed)
                after = None if pulled is None else void_area(_box_spaces(pulled))
                _debug(f"  compact: void {void:.1f} -> {after} m2 ({len(added)} pairs pulled)")
                if after is not None and after < void - 1e-9:
                    pulls.update(added)
                    current, void, kept = pulled, after, True
                    break
            if not kept:
                break
        return void, current

    # pulling on the pairs across every void at once can close one void's mouth while
    # another shrinks, and pulling across one void at a time (the largest first) can stop
    # short: both are tried, and the one that leaves less void is kept
    void, current = min((pulled_together(all_first) for all_first in (True, False)), key=lambda found: found[0])
    return None if current is geometry else current


def _pulled(problem: _Problem, options, orientations, pulls: dict[Pair, float], current: dict[str, Rect],
            spec: Spec, joined, usable_width: float, deadline: float, nodes: int,
            seed: int) -> dict[str, Rect] | None:
    """One solve of compacted: the rectangles with `pulls` on, verified and without slivers
    (None when the relations do not allow it)."""
    from layoutdsl.layout.realism import find_slivers

    pulled = _sized_again(problem, options, orientations, current, deadline=deadline, nodes=nodes, seed=seed,
                          pulls=pulls)
    if pulled is not None and any(frozenset((sliver.a, sliver.b)) not in joined
                                  for sliver in find_slivers(_box_spaces(pulled), problem.walldim, usable_width)):
        pulled = without_slivers(spec, pulled, usable_width=usable_width, deadline=deadline, nodes=nodes, seed=seed)
    return pulled


def _gap_centre(a: Rect, b: Rect) -> tuple[float, float]:
    """The middle of the gap between two rectangles that face each other."""
    x1, y1, x2, y2 = gap_between(a, b)
    return ((x1 + x2) / 2, (y1 + y2) / 2)


def _least_kept(room: Room, rect: Rect) -> Room:
    """The room with its rectangle's sizes as targets and (a hair below, for SCIP's SAFETY
    margins) as the least it may become, within its own bounds in either orientation."""
    _x, _y, w, h = rect
    sizes = RoomSizes.of(room)
    long_side, short_side = max(w, h), min(w, h)
    least_long = max(sizes.lo_long, min(long_side - 4 * SAFETY, sizes.hi_long))
    least_short = max(sizes.lo_short, min(short_side - 4 * SAFETY, sizes.hi_short))
    min_w, min_h = (least_long, least_short) if w >= h else (least_short, least_long)
    return replace(room, target_w=w, target_h=h, min_w=min_w, min_h=min_h)
