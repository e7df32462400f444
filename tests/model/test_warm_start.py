"""warm_start_from_rects: which relation a start hands the model for a pair apart on both axes."""

from __future__ import annotations

import pytest

from layoutdsl.layout.geometry import layout_from_rects
from layoutdsl.layout.verify import verify
from layoutdsl.model import build_model, rects_from_model, relations_of_rects, warm_start_from_rects
from layoutdsl.solve import SolveOptions, polish

from spec_cases import room, spec

# Two 3 x 3 rooms that want to be 6 wide, 1 m apart along x and 5 m along y: side by side
# they cannot both reach 6 in a 10 m boundary, one above the other they can.
PAIR = spec("pair", [room("A", (3, 8, 6), (3, 4, 3)), room("B", (3, 8, 6), (3, 4, 3))], 10, 14)
START = {"A": (0.0, 0.0, 3.0, 3.0), "B": (4.0, 8.0, 3.0, 3.0)}


def test_a_diagonal_pair_keeps_the_relation_with_the_wider_gap():
    model = build_model(PAIR)
    assert warm_start_from_rects(model, PAIR, START) == []
    chosen = [s for s in ("left", "right", "below", "above") if model.eq5_8_non_overlap.side["A", "B", s].value == 1]
    assert chosen == ["below"]
    assert relations_of_rects(PAIR, START) == {("A", "B"): "below"}


def test_the_polish_then_grows_both_rooms_to_their_targets():
    model = build_model(PAIR)
    warm_start_from_rects(model, PAIR, START)
    assert polish(model, SolveOptions(time_limit=10, quiet=True)).has_solution
    rects = rects_from_model(model)
    for r in ("A", "B"):
        _x, _y, w, h = rects[r]
        assert (max(w, h), min(w, h)) == (pytest.approx(6, abs=1e-3), pytest.approx(3, abs=1e-3)), rects[r]
    assert verify(PAIR, layout_from_rects(PAIR, rects)) == []



def test_the_polish_leaves_out_only_separations_that_cannot_bind(monkeypatch):
    """The polish translates only the side each pair's fixed ω chose: it finds the optimum
    the whole model has for those relations, and the model is whole again afterwards."""
    import pyomo.environ as pyo

    from layoutdsl import solve as solve_module
    from planted import planted

    spec_, planted_rects = planted(3, 2)
    # the rooms shrunk in place: the polish has to grow them back against their neighbours
    rects = {r: (x, y, 0.9 * w, 0.9 * h) for r, (x, y, w, h) in planted_rects.items()}
    whole = solve_module._idle_separations
    left_out = []

    def recorded(model):
        idle = whole(model)
        left_out.append(len(idle))
        return idle

    objectives = []
    for skipping in (recorded, lambda model: []):
        monkeypatch.setattr(solve_module, "_idle_separations", skipping)
        model = build_model(spec_)
        warm_start_from_rects(model, spec_, rects)
        free = [v for v in model.component_data_objects(pyo.Var) if v.is_binary() and not v.fixed]
        outcome = polish(model, SolveOptions(time_limit=20, quiet=True))
        assert outcome.has_solution
        objectives.append(outcome.objective)
        assert all(c.active for c in model.component_data_objects(pyo.Constraint))
        assert not any(v.fixed for v in free)
        assert verify(spec_, layout_from_rects(spec_, rects_from_model(model))) == []
    pairs = len(model.eq5_8_non_overlap.pairs)
    # three sides and the "one side" constraint of every pair with its four ω fixed
    assert pairs > 0 and left_out[0] >= pairs
    assert objectives[0] == pytest.approx(objectives[1], rel=1e-6, abs=1e-6)


def test_a_settled_model_builds_only_the_start_s_separations_and_polishes_the_same():
    from planted import planted

    from layoutdsl.model import settle_separations

    spec_, planted_rects = planted(3, 2)
    rects = {r: (x, y, 0.9 * w, 0.9 * h) for r, (x, y, w, h) in planted_rects.items()}
    objectives, built, polished = [], [], []
    for deferred in (False, True):
        model = build_model(spec_, defer_separations=deferred)
        assert hasattr(model.eq5_8_non_overlap, "separate") is not deferred
        warm_start_from_rects(model, spec_, rects)
        if deferred:
            settle_separations(model)
        built.append(len(model.eq5_8_non_overlap.separate) + len(model.eq5_8_non_overlap.one_side))
        outcome = polish(model, SolveOptions(time_limit=20, quiet=True))
        assert outcome.has_solution
        objectives.append(outcome.objective)
        polished.append(rects_from_model(model))
        assert verify(spec_, layout_from_rects(spec_, polished[-1])) == []
    pairs = len(model.eq5_8_non_overlap.pairs)
    # one separation per pair, where the whole model has four and a "one side at least"
    assert built == [5 * pairs, pairs]
    # the start's relations stay: each pair keeps the side the warm start put it on
    side = model.eq5_8_non_overlap.side
    assert all(side[a, b, s].fixed for a, b in model.eq5_8_non_overlap.pairs for s in model.sides)
    assert objectives[0] == pytest.approx(objectives[1], rel=1e-6, abs=1e-6)
    for room_id, rect in polished[0].items():
        assert polished[1][room_id] == pytest.approx(rect, abs=1e-3)
