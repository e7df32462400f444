"""E_cover counts a room's area up to its target (Formulation.cover_up_to_target), and the
thesis' formulation as written counts all of it: sizes checked on the solved rectangles."""

from __future__ import annotations

from dataclasses import replace

import pyomo.environ as pyo
import pytest

from layoutdsl.compile import compile_spec
from layoutdsl.layout.verify import verify
from layoutdsl.model import THESIS_AS_WRITTEN, Formulation, build_model, objective_of_rects, rects_from_model
from layoutdsl.solve import SolveOptions, solve

from spec_cases import room, spec

# A room and a 20 m corridor with space all around them, at the default λ_cover = 0.1: the
# thesis' E_cover widens the corridor by about λ_cover / 2 x its length (1 m on a 2 m target)
ROOMY = spec("roomy", [room("A", (2, 12, 6), (2, 8, 4)), room("K", (10, 30, 20), (1.5, 6, 2), rtype="C")], 40, 30)
TARGET_AREA = {"A": 24.0, "K": 40.0}


def _areas(rects) -> dict[str, float]:
    return {r: w * h for r, (_x, _y, w, h) in rects.items()}


def _solved(formulation: Formulation) -> dict:
    model = build_model(ROOMY, formulation=formulation)
    outcome = solve(model, SolveOptions(time_limit=20, gap=1e-4, quiet=True))
    assert outcome.has_solution
    return model


def test_rooms_with_space_settle_at_their_target_sizes():
    rects = rects_from_model(_solved(Formulation()))
    for r, area in _areas(rects).items():
        assert area == pytest.approx(TARGET_AREA[r], rel=0.01), (r, rects[r])
    _x, _y, w, h = rects["K"]
    assert (max(w, h), min(w, h)) == (pytest.approx(20, abs=0.05), pytest.approx(2, abs=0.05))


def test_the_thesis_cover_grows_them_past_their_targets():
    areas = _areas(rects_from_model(_solved(Formulation(cover_up_to_target=False))))
    assert areas["K"] > 1.3 * TARGET_AREA["K"]
    assert areas["A"] > 1.05 * TARGET_AREA["A"]


@pytest.mark.parametrize("formulation", [Formulation(), THESIS_AS_WRITTEN], ids=["capped", "thesis"])
def test_objective_of_rects_counts_the_cover_as_the_model_does(formulation):
    model = _solved(formulation)
    evaluated = objective_of_rects(ROOMY, rects_from_model(model), formulation=formulation)
    assert evaluated == pytest.approx(pyo.value(model.eq5_1_objective.expr), rel=1e-3, abs=1e-3)


def test_strategy_thesis_keeps_the_thesis_cover_and_auto_the_targets():
    options = SolveOptions(time_limit=20, gap=1e-3, quiet=True)
    sizes = {}
    for strategy in ("auto", "thesis"):
        result = compile_spec(ROOMY, replace(options, strategy=strategy))
        assert result.layout is not None and verify(ROOMY, result.layout) == []
        sizes[strategy] = {r.id: r.w * r.h for r in result.layout.rooms}
    assert sizes["auto"]["K"] == pytest.approx(TARGET_AREA["K"], rel=0.01)
    assert sizes["thesis"]["K"] > 1.3 * TARGET_AREA["K"]
