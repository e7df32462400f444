"""The realism report on small synthetic plans: topology, areas, sizes, paths, determinism."""

from __future__ import annotations

import json

import pytest

from layoutdsl.evaluate.plan import EvaluateOptions
from layoutdsl.evaluate.report import evaluate, render_markdown, write_report
from layoutdsl.evaluate.topology import compare_topology, room_graph, room_ids

from .synthetic import building, corridor_plan, rect_space

FAST = EvaluateOptions(resolution_m=0.05, explore_resolution_m=0.1)


@pytest.fixture(scope="module")
def self_report():
    plan = corridor_plan()
    return evaluate(plan, [plan, plan], ["orig.xml", "gen1.xml", "gen2.xml"], FAST)


def test_a_plan_against_itself_shows_zero_deviation_everywhere(self_report):
    for generated in self_report["generated"]:
        assert generated["topology"]["isomorphic"] and generated["topology"]["identical"]
        deviation = generated["deviation"]
        assert deviation["room_area"] == 0 and deviation["bbox_area"] == 0
        assert deviation["room_size_mean"] == 0 and deviation["room_size_max"] == 0
        assert all(v == 0 for v in deviation["paths"].values())
        assert generated["exploration"] == self_report["original"]["exploration"]
    (pair,) = self_report["path_pairs"]
    assert pair["pair"] == "E0-E1"
    assert pair["generated_mean_m"] == pair["original_m"] and pair["generated_std_m"] == 0


def test_known_areas_and_entrance_path(self_report):
    original = self_report["original"]
    assert original["room_area_m2"] == pytest.approx(16 + 14.4 + 16)
    assert original["bbox_area_m2"] == pytest.approx(20 * 4)
    # centre of E0 (2, 2) to centre of E1 (18, 2), straight through both doors
    assert original["paths_m"]["E0-E1"] == pytest.approx(16.0, rel=0.01)


def test_a_closed_door_is_reported_as_a_topology_difference():
    report = evaluate(corridor_plan(), [corridor_plan(close_door=True)], ["orig.xml", "closed.xml"], FAST)
    (generated,) = report["generated"]
    topology = generated["topology"]
    assert not topology["isomorphic"]
    assert topology["missing_adjacencies"] == [["C0", "E1"]]
    assert "missing adjacencies C0-E1" in topology["summary"]
    assert generated["paths_m"]["E0-E1"] is None  # the door really is shut on the map
    assert report["path_pairs"][0]["generated_unreachable"] == 1
    assert "**no**" in render_markdown(report)


def test_isomorphic_plans_with_swapped_rooms_count_as_isomorphic():
    # two identical side rooms off a corridor: swapping which is R0 and R1 keeps the graph
    def plan(first, second):
        return building([
            rect_space("C0", "C", "CORRIDOR", 0, 0, 1000, 200, (((300, 200), first, "EXPLICIT"), ((700, 200), second, "EXPLICIT"))),
            rect_space("R0", "R", "OFFICE", 0, 200, 500, 400, (((300, 200), "C0", "EXPLICIT"),)),
            rect_space("R1", "R", "OFFICE", 500, 200, 500, 400, (((700, 200), "C0", "EXPLICIT"),)),
        ])

    difference = compare_topology(room_graph(plan("R0", "R1")), room_graph(plan("R0", "R1")))
    assert difference.isomorphic and difference.identical
    relabelled = building([
        rect_space("C0", "C", "CORRIDOR", 0, 0, 1000, 200, (((300, 200), "R0", "EXPLICIT"),)),
        rect_space("R0", "R", "OFFICE", 0, 200, 500, 400, (((300, 200), "C0", "EXPLICIT"),)),
        rect_space("R1", "R", "CLASSROOM", 500, 200, 500, 400),
    ])
    difference = compare_topology(room_graph(plan("R0", "R1")), room_graph(relabelled))
    assert not difference.isomorphic
    assert ("R1", "R:OFFICE", "R:CLASSROOM") in difference.relabelled_rooms


def test_original_space_ids_become_type_and_order_ids():
    plan = building([
        rect_space("uuid-b", "R", "OFFICE", 0, 0, 100, 100),
        rect_space("uuid-a", "E", "ENTRANCE", 100, 0, 100, 100),
        rect_space("uuid-c", "R", "OFFICE", 200, 0, 100, 100),
    ])
    assert room_ids(plan) == {"uuid-b": "R0", "uuid-a": "E0", "uuid-c": "R1"}


def test_report_files_are_written_and_identical_for_the_same_seed(tmp_path, self_report):
    plan = corridor_plan()
    again = evaluate(plan, [plan, plan], ["orig.xml", "gen1.xml", "gen2.xml"], FAST)
    assert again == self_report
    first = write_report(self_report, tmp_path / "a")
    second = write_report(again, tmp_path / "b")
    assert sorted(p.name for p in first) == ["areas.png", "exploration.png", "paths.png", "report.json", "report.md"]
    for a, b in zip(first, second):
        assert a.read_bytes() == b.read_bytes(), a.name
    assert json.loads((tmp_path / "a" / "report.json").read_text())["original"]["rooms"] == 3
    assert not [p for p in (tmp_path / "a").iterdir() if p.name.startswith(".")]


def test_plans_of_the_same_file_name_from_different_folders_keep_distinct_names(tmp_path):
    from layoutdsl.evaluate.report import distinct_names

    files = [str(tmp_path / "orig" / "plan.xml"), str(tmp_path / "run1" / "plan-0.xml"),
             str(tmp_path / "run2" / "plan-0.xml"), str(tmp_path / "run2" / "plan-1.xml")]
    assert distinct_names(files) == ["plan", "run1/plan-0", "run2/plan-0", "plan-1"]
    # the same file twice is the same plan: one name
    assert distinct_names([files[0], files[0]]) == ["plan", "plan"]


def test_rooms_are_compared_by_their_real_shapes() -> None:
    """An L-shaped room (area 75 of a 100 m² box) counts as non-rectangular, and its area
    is its polygon's, not its box's (issue 14)."""
    from dataclasses import replace

    from layoutdsl.evaluate.metrics import room_shapes, shape_deviation
    from layoutdsl.importer.building import Point

    square = rect_space("A", "R", "OFFICE", 0, 0, 1000, 1000)
    l_shape = replace(square, polygon=(Point(0, 0), Point(1000, 0), Point(1000, 500), Point(500, 500),
                                       Point(500, 1000), Point(0, 1000)))
    original, generated = room_shapes(building([l_shape])), room_shapes(building([square]))
    (area, fill), = original.values()
    assert (area, fill) == (75.0, pytest.approx(0.75))
    deviation = shape_deviation(original, generated)
    assert deviation["non_rectangular_original"] == 1 and deviation["non_rectangular_generated"] == 0
    assert deviation["room_area_change_mean"] == pytest.approx(100 / 75 - 1)
