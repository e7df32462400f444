"""evaluate names every room the robot cannot reach, and why; and measures a plan's realism."""

from __future__ import annotations

from layoutdsl.importer.building import Building
from layoutdsl.evaluate.plan import EvaluateOptions, measure_plan

from tests.evaluate.synthetic import building, rect_space

FAST = EvaluateOptions(resolution_m=0.05, explore_resolution_m=0.1)


def scaled(spaces, door_m: float):
    """A plan whose doors (90 units) are `door_m` metres wide; 1 unit = door_m / 90 m."""
    return Building(name="narrow", represented_distance=90.0, real_distance_m=door_m, spaces=tuple(spaces))


def test_a_door_narrower_than_the_robot_is_named_as_the_reason():
    # two 4 m rooms side by side (1 unit = 0.35/90 m: 4 m = 1029 units) joined by a 0.35 m
    # door; the robot (radius 0.2 m) is 0.4 m across
    side = 1029
    plan = scaled([
        rect_space("E0", "E", "ENTRANCE", 0, 0, side, side, (((side, side // 2), "E1", "EXPLICIT"),)),
        rect_space("E1", "E", "ENTRANCE", side, 0, side, side, (((side, side // 2), "E0", "EXPLICIT"),)),
    ], door_m=0.35)
    m = measure_plan(plan, FAST)
    assert m.path_lengths[("E0", "E1")] is None
    assert "opening between `E0` and `E1` is narrower than the robot" in m.path_notes[("E0", "E1")]
    assert list(m.unreachable) == ["E1"] and "narrower than the robot" in m.unreachable["E1"]


def test_a_room_smaller_than_the_robot_is_named_as_such_and_wide_doors_pass():
    # E0 4 x 4 m, a 0.25 x 0.5 m duct R0 on its right wall, E1 beyond a 0.9 m door
    plan = building([
        rect_space("E0", "E", "ENTRANCE", 0, 0, 400, 400,
                   (((400, 100), "R0", "EXPLICIT"), ((200, 400), "E1", "EXPLICIT"))),
        rect_space("R0", "R", "CLOSET", 400, 75, 25, 50, (((400, 100), "E0", "EXPLICIT"),)),
        rect_space("E1", "E", "ENTRANCE", 0, 400, 400, 400, (((200, 400), "E0", "EXPLICIT"),)),
    ])
    m = measure_plan(plan, FAST)
    assert m.path_lengths[("E0", "E1")] is not None and m.path_notes == {}
    assert list(m.unreachable) == ["R0"]
    assert "`R0` is smaller than the robot" in m.unreachable["R0"]


def test_a_plan_is_measured_for_open_entrances_and_voids():
    plan = building([
        rect_space("E0", "E", "ENTRANCE", 0, 0, 400, 400, (((400, 200), "C0", "EXPLICIT"),)),
        rect_space("C0", "C", "CORRIDOR", 400, 140, 1200, 120, (((400, 200), "E0", "EXPLICIT"),)),
    ])
    m = measure_plan(plan, FAST)
    assert m.realism is not None
    assert m.realism.open_entrances == ("E0",) and m.realism.void_area == 0
    assert set(m.realism.rooms_with_outside_wall) == {"E0", "C0"}
