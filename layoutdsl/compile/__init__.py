"""Compile a checked spec to a verified Layout: the dispatcher over the strategies.

    from layoutdsl.compile import compile_spec
    result = compile_spec(spec, SolveOptions(time_limit=60))

The strategies, each a module of this package:
- 'auto' and 'thesis' (`pipeline.compile_from_start`): a first feasible layout (the
  construction, `construct.py`) polished by SCIP; 'thesis' solves the thesis' formulation
  as written from scratch (the thesis, §5.5.1).
- 'cycles' (`cycles.compile_with_cycles`): cycle decomposition (§5.5.3), also the fallback
  of 'auto' when the construction finds no start.
`variants.py` compiles several different layouts of one spec; `explain.py` says why a spec
has none.
"""

from __future__ import annotations

from collections.abc import Mapping

from layoutdsl.compile import cycles, explain
from layoutdsl.compile.pipeline import CompileResult, StartProvider, compile_from_start
from layoutdsl.layout.geometry import Rect
from layoutdsl.solve import ProgressCallback, SolveOptions
from layoutdsl.syntax.ast import Spec

__all__ = ["CompileResult", "compile_spec"]


def compile_spec(
    spec: Spec,
    options: SolveOptions,
    *,
    start: Mapping[str, Rect] | None = None,
    start_provider: StartProvider | None = None,
    progress: ProgressCallback | None = None,
    explain_infeasible: bool = True,
) -> CompileResult:
    """Compile a checked spec to a verified Layout under `options` (strategy, limits, seed).

    options.strategy picks the strategy ('auto', 'thesis' or 'cycles'); `start`,
    `start_provider` and `explain_infeasible` go to 'auto' and 'thesis'. When 'auto' finds
    no start and the room graph has cycles, it spends the time left on cycle decomposition
    (unless options.cycles_fallback is off).
    """
    if spec.arms and options.strategy in ("cycles", "thesis"):
        return CompileResult(None, [explain.strategy_without_l_rooms(spec, options.strategy)], "no_layout")
    if options.strategy == "cycles":
        return cycles.compile_with_cycles(spec, options, progress=progress)
    # The thesis' remedy when generation finds nothing (§5.5.3). SCIP from scratch, the
    # alternative, finds no layout from about 20 rooms up (solver scouting), so the time left
    # is better spent decomposing.
    # (not with L-rooms: the decomposition solves the thesis' model of rectangles)
    decompose = (options.strategy == "auto" and options.cycles_fallback and not spec.arms
                 and cycles.cycle_rank(spec) > 0)
    fallback = _decompose_cycles if decompose else None
    return compile_from_start(
        spec, options, start=start, start_provider=start_provider, progress=progress,
        explain_infeasible=explain_infeasible, no_start_fallback=fallback,
    )  # fmt: skip


def _decompose_cycles(spec: Spec, options: SolveOptions, progress: ProgressCallback | None) -> CompileResult:
    return cycles.compile_with_cycles(spec, options, progress=progress)
