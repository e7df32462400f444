"""What the model is built from: the formulation switches, the spec's bounds, the vocabulary.

`ModelData` gathers, once per build, the numbers every equation unit of `equations.py`
needs (boundary, wall, per-room bounds, big-M), so each unit reads like its equation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from layoutdsl.layout.geometry import OPPOSITE_SIDE, SIDES
from layoutdsl.syntax.ast import Obstacle, Room, Spec

__all__ = ["OPPOSITE_SIDE", "SIDES"]  # the four ω of (5.8), re-exported for the model's users

BOUNDARY_SIDES = ("left", "right", "bottom", "top")
"""Which side of the boundary an onB room touches (the four β of (5.12))."""


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
    cover_up_to_target: bool = True
    """E_cover (5.2) counts each room's area only up to its target area (target w x target
    h). The thesis' term rewards every square metre a room covers, so the optimum of (5.1)
    grows each room with space around it until the size error balances λ_cover: with the
    default λ_cover = 0.1 a room's side settles 0.05 x its other side past its target, so a
    40 m corridor's width grows by 2 m, and generated buildings came out 1.10-1.17 x the
    original's room area on sparse plans (bench/results/generation-60s.txt). Capped, the
    term still pulls rooms below their targets up to them (harder than the size error
    alone, whose pull vanishes near the target) and the optimum of a room with space
    around it is its target size."""


THESIS_AS_WRITTEN = Formulation(
    tight_big_m=False, prune_pairs=False, symmetry_breaking=False, adjacency_links=False,
    long_short=False, cover_up_to_target=False,
)
"""The formulation of §5.5.1 with only the corrections needed for correctness."""


@dataclass(frozen=True, slots=True)
class Bounds:
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


def room_bounds(spec: Spec) -> dict[str, Bounds]:
    """Interval bounds of x, y, w, h per room, from sizes, boundary, positions and connections."""
    assert spec.boundary is not None, "build_model needs a checked spec with a boundary"
    width, height = spec.boundary.w, spec.boundary.h
    bounds: dict[str, Bounds] = {}
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
        bounds[room.id] = Bounds((w_lo, w_hi), (h_lo, h_hi), (x_lo, x_hi), (y_lo, y_hi), (width, height))
    return bounds


def orientation_bounds(room: Room, o: int) -> tuple[float, float, float, float]:
    """(min_w, max_w, min_h, max_h) of the placed room for orientation o (0: w is the long side)."""
    lo_short, lo_long = sorted((room.min_w, room.min_h))
    hi_short, hi_long = sorted((room.max_w, room.max_h))
    if o == 0:
        return (lo_long, hi_long, lo_short, hi_short)
    return (lo_short, hi_short, lo_long, hi_long)


def target_area(room: Room) -> float:
    """The room's target area: the most E_cover counts with Formulation.cover_up_to_target."""
    return room.target_w * room.target_h


def orientation_targets(room: Room, o: int) -> tuple[float, float]:
    """(target w, target h) for orientation o: the long target goes to the long side."""
    short, long = sorted((room.target_w, room.target_h))
    return (long, short) if o == 0 else (short, long)


def interchangeable_groups(spec: Spec) -> list[list[str]]:
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


@dataclass(frozen=True, slots=True)
class ModelData:
    """The numbers of one spec that the equations share (derived once per build_model)."""

    spec: Spec
    formulation: Formulation
    width: float
    height: float
    wall: float
    bounds: dict[str, Bounds]
    rooms: dict[str, Room]
    obstacles: dict[str, Obstacle]
    lo: dict[str, tuple[float, float]]
    """Per room: (smaller, larger) of its two minimum sizes."""
    hi: dict[str, tuple[float, float]]
    """Per room: (smaller, larger) of its two maximum sizes."""
    global_m: float
    """The thesis' single M: at least every per-constraint value."""
    defer_separations: bool = False
    """(5.8) is built without its constraints; equations.settle_separations adds those of
    the relations a start puts on the model (a polish that searches nothing else)."""

    def big_m(self, value: float) -> float:
        """The big-M of one constraint: `value` (its worst violation) or the thesis' single M."""
        return max(value, 0.0) if self.formulation.tight_big_m else self.global_m

    def side_bounds(self, r: str) -> tuple[float, float]:
        """Bounds of room r's long and short side variables."""
        bounds = self.bounds[r]
        return (min(bounds.w[0], bounds.h[0]), max(bounds.w[1], bounds.h[1]))


def model_data(spec: Spec, formulation: Formulation) -> ModelData:
    """The shared numbers of a checked spec."""
    assert spec.boundary is not None, "build_model needs a checked spec with a boundary"
    width, height = float(spec.boundary.w), float(spec.boundary.h)
    wall = float(spec.settings.walldim)
    max_ar = max([r.max_ar for r in spec.rooms if not r.is_corridor] + [1.0])
    max_need = max([a.door / spec.settings.door_utilization for a in spec.adjacencies] + [0.0])
    # the thesis' single M: at least every per-constraint value below (aspect ratio needs
    # maxAR times a side, adjacency a side plus the shared wall, non-overlap a side plus a wall)
    global_m = max(width, height) * max(max_ar, 1.0) + max(width, height) + wall + max_need
    return ModelData(
        spec=spec, formulation=formulation, width=width, height=height, wall=wall,
        bounds=room_bounds(spec),
        rooms={room.id: room for room in spec.rooms},
        obstacles={ob.id: ob for ob in spec.boundary.obstacles},
        lo={r.id: (min(r.min_w, r.min_h), max(r.min_w, r.min_h)) for r in spec.rooms},
        hi={r.id: (min(r.max_w, r.max_h), max(r.max_w, r.max_h)) for r in spec.rooms},
        global_m=global_m,
    )  # fmt: skip
