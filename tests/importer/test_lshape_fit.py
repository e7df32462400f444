"""importer/lshape.py: the L that covers a polygon best."""

from __future__ import annotations

import pytest

from layoutdsl.importer.lshape import fit_l


def _area(box):
    return (box[2] - box[0]) * (box[3] - box[1])


@pytest.mark.parametrize("polygon, notch", [
    ([(0, 0), (10, 0), (10, 2), (2, 2), (2, 8), (0, 8)], "top right"),
    ([(0, 0), (10, 0), (10, 8), (8, 8), (8, 2), (0, 2)], "top left"),
    ([(0, 6), (10, 6), (10, 8), (0, 8), (0, 0), (2, 0), (2, 6)][::-1], "mixed order"),
    ([(0, 0), (3, 0), (3, 5), (9, 5), (9, 7), (0, 7)], "bottom right"),
])  # fmt: skip
def test_an_l_polygon_is_fitted_exactly(polygon, notch) -> None:
    fit = fit_l(polygon)
    assert fit is not None, notch
    assert fit.mismatch == 0 and fit.first_fill == 1 and fit.second_fill == 1
    xs, ys = [p[0] for p in polygon], [p[1] for p in polygon]
    # the arms lie on the polygon's own coordinates and their areas add up to the polygon's
    for box in (fit.first, fit.second):
        assert box[0] in xs and box[2] in xs and box[1] in ys and box[3] in ys
    shoelace = abs(sum(x1 * y2 - x2 * y1 for (x1, y1), (x2, y2) in zip(polygon, polygon[1:] + polygon[:1]))) / 2
    assert _area(fit.first) + _area(fit.second) == pytest.approx(shoelace)
    assert _area(fit.first) >= _area(fit.second)


def test_a_rectangle_needs_no_l() -> None:
    assert fit_l([(0, 0), (4, 0), (4, 3), (0, 3)]) is None


def test_a_u_shape_gets_the_best_l_but_not_an_exact_one() -> None:
    u_shape = [(0, 0), (9, 0), (9, 6), (6, 6), (6, 2), (3, 2), (3, 6), (0, 6)]
    fit = fit_l(u_shape)
    assert fit is not None and 0 < fit.mismatch < fit.box_mismatch
