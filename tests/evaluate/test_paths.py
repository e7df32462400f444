"""Known answers for the path metric (issue 7: any-angle, not the 8-connected error)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from layoutdsl.evaluate.grid import inflate
from layoutdsl.evaluate.paths import DistanceGrid, shortest_path


def test_l_shaped_corridor_matches_its_centre_line_within_3_percent():
    # An L corridor 1 m wide at 0.05 m: 20 m along x, then 15 m down. The shortest path
    # cuts the inner corner by about 0.6 m (the free width after inflating by 0.2 m), 1.7 %.
    res = 0.05
    width = round(1.0 / res)
    occupied = np.ones((round(17 / res), round(22 / res)), dtype=bool)
    top, left = 10, 10
    leg_x, leg_y = round(20 / res), round(15 / res)
    occupied[top : top + width, left : left + leg_x + width] = False  # horizontal leg
    occupied[top : top + leg_y + width, left + leg_x : left + leg_x + width] = False  # vertical leg
    free = ~inflate(occupied, 0.2, res)
    start = (top + width // 2, left + width // 2)
    goal = (top + leg_y + width // 2, left + leg_x + width // 2)
    centre_line = (goal[1] - start[1]) + (goal[0] - start[0])  # cells
    result = shortest_path(DistanceGrid(free), start, goal)
    assert result is not None
    assert abs(result.length - centre_line) / centre_line < 0.03
    # the exact any-angle answer cuts the inner corner of the inflated corridor
    corner = (top + width - 1 - round(0.2 / res), left + leg_x + round(0.2 / res))
    exact = math.dist(start, corner) + math.dist(corner, goal)
    assert result.length == pytest.approx(exact, rel=0.01)
    assert result.length <= result.grid_length + 1e-9


@pytest.mark.parametrize("goal", [(10, 190), (60, 190), (100, 190), (190, 150), (190, 30)])
def test_open_space_paths_are_straight_and_the_grid_bound_holds(goal):
    free = np.ones((200, 200), dtype=bool)
    start = (10, 10)
    result = shortest_path(DistanceGrid(free), start, goal)
    straight = math.dist(start, goal)
    assert result.length == pytest.approx(straight, rel=1e-9)
    # 16-connected distances overestimate by at most 1/cos(13.28°) - 1 = 2.75 %
    assert straight - 1e-9 <= result.grid_length <= straight * 1.0275 + 1e-9


def test_paths_go_round_walls_and_never_through_them():
    free = np.ones((60, 60), dtype=bool)
    free[0:50, 30] = False  # a one-cell wall with a gap at the bottom
    grid = DistanceGrid(free)
    result = shortest_path(grid, (5, 5), (5, 55))
    assert result.length > math.dist((5, 5), (50, 30)) + math.dist((50, 30), (5, 55)) - 1
    free[:, 30] = False
    assert shortest_path(DistanceGrid(free), (5, 5), (5, 55)) is None


def test_no_diagonal_squeeze_between_touching_wall_cells():
    free = np.ones((3, 3), dtype=bool)
    free[0, 1] = free[1, 0] = False  # (0,0) touches the rest only diagonally
    assert not math.isfinite(DistanceGrid(free).distances([(1, 1)])[0, 0])


def test_inflation_closes_doors_narrower_than_the_robot():
    res = 0.05
    occupied = np.zeros((40, 40), dtype=bool)
    occupied[:, 20] = True
    occupied[10:16, 20] = False  # a 0.30 m opening: a 0.2 m robot (0.4 m wide) cannot pass
    assert shortest_path(DistanceGrid(~inflate(occupied, 0.2, res)), (13, 5), (13, 35)) is None
    occupied[10:22, 20] = False  # 0.60 m: it can
    assert shortest_path(DistanceGrid(~inflate(occupied, 0.2, res)), (16, 5), (16, 35)) is not None
