"""Known answers for the simulated exploration (the thesis, §6.5)."""

from __future__ import annotations

import math

import numpy as np

from layoutdsl.evaluate.explore import ExploreSettings, explore

from .synthetic import corridor_plan
from layoutdsl.evaluate.plan import EvaluateOptions, measure_plan


def _room(width_m, height_m, res):
    occupied = np.ones((round(height_m / res) + 2, round(width_m / res) + 2), dtype=bool)
    occupied[1:-1, 1:-1] = False
    return occupied


def test_one_empty_room_is_covered_without_driving():
    # Bound: the room is convex and its diagonal (11.7 m) is shorter than the laser's 30 m,
    # and the beams' spacing there (11.7 m x 0.25° = 5 cm) is below a cell, so one turn in
    # place (facing the blind sector: at most 180°) sees every cell: 99 % needs 0 m of
    # driving, and chasing stray cells afterwards never needs more than the diagonal.
    res = 0.1
    for seed in range(3):
        result = explore(_room(10, 6, res), res, (20, 30), robot_radius_m=0.2, seed=seed)
        assert result.reached_target and result.final_coverage >= 0.99
        assert result.distance_to_target_m == 0.0
        assert result.total_distance_m <= math.hypot(10, 6)
        # time to target: at most a half turn (2 s at 90°/s) and one goal stop (1 s)
        assert result.time_to_target_s <= 3.0 + 1e-9
        assert not result.hit_goal_limit


def test_a_long_room_needs_driving_and_is_fully_covered():
    # 40 m long, laser 30 m: the far end is out of range from the start at one end
    res = 0.1
    result = explore(_room(40, 3, res), res, (15, 5), robot_radius_m=0.2, seed=0)
    assert result.reached_target and result.final_coverage >= 0.99
    # it must get within 30 m of the far wall (>= 10 m), and never needs to go past it
    assert 9.0 <= result.distance_to_target_m <= 40.0
    assert result.time_to_target_s >= result.distance_to_target_m / ExploreSettings().linear_speed_m_s


def test_exploration_is_deterministic_for_a_seed_and_explores_through_doors():
    measures = [measure_plan(corridor_plan(), EvaluateOptions(seed=3)) for _ in range(2)]
    first, second = (m.exploration for m in measures)
    assert first == second
    assert first.reached_target and first.final_coverage >= 0.99
    # from E0's centre it has to pass the corridor to see E1's far half
    assert first.distance_to_target_m > 5.0
    assert measures[0].explore_start.room == "E0"
