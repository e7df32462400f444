"""Many different verified layouts from one spec (the thesis, §6.2; issue 11).

Two sources of variants:

- "graph" (the default): each variant is a NEW arrangement generated from the room graph
  alone (layoutdsl.generate), ignoring the spec's hints, so variants differ from the
  original plan and from one another: seeds seed, seed + 1, ... are tried in turn and a
  layout is kept when it differs from every one kept before it (_new_arrangements); once
  one is kept, arrangements derived from the kept ones (generator.derive: a kick and a
  short walk of chains) are tried before more seeds;
- "hints": as before issue 11, for comparison: the first layout is repaired from the hints
  perturbed by the seed, and (as in the thesis) a chosen room, an entrance if there is
  one, gets a `Position` at another point of the boundary per variant (dropped again if that
  variant finds no layout with it). Variant k has seed + k - 1. These stay close to the
  original arrangement.

Each variant stops at a short deterministic rule: its first verified layout, polished with
its relations fixed (SolveOptions.search off), so the same spec and seed give the same
bytes and a 50-room variant costs seconds, not the compile's full time limit. A new
arrangement's first try is quick (ROUND_TIERS[0] rounds of the generator, then the seed is
given up); the seeds whose quick try found nothing go on to the next tier's rounds if the
tries run out before N different arrangements are kept, and so on to the generator's full
budget, each resumed where the tier before stopped (generator.Resume): no round is made
twice, and a seed that would need all of its rounds waits until the cheaper seeds are done.

`diversity` is the plain share of room pairs whose relation differs; `compile --variants`
reports the arrangement difference of layoutdsl.layout.difference (best of the 8
rotations and mirrors) pairwise and from the hints, and writes NAME-variants.json.
"""

from __future__ import annotations

import multiprocessing
import random
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, replace
from itertools import combinations
from pathlib import Path
from typing import NamedTuple

from layoutdsl.compile.explain import variants_not_distinct
from layoutdsl.diagnostics import Diagnostic
from layoutdsl.syntax.ast import Position, Spec
from layoutdsl.layout import Layout

def default_workers() -> int:
    """Parallel variant processes: one per core this process may use."""
    import os

    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on every platform
        return max(1, os.cpu_count() or 1)


SOURCES = ("graph", "hints")
"""Where variants come from: generated from the room graph, or perturbed from the hints."""


@dataclass(frozen=True, slots=True)
class VariantsResult:
    """The variants (None where one found no layout), their diversity and the files written."""

    layouts: list[Layout | None]
    seeds: list[int | None]
    """The seed each variant was compiled with (None where a new arrangement found none)."""
    diversity: float | None
    """Mean share of room pairs whose relation differs between two variants found (None
    with fewer than two); the CLI reports the symmetry-aware arrangement difference."""
    paths: list[Path]
    positions: list[tuple[str, float, float] | None]
    """The (room, x, y) each variant fixed, or None where it kept the spec's own positions."""
    distinct: list[bool] | None = None
    """New arrangements: per variant, whether it lies MIN_PAIRWISE or more from every variant
    before it (False for one that only fills a place no such arrangement was found for, and
    where no layout was found). None for variants from the hints, which are not compared."""
    diagnostics: tuple[Diagnostic, ...] = ()
    """W906 when fewer than N new arrangements were MIN_PAIRWISE apart."""
    kicks: list[int | None] | None = None
    """New arrangements: per variant, the kick of its seed's layout it was derived from
    (generator.derive), or None for the seed's own layout."""


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
    """Where a lies relative to b along the axis that separates them most (layout.geometry.SIDES)."""
    gap_x = max(b.x - a.x2, a.x - b.x2)
    gap_y = max(b.y - a.y2, a.y - b.y2)
    (acx, acy), (bcx, bcy) = a.centre, b.centre
    if gap_x >= gap_y:
        return "left" if bcx > acx else "right"
    return "below" if bcy > acy else "above"


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


class Job(NamedTuple):
    """One try of a variant: a seed (for a derived arrangement, the seed its origin came
    from), how it is made, and for a new arrangement the tier's rounds and where the seed's
    last tier stopped (generator.Resume); for a derived one (source "derived") the origin
    (generator.Origin) and which kick of it."""

    seed: int
    options: object
    point: tuple[str, float, float] | None
    source: str
    rounds: int | None = None
    resume: object = None
    derived: int | None = None
    from_variant: int | None = None
    """For a derived one: which variant kept (1-based) its origin is, for the progress line."""


def _solve_variant(job: Job):
    """Compile one variant in a worker (_compile_variant)."""
    spec = _SPEC_FOR_WORKERS
    assert spec is not None
    return _compile_variant(spec, job)


ROUND_TIERS: tuple[int | None, ...] = (3, 5, None)
"""Rounds of the generator's schedule a seed makes in each tier of tries (None: its full
budget, budgets.WORK["max_rounds"]); a tier's tries resume where the tier before stopped.
The rounds double their moves, so a seed that finds nothing in 8 rounds costs about 6
times what 5 rounds cost. Measured on office_floorplanMAIN (`--variants 8 --workers 2`,
idle): a quick try, then a full construction from round 0, took 233 s for 8 variants;
these tiers, resumed, 192 s."""

VARIANT_TIME_SHARE = 0.75
"""Share of a variant's time limit its generator may use before it is cut off."""


def _compile_variant(spec: Spec, job: Job):
    """(layout, position kept, None, origin) of one variant, or (None, None, resume, None).

    `job.rounds`: the generator gives up after so many rounds of its schedule instead of
    its full budget (a tier of ROUND_TIERS): another seed is cheaper than the slowest ones.
    The `resume` it returns (generator.Resume; None if the clock cut it off) lets the seed's
    next tier go on from there instead of making those rounds again. The `origin`
    (generator.Origin) of a layout found lets later jobs derive arrangements from it.
    """
    from layoutdsl.compile import compile_spec
    from layoutdsl.compile.generator import derive, generate

    variant_seed, options, point, source, rounds, resume = job.seed, job.options, job.point, job.source, \
        job.rounds, job.resume
    began = time.monotonic()
    deadline = began + options.time_limit
    from_hints = source == "hints"

    attempts = [point, None] if point is not None else [None]
    stopped = None
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
        attempt_began = time.monotonic()
        # constructed first and handed over as the start: compile then skips its presolve
        # probe, which translates the whole model to SCIP once more (measured on
        # school_wilbraham: 1.3 of a variant's 5.1 s); the spec's feasibility is not in
        # question for a variant, and one that finds no start gives way to another seed
        if source == "derived":
            generated = derive(variant_spec, resume, seed=_kick_seed(variant_seed, job.derived),
                               deadline=time.monotonic() + VARIANT_TIME_SHARE * limit,
                               grow_boundary=options.grow_boundary)
        else:
            generated = generate(variant_spec, seed=variant_seed, use_hints=from_hints, perturb_hints=from_hints,
                                 deadline=time.monotonic() + VARIANT_TIME_SHARE * limit,
                                 grow_boundary=options.grow_boundary,
                                 max_rounds=rounds,
                                 resume=resume if attempt_point is None else None)
        rects, variant_spec = generated.rects, generated.spec
        if rects is None:
            if attempt_point is None and source != "derived":
                stopped = generated.resume
            continue
        variant_options = replace(options, time_limit=max(0.5, limit - (time.monotonic() - attempt_began)),
                                  seed=variant_seed, quiet=True, search=False)
        result = compile_spec(variant_spec, variant_options, start=rects, explain_infeasible=False)
        if result.layout is not None:
            return result.layout, attempt_point, None, generated.origin
    return None, None, stopped, None


def _kick_seed(seed: int, kick: int | None) -> int:
    """The seed of a derived arrangement's kick: from the seed its origin came from and the
    kick's number, so two origins never share their kicks."""
    return random.Random(f"kick:{seed}:{kick}").randrange(2**31)


def compile_variants(
    spec: Spec,
    n: int,
    *,
    seed: int = 0,
    options=None,
    outdir: Path | str | None = None,
    formats=None,
    robot_room: str | None = None,
    workers: int | None = None,
    source: str = "graph",
    world_options: dict | None = None,
    progress: Callable[[str], None] | None = None,
) -> VariantsResult:
    """Compile N variants of the spec; write NAME-vK.* (and NAME-vK.layout.json) to `outdir`.

    Each try of a seed gets at most options.time_limit seconds (a new arrangement's seed may
    have up to one try per tier of ROUND_TIERS, each resumed from the last); up to `workers`
    (default: one per usable core) run at once. `source` is one of SOURCES (see the module
    docstring).
    `world_options` (wall_height, robot) go to the 3D emitters. `progress` gets a line per
    new arrangement kept.
    """
    from layoutdsl.solve import SolveOptions

    if source not in SOURCES:
        raise ValueError(f"unknown variant source {source!r}; expected one of {SOURCES}")
    if options is None:
        options = SolveOptions.from_settings(spec.settings)
    workers = max(1, min(workers or default_workers(), n))
    distinct: list[bool] | None = None
    kicks: list[int | None] | None = None
    diagnostics: tuple[Diagnostic, ...] = ()
    if source == "graph":
        results, seeds, distinct, kicks = _new_arrangements(spec, n, seed, options, workers, progress)
        close = [index for index, ((layout, _), kept) in enumerate(zip(results, distinct), start=1)
                 if layout is not None and not kept]
        if close:
            diagnostics = (variants_not_distinct(spec, close, n, MIN_PAIRWISE),)
    else:
        room = chosen_room(spec)
        jobs = []
        for index in range(1, n + 1):
            point = None
            if room is not None and spec.boundary is not None:
                x, y = variant_point(spec, seed, index)
                point = (room, x, y)
            jobs.append(Job(seed + index - 1, options, point, source))
        results = [(layout, point) for layout, point, _, _ in _run_jobs(spec, jobs, workers)]
        seeds = [job.seed for job in jobs]
    layouts = [layout for layout, _ in results]
    positions = [point for _, point in results]
    found = [layout for layout in layouts if layout is not None]
    paths: list[Path] = []
    if outdir is not None:
        paths = _write(spec, layouts, Path(outdir), formats, robot_room, world_options or {})
    return VariantsResult(layouts, seeds, diversity(found), paths, positions, distinct, diagnostics, kicks)


MIN_PAIRWISE = 0.3
"""Least arrangement difference (layoutdsl.layout.difference) a new-arrangement variant
must have from every variant kept before it."""

SEEDS_PER_VARIANT = 3
"""Quick tries (one seed each) new arrangements may take per variant asked for beyond the
first, before the seeds whose quick try found nothing get their full construction."""

KICKS_WITHOUT_KEEP = 12
"""Kicks (generator.derive) that may keep nothing in a row before compile goes back to
seeds; a seed's layout kept later starts the kicks again. Measured on office_floorplanMAIN:
8 kicks in 56 gave a layout 0.3 or more from their origin, on school_wilbraham 3 in 24, on
office_floorplanLOWER none in 24."""

DERIVE_BATCH = 8
"""Kicks handed out at once, each from the origin of a kept variant in turn (round robin
over those kept when the batch began), so a batch's origins depend on the outcomes taken
before it, never on the workers' timing. Measured on office_floorplanMAIN (`--variants 25`,
2 workers): with every kick from the first layout kept, the first 5 variants came within 23
s and then the kicks mostly landed within 0.3 of a variant kept before (all 25 at 641 s)."""

FIRST_FAILURES = 2
"""Quick tries a worker that may find nothing before any layout is kept, before the seeds
that failed go on with more rounds. Measured on office_floorplanMAIN (`--variants 25`,
2 workers): with QUICK_FAILURES x N (50) the first layout came after 126 s of failing quick
tries, and all 25 after 342 s."""

QUICK_FAILURES = 2
"""...and quick tries that may find nothing per variant asked for: a plan whose quick tries
mostly fail (school_hendersonhighschool: 3 of 20 seeds constructed in two geometries) goes
on to full constructions without spending its whole quick budget first."""


def _new_arrangements(spec: Spec, n: int, seed: int, options, workers: int,
                      progress: Callable[[str], None] | None = None
                      ) -> tuple[list, list[int | None], list[bool], list[int | None]]:
    """(layout, None) of each of N new arrangements, the seed each came from, whether it
    lies MIN_PAIRWISE or more from every one before it, and which kick of its seed's layout
    it was derived from (None: the seed's own).

    Seeds seed, seed + 1, ... get a quick try each (_compile_variant), `workers` at a time
    and a few queued, so no core waits for a slow seed; their outcomes are taken in seed
    order, and one is kept when it lies at least MIN_PAIRWISE from every variant kept
    before it. Once one is kept, kicks 1, 2, ... of the kept layouts (generator.derive: a
    few rooms traded, a short walk of chains, a short sizing) are tried the same way,
    DERIVE_BATCH at a time, each batch's kicks from the kept layouts in turn, until
    KICKS_WITHOUT_KEEP in a row keep nothing: a few chains cost less than the 3-8 rounds a
    new seed needs on a plan with cycles. The quick tries then go on where they stopped
    (a seed's layout kept starts the kicks again), until N are kept,
    1 + SEEDS_PER_VARIANT * (N - 1) seeds are used or QUICK_FAILURES * N quick tries found
    nothing. Then the seeds whose tries found nothing go on, in seed order, with the rounds
    of each later tier of ROUND_TIERS in turn, until N are kept; then layouts within
    MIN_PAIRWISE of a kept one fill any still missing (None where even those run out).

    Taking outcomes in job order makes the variants a function of the spec and seed
    wherever each variant's own stopping rule is, however the workers' timing falls; and
    `--variants 1 --seed S` (the tiers of S, resumed one from another: one full
    construction) gives the variant of seed S again. Measured on school_wilbraham (2
    workers, `--variants 20`): a round of N variants, then rounds of redraws, waited on each
    round's slowest seed (148 s); seeds streamed as workers free up spend no such wait (111
    s).
    """
    from layoutdsl.layout.difference import difference, layout_centres

    kept: list[tuple[int, Layout, dict, int | None]] = []
    close: list[tuple[int, Layout, int | None]] = []
    failed: list[tuple[int, object]] = []
    origins: list[tuple[int, object, int]] = []  # (seed, generator.Origin, variant number)

    def take(job: Job, outcome: tuple, how: str) -> None:
        layout, _, resume, origin = outcome
        if layout is None:
            if job.source != "derived":
                failed.append((job.seed, resume))
            return
        centres = layout_centres(layout)
        if all(difference(centres, other) >= MIN_PAIRWISE for _, _, other, _ in kept):
            kept.append((job.seed, layout, centres, job.derived))
            if origin is not None:
                origins.append((job.seed, origin, len(kept)))
            if progress is not None:
                what = f"seed {job.seed}" + (f", kick {job.derived} of variant {job.from_variant}"
                                             if job.derived else "")
                progress(f"variant {len(kept)} of {n}: {what} ({how})")
        else:
            close.append((job.seed, layout, job.derived))

    def enough() -> bool:
        return len(kept) >= n

    def quick_done() -> bool:
        return enough() or len(failed) >= QUICK_FAILURES * n

    derived_until = 0  # origins there were when the kicks last stopped
    kicks_made = 0

    def new_origin() -> bool:
        return len(origins) > derived_until

    def run(jobs: list[Job], how: str, stop: Callable[[], bool]) -> list[Job]:
        """The jobs' outcomes taken in job order until `stop()`; the jobs not taken."""
        done = 0
        for job, outcome in _in_seed_order(spec, jobs, workers, stop):
            done += 1
            take(job, outcome, how)
        return jobs[done:]

    def derive_more() -> None:
        # kicks of the kept layouts, DERIVE_BATCH at a time, until KICKS_WITHOUT_KEEP in a
        # row keep nothing: one short walk a try instead of whole rounds; only once a layout
        # was kept since the kicks last stopped
        nonlocal derived_until, kicks_made
        if not new_origin():
            return
        idle = 0
        while not enough() and idle < KICKS_WITHOUT_KEEP:
            batch = []
            for _ in range(DERIVE_BATCH):
                kicks_made += 1
                base_seed, origin, variant = origins[kicks_made % len(origins)]
                batch.append(Job(base_seed, options, None, "derived", resume=origin, derived=kicks_made,
                                 from_variant=variant))
            for job, outcome in _in_seed_order(spec, batch, workers,
                                               lambda: enough() or idle >= KICKS_WITHOUT_KEEP):
                before = len(kept)
                take(job, outcome, "derived")
                idle = 0 if len(kept) > before else idle + 1
        derived_until = len(origins)

    def run_deriving(jobs: list[Job], how: str, stop: Callable[[], bool]) -> None:
        # the jobs in order until `stop()`, the kicks of each new layout kept made before the
        # next job's outcome is taken
        while jobs and not stop():
            jobs = run(jobs, how, lambda: stop() or new_origin())
            derive_more()

    def tiers(until_first: bool) -> None:
        # the seeds whose last try found nothing, with each later tier's rounds in turn, each
        # going on from where its last tier stopped (one the clock cut off starts over);
        # `until_first`: only until a first layout is kept (the next ones are derived)
        for tier in ROUND_TIERS[1:]:
            if enough() or not failed or (until_first and origins):
                break
            longer = [Job(s, options, None, "graph", tier, resume) for s, resume in failed]
            failed.clear()
            run_deriving(longer, "full construction" if tier is None else f"{tier} rounds", enough)

    quick = [Job(s, options, None, "graph", ROUND_TIERS[0]) for s in range(seed, seed + 1 + SEEDS_PER_VARIANT * (n - 1))]
    # before any layout, a plan whose quick tries fail goes deeper after FIRST_FAILURES of
    # them a worker, whatever N: more quick tries would only delay the first layout, from
    # which the rest are derived
    rest = run(quick, "quick try",
               lambda: quick_done() or bool(origins) or len(failed) >= FIRST_FAILURES * workers)
    derive_more()
    if not origins:
        tiers(until_first=True)
    run_deriving(rest, "quick try", quick_done)
    tiers(until_first=False)
    chosen = [(s, layout, kick) for s, layout, _, kick in kept]
    for variant_seed, layout, kick in close[:n - len(kept)]:
        chosen.append((variant_seed, layout, kick))
        if progress is not None:
            progress(f"variant {len(chosen)} of {n}: seed {variant_seed}, within {MIN_PAIRWISE:g} of an "
                     "earlier variant (no arrangement farther from them among the seeds tried)")
    distinct = [True] * len(kept) + [False] * (n - len(kept))
    chosen += [(None, None, None)] * (n - len(chosen))
    return ([(layout, None) for _, layout, _ in chosen], [s for s, _, _ in chosen], distinct,
            [kick for _, _, kick in chosen])


LOOKAHEAD = 2
"""Jobs handed to the pool per worker (running or waiting), so a worker that finishes
finds the next one while the outcomes are still taken in order."""


def _in_seed_order(spec: Spec, jobs: list, workers: int, enough: Callable[[], bool]):
    """(job, (layout, position kept)) of each job, in job order, until `enough()`: on
    `workers` forked processes (the jobs still running then are stopped), or in this one."""
    if workers <= 1 or "fork" not in multiprocessing.get_all_start_methods():
        for job in jobs:
            if enough():
                return
            yield job, _compile_variant(spec, job)
        return
    global _SPEC_FOR_WORKERS
    _SPEC_FOR_WORKERS = spec
    pool = multiprocessing.get_context("fork").Pool(workers)
    try:
        waiting = iter(jobs)
        queued: deque = deque()

        def top_up() -> None:
            while len(queued) < workers * LOOKAHEAD:
                job = next(waiting, None)
                if job is None:
                    return
                queued.append((job, pool.apply_async(_solve_variant, (job,))))

        top_up()
        while queued and not enough():
            job, outcome = queued.popleft()
            result = outcome.get()
            top_up()
            yield job, result
    finally:
        # what is still running or queued is not needed: stopped, not waited for
        pool.terminate()
        pool.join()
        _SPEC_FOR_WORKERS = None


def _run_jobs(spec: Spec, jobs: list, workers: int) -> list:
    """(layout, position kept, resume) per job, in job order: every job, `workers` at a time."""
    return [result for _, result in _in_seed_order(spec, jobs, workers, enough=lambda: False)]


def _write(
    spec: Spec, layouts: list[Layout | None], outdir: Path, formats, robot_room, world_options: dict
) -> list[Path]:
    """NAME-vK.layout.json plus the emitters' files for each variant that has a layout."""
    from layoutdsl.emit.atomic import write_text_atomic
    from layoutdsl.emit import DEFAULT_FORMATS, write_outputs

    outdir.mkdir(parents=True, exist_ok=True)
    paths: list[Path] = []
    for index, layout in enumerate(layouts, start=1):
        if layout is None:
            continue
        stem = f"{spec.name}-v{index}"  # NAME-vK, as batch names its buildings (one scheme, issue 42)
        paths.append(write_text_atomic(outdir / f"{stem}.layout.json", layout.to_json()))
        paths += write_outputs(layout, outdir, stem, formats or DEFAULT_FORMATS,
                               robot_room=robot_room, **world_options)
    return paths
