"""Many different verified layouts from one spec (seed §6.2).

Variant k (1..N) differs from the others in two ways:
- as in the thesis, a chosen room (an entrance if there is one) gets a `Position` at a
  different point of the boundary for each variant (dropped again if that variant finds no
  layout with it, so every variant still gets one);
- the first feasible layout is constructed from a randomised seed geometry (perturbed hints,
  or a spring embedding of the room graph) drawn from seed + k - 1, so the rooms' relative
  positions differ, not just the entrance.

`diversity` measures how different they are: over all pairs of variants, the mean fraction
of room pairs whose relative position (left/right/above/below) differs.
"""

from __future__ import annotations

import multiprocessing
import random
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, replace
from itertools import combinations
from pathlib import Path

from layoutdsl.ast import Position, Spec
from layoutdsl.layout import Layout

MAX_WORKERS = 2
"""Variants solve in parallel processes; the target machines have 2 cores."""


@dataclass(frozen=True, slots=True)
class VariantsResult:
    """The variants (None where one found no layout), their diversity and the files written."""

    layouts: list[Layout | None]
    diversity: float | None
    paths: list[Path]
    positions: list[tuple[str, float, float] | None]
    """The (room, x, y) each variant fixed, or None where it kept the spec's own positions."""


def chosen_room(spec: Spec) -> str | None:
    """The room whose position varies: the first entrance, else the best-connected room.

    Rooms that already have a position in the spec are left as they are.
    """
    fixed = {p.room for p in spec.positions}
    free = [room for room in spec.rooms if room.id not in fixed]
    if not free:
        return None
    for room in free:
        if room.rtype == "E":
            return room.id
    degree = {room.id: 0 for room in free}
    for adj in spec.adjacencies:
        for room_id in (adj.a, adj.b):
            if room_id in degree:
                degree[room_id] += 1
    return max(free, key=lambda room: degree[room.id]).id


def variant_point(spec: Spec, seed: int, index: int) -> tuple[float, float]:
    """The point variant `index` puts the chosen room on: spread over the boundary's inside."""
    assert spec.boundary is not None
    rng = random.Random(f"{seed}:{index}")
    return (
        rng.uniform(0.1, 0.9) * spec.boundary.w,
        rng.uniform(0.1, 0.9) * spec.boundary.h,
    )


def relation(a, b) -> str:
    """Where b lies relative to a along the axis that separates them most: R, L, U or D."""
    gap_x = max(b.x - a.x2, a.x - b.x2)
    gap_y = max(b.y - a.y2, a.y - b.y2)
    (acx, acy), (bcx, bcy) = a.centre, b.centre
    if gap_x >= gap_y:
        return "R" if bcx > acx else "L"
    return "U" if bcy > acy else "D"


def diversity(layouts: list[Layout]) -> float | None:
    """Mean over variant pairs of the fraction of room pairs whose relation differs."""
    if len(layouts) < 2:
        return None
    fractions = []
    for first, second in combinations(layouts, 2):
        rooms_a = {room.id: room for room in first.rooms}
        rooms_b = {room.id: room for room in second.rooms}
        ids = sorted(rooms_a)
        pairs = list(combinations(ids, 2))
        if not pairs:
            continue
        differ = sum(
            relation(rooms_a[i], rooms_a[j]) != relation(rooms_b[i], rooms_b[j]) for i, j in pairs
        )
        fractions.append(differ / len(pairs))
    return sum(fractions) / len(fractions) if fractions else None


_SPEC_FOR_WORKERS: Spec | None = None
"""The spec, inherited by forked workers (AST spans hold mapping proxies, which don't pickle)."""


def _solve_variant(job: tuple[int, int, object, tuple[str, float, float] | None]):
    """Compile one variant in a worker: its layout and the position it kept (or None)."""
    index, seed, options, point = job
    spec = _SPEC_FOR_WORKERS
    assert spec is not None
    return _compile_variant(spec, index, seed, options, point)


def _compile_variant(spec: Spec, index: int, seed: int, options, point):
    from layoutdsl.compiler import compile_spec
    from layoutdsl.construct import construct_start

    variant_seed = seed + index - 1
    began = time.monotonic()
    deadline = began + options.time_limit

    def provider(sub_spec: Spec, sub_options) -> dict | None:
        return construct_start(sub_spec, seed=variant_seed, randomize=True,
                               deadline=time.monotonic() + sub_options.time_limit)

    attempts = [point, None] if point is not None else [None]
    for attempt_point in attempts:
        variant_spec = spec
        if attempt_point is not None:
            room, x, y = attempt_point
            variant_spec = replace(spec, positions=spec.positions + (Position(room, x, y),))
        left = deadline - time.monotonic()
        if left <= 0.5:
            break
        # with a position, keep half the time for the variant without it
        limit = left / 2 if attempt_point is not None else left
        variant_options = replace(options, time_limit=limit, seed=variant_seed, quiet=True)
        result = compile_spec(variant_spec, variant_options, start_provider=provider,
                              explain_infeasible=False)
        if result.layout is not None:
            return result.layout, attempt_point
    return None, None


def compile_variants(
    spec: Spec,
    n: int,
    *,
    seed: int = 0,
    options=None,
    outdir: Path | str | None = None,
    formats=None,
    robot_room: str | None = None,
    workers: int = MAX_WORKERS,
    world_options: dict | None = None,
) -> VariantsResult:
    """Compile N variants of the spec; write NAME-k.* (and NAME-k.layout.json) to `outdir`.

    Each variant gets options.time_limit seconds; up to `workers` run at once.
    `world_options` (wall_height, robot) go to the 3D emitters.
    """
    from layoutdsl.solve import SolveOptions

    global _SPEC_FOR_WORKERS
    if options is None:
        options = SolveOptions.from_settings(spec.settings)
    room = chosen_room(spec)
    jobs = []
    for index in range(1, n + 1):
        point = None
        if room is not None and spec.boundary is not None:
            x, y = variant_point(spec, seed, index)
            point = (room, x, y)
        jobs.append((index, seed, options, point))

    results: list[tuple[Layout | None, object]]
    workers = max(1, min(workers, n, MAX_WORKERS))
    if workers > 1 and "fork" in multiprocessing.get_all_start_methods():
        _SPEC_FOR_WORKERS = spec
        try:
            context = multiprocessing.get_context("fork")
            with ProcessPoolExecutor(max_workers=workers, mp_context=context) as pool:
                results = list(pool.map(_solve_variant, jobs))
        finally:
            _SPEC_FOR_WORKERS = None
    else:
        results = [_compile_variant(spec, *job) for job in jobs]

    layouts = [layout for layout, _ in results]
    positions = [point for _, point in results]
    paths: list[Path] = []
    if outdir is not None:
        paths = _write(spec, layouts, Path(outdir), formats, robot_room, world_options or {})
    found = [layout for layout in layouts if layout is not None]
    return VariantsResult(layouts, diversity(found), paths, positions)


def _write(
    spec: Spec, layouts: list[Layout | None], outdir: Path, formats, robot_room, world_options: dict
) -> list[Path]:
    """NAME-k.layout.json plus the emitters' files for each variant that has a layout."""
    from layoutdsl.atomic import write_text_atomic
    from layoutdsl.emit import DEFAULT_FORMATS, write_outputs

    outdir.mkdir(parents=True, exist_ok=True)
    paths: list[Path] = []
    for index, layout in enumerate(layouts, start=1):
        if layout is None:
            continue
        stem = f"{spec.name}-{index}"
        paths.append(write_text_atomic(outdir / f"{stem}.layout.json", layout.to_json()))
        paths += write_outputs(layout, outdir, stem, formats or DEFAULT_FORMATS,
                               robot_room=robot_room, **world_options)
    return paths
