"""The room-pair relation difference: known cases counted by hand."""

import pytest

from layoutdsl.layout.difference import (
    difference,
    difference_by_symmetry,
    least_from_earlier,
    pairwise_differences,
    relations,
)

ROW = {"A": (0.0, 0.0), "B": (1.0, 0.0), "C": (2.0, 0.0), "D": (3.0, 0.0)}
"""Four rooms in a row, left to right."""

PLAN = {"R0": (2.0, 3.0), "R1": (7.5, 3.2), "C0": (5.0, 8.0), "E0": (1.0, 12.0), "R2": (9.0, 11.0)}


def test_relations_read_along_the_axis_of_largest_difference():
    assert relations({"a": (0, 0), "b": (5, 1), "c": (1, -4)}) == {
        ("a", "b"): "right", ("a", "c"): "below", ("b", "c"): "below"}


def test_identical_plans_score_zero():
    assert difference(PLAN, PLAN) == 0.0


@pytest.mark.parametrize("transform", [
    lambda x, y: (-x, y), lambda x, y: (x, -y), lambda x, y: (-y, x), lambda x, y: (y, -x),
    lambda x, y: (-x, -y), lambda x, y: (y, x), lambda x, y: (-y, -x),
])
def test_a_rotated_or_mirrored_copy_scores_zero(transform):
    # moved and scaled as well: relations do not depend on origin or unit
    copy = {room: transform(3 * x + 40, 3 * y - 7) for room, (x, y) in PLAN.items()}
    assert difference(PLAN, copy) == 0.0
    assert difference(copy, PLAN) == 0.0


def test_swapping_two_neighbours_in_a_row_is_one_pair_in_six():
    # B A C D: only the pair (A, B) changes side (1 of 6), also upside down; the left-right
    # mirror and the half turn keep A-B but turn the other five pairs (5 of 6); the quarter
    # turns and diagonal mirrors make every horizontal pair vertical (6 of 6)
    swapped = dict(ROW, A=(1.0, 0.0), B=(0.0, 0.0))
    by_symmetry = difference_by_symmetry(ROW, swapped)
    assert sorted(by_symmetry) == pytest.approx([1 / 6, 1 / 6, 5 / 6, 5 / 6, 1, 1, 1, 1])
    assert difference(ROW, swapped) == pytest.approx(1 / 6)


def test_a_known_rearrangement_scores_its_hand_counted_value():
    # two rows of three, B and E (the middle ones) swap rows. Of the 15 pairs only B-E turns
    # (above -> below): every other pair of B or E is diagonal, a tie read along x, and keeps
    # its side. So 1/15 as drawn; every other symmetry turns a row pair such as A-D.
    original = {"A": (0, 0), "B": (10, 0), "C": (20, 0), "D": (0, 10), "E": (10, 10), "F": (20, 10)}
    rearranged = dict(original, B=(10, 10), E=(10, 0))
    scores = difference_by_symmetry(original, rearranged)
    assert scores[0] == pytest.approx(1 / 15)
    assert all(score > 1 / 15 for score in scores[1:])
    assert difference(original, rearranged) == pytest.approx(1 / 15)


def test_a_square_whose_corners_swap_along_a_diagonal_is_its_own_mirror_image():
    original = {"A": (0, 0), "B": (10, 0), "C": (0, 10), "D": (10, 10)}
    swapped = dict(original, A=(10, 10), D=(0, 0))
    assert difference_by_symmetry(original, swapped)[0] == pytest.approx(5 / 6)
    assert difference(original, swapped) == 0.0


def test_only_rooms_in_both_plans_count():
    assert difference(ROW, {"A": (0, 0)}) == 0.0
    assert difference(ROW, dict(ROW, Z=(-5.0, 3.0))) == 0.0


def test_pairwise_differences_cover_every_pair_once():
    swapped = dict(ROW, A=(1.0, 0.0), B=(0.0, 0.0))
    result = pairwise_differences([ROW, swapped, ROW])
    assert set(result) == {(0, 1), (0, 2), (1, 2)}
    assert result[(0, 2)] == 0.0
    assert result[(0, 1)] == pytest.approx(1 / 6)


def test_least_from_earlier_is_the_least_difference_from_any_plan_before():
    import random

    rng = random.Random(3)
    plans = [{room: (rng.uniform(0, 20), rng.uniform(0, 10)) for room in "ABCDEFG"} for _ in range(6)]
    plans.insert(3, {room: (-x, y) for room, (x, y) in plans[1].items()})  # a mirror image of plan 1
    least = least_from_earlier(plans)
    assert least[0] is None and least[3] == 0.0
    for k in range(1, len(plans)):
        assert least[k] == pytest.approx(min(difference(plans[k], plans[j]) for j in range(k)))
    swapped = dict(ROW, A=(1.0, 0.0), B=(0.0, 0.0))
    assert least_from_earlier([ROW, swapped]) == [None, pytest.approx(1 / 6)]
