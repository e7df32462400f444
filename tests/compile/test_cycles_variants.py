"""Cycle decomposition (§5.5.3) and variants (§6.2)."""

from __future__ import annotations

import json
import time

from layoutdsl.compile import compile_spec
from layoutdsl.compile.construct import construct_start, rects_to_layout
from layoutdsl.compile.cycles import (
    compile_with_cycles,
    cycle_cluster,
    cycle_rank,
    pick_cycle,
    subproblem,
)
from layoutdsl.solve import SolveOptions
from layoutdsl.compile.variants import compile_variants, diversity
from layoutdsl.layout.verify import verify

from _specs import adjacent, cycle_spec, room, tree_spec
from dataclasses import replace


def two_cycle_spec():
    """A 5-ring and a triangle sharing room A: two basis cycles of lengths 5 and 3."""
    spec = cycle_spec()
    extra = (room("H", 3.0, 3.0),)
    adjacencies = spec.adjacencies + (adjacent("F", "H"), adjacent("A", "H"))
    return replace(spec, rooms=spec.rooms + extra, adjacencies=adjacencies,
                   boundary=replace(spec.boundary, w=24.0, h=24.0))


def test_cycle_choice_longest_and_shortest():
    spec = two_cycle_spec()
    assert cycle_rank(spec) == 2
    assert pick_cycle(spec, choose="longest") == ["A", "B", "C", "D", "E"]
    assert pick_cycle(spec, choose="shortest") == ["A", "F", "H"]
    # clustered rooms are removed before the next cycle is looked for
    assert pick_cycle(spec, {"A", "B", "C", "D", "E"}) is None
    assert pick_cycle(tree_spec()) is None


def test_subproblem_keeps_cycle_and_neighbours_only():
    spec = two_cycle_spec()
    sub = subproblem(spec, ["A", "B", "C", "D", "E"])
    assert set(sub.room_ids) == {"A", "B", "C", "D", "E", "F", "G", "H"}
    sub = subproblem(spec, ["A", "F", "H"])
    assert set(sub.room_ids) == {"A", "B", "E", "F", "H"}
    assert all(a.a in sub.room_ids and a.b in sub.room_ids for a in sub.adjacencies)


def test_cluster_from_a_solved_cycle_is_normalised_and_solvable():
    spec = cycle_spec()
    cycle = pick_cycle(spec)
    sub = subproblem(spec, cycle)
    rects = construct_start(sub, deadline=time.monotonic() + 20)
    centres = {r.id: r.centre for r in rects_to_layout(sub, rects).rooms}
    cluster = cycle_cluster("cycle0", cycle, centres)
    assert min(m.x for m in cluster.members) == 0.0
    assert min(m.y for m in cluster.members) == 0.0
    assert {m.room for m in cluster.members} == set(cycle)
    clustered = replace(spec, clusters=(cluster,))
    rects = construct_start(clustered, deadline=time.monotonic() + 20)
    assert rects is not None
    assert verify(clustered, rects_to_layout(clustered, rects)) == []


def test_compile_with_cycles_gives_a_verified_layout_marked_as_such():
    spec = cycle_spec()
    result = compile_with_cycles(spec, SolveOptions(time_limit=6, quiet=True, strategy="cycles"))
    assert result.layout is not None
    assert result.layout.solve.method.startswith("cycles")
    assert verify(spec, result.layout) == []


def test_variants_are_verified_different_and_written(tmp_path):
    spec = tree_spec()
    result = compile_variants(spec, 3, seed=1, options=SolveOptions(time_limit=4, quiet=True),
                              outdir=tmp_path, formats=("xml",))
    assert all(layout is not None for layout in result.layouts)
    for layout in result.layouts:
        assert verify(spec, layout) == []
    assert result.diversity is not None and result.diversity > 0
    for k in (1, 2, 3):
        data = json.loads((tmp_path / f"tree-{k}.layout.json").read_text())
        assert {r["id"] for r in data["rooms"]} == set(spec.room_ids)
        assert (tmp_path / f"tree-{k}.xml").exists()


def test_diversity_of_identical_layouts_is_zero():
    spec = cycle_spec()
    layout = rects_to_layout(spec, construct_start(spec, deadline=time.monotonic() + 20))
    assert diversity([layout, layout]) == 0.0


def test_auto_falls_back_to_cycle_decomposition_when_construction_finds_nothing():
    # A start provider that fails stands in for a construction that found nothing in time.
    spec = cycle_spec()
    result = compile_spec(spec, SolveOptions(time_limit=8, quiet=True),
                          start_provider=lambda _spec, _options: None)
    assert result.layout is not None
    assert result.layout.solve.method.startswith("cycles")
    assert verify(spec, result.layout) == []


def test_auto_without_cycles_falls_back_to_scip_alone(monkeypatch):
    # Nothing to decompose: SCIP alone. A three-room tree keeps SCIP's part well inside the
    # limit on a loaded machine (the ten-room tree took all of 8 s under load).
    from layoutdsl.compile import cycles

    def no_decomposition(*args, **kwargs):
        raise AssertionError("a tree has no cycle to decompose")

    monkeypatch.setattr(cycles, "compile_with_cycles", no_decomposition)
    full = tree_spec()
    kept = {"C0", "R0", "R1"}
    spec = replace(full, rooms=tuple(r for r in full.rooms if r.id in kept),
                   adjacencies=tuple(a for a in full.adjacencies if {a.a, a.b} <= kept))
    result = compile_spec(spec, SolveOptions(time_limit=8, quiet=True),
                          start_provider=lambda _spec, _options: None)
    assert result.layout is not None
    assert result.layout.solve.method == "scip"
    assert verify(spec, result.layout) == []
