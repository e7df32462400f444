"""SCIP lives here: solve a model from model.py and load the best layout back onto it.

We use Pyomo's `scip_direct` interface (pyomo.contrib.solver, Pyomo 6.10.x, PySCIPOpt 6.x) to
translate the Pyomo model, then drive the PySCIPOpt model ourselves, because we need what
`solve()` does not offer: a complete warm start (continuous variables too), SCIP's emphasis
meta settings, progress lines and a wall-clock guard (an event handler plus a ticker thread
while SCIP runs without the GIL), re-solving one translated model with changed bounds
(neighbourhood search), and our own gap.

Console output stays off (`display/verblevel 0`): more than ~64 KiB of SCIP output through
Pyomo's capture pipe deadlocks the process (shared/notes/solver-scouting.md). What C code
still writes to fds 1 and 2 (SoPlex's warnings) is discarded by `quiet.native_output_silenced`.

Reproducible: every solve stops at deterministic work limits (branch-and-bound nodes, LP
iterations, improving solutions, neighbourhood rounds), counted by SCIP on one thread with
its random seed shifted by the seed, so a spec and a seed give the same layout on an idle
and on a loaded machine. The wall clock is only the outer cap; a solve that reaches it says
so (`SolveOutcome.wall_clock_limited`), because its result may then depend on the load.
"""

from __future__ import annotations

import math
import random
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import pyomo.environ as pyo  # registers the solver plugins: must come before the solver import
from pyomo.common.timing import HierarchicalTimer
from pyomo.contrib.solver.solvers.scip.scip_direct import ScipDirect
from pyscipopt import SCIP_EVENTTYPE, SCIP_PARAMEMPHASIS, SCIP_PARAMSETTING, Eventhdlr

from layoutdsl import private_api
from layoutdsl.model import Formulation
from layoutdsl.solve.quiet import native_output_silenced
from layoutdsl.syntax.ast import EMPHASES, Settings

DEFAULT_NODE_LIMIT = 2000
"""Branch-and-bound nodes of one solve when the options name no node limit: the
deterministic stopping rule that stands in for the wall clock.

It bounds the polish and the neighbourhood rounds well inside a compile's time limit, but not
a whole-model search with aggressive heuristics: there the root node alone can outlast the
limit (measured on school_Sabadell3, 19 rooms, at load 8 on 2 cores: 31 nodes in 28 s, 16 of
them in SCIP's sub-solver heuristics mpec, rens, trustregion and alns, whose work SCIP counts
in none of its own limits). Such a search ends at the wall clock and says so
(wall_clock_limited); a dataset that must not depend on the machine uses --variants (no
whole-model search) or a --node-limit small enough to come first."""

DEFAULT_LP_ITERATIONS = 200_000
"""Simplex iterations of one solve (all its LPs together) when the options name no limit.
Nodes alone do not bound the work: one node of a 100-room model can take a second."""

POLISH_NODE_LIMIT = 500
"""Nodes of a polish (binaries fixed: a small nonconvex problem that closes its gap in a
few dozen nodes on the real plans)."""

GUARD_GRACE_SECONDS = 1.0
"""How far past its time limit a solve may run before our guard interrupts it (SCIP's own
time limit normally stops it first)."""


@dataclass(frozen=True, slots=True)
class SolveOptions:
    """How to solve: the spec's settings with command-line overrides applied."""

    time_limit: float = 60.0
    """Wall-clock seconds for the whole compile (construction plus SCIP)."""
    gap: float = 0.01
    """Stop when (incumbent - bound) / |incumbent| falls to this."""
    seed: int = 0
    """SCIP's randomization/randomseedshift and the construction's seed."""
    emphasis: str = "default"
    """One of EMPHASES: SCIP's meta setting (heuristics = aggressive heuristics)."""
    node_limit: int | None = None
    """Stop after this many branch-and-bound nodes (deterministic); None: DEFAULT_NODE_LIMIT."""
    solution_limit: int | None = None
    """Stop after this many improving solutions (deterministic)."""
    lp_iteration_limit: int | None = None
    """Stop after this many simplex iterations in all (deterministic); None:
    DEFAULT_LP_ITERATIONS."""
    quiet: bool = False
    """No progress lines on stderr."""
    threads: int = 1
    """SCIP is deterministic single-threaded; more threads only for the LP solver (and a
    result that may then depend on thread timing)."""
    strategy: str = "auto"
    """auto: first-feasible construction then SCIP; thesis: SCIP from scratch; cycles: §5.5.3
    (layoutdsl.compile dispatches on it; the CLI's STRATEGIES lists them)."""
    formulation: Formulation = field(default_factory=Formulation)
    """Which model improvements over the thesis formulation as written to use."""
    search: bool = True
    """After the (polished) first layout, search for better ones (neighbourhoods, then
    branch-and-bound) until a limit. Off: the polished first layout is the answer, a short
    deterministic stopping rule (variants, issue 11)."""
    grow_boundary: bool = False
    """auto: the generator may grow a given boundary that is too tight for an arrangement
    (compile --grow-boundary); the layout's SolveInfo.grown_boundary reports the growth."""

    @staticmethod
    def from_settings(settings: Settings, **overrides) -> SolveOptions:
        """Options from a spec's settings; keyword overrides (CLI flags) win when not None."""
        values = {
            "time_limit": settings.time_limit,
            "gap": settings.gap,
            "seed": settings.seed,
            "emphasis": settings.emphasis,
            "node_limit": settings.node_limit,
        }
        values.update({k: v for k, v in overrides.items() if v is not None})
        return SolveOptions(**values)

    def with_time_limit(self, seconds: float) -> SolveOptions:
        return replace(self, time_limit=seconds)


@dataclass(slots=True)
class SolveOutcome:
    """What one SCIP run found. The best solution, if any, is loaded on the model."""

    status: str
    """'optimal', 'gap_limit', 'time_limit', 'node_limit', 'solution_limit',
    'iteration_limit', 'infeasible', 'interrupted' or 'unknown'."""
    has_solution: bool
    objective: float | None = None
    """SCIP's incumbent value (helper slack may make it higher than (5.1) of the layout)."""
    bound: float | None = None
    gap: float | None = None
    """(incumbent - bound) / |incumbent|, computed here (SCIP's getGap is 1e20 across signs)."""
    seconds: float = 0.0
    first_solution_seconds: float | None = None
    nodes: int = 0
    start_accepted: bool | None = None
    """Whether SCIP accepted the warm start as feasible (None: no start given)."""
    wall_clock_limited: bool = False
    """The wall clock (the outer cap) stopped this solve before its deterministic limits:
    the result may differ on a faster or less loaded machine. SolveInfo carries it."""
    lp_iterations: int = 0
    """Simplex iterations spent (a deterministic measure of the work done)."""
    crash_detail: str | None = None
    """For a search whose process died or hung (solve.isolated): how ('killed by SIGABRT')."""


ProgressCallback = Callable[[float, float | None, float | None], None]
"""progress(elapsed_seconds, incumbent_objective, gap) during a solve."""


def relative_gap(primal: float | None, dual: float | None) -> float | None:
    """(primal - dual) / |primal|, 0 when both are 0, None without an incumbent."""
    if primal is None or dual is None or not math.isfinite(primal):
        return None
    if not math.isfinite(dual):
        return math.inf
    diff = max(primal - dual, 0.0)
    if diff <= 1e-9:
        return 0.0
    return diff / max(abs(primal), 1e-9)


def stderr_progress(elapsed: float, incumbent: float | None, gap: float | None) -> None:
    """The default progress line: elapsed time, incumbent objective, gap."""
    inc = "none yet" if incumbent is None else f"{incumbent:.4g}"
    gap_text = "-" if gap is None else ("inf" if math.isinf(gap) else f"{100 * gap:.1f}%")
    print(f"  solving: {elapsed:6.1f} s  incumbent {inc}  gap {gap_text}", file=sys.stderr, flush=True)


class _Watch(Eventhdlr):
    """Tracks the incumbent and bound as SCIP finds them, stops SCIP at its LP-iteration
    budget, and interrupts it past the hard deadline. Progress lines come from a ticker
    thread (see _optimize): SCIP can spend long stretches in heuristics' sub-solvers, whose
    events never reach this handler.

    The iteration budget is checked here, in SCIP's own thread at its own events, so it
    stops every run at the same point; the deadline is checked by the ticker too, so it
    stops a run wherever the clock finds it (the outer cap, reported as such)."""

    EVENTS = (
        SCIP_EVENTTYPE.BESTSOLFOUND,
        SCIP_EVENTTYPE.NODESOLVED,
        SCIP_EVENTTYPE.LPSOLVED,
        SCIP_EVENTTYPE.PRESOLVEROUND,
    )

    def __init__(self, started: float, hard_deadline: float, progress: ProgressCallback | None,
                 interval: float = 1.5, lp_iteration_limit: int | None = None):
        super().__init__()
        self.lp_iteration_limit = lp_iteration_limit
        self.work_limit_fired = False
        self.started = started
        self.hard_deadline = hard_deadline
        self.progress = progress
        self.interval = interval
        self.next_report = started + interval
        self.first_solution: float | None = None
        self.primal: float | None = None
        self.dual: float | None = None
        self.guard_fired = False

    def eventinit(self):
        for event in self.EVENTS:
            self.model.catchEvent(event, self)

    def eventexit(self):
        for event in self.EVENTS:
            self.model.dropEvent(event, self)

    def eventexec(self, event):
        now = time.monotonic()
        if event.getType() == SCIP_EVENTTYPE.BESTSOLFOUND:
            if self.first_solution is None:
                self.first_solution = now - self.started
            self.primal = self.model.getPrimalbound()
        if self.primal is not None and event.getType() in (SCIP_EVENTTYPE.NODESOLVED, SCIP_EVENTTYPE.BESTSOLFOUND):
            dual = self.model.getDualbound()
            self.dual = dual if abs(dual) < self.model.infinity() else None
        if (self.lp_iteration_limit is not None and not self.work_limit_fired
                and event.getType() in (SCIP_EVENTTYPE.NODESOLVED, SCIP_EVENTTYPE.LPSOLVED)
                and self.model.getNLPIterations() >= self.lp_iteration_limit):
            self.work_limit_fired = True
            self.model.interruptSolve()
        if now >= self.hard_deadline and not self.guard_fired and not self.work_limit_fired:
            self.guard_fired = True
            self.model.interruptSolve()

    def tick(self, scip_model) -> None:
        """Called by the ticker thread about four times a second."""
        now = time.monotonic()
        if now >= self.hard_deadline and not self.guard_fired and not self.work_limit_fired:
            self.guard_fired = True
            try:
                scip_model.interruptSolve()  # sets SCIP's interrupt flag; SCIP stops at its next check
            except Exception:  # noqa: BLE001  (SCIP refuses outside its solving stages)
                self.guard_fired = False
        if self.progress is not None and now >= self.next_report:
            self.next_report = now + self.interval
            self.progress(now - self.started, self.primal, relative_gap(self.primal, self.dual))


def _optimize(scip_model, watch: _Watch) -> None:
    """Run SCIP without holding the GIL while a ticker thread reports progress and guards time."""
    stop = threading.Event()

    def ticker() -> None:
        while not stop.wait(0.25):
            watch.tick(scip_model)

    thread = threading.Thread(target=ticker, name="layoutdsl-scip-ticker", daemon=True)
    thread.start()
    try:
        with native_output_silenced():
            scip_model.optimizeNogil()
    finally:
        stop.set()
        thread.join()


_STATUS = {
    "optimal": "optimal",
    "gaplimit": "gap_limit",
    "timelimit": "time_limit",
    "nodelimit": "node_limit",
    "totalnodelimit": "node_limit",
    "stallnodelimit": "node_limit",
    "sollimit": "solution_limit",
    "bestsollimit": "solution_limit",
    "infeasible": "infeasible",
    # every variable is bounded, so "infeasible or unbounded" can only be infeasible
    "inforunbd": "infeasible",
    "userinterrupt": "interrupted",
}

ITERATION_LIMIT = "iteration_limit"
"""The status of a solve stopped by its LP-iteration budget (deterministic, like a node limit)."""


def _apply_emphasis(scip_model, emphasis: str) -> None:
    if emphasis not in EMPHASES:
        raise ValueError(f"unknown emphasis {emphasis!r}; expected one of {', '.join(EMPHASES)}")
    if emphasis == "heuristics":
        scip_model.setHeuristics(SCIP_PARAMSETTING.AGGRESSIVE)
    elif emphasis == "feasibility":
        scip_model.setEmphasis(SCIP_PARAMEMPHASIS.FEASIBILITY)
    elif emphasis == "optimality":
        scip_model.setEmphasis(SCIP_PARAMEMPHASIS.OPTIMALITY)
    elif emphasis == "easycip":
        scip_model.setEmphasis(SCIP_PARAMEMPHASIS.EASYCIP)


def _has_full_start(model: pyo.ConcreteModel) -> bool:
    return all(v.value is not None for v in model.component_data_objects(pyo.Var, active=True))


def solve(
    model: pyo.ConcreteModel,
    options: SolveOptions,
    *,
    progress: ProgressCallback | None = None,
    warm_start: bool = False,
    feasibility_only: bool = False,
) -> SolveOutcome:
    """Solve `model` with SCIP under `options`; load the best solution onto the model.

    `warm_start` hands the values currently on the variables to SCIP as a start (complete
    when every variable has a value, else the integer ones as a partial start). With
    `feasibility_only` the objective is dropped: SCIP stops at the first feasible layout.
    `progress` is called every ~1.5 s; by default (and unless options.quiet) a line goes to
    stderr. The solve stops at options' deterministic limits (nodes, LP iterations,
    solutions, gap); options.time_limit is the outer cap, and a solve stopped by it says so.
    """
    if progress is None and not options.quiet:
        progress = stderr_progress
    if options.quiet:
        progress = None
    started = time.monotonic()
    with native_output_silenced():
        return _solve(model, options, progress, warm_start, feasibility_only, started)


def _solve(model: pyo.ConcreteModel, options: SolveOptions, progress: ProgressCallback | None,
           warm_start: bool, feasibility_only: bool, started: float) -> SolveOutcome:
    interface, scip_model, loader = _translate(model, feasibility_only=feasibility_only)
    _configure(scip_model, options, remaining=options.time_limit - (time.monotonic() - started))
    if feasibility_only:
        scip_model.setParam("limits/solutions", 1)

    start_accepted = None
    if warm_start:
        start_accepted = _add_start(interface, scip_model, model, feasibility_only)

    watch = _Watch(started, started + options.time_limit + GUARD_GRACE_SECONDS, progress,
                   lp_iteration_limit=_lp_iteration_limit(options))
    if start_accepted and not feasibility_only:
        watch.primal = pyo.value(model.eq5_1_objective.expr)  # no event announces a start
    scip_model.includeEventhdlr(watch, "layoutdsl_watch", "progress, work limit and wall-clock guard")
    _optimize(scip_model, watch)
    seconds = time.monotonic() - started

    raw = scip_model.getStatus()
    status = _STATUS.get(raw, "unknown")
    if status == "interrupted":
        if watch.work_limit_fired:
            status = ITERATION_LIMIT
        elif not watch.guard_fired:
            scip_model.freeProb()
            raise KeyboardInterrupt  # SCIP caught the user's Ctrl-C: stop the whole compile
        else:
            status = "time_limit"
    has_solution = scip_model.getNSols() > 0
    primal = bound = None
    if has_solution:
        loader.load_vars()
        if not feasibility_only:
            primal = scip_model.getPrimalbound()
            bound = scip_model.getDualbound()
            if abs(bound) >= scip_model.infinity():
                bound = None  # SCIP's "infinity" (1e20) is a finite float: no bound yet
    gap = relative_gap(primal, bound) if not feasibility_only else None
    first = watch.first_solution
    if has_solution and first is None:
        first = seconds  # no event reported when: the end is an upper bound
    if has_solution and start_accepted:
        first = 0.0  # the start itself is a layout
    outcome = SolveOutcome(
        status=status,
        has_solution=has_solution,
        objective=primal,
        bound=bound if bound is None or math.isfinite(bound) else None,
        gap=gap,
        seconds=seconds,
        first_solution_seconds=first,
        nodes=int(scip_model.getNNodes()),
        start_accepted=start_accepted,
        wall_clock_limited=status == "time_limit",
        lp_iterations=int(scip_model.getNLPIterations()),
    )
    scip_model.freeProb()
    return outcome


def _lp_iteration_limit(options: SolveOptions) -> int:
    return DEFAULT_LP_ITERATIONS if options.lp_iteration_limit is None else int(options.lp_iteration_limit)


def _translate(model: pyo.ConcreteModel, *, feasibility_only: bool = False):
    """Pyomo model -> (ScipDirect interface, PySCIPOpt model, solution loader)."""
    objective = model.eq5_1_objective
    if feasibility_only:
        objective.deactivate()
    try:
        interface = ScipDirect()
        config = interface.config(value={}, preserve_implicit=True)
        config.timer = HierarchicalTimer()
        # Pyomo's translation alone: the public solve() would run optimize() itself, without
        # our event handler, emphasis and full warm start
        scip_model, loader = private_api.scip_model_of(interface, model, config)
    finally:
        if feasibility_only:
            objective.activate()
    scip_model.hideOutput(True)
    return interface, scip_model, loader


def _configure(scip_model, options: SolveOptions, *, remaining: float) -> None:
    """SCIP parameters from the options: quiet, emphasis, seed, limits, wall clock."""
    scip_model.setParam("display/verblevel", 0)
    _apply_emphasis(scip_model, options.emphasis)
    scip_model.setParam("randomization/randomseedshift", int(options.seed) % 2**31)
    scip_model.setParam("lp/threads", max(1, int(options.threads)))
    scip_model.setParam("parallel/maxnthreads", max(1, int(options.threads)))
    scip_model.setParam("timing/clocktype", 2)  # wall clock: the outer cap a user means
    scip_model.setParam("limits/time", max(0.05, remaining))
    scip_model.setParam("limits/gap", float(options.gap))
    # the deterministic stopping rules: nodes of this run and of all its restarts together
    # (SCIP's limits/nodes restarts counting after a presolve restart)
    nodes = DEFAULT_NODE_LIMIT if options.node_limit is None else int(options.node_limit)
    scip_model.setParam("limits/nodes", nodes)
    scip_model.setParam("limits/totalnodes", nodes)
    if options.solution_limit is not None:
        scip_model.setParam("limits/solutions", int(options.solution_limit))


def _add_start(interface: ScipDirect, scip_model, model: pyo.ConcreteModel, feasibility_only: bool,
               *, partial_fallback: bool = True) -> bool:
    """Hand the values on the Pyomo variables to SCIP; True when SCIP finds them feasible.

    Without `partial_fallback`, a start SCIP rejects is dropped rather than offered as a
    partial solution: a SCIP model re-solved many times (the neighbourhood search) keeps its
    partial solutions across rounds and refuses more than limits/maxorigsol of them.
    """
    var_map = private_api.scip_variables(interface)
    full = _has_full_start(model)
    if not full and not partial_fallback:
        return False
    sol = scip_model.createSol() if full else scip_model.createPartialSol()
    for pyomo_var, scip_var in var_map.items():
        if pyomo_var.value is None or (not full and not pyomo_var.is_integer()):
            continue
        value = pyomo_var.value
        if pyomo_var.is_integer():
            value = round(value)
        scip_model.setSolVal(sol, scip_var, value)
    if not full:
        scip_model.addSol(sol)
        return True
    # Pyomo moves the objective into a variable t >= expr; give it the expression's value
    obj_var = private_api.scip_objective_variable(interface)
    if obj_var is not None:
        value = 0.0 if feasibility_only else pyo.value(model.eq5_1_objective.expr)
        scip_model.setSolVal(sol, obj_var, value)
    feasible = scip_model.checkSol(sol, printreason=False, completely=False, original=True)
    if feasible:
        scip_model.addSol(sol, free=True)
        return True
    if not partial_fallback:
        scip_model.freeSol(sol)
        return False
    # An inexact start still helps: SCIP repairs partial starts with its completion heuristic
    partial = scip_model.createPartialSol()
    for pyomo_var, scip_var in var_map.items():
        if pyomo_var.value is not None and pyomo_var.is_integer():
            scip_model.setSolVal(partial, scip_var, round(pyomo_var.value))
    scip_model.addSol(partial)
    scip_model.freeSol(sol)
    return False


def polish(model: pyo.ConcreteModel, options: SolveOptions, *, gap: float = 1e-4) -> SolveOutcome:
    """Best continuous geometry for the binaries currently on the model (relations, orientations).

    Every binary variable is fixed at its current value, the rest (a linear program plus the
    area and error terms) solved to `gap`, and the binaries released again. With the relative
    positions decided, this takes a fraction of a second where full branch-and-bound may not
    improve a start at all within its limit. The model keeps the polished values when a
    solution is found, else the values it had.
    """
    binaries = [v for v in model.component_data_objects(pyo.Var) if v.is_binary() and not v.fixed]
    for var in binaries:
        if var.value is None:
            raise ValueError(f"polish needs a value on every binary; {var.name} has none")
        var.fix(round(var.value))
    idle = _idle_separations(model)
    for constraint in idle:
        constraint.deactivate()
    try:
        return solve(model, replace(options, gap=gap, emphasis="default", node_limit=POLISH_NODE_LIMIT,
                                    solution_limit=None, lp_iteration_limit=None),
                     warm_start=True)
    finally:
        for var in binaries:
            var.unfix()
        for constraint in idle:
            constraint.activate()


def _idle_separations(model: pyo.ConcreteModel) -> list:
    """The (5.8) constraints that cannot bind once every binary is fixed: each side whose ω
    is 0 (its big-M holds it for every value the variables' bounds allow) and each pair's
    "one side at least", met by the fixed values. Left out of the translation, they cost
    nothing: they are 3 in 4 of a model's constraints, and translating them took a third of
    a 52-room polish (measured on school_wilbraham: 0.9 of 1.6 s translating, 9712
    constraints)."""
    block = getattr(model, "eq5_8_non_overlap", None)
    if block is None:
        return []
    idle = []
    for a, b in block.pairs:
        sides = [(s, block.side[a, b, s]) for s in model.sides]
        if not all(var.fixed for _, var in sides):
            continue
        # a settled model (settle_separations) has only the separations that bind
        idle += [block.separate[a, b, s] for s, var in sides
                 if round(var.value) == 0 and (a, b, s) in block.separate]
        if sum(round(var.value) for _, var in sides) >= 1 and (a, b) in block.one_side:
            idle.append(block.one_side[a, b])
    return [constraint for constraint in idle if constraint.active]


@dataclass(slots=True)
class NeighbourhoodOutcome:
    """What improve_by_neighbourhoods did; the best layout found is loaded on the model."""

    rounds: int
    improvements: int
    objective: float
    """The model's objective at the end (SCIP's form, helper slack included)."""
    seconds: float
    wall_clock_limited: bool = False
    """The deadline stopped the search (or one of its rounds) before its deterministic rules."""


def _binaries_by_rooms(model: pyo.ConcreteModel) -> list[tuple[object, tuple[str, ...]]]:
    """Every free binary of the model with the rooms whose geometry it decides."""
    rooms = set(model.rooms)
    found = [(model.o[r], (r,)) for r in model.rooms]
    for (a, b, _side), var in model.eq5_8_non_overlap.side.items():
        found.append((var, tuple(r for r in (a, b) if r in rooms)))
    for (a, b), var in model.eq5_9_adjacency.stacked.items():
        found.append((var, (a, b)))
    for (r, _side), var in model.eq5_12_on_boundary.side.items():
        found.append((var, (r,)))
    return [(var, owners) for var, owners in found if not var.fixed]


def _continuous_by_room(model: pyo.ConcreteModel) -> dict[str, list]:
    """Each room's continuous variables: its geometry and its objective helpers."""
    families = [model.x, model.y, model.w, model.h, model.eq5_2_cover.area,
                model.eq5_3_error.err_w, model.eq5_3_error.err_h, model.eq5_3_error.sq]
    if hasattr(model, "long"):
        families += [model.long, model.short]
    return {r: [family[r] for family in families] for r in model.rooms}


def _nearest_rooms(model: pyo.ConcreteModel, centre_room: str, size: int) -> set[str]:
    """`centre_room` and the `size - 1` rooms nearest its walls: by the gap between the two
    rectangles, then by centre distance, then by id.

    A room grows only when the rooms across its walls give way, and beside a long corridor
    or hall those are not the rooms with the nearest centres. Measured on office_PineCondos
    (43 rooms, 60 s compile): 24-26 of 44-49 rounds improved with this order and the rooms
    reached 0.86 of their target area; by centre distance 32 of 79 rounds, 0.845.
    """
    boxes = {r: (pyo.value(model.x[r]), pyo.value(model.y[r]), pyo.value(model.w[r]), pyo.value(model.h[r]))
             for r in model.rooms}
    cx, cy, cw, ch = boxes[centre_room]

    def distance(r: str) -> tuple[float, float, str]:
        x, y, w, h = boxes[r]
        gap_x = max(0.0, x - (cx + cw), cx - (x + w))
        gap_y = max(0.0, y - (cy + ch), cy - (y + h))
        off_x, off_y = x + w / 2 - (cx + cw / 2), y + h / 2 - (cy + ch / 2)
        # rounded: rooms a wall apart tie despite solver noise, and the centres decide
        return (round(gap_x**2 + gap_y**2, 6), off_x**2 + off_y**2, r)

    return set(sorted(model.rooms, key=distance)[:size])


def _free_only(scip_model, binaries, continuous, free_binaries: set[str], free_rooms: set[str]) -> None:
    """Fix every SCIP variable at its current value except the free rooms' (their bounds back)."""
    for var, scip_var, owners in binaries:
        if owners and all(owner in free_binaries for owner in owners):
            scip_model.chgVarLb(scip_var, 0)
            scip_model.chgVarUb(scip_var, 1)
        else:
            value = round(var.value)
            scip_model.chgVarLb(scip_var, value)
            scip_model.chgVarUb(scip_var, value)
    for room, entries in continuous.items():
        for var, scip_var, (lb, ub) in entries:
            if room in free_rooms:
                scip_model.chgVarLb(scip_var, -scip_model.infinity() if lb is None else lb)
                scip_model.chgVarUb(scip_var, scip_model.infinity() if ub is None else ub)
            else:
                scip_model.chgVarLb(scip_var, var.value)
                scip_model.chgVarUb(scip_var, var.value)


def improve_by_neighbourhoods(
    model: pyo.ConcreteModel,
    options: SolveOptions,
    *,
    deadline: float,
    size: int = 4,
    sub_nodes: int = 200,
    sub_lp_iterations: int = 20_000,
    max_rounds: int | None = None,
    progress: ProgressCallback | None = None,
    sub_seconds: float | None = None,
) -> NeighbourhoodOutcome:
    """Large-neighbourhood search from the layout on the model, until `deadline`.

    Each round frees one room and the `size - 1` rooms nearest its walls: their binaries (relations,
    orientations, sides) and their geometry; every other room keeps its place, size and
    relations. SCIP re-places the neighbourhood (warm-started from the current layout, at
    most `sub_nodes` branch-and-bound nodes and `sub_lp_iterations` simplex iterations).
    After an improvement, a polish round keeps every binary and frees all geometry. Rooms
    are visited in an order drawn from the seed; the search stops after a full pass without
    an improvement or after `max_rounds` rounds (default: three per room). Those rules are
    deterministic, so the result depends only on the seed; `deadline` is only the outer
    cap, and the outcome says when it stopped the search. (`sub_seconds`, a per-round wall
    clock that made rounds end differently under load, is accepted and ignored.) Branch-and-bound over the whole model rarely improves a
    layout of 15+ rooms within a minute (its area terms are nonconvex for every room); a
    neighbourhood of four rooms solves in about a second.
    """
    if progress is None and not options.quiet:
        progress = stderr_progress
    if options.quiet:
        progress = None
    started = time.monotonic()
    with native_output_silenced():
        return _improve_by_neighbourhoods(model, options, deadline, size, sub_nodes, sub_lp_iterations,
                                          max_rounds, progress, started)


def _improve_by_neighbourhoods(model, options, deadline, size, sub_nodes, sub_lp_iterations, max_rounds,
                               progress, started) -> NeighbourhoodOutcome:
    interface, scip_model, loader = _translate(model)
    sub_options = replace(options, gap=1e-4, emphasis="default", node_limit=sub_nodes, solution_limit=None)
    _configure(scip_model, sub_options, remaining=max(0.05, deadline - time.monotonic()))
    scip_model.setPresolve(SCIP_PARAMSETTING.FAST)  # measured: sub-problems solve faster
    watch = _Watch(started, deadline + GUARD_GRACE_SECONDS, None, lp_iteration_limit=sub_lp_iterations)
    scip_model.includeEventhdlr(watch, "layoutdsl_watch", "wall-clock guard")
    var_map = private_api.scip_variables(interface)
    binaries = [(var, var_map[var], owners) for var, owners in _binaries_by_rooms(model) if var in var_map]
    continuous = {r: [(v, var_map[v], v.bounds) for v in vs if v in var_map and not v.fixed]
                  for r, vs in _continuous_by_room(model).items()}
    order = list(model.rooms)
    random.Random(options.seed).shuffle(order)
    if max_rounds is None:
        max_rounds = 3 * len(order)
    objective = pyo.value(model.eq5_1_objective.expr)
    rounds = improvements = stale = visits = 0
    polish_next = False
    clock_stopped = False
    next_report = started + 1.5
    while stale < len(order) and rounds < max_rounds:
        if deadline - time.monotonic() <= 0.1:
            clock_stopped = True
            break
        rounds += 1
        if polish_next:
            free_binaries, free_rooms = set(), set(model.rooms)
        else:
            free_rooms = free_binaries = _nearest_rooms(model, order[visits % len(order)], size)
            visits += 1
        scip_model.freeTransform()
        _free_only(scip_model, binaries, continuous, free_binaries, free_rooms)
        # the clock is only the outer cap; each round stops at its node and iteration limits
        scip_model.setParam("limits/time", max(0.05, deadline - time.monotonic()))
        watch.work_limit_fired = False
        _add_start(interface, scip_model, model, False, partial_fallback=False)
        _optimize(scip_model, watch)
        round_status = scip_model.getStatus()
        if round_status == "userinterrupt" and not watch.guard_fired and not watch.work_limit_fired:
            scip_model.freeProb()
            raise KeyboardInterrupt  # SCIP caught the user's Ctrl-C: stop the whole compile
        if round_status == "timelimit" or watch.guard_fired:
            clock_stopped = True  # this round's answer depends on the load: keep what came before
            break
        # improvements below a tenth of the target gap are noise that would keep the search
        # going without changing the answer
        threshold = max(1e-6, options.gap / 10) * max(1.0, abs(objective))
        improved = scip_model.getNSols() > 0 and scip_model.getPrimalbound() < objective - threshold
        if improved:
            loader.load_vars()
            objective = pyo.value(model.eq5_1_objective.expr)
            improvements += 1
        if polish_next:
            polish_next = False
        elif improved:
            stale = 0
            polish_next = True
        else:
            stale += 1
        now = time.monotonic()
        if progress is not None and now >= next_report:
            next_report = now + 1.5
            progress(now - started, objective, None)
    scip_model.freeProb()
    return NeighbourhoodOutcome(rounds, improvements, objective, time.monotonic() - started,
                                wall_clock_limited=clock_stopped)
