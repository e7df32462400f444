"""Compile a checked spec to a verified Layout.

    from layoutdsl.compile import compile_spec
    result = compile_spec(spec, SolveOptions(time_limit=60))

The package is laid out as the design (docs/generator.md):
- strategies.py: the strategy table ('auto', 'thesis');
- pipeline.py: the stages, from a first layout to a verified Layout;
- budgets.py: every work limit and time share, in one table;
- generator.py: the one generator of first layouts, built of
  structure.py (what cannot be drawn), shapes.py (how a corridor becomes an L), initial.py
  (the initial state), representation.py
  (sequence pairs and their packing), moves.py, cost.py and schedule.py (the annealing);
  the sizing with relations fixed lives in layoutdsl.solve.relations;
- variants.py: several different layouts of one spec; explain.py: why a spec has none.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from layoutdsl.compile.strategies import STRATEGIES

if TYPE_CHECKING:
    from layoutdsl.compile.pipeline import CompileResult, StartProvider
    from layoutdsl.layout.geometry import Rect
    from layoutdsl.solve import ProgressCallback, SolveOptions
    from layoutdsl.syntax.ast import Spec

__all__ = ["CompileResult", "STRATEGIES", "compile_spec"]


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

    options.strategy names a row of STRATEGIES; `start` (rectangles to polish instead of
    generating), `start_provider` (another first-layout provider) and `explain_infeasible`
    go to the pipeline.
    """
    from layoutdsl.compile import explain
    from layoutdsl.compile.pipeline import CompileResult, compile_from_start

    if options.strategy not in STRATEGIES:
        raise ValueError(f"unknown strategy {options.strategy!r}; one of {', '.join(STRATEGIES)}")
    if spec.arms and options.strategy == "thesis":
        return CompileResult(None, [explain.strategy_without_l_rooms(spec, options.strategy)], "no_layout")
    return compile_from_start(spec, options, start=start, start_provider=start_provider, progress=progress,
                              explain_infeasible=explain_infeasible)


def __getattr__(name: str):
    # CompileResult is imported lazily: the pipeline pulls in SCIP and numba
    if name == "CompileResult":
        from layoutdsl.compile.pipeline import CompileResult

        return CompileResult
    raise AttributeError(name)
