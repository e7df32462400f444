"""The generator: one way from a checked spec to a first layout that passes verification.

    structure    -> can the room graph be drawn at all?          (structure.py)
    hints        -> the original plan's boxes, when the spec keeps its arrangement
    initial      -> a sequence pair read off the room graph      (initial.py)
    schedule     -> annealing: moves, one cost, work limits      (schedule.py, moves.py, cost.py)
    sizing       -> relations fixed, SCIP's LP/MIP finds sizes   (layoutdsl.solve.relations)
    verify       -> the independent verifier                     (layoutdsl.layout.verify)

A spec that keeps its arrangement (`hints`, from `import --keep-arrangement`) is sized from
the original boxes first. Otherwise, and when that fails, each round of the schedule anneals
CHAINS sequence-pair states from new spring embeddings of the room graph, with more moves
than the round before; its best state, when within `repair_max_violation_m` of a layout, is
packed and handed to the sizing stage, whose relation model meets every door exactly, keeps
every other pair a wall apart and brings the sizes near their targets. The first rectangles
that pass `check_start` are the answer. Every limit is work (budgets.WORK); the deadline
only cuts a compile off, and the result then says so (`cut_off`).

A spec without a boundary of its own (`boundary.chosen`), or a compile allowed to grow a
given one (`grow_boundary`), treats the outline as a guide only (cost.CHOSEN_OVERFLOW_WEIGHT);
the boundary is then drawn round the annealed packing, never smaller than the one given,
and `Generated.boundary` reports it.
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass, replace

from layoutdsl.compile import initial, schedule
from layoutdsl.compile.budgets import WORK
from layoutdsl.compile.representation import Rooms
from layoutdsl.layout import lshape
from layoutdsl.layout.geometry import Rect
from layoutdsl.solve.relations import (
    RepairLimits,
    boxed_problem,
    hint_geometry,
    perturbed_hint_geometry,
    problem_of,
    repair,
)
from layoutdsl.syntax.ast import Spec

HINT_SHRINKS: tuple[bool | float, ...] = (False, True)
"""Hint geometries in the order tried: the original boxes, then boxes shrunk to target."""

BOUNDARY_MARGIN = 1.0
"""Share of slack (1.0 = none) of a boundary drawn round an annealed packing; the sizing
stage may use only what the packing used."""


@dataclass(frozen=True)
class Generated:
    """What the generator found: rectangles (None: nothing within its work limits), the spec
    they are for (its boundary may have been chosen or grown), and how much work it took."""

    rects: dict[str, Rect] | None
    spec: Spec
    source: str
    """'hints' or 'annealed' (or '' without rectangles)."""
    rounds: int = 0
    moves: int = 0
    cut_off: bool = False
    """The wall clock cut the generator off before its work limits."""
    grown: tuple[float, float] | None = None
    """(width, height) of a boundary grown beyond the spec's (None: not grown)."""
    unmet: tuple[tuple[str, str, float], ...] = ()
    """Without rectangles: the doors the closest annealed arrangement left unmet, (room,
    room, metres) worst first; they say where the room graph is hard to draw."""


def generate(spec: Spec, *, seed: int = 0, deadline: float | None = None, use_hints: bool = True,
             perturb_hints: bool = False, grow_boundary: bool = False,
             max_rounds: int | None = None) -> Generated:
    """A first layout of the spec (see the module docstring). `perturb_hints`: the hints'
    boxes moved a little first (variants that stay near the original plan); `max_rounds`:
    fewer rounds than budgets.WORK's (variants try another seed sooner)."""
    if spec.boundary is None or not spec.rooms:
        return Generated(None, spec, "")
    if deadline is None:
        deadline = time.monotonic() + 3600.0
    limits = RepairLimits(deadline=deadline, round_nodes=WORK["repair_round_nodes"],
                          final_nodes=WORK["final_nodes"])
    rng = random.Random(seed)
    drawn = lshape.seeds_spec(spec)
    if use_hints and hint_geometry(drawn) is not None:
        found = _from_hints(spec, drawn, rng, seed, replace(limits, round_nodes=WORK["hint_round_nodes"]),
                            perturb_hints)
        if found is not None:
            return Generated(found, spec, "hints")
    return _annealed(spec, drawn, rng, seed, limits, grow_boundary,
                     max_rounds if max_rounds is not None else WORK["max_rounds"])


def _from_hints(spec: Spec, drawn: Spec, rng: random.Random, seed: int, limits: RepairLimits,
                perturb: bool) -> dict[str, Rect] | None:
    geometries = [perturbed_hint_geometry(drawn, rng)] if perturb else []
    geometries += [hint_geometry(drawn, shrink=shrink) for shrink in HINT_SHRINKS]
    crossing = lshape.crossings(spec) if spec.arms else None
    for geometry in geometries:
        if time.monotonic() >= limits.deadline:
            return None
        geometry = _with_pinned_points(spec, geometry)
        problem, rebox = problem_of(spec), None
        if spec.arms:
            geometry = lshape.seed_arms(spec, geometry, rng, hints=True)
            problem = boxed_problem(spec, geometry, crossing)
            rebox = lambda rects: boxed_problem(spec, rects, crossing)  # noqa: E731
        rects = repair(problem, geometry, limits, seed, local=True, rebox=rebox)
        if rects is not None:
            return rects
    return None


def _annealed(spec: Spec, drawn: Spec, rng: random.Random, seed: int, limits: RepairLimits,
              grow_boundary: bool, max_rounds: int) -> Generated:
    boundary = spec.boundary
    assert boundary is not None
    outline = (boundary.w, boundary.h)
    soft = grow_boundary or boundary.chosen
    sides = initial.drawn_sides(drawn, outline, shrink=1.0 if soft else None)
    rooms = Rooms.of(drawn, sides, outline, outline_given=not soft)

    best: list = []

    def starts(round_index: int, chain: int):
        # the first chain of a later round goes on from the best state so far (longer, so
        # it can leave its local minimum); the others start from new embeddings
        if chain == 0 and best:
            return best[0].state
        return initial.initial_state(drawn, rooms, _embedding_seed(seed, round_index, chain))

    done_rounds = moves = 0

    def unmet() -> tuple[tuple[str, str, float], ...]:
        return tuple(rooms.unmet_doors(best[0].state)) if best else ()

    for found in schedule.rounds(rooms, starts, seed, limits.deadline, max_rounds):
        if found is None:
            return Generated(None, spec, "", done_rounds, moves, cut_off=True, unmet=unmet())
        done_rounds += 1
        moves += found.moves
        if not best or (found.violation, found.cost) < (best[0].violation, best[0].cost):
            best[:] = [found]
        if found.violation > WORK["repair_max_violation_m"]:
            continue
        geometry = rooms.geometry(found.state)
        target = spec
        if soft:
            target = _drawn_round(spec, geometry)
        rects = _sized(target, geometry, rng, seed, limits)
        if rects is not None:
            grown = None
            if target.boundary is not None and (target.boundary.w > boundary.w + 1e-9
                                                or target.boundary.h > boundary.h + 1e-9):
                grown = (target.boundary.w, target.boundary.h)
            return Generated(rects, target, "annealed", done_rounds, moves, grown=grown)
        if time.monotonic() >= limits.deadline:
            return Generated(None, spec, "", done_rounds, moves, cut_off=True, unmet=unmet())
    return Generated(None, spec, "", done_rounds, moves, unmet=unmet())


def _sized(spec: Spec, geometry: dict[str, Rect], rng: random.Random, seed: int,
           limits: RepairLimits) -> dict[str, Rect] | None:
    """The sizing stage on a packed geometry (of the drawn spec: an L's arm a room): a few
    rounds only, since another round of annealing is cheaper than a long repair."""
    limits = replace(limits, max_rounds=WORK["repair_rounds"], max_stalls=WORK["repair_stalls"])
    geometry = _with_pinned_points(spec, geometry)
    problem = problem_of(spec)
    if spec.arms:
        geometry = lshape.seed_arms(spec, geometry, rng)
        problem = boxed_problem(spec, geometry)
    return repair(problem, geometry, limits, seed, free_defects=True)


def _drawn_round(spec: Spec, geometry: dict[str, Rect]) -> Spec:
    """The spec with its boundary drawn round the packing, never smaller than its own."""
    boundary = spec.boundary
    assert boundary is not None
    right = max(x + w for x, _y, w, _h in geometry.values())
    top = max(y + h for _x, y, _w, h in geometry.values())
    width = max(boundary.w if not boundary.chosen else 0.0, round(right * BOUNDARY_MARGIN, 3))
    height = max(boundary.h if not boundary.chosen else 0.0, round(top * BOUNDARY_MARGIN, 3))
    return replace(spec, boundary=replace(boundary, w=width, h=height))


def _with_pinned_points(spec: Spec, geometry: dict[str, Rect]) -> dict[str, Rect]:
    """Each room with a position (or connection) moved so its rectangle covers the point:
    the relations then already put it where the hard constraint wants it."""
    moved = dict(geometry)
    for room_id, (px, py) in initial.pinned_points(spec).items():
        if room_id in moved:
            _x, _y, w, h = moved[room_id]
            moved[room_id] = (px - w / 2, py - h / 2, w, h)
    return moved


def _embedding_seed(seed: int, round_index: int, chain: int) -> int:
    return random.Random(f"embedding:{seed}:{round_index}:{chain}").randrange(2**31)


__all__ = ["Generated", "generate"]
