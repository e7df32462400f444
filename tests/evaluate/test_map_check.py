"""evaluate checks that each map realises its portal graph, opens missed doors, names the rest."""

from __future__ import annotations

from dataclasses import replace

import pytest

from layoutdsl.building import LineSegment, Point

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
    assert report["original"]["map_check"]["joins_without_portal"] == [["C0", "R0"]]
    assert report["generated"][0]["map_check"]["realises_portal_graph"]
    assert map_check_warnings(report) == ["orig: rooms `C0` and `R0` are joined in the map without a portal"]
    assert "`C0` and `R0` are joined in the map without a portal" in render_markdown(report)
