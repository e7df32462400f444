"""The compile pipeline: checked spec -> first layout -> model -> SCIP -> verified Layout.

Stages, each callable alone: a first feasible geometry (`start`, or a `start_provider`, by
default the generator: layoutdsl.compile.generator), `model.build_model`, `model.warm_start_from_rects`,
`solve.polish` (best geometry for the start's relations), `solve.improve_by_neighbourhoods`
(large-neighbourhood search), `solve.solve` (branch-and-bound over the whole model, warm
started), `layout_from_rects`, `verify.verify`. A layout that fails verification is never
returned; infeasibility and time-outs become E9xx diagnostics (explain.py).
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace

from layoutdsl.compile import explain, structure
from layoutdsl.compile.budgets import LNS_SIZE, LNS_SMALL, TIME, WORK
from layoutdsl.compile.generator import Generated, generate
from layoutdsl.layout import lshape
from layoutdsl.syntax.ast import Spec
from layoutdsl.diagnostics import Diagnostic
from layoutdsl.layout import Layout, SolveInfo, round_layout_number
from layoutdsl.layout.geometry import layout_from_rects
from layoutdsl.model import (
    THESIS_AS_WRITTEN,
    Formulation,
    build_model,
    objective_of_rects,
    rects_from_model,
    settle_separations,
    warm_start_from_rects,
)
from layoutdsl.solve import (
    ProgressCallback,
    SolveOptions,
    SolveOutcome,
    improve_by_neighbourhoods,
    polish,
    relative_gap,
    solve,
    stderr_progress,
)
from layoutdsl.layout.geometry import Rect
from layoutdsl.layout.verify import USABLE_WIDTH, slivers, verify
from layoutdsl.solve.isolated import SOLVER_CRASHED, solve_isolated
from layoutdsl.solve.relations import compacted, without_slivers

StartProvider = Callable[[Spec, SolveOptions], "Generated | dict[str, Rect] | None"]
"""start_provider(spec, options) -> a Generated (or rectangles satisfying every hard
constraint, or None). It must return within options.time_limit seconds."""


@dataclass(slots=True)
class CompileResult:
    """What a compile produced: a verified layout, or diagnostics saying why not."""

    layout: Layout | None
    diagnostics: list[Diagnostic]
    status: str
    """A SolveInfo status when there is a layout; else 'infeasible', 'no_layout' (time limit
    without one) or 'verify_failed'."""
    timings: dict[str, float] = field(default_factory=dict)
    """Seconds per stage: 'build', 'presolve', 'start', 'polish', 'neighbourhoods', 'solve',
    'verify', 'explain', 'total'."""
    outcome: SolveOutcome | None = None


def default_start_provider(spec: Spec, options: SolveOptions) -> Generated:
    """The generator's first layout (layoutdsl.compile.generator), cut off at the time limit."""
    return generate(spec, seed=options.seed, deadline=time.monotonic() + options.time_limit,
                    grow_boundary=options.grow_boundary)


def compile_from_start(
    spec: Spec,
    options: SolveOptions,
    *,
    start: Mapping[str, Rect] | None = None,
    start_provider: StartProvider | None = None,
    progress: ProgressCallback | None = None,
    explain_infeasible: bool = True,
) -> CompileResult:
    """The strategies 'auto' and 'thesis': a verified Layout from a start polished by SCIP.

    strategy 'thesis': the thesis' formulation as written, solved by SCIP from scratch.
    strategy 'auto': a first feasible layout from `start`, else from `start_provider` (by
    default the generator), handed to SCIP as its start for polishing. The start itself is
    the answer if SCIP finds nothing better in time; without one, SCIP searches alone.
    """
    began = time.monotonic()
    deadline = began + options.time_limit
    timings: dict[str, float] = {}
    progress = _progress_since(began, progress, options)
    formulation = options.formulation
    rects_start: dict[str, Rect] | None = dict(start) if start is not None else None
    generated: Generated | None = None
    made_l: list[str] = []
    if options.strategy == "thesis":
        formulation = THESIS_AS_WRITTEN
        rects_start = None
    elif rects_start is None:
        given = spec
        spec, made_l = structure.with_l_rooms(spec)
        if made_l and not options.quiet:
            print(f"compile: {', '.join(made_l)} drawn as L-shaped rooms ({structure.why_l_rooms(given, made_l)})",
                  file=sys.stderr)
        undrawable = structure.undrawable(spec)
        if undrawable:
            timings["total"] = time.monotonic() - began
            return CompileResult(None, undrawable, "infeasible", timings)
        soft = options.grow_boundary or (spec.boundary is not None and spec.boundary.chosen)
        if not soft and not spec.arms:
            # SCIP's presolve proves typical conflicts in milliseconds: the generator would
            # otherwise spend its whole work budget on a spec that has no layout
            t0 = time.monotonic()
            model = build_model(spec, formulation=formulation)
            timings["build"] = time.monotonic() - t0
            probe = _presolve_probe(model, options, timings)
            if probe.status == "infeasible":
                return _no_layout(spec, options, probe, [], explain_infeasible, timings, began)
        generated = _provided_start(spec, options, start_provider, timings)
        # without a first layout SCIP searches alone in the time left (thesis, §5.5.1): it
        # finds the small specs' layouts, rarely one of 20 rooms or more
        spec, rects_start = generated.spec, generated.rects
        if generated.turned and not options.quiet:
            print(f"compile: {', '.join(generated.turned)} turn a corner (L-shaped rooms) to reach doors "
                  "a straight corridor left unmet", file=sys.stderr)
        if generated.grown is not None and not options.quiet:
            print(f"compile: the boundary grew to {generated.grown[0]:g} x {generated.grown[1]:g} m "
                  f"for this arrangement (--grow-boundary)", file=sys.stderr)
    if spec.arms:
        result = _compile_l_rooms(spec, options, rects_start, progress, timings, began, deadline, generated)
        if result.layout is None and generated is not None:
            # rooms that an L makes drawable (four joined pairwise, or threes that rectangles
            # could not keep open), yet the generator did not draw: say which, and why
            result = replace(result, diagnostics=result.diagnostics + structure.not_placed(spec))
        return _with_closest_arrangement(result, spec, options, generated)
    # a verified start polished with nothing searched after: the model needs only the
    # separations of the start's relations (model.settle_separations, in _polish_start)
    checked = (_verified_start(spec, rects_start)
               if options.strategy != "thesis" and not options.search and rects_start is not None else None)
    settle = checked is not None and checked[0] is not None
    t0 = time.monotonic()
    model = build_model(spec, formulation=formulation, defer_separations=settle)
    timings["build"] = timings.get("build", 0.0) + time.monotonic() - t0
    rects_start, method = checked if checked is not None else _verified_start(spec, rects_start)

    polished: dict[str, Rect] | None = None
    if rects_start is not None:
        polished = _polish_start(model, spec, options, rects_start, deadline, progress, timings)
    outcome = _search_whole_model(model, spec, options, rects_start, polished, deadline, progress,
                                  timings)
    candidates = _candidates(model, outcome, polished, rects_start)

    t0 = time.monotonic()
    first = _first_feasible_seconds(outcome, method, timings)
    best, failures = _best_verified(spec, options, candidates, outcome, method, first, began, formulation,
                                    generated=generated)
    timings["verify"] = time.monotonic() - t0
    if best is not None:
        timings["total"] = time.monotonic() - began
        return CompileResult(best[1], [], best[2], timings, outcome)

    return _with_closest_arrangement(_no_layout(spec, options, outcome, failures, explain_infeasible, timings, began,
                                                generated),
                                     spec, options, generated)


def _with_closest_arrangement(result: CompileResult, spec: Spec, options: SolveOptions,
                              generated: Generated | None) -> CompileResult:
    """A result without a layout, with what kept the generator's closest arrangement from
    one: I909 names the doors it left unmet (where the room graph is hard to draw), I910
    the entrances it left inside and how far it stuck out of a given boundary."""
    if result.status != "no_layout" or generated is None or generated.rects is not None:
        return result  # a layout, or a proof that there is none (E901), says more
    notes = []
    if generated.unmet:
        notes.append(explain.unmet_doors(spec, generated.unmet, generated.rounds, generated.moves,
                                         generated.between, options))
    if generated.away or any(metres > 0 for metres in generated.overflow):
        notes.append(explain.outside_shortfall(spec, generated.away, generated.overflow, generated.rounds,
                                               generated.moves))
    return replace(result, diagnostics=result.diagnostics + notes)


def _compile_l_rooms(spec: Spec, options: SolveOptions, rects_start: dict[str, Rect] | None,
                     progress: ProgressCallback | None, timings: dict[str, float], began: float,
                     deadline: float, generated: Generated | None) -> CompileResult:
    """The strategy 'auto' for a spec with L-shaped rooms: the same stages on its boxes.

    The thesis' model places one rectangle per room, so it is built on the spec's boxes
    (layout.lshape.boxes_spec: each L-room's arm a room of its own, each adjacency of an L
    on the box the start realises it with) with each L's two boxes joined as the start
    joins them (model.equations.join_l_arms). SCIP then polishes, searches neighbourhoods
    and branches as for any spec; every candidate is verified against the spec itself.
    Without a start there is nothing to build the boxes from: no layout (E902).
    """
    rects_start, method = _verified_start(spec, rects_start)
    if rects_start is None:
        timings["total"] = time.monotonic() - began
        return CompileResult(None, [explain.no_layout_in_time(spec, options, exhausted=_work_ran_out(generated))],
                             "no_layout", timings)
    boxes, joined = lshape.boxes_spec(spec, rects_start)
    joins = {pair: lshape.join_option(rects_start[pair[0]], rects_start[pair[1]]) for pair in joined}
    t0 = time.monotonic()
    model = build_model(boxes, formulation=options.formulation, joins=joins, crossing=lshape.crossings(spec),
                        defer_separations=not options.search)
    timings["build"] = time.monotonic() - t0
    polished = _polish_start(model, boxes, options, rects_start, deadline, progress, timings)
    outcome = _search_whole_model(model, boxes, options, rects_start, polished, deadline, progress, timings)
    candidates = _candidates(model, outcome, polished, rects_start)
    t0 = time.monotonic()
    first = _first_feasible_seconds(outcome, method, timings)
    best, failures = _best_verified(spec, options, candidates, outcome, method, first, began,
                                    options.formulation, model_spec=boxes, generated=generated)
    timings["verify"] = time.monotonic() - t0
    timings["total"] = time.monotonic() - began
    if best is not None:
        return CompileResult(best[1], [], best[2], timings, outcome)
    return _no_layout(spec, options, outcome, failures, False, timings, began, generated)


def _progress_since(began: float, progress: ProgressCallback | None,
                    options: SolveOptions) -> ProgressCallback | None:
    """The progress callback (stderr unless quiet) fed the seconds since `began`."""
    if progress is None and not options.quiet:
        progress = stderr_progress
    if progress is None:
        return None
    report = progress
    # every stage reports seconds since the compile began, not since its own start

    def since_began(_elapsed: float, incumbent: float | None, gap: float | None) -> None:
        report(time.monotonic() - began, incumbent, gap)
    return since_began


def _presolve_probe(model, options: SolveOptions, timings: dict[str, float]) -> SolveOutcome:
    """SCIP's presolve alone on the model: its status is 'infeasible' for typical conflicts.

    It proves them in milliseconds (about a second at 100 rooms); without this probe the
    construction would spend its whole share of the time limit on a spec that has no layout.
    """
    t0 = time.monotonic()
    probe = solve(model, replace(options, time_limit=max(0.5, min(5.0, TIME['probe'] * options.time_limit)),
                                 node_limit=0, solution_limit=None, emphasis="default", quiet=True),
                  feasibility_only=True)
    timings["presolve"] = time.monotonic() - t0
    return probe


def _provided_start(spec: Spec, options: SolveOptions, start_provider: StartProvider | None,
                    timings: dict[str, float]) -> Generated:
    """The start provider's first layout (default: the generator), cut off at its share of
    the time limit."""
    provider = start_provider or default_start_provider
    share = replace(options, time_limit=max(0.1, TIME["generate"] * options.time_limit))
    t0 = time.monotonic()
    found = provider(spec, share)
    timings["start"] = time.monotonic() - t0
    if isinstance(found, Generated):
        return found
    return Generated(None if found is None else dict(found), spec, "provided" if found is not None else "")


def _verified_start(spec: Spec, rects_start: dict[str, Rect] | None) -> tuple[dict[str, Rect] | None, str]:
    """(the start if it passes verification else None, the method: 'construction' or 'scip')."""
    if rects_start is None:
        return None, "scip"
    # a start that fails verification is never handed on as an answer
    start_layout = layout_from_rects(spec, rects_start)
    if verify(spec, start_layout):
        return None, "scip"
    return rects_start, "construction"


def _polish_start(model, spec: Spec, options: SolveOptions, rects_start: dict[str, Rect],
                  deadline: float, progress: ProgressCallback | None,
                  timings: dict[str, float]) -> dict[str, Rect] | None:
    """Warm-start the model from the start and polish it, then search its neighbourhoods.

    Returns the polished rectangles (None when polishing found nothing); the model is left
    holding them, or the start itself.
    """
    polished: dict[str, Rect] | None = None
    warm_start_from_rects(model, spec, rects_start)
    if not hasattr(model.eq5_8_non_overlap, "separate"):
        settle_separations(model)  # built with them deferred: the start's relations, fixed
    # the start's relations with their best sizes and places: a much better start for SCIP
    t0 = time.monotonic()
    # without a search after it (variants) nothing needs the time polishing leaves: its node
    # limit, not a share of the clock, decides where it stops, so a loaded machine polishes
    # as far as an idle one (school_Neulengbach1 seed 1 was cut at its 10 % share under
    # load only)
    share = deadline - time.monotonic()
    if options.search:
        share = min(TIME['polish'] * options.time_limit, share)
    share = max(0.2, share)
    first_polish = polish(model, replace(options, time_limit=share, quiet=True))
    # a stage the clock stopped before its work limits makes the layout load-dependent:
    # remembered on the model for _search_whole_model's outcome (SolveInfo.wall_clock_limited)
    model.clock_limited = first_polish.wall_clock_limited
    if first_polish.has_solution:
        polished = rects_from_model(model)
    else:
        warm_start_from_rects(model, spec, rects_start)
    timings["polish"] = time.monotonic() - t0
    # neighbourhoods of LNS_SIZE rooms only pay off when they are a small part of the spec
    if first_polish.has_solution and len(spec.rooms) > 2 * LNS_SIZE and options.search:
        t0 = time.monotonic()
        lns_share = TIME['lns'][len(spec.rooms) <= LNS_SMALL]
        lns_deadline = time.monotonic() + lns_share * max(0.0, deadline - time.monotonic())
        searched = improve_by_neighbourhoods(model, options, deadline=lns_deadline, size=LNS_SIZE,
                                             progress=progress)
        model.clock_limited = model.clock_limited or searched.wall_clock_limited
        polished = rects_from_model(model)
        timings["neighbourhoods"] = time.monotonic() - t0
    return polished


def _search_whole_model(model, spec: Spec, options: SolveOptions, rects_start: dict[str, Rect] | None,
                        polished: dict[str, Rect] | None, deadline: float,
                        progress: ProgressCallback | None, timings: dict[str, float]) -> SolveOutcome:
    """Branch-and-bound over the whole model (unless search is off and there is a start),
    then, if SCIP beat the polished start, its incumbent polished in place."""
    # keep time for polishing SCIP's incumbent; translating the model costs about what
    # building it did
    reserve = min(TIME['polish'] * options.time_limit, timings["build"] + 1.0)
    remaining = max(0.5, deadline - time.monotonic() - reserve)
    start_objective = (objective_of_rects(spec, polished, formulation=model.formulation)
                       if polished is not None else None)
    t0 = time.monotonic()
    if options.search or rects_start is None:
        # in a child process: SCIP aborting deep in a long search (it does, natively, on
        # some L-room models) then costs the search, not the layout already in hand
        outcome = solve_isolated(model, replace(options, time_limit=remaining), progress=progress,
                                 warm_start=rects_start is not None)
    else:
        outcome = SolveOutcome(status="construction", has_solution=False)
    outcome.wall_clock_limited = outcome.wall_clock_limited or getattr(model, "clock_limited", False)
    timings["solve"] = time.monotonic() - t0
    improved = outcome.has_solution and (
        start_objective is None or outcome.objective is None or outcome.objective < start_objective - 1e-6)
    if improved:
        # SCIP's incumbent need not be the best geometry for its own relations
        t0 = time.monotonic()
        incumbent = rects_from_model(model)
        last = max(0.2, deadline - time.monotonic())
        last_polish = polish(model, replace(options, time_limit=last, quiet=True))
        outcome.wall_clock_limited = outcome.wall_clock_limited or last_polish.wall_clock_limited
        if not last_polish.has_solution:
            warm_start_from_rects(model, spec, incumbent)
        timings["polish"] = timings.get("polish", 0.0) + time.monotonic() - t0
    return outcome


def _candidates(model, outcome: SolveOutcome, polished: dict[str, Rect] | None,
                rects_start: dict[str, Rect] | None) -> list[tuple[dict[str, Rect], str]]:
    """(rectangles, status) that may be the answer, in order of preference on a tie."""
    # SCIP's (polished) incumbent, the polished start and the start itself: the best one
    # that passes verification is the answer
    candidates: list[tuple[dict[str, Rect], str]] = []
    if outcome.has_solution:
        candidates.append((rects_from_model(model), outcome.status))
    # a start that stands because the solver's search died says so
    own = SOLVER_CRASHED if outcome.status == SOLVER_CRASHED else "construction"
    if polished is not None:
        candidates.append((polished, own))
    if rects_start is not None:
        candidates.append((rects_start, own))
    return candidates


def _first_feasible_seconds(outcome: SolveOutcome, method: str, timings: dict[str, float]) -> float | None:
    """Seconds to the first feasible layout: the construction's, or SCIP's plus the build."""
    first = outcome.first_solution_seconds
    if method == "construction":
        first = timings.get("start", 0.0)
    elif first is not None:
        first += timings["build"]
    return first


def _best_verified(spec: Spec, options: SolveOptions, candidates: list[tuple[dict[str, Rect], str]],
                   outcome: SolveOutcome, method: str, first: float | None,
                   began: float, formulation: Formulation,
                   model_spec: Spec | None = None,
                   generated: Generated | None = None) -> tuple[tuple[float, Layout, str] | None, list]:
    """(objective, layout, status) of the best candidate that passes verification, or None;
    and the violations of the candidates that failed. The objective is the model's (built
    with `formulation`), of `model_spec` when the model was built on another spec (an
    L-spec's boxes)."""
    failures = []
    best: tuple[float, Layout, str] | None = None
    best_rects: dict[str, Rect] | None = None

    def checked_layout(rects: dict[str, Rect], status: str, objective: float) -> Layout:
        # SCIP's bound is a lower bound on (5.1) over all layouts, so it bounds every candidate
        gap = relative_gap(objective, outcome.bound) if outcome.bound is not None else None
        info = SolveInfo(
            status=status,
            objective=round_layout_number(objective),
            bound=None if outcome.bound is None else round_layout_number(outcome.bound),
            gap=None if gap is None else round_layout_number(gap),
            seconds=round(time.monotonic() - began, 3),
            first_feasible_seconds=None if first is None else round(first, 3),
            seed=options.seed,
            method=method,
            grown_boundary=None if generated is None else generated.grown,
            # the search's own report; polish and neighbourhood outcomes carry the same flag
            wall_clock_limited=outcome.wall_clock_limited,
        )
        return layout_from_rects(spec, rects, info)

    for rects, status in candidates:
        # (5.1) with o chosen per room as the thesis' model may choose it: the best
        # orientation that satisfies (5.4)-(5.6)
        objective = objective_of_rects(model_spec or spec, rects, formulation=formulation)
        # a tie (the solver's incumbent is the polished start, up to its tolerances) keeps
        # the earlier candidate, so the layout reports the rule that stopped the solve
        if best is not None and objective >= best[0] - 1e-6 * max(1.0, abs(best[0])):
            continue
        layout = checked_layout(rects, status, objective)
        violations = verify(spec, layout)
        if violations:
            failures.append(violations)
        else:
            best, best_rects = (objective, layout, status), rects
    if best is not None and best_rects is not None and options.strategy != "thesis":
        # realism the layout guarantees (issue 40), each pass with the best layout's relations
        # fixed: a gap between two rooms is a wall or a space, never a sliver; then no
        # enclosed voids a real building would not have, the rooms around each pulled
        # together and grown into it (slivers that this opens are shut or opened again).
        # Each pass may run to the compile's own deadline (at least its share of the time
        # limit): their work limits, not a share of the clock, decide where they stop, so a
        # variant on a loaded machine gets the layout an idle one does (a 10 % share cut the
        # void pass short under load: school_Neulengbach1 seed 0, school_hendersonhighschool
        # seed 1)
        def until(share: float) -> float:
            return max(time.monotonic() + share * options.time_limit, began + options.time_limit)

        passes = (
            lambda rects: without_slivers(spec, rects, usable_width=USABLE_WIDTH, seed=options.seed,
                                          nodes=WORK["final_nodes"], deadline=until(TIME["slivers"])),
            lambda rects: compacted(spec, rects, usable_width=USABLE_WIDTH, seed=options.seed,
                                    nodes=WORK["final_nodes"], deadline=until(TIME["compact"])),
        )
        for realism_pass in passes:
            changed = realism_pass(best_rects)
            if changed is None:
                continue
            objective = objective_of_rects(model_spec or spec, changed, formulation=formulation)
            layout = checked_layout(changed, best[2], objective)
            if not verify(spec, layout):
                best, best_rects = (objective, layout, best[2]), changed
        # the gate of that promise: a layout the sliver pass could not rid of its slivers is
        # not written (E903 names the rooms), so variants try another seed
        gaps = slivers(spec, best[1], usable_width=USABLE_WIDTH)
        if gaps:
            failures.insert(0, gaps)  # what E903 reports: the reason nothing was written
            best = None
    return best, failures


def _no_layout(spec: Spec, options: SolveOptions, outcome: SolveOutcome, failures: list, explain_infeasible: bool,
               timings: dict[str, float], began: float, generated: Generated | None = None) -> CompileResult:
    """The CompileResult without a layout: E903 (verification), E901/E904 (infeasible), E902
    (what stopped the generator, when it found nothing, and then SCIP's search alone)."""
    if failures:
        diagnostics = [explain.verification_failed(spec, failures[0])]
        status = "verify_failed"
    elif outcome.status == "infeasible":
        status = "infeasible"
        t0 = time.monotonic()
        diagnostics = (
            explain.explain_infeasibility(spec, options) if explain_infeasible
            else [explain.infeasible_without_explanation(spec)]
        )
        timings["explain"] = time.monotonic() - t0
    else:
        status = "no_layout"
        # without the generator's rectangles SCIP searched the whole model alone
        diagnostics = [explain.no_layout_in_time(spec, options, outcome.status,
                                                 exhausted=_work_ran_out(generated), searched=True)]
    timings["total"] = time.monotonic() - began
    return CompileResult(None, diagnostics, status, timings, outcome)


def _work_ran_out(generated: Generated | None) -> tuple[int, int] | None:
    """(rounds, moves) of a generator that ran out of its work limits without rectangles, for
    E902; None when it found some, did not run, or the clock cut it off."""
    if generated is None or generated.rects is not None or generated.rounds == 0 or generated.cut_off:
        return None
    return generated.rounds, generated.moves
