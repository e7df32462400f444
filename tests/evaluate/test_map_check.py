"""evaluate checks that each map realises its portal graph, opens missed doors, names the rest."""

from __future__ import annotations

from dataclasses import replace

import pytest

from layoutdsl.importer.building import LineSegment, Point

from layoutdsl.evaluate.plan import EvaluateOptions, measure_plan
from layoutdsl.evaluate.report import evaluate, map_check_warnings, render_markdown

from .synthetic import building, corridor_plan, rect_space

OPTIONS = EvaluateOptions(seed=1)


def _door_off_the_wall():
    """corridor_plan with the C0-E1 door drawn 1 m inside E1: the rasterization cannot open it."""
    return building([
        rect_space("E0", "E", "ENTRANCE", 0, 0, 400, 400, (((400, 200), "C0", "EXPLICIT"),)),
        rect_space("C0", "C", "CORRIDOR", 400, 140, 1200, 120,
                   (((400, 200), "E0", "EXPLICIT"), ((1700, 200), "E1", "EXPLICIT"))),
        rect_space("E1", "E", "ENTRANCE", 1600, 0, 400, 400, (((1700, 200), "C0", "EXPLICIT"),)),
    ])


def test_a_good_map_realises_its_portal_graph_untouched():
    check = measure_plan(corridor_plan(), OPTIONS).map_check
    assert check.realised_before and check.realised and not check.opened


def test_a_door_the_rasterization_missed_is_opened_and_the_entrance_reachable():
    good = measure_plan(corridor_plan(), OPTIONS)
    broken = measure_plan(_door_off_the_wall(), OPTIONS)
    check = broken.map_check
    assert check.missing_before == (("C0", "E1"),)
    assert check.opened == (("C0", "E1"),)
    assert check.realised and not check.realised_before
    # the path between the entrances exists again, about as long as through the real door
    length = broken.path_lengths[("E0", "E1")]
    assert length is not None
    assert length == pytest.approx(good.path_lengths[("E0", "E1")], rel=0.05)
    assert broken.exploration.final_coverage >= 0.99


def test_joins_without_a_portal_are_named_in_the_report():
    # R0 has a PORTAL segment on the wall it shares with C0 that no <portal> references (as
    # in real plans): the rasterization opens it, joining rooms the portal graph keeps apart
    office = rect_space("R0", "R", "OFFICE", 900, 260, 300, 300)
    stray = LineSegment("R0-stray", Point(1050, 260), Point(1050, 260), "PORTAL", "EXPLICIT")
    plan = building([
        rect_space("E0", "E", "ENTRANCE", 0, 0, 400, 400, (((400, 200), "C0", "EXPLICIT"),)),
        rect_space("C0", "C", "CORRIDOR", 400, 140, 1200, 120, (((400, 200), "E0", "EXPLICIT"),)),
        replace(office, segments=office.segments + (stray,)),
    ])
    report = evaluate(plan, [corridor_plan()], ["orig.xml", "gen.xml"], OPTIONS)
    check = report["original"]["map_check"]
    assert not check["realised_as_rasterized"]
    # a one-cell wall on one side of the opening parts them, and E0-C0 stays joined
    assert check["sealed_joins"] == [["C0", "R0"]]
    assert check["realises_portal_graph"] and check["joins_without_portal"] == []
    assert report["generated"][0]["map_check"]["realises_portal_graph"]
    assert map_check_warnings(report) == [
        "orig: walled `C0` off from `R0`, joined in the rasterized map without a portal"]
    assert "walled `C0` off from `R0`" in render_markdown(report)


def test_a_join_that_cannot_be_sealed_without_parting_a_portal_is_named():
    import numpy as np

    from layoutdsl.evaluate.portals import realise_portal_graph

    # A and C at the ends of a free gap strip, B touching the strip from above: every room
    # touches the one gap. A-B and B-C have portals, A-C none; walling A or C off from the
    # gap would also part it from B, so the join is left as it is and named
    labels_one_gap = np.array([[0, 0, -1, -1, -1, -1, 2, 2]] * 3)
    labels_one_gap[0, 3:5] = 1
    occupied_one_gap = np.zeros(labels_one_gap.shape, dtype=bool)
    _, check = realise_portal_graph(occupied_one_gap, labels_one_gap, ("A", "B", "C"),
                                    {("A", "B"), ("B", "C")}, 1.0, 1.0)
    assert check.extra == (("A", "C"),)
    assert "rooms `A` and `C` are joined in the map without a portal" in check.warnings()
