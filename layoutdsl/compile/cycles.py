"""Cycle decomposition (the thesis, §5.5.3): solve a cycle of rooms alone, keep it as a cluster.

Rooms on a cycle of the room graph constrain each other's positions *and* sizes, which is
what makes a spec hard. The thesis' remedy, reproduced here:

1. the minimum cycle basis of the room graph (networkx), which holds chordless cycles;
   among them the longest (default, "usually works better") or the shortest;
2. a sub-problem: the cycle's rooms plus every room adjacent to them, with the adjacencies
   among those rooms, compiled with its own time limit (default 40 % of the time left:
   the thesis used 40 s of a 4-minute budget, and it is the share it tunes);
3. the centres of the cycle's rooms in that solution, translated so the smallest x and y
   are 0, become a new Cluster (margin = settings.cluster_margin);
4. the global problem is compiled again with the cluster; if it still fails, the next cycle
   is taken from the graph with the already-clustered rooms removed, until none is left.
"""

from __future__ import annotations

import time
from dataclasses import replace

import networkx as nx

from layoutdsl.compile import explain
from layoutdsl.compile.generate import room_graph
from layoutdsl.compile.pipeline import compile_from_start
from layoutdsl.syntax.ast import Cluster, ClusterMember, Spec

DEFAULT_SUB_SHARE = 0.4
"""Share of the remaining time a cycle's sub-problem may use."""

CHOICES = ("longest", "shortest")


def cycle_rank(spec: Spec) -> int:
    """Independent cycles of the room graph: edges - nodes + components."""
    graph = room_graph(spec)
    return graph.number_of_edges() - graph.number_of_nodes() + nx.number_connected_components(graph)


def pick_cycle(
    spec: Spec, exclude: set[str] = frozenset(), choose: str = "longest"
) -> list[str] | None:
    """A cycle of the minimum cycle basis (without the excluded rooms), or None if none is left.

    Ties are broken by the sorted room ids, so the choice is deterministic.
    """
    if choose not in CHOICES:
        raise ValueError(f"choose must be one of {CHOICES}, got {choose!r}")
    graph = room_graph(spec)
    graph.remove_nodes_from(exclude)
    basis = [sorted(cycle) for cycle in nx.minimum_cycle_basis(graph)]
    if not basis:
        return None
    if choose == "longest":
        return min(basis, key=lambda cycle: (-len(cycle), cycle))
    return min(basis, key=lambda cycle: (len(cycle), cycle))


def subproblem(spec: Spec, cycle: list[str]) -> Spec:
    """The cycle's rooms and their neighbours, with every constraint among them only."""
    graph = room_graph(spec)
    keep = set(cycle)
    for room_id in cycle:
        keep.update(graph.neighbors(room_id))
    return spec.restricted_to(keep, f"{spec.name}-cycle")


def cycle_cluster(
    cluster_id: str, cycle: list[str], centres: dict[str, tuple[float, float]]
) -> Cluster:
    """The cycle rooms' centres as a cluster, normalised so min x = min y = 0 (Figure 5.8)."""
    min_x = min(centres[room][0] for room in cycle)
    min_y = min(centres[room][1] for room in cycle)
    members = tuple(
        ClusterMember(room, centres[room][0] - min_x, centres[room][1] - min_y)
        for room in cycle
    )
    return Cluster(cluster_id, members)


def _fresh_cluster_id(spec: Spec) -> str:
    taken = {c.id for c in spec.clusters} | set(spec.room_ids)
    index = 0
    while f"cycle{index}" in taken:
        index += 1
    return f"cycle{index}"


def compile_with_cycles(
    spec: Spec,
    options,
    progress=None,
    *,
    choose: str = "longest",
    sub_share: float = DEFAULT_SUB_SHARE,
    try_plain_first: bool = False,
):
    """Compile with cycle decomposition (§5.5.3); a pipeline.CompileResult.

    With `try_plain_first`, the spec is first compiled as it is ('auto') and decomposed only
    if that finds nothing, as the thesis used it; `strategy="cycles"` decomposes at once.
    The whole run keeps to options.time_limit.
    """
    began = time.monotonic()
    deadline = began + options.time_limit
    # the decomposition's own solves must not fall back to decomposition again
    auto = replace(options, strategy="auto", cycles_fallback=False)

    def remaining() -> float:
        return max(0.1, deadline - time.monotonic())

    result = None
    if try_plain_first:
        result = compile_from_start(spec, replace(auto, time_limit=remaining() * 0.5),
                              progress=progress, explain_infeasible=False)
        if result.layout is not None:
            return result
    current = spec
    clustered: set[str] = set()
    while deadline - time.monotonic() > 0.2:
        cycle = pick_cycle(current, clustered, choose)
        if cycle is None:
            break
        sub = subproblem(current, cycle)
        sub_result = compile_from_start(sub, replace(auto, time_limit=remaining() * sub_share),
                                  progress=progress, explain_infeasible=False)
        clustered.update(cycle)
        if sub_result.layout is None:
            continue  # this cycle alone is too hard in its time: try the next one
        centres = {room.id: room.centre for room in sub_result.layout.rooms}
        cluster = cycle_cluster(_fresh_cluster_id(current), cycle, centres)
        current = replace(current, clusters=current.clusters + (cluster,))
        result = compile_from_start(current, replace(auto, time_limit=remaining()),
                              progress=progress, explain_infeasible=False)
        if result.layout is not None:
            return _as_cycles(result)
    if result is None:
        result = compile_from_start(current, replace(auto, time_limit=remaining()), progress=progress)
    if result.layout is None:
        status = result.outcome.status if result.outcome is not None else "time_limit"
        result = replace(result, diagnostics=explain.restate_limit(result.diagnostics, spec, options, status))
    return _as_cycles(result)


def _as_cycles(result):
    """Mark a layout found with decomposition as such (SolveInfo.method)."""
    if result.layout is None or result.layout.solve is None:
        return result
    info = replace(result.layout.solve, method=f"cycles+{result.layout.solve.method}")
    return replace(result, layout=replace(result.layout, solve=info))
