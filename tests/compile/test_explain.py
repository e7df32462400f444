"""Infeasible specs: the deletion filter names exactly the conflicting lines."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from layoutdsl.api import read_source, lint_source
from layoutdsl.compile import compile_spec
from layoutdsl.compile.explain import E901, conflicting_groups, constraint_groups, scip_feasibility, spec_without
from layoutdsl.solve import SolveOptions

from spec_cases import room, spec
from layoutdsl.syntax.ast import Adjacency, Position

SOLVE = Path(__file__).resolve().parents[1] / "diagnostics" / "solve"


def _no_start(spec, options):
    return None


def test_ten_room_spec_with_positions_too_far_apart_names_exactly_the_conflicting_lines():
    source = read_source(str(SOLVE / "E901-positions-too-far.lay"))
    parsed, lint = lint_source(source)
    assert parsed is not None and not lint, "lint cannot see this conflict"
    result = compile_spec(parsed, SolveOptions(time_limit=20, quiet=True), start_provider=_no_start)
    assert result.layout is None and result.status == "infeasible"
    lines = {source.line_text(d.span.line).split("#")[0].strip() for d in result.diagnostics}
    assert {d.code for d in result.diagnostics} == {E901}
    assert lines == {
        "A1 2.7 4.1 3.4 2.6 4 3.3 1 1.6 R OFFICE",  # A1's maximum size
        "A2 2.7 4.1 3.4 2.6 4 3.3 1 1.6 R OFFICE",  # A2's maximum size
        "A1 A2 0.9 e",  # the adjacency
        "A1 1.5 11",  # the two positions
        "A2 15.5 11",
    }


def test_the_reported_lines_are_an_irreducible_conflict():
    # with every unreported line dropped, the reported ones still conflict, and dropping any
    # one of them as well leaves a feasible spec
    source = read_source(str(SOLVE / "E901-positions-too-far.lay"))
    parsed, _ = lint_source(source)
    import time

    groups = conflicting_groups(parsed, deadline=time.monotonic() + 30)
    assert groups is not None and len(groups) == 5
    reported = {(g.kind, g.key) for g in groups}
    background = {(g.kind, g.key) for g in constraint_groups(parsed)} - reported
    assert scip_feasibility(spec_without(parsed, background), 5) is False
    for group in groups:
        relaxed = spec_without(parsed, background | {(group.kind, group.key)})
        assert scip_feasibility(relaxed, 5) is True, group.describe


def test_on_boundary_flag_can_be_part_of_a_conflict():
    # A must cover the centre of a 12 x 12 boundary and touch a side, but is at most 4 m wide
    s = spec("onb", [room("A", (2, 4, 3), (2, 4, 3), on_boundary=True), room("B", (2, 4, 3), (2, 4, 3))],
             12, 12, positions=[Position("A", 6, 6)], adjacencies=[Adjacency("A", "B", 0.9, "e")])
    import time

    groups = conflicting_groups(s, deadline=time.monotonic() + 20)
    assert groups is not None
    assert {(g.kind, g.key) for g in groups} == {("onB", "A"), ("position", 0), ("size", "A")}


def test_no_layout_says_whether_work_or_the_clock_stopped_the_generator():
    from layoutdsl.compile import explain
    from layoutdsl.compile.generator import Generated
    from layoutdsl.compile.pipeline import _work_ran_out

    one = spec("one", [room("A", (2, 3, 2.5), (2, 3, 2.5))], 5, 5)
    options = SolveOptions(time_limit=60.0)
    ran_out = _work_ran_out(Generated(None, one, "", rounds=8, moves=4_590_000))
    assert ran_out == (8, 4_590_000)
    # the work limits ran out and nothing searched after: the clock had no part in it
    alone = explain.no_layout_in_time(one, options, exhausted=ran_out)
    assert alone.message == "no layout found within the generator's work limits (8 rounds, 4,590,000 moves)"
    assert "--time-limit" not in alone.help and "--seed" in alone.help
    # SCIP searched alone after the generator, until the time limit: both are said, and more
    # time is worth a try for that search
    searched = explain.no_layout_in_time(one, options, "time_limit", exhausted=ran_out, searched=True)
    assert searched.message == ("no layout found within the generator's work limits (8 rounds, 4,590,000 moves), "
                                "nor by the solver alone within the time limit of 60 s")
    assert "`--time-limit`" in searched.help
    # the clock cut the generator off: the time limit is what stopped it
    cut_off = _work_ran_out(Generated(None, one, "", rounds=3, moves=90_000, cut_off=True))
    assert cut_off is None
    cut = explain.no_layout_in_time(one, options, exhausted=cut_off)
    assert cut.message == "no layout found within the time limit of 60 s" and "`--time-limit`" in cut.help
    # a node limit that stopped SCIP is the limit to raise
    nodes = explain.no_layout_in_time(one, SolveOptions(time_limit=60.0, node_limit=1), "node_limit")
    assert nodes.message == "no layout found within the node limit of 1"
    assert "`--node-limit`" in nodes.help and "--time-limit" not in nodes.help
    assert {d.code for d in (alone, searched, cut, nodes)} == {"E902"}
