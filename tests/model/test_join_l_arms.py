"""The thesis' model on an L-spec's boxes: join_l_arms keeps each L joined while SCIP polishes."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from layoutdsl.layout import lshape
from layoutdsl.layout.geometry import layout_from_rects
from layoutdsl.layout.verify import verify
from layoutdsl.model import build_model, rects_from_model, warm_start_from_rects
from layoutdsl.solve import SolveOptions, polish
from layoutdsl.syntax.ast import arm_id

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
from planted_specs import l_corridor  # noqa: E402


def _planted_rects():
    spec, layout, _ = l_corridor()
    rects = {room.id: (room.x, room.y, room.w, room.h) for room in layout.rooms}
    rects[arm_id("C0")] = layout.room("C0").arm
    return spec, rects


def test_polishing_the_planted_l_keeps_it_an_l_and_verified() -> None:
    spec, rects = _planted_rects()
    boxes, joined = lshape.boxes_spec(spec, rects)
    joins = {pair: lshape.join_option(rects[pair[0]], rects[pair[1]]) for pair in joined}
    assert joins == {("C0", "C0/arm"): "below:lo"}  # the box below the arm, left edges flush
    model = build_model(boxes, joins=joins, crossing=lshape.crossings(spec))
    warm_start_from_rects(model, boxes, rects)
    outcome = polish(model, SolveOptions(time_limit=20, quiet=True))
    assert outcome.has_solution
    polished = rects_from_model(model)
    layout = layout_from_rects(spec, polished)
    assert verify(spec, layout) == []
    box, arm = polished["C0"], polished["C0/arm"]
    assert box[0] == pytest.approx(arm[0], abs=1e-6)  # still flush on the left
    assert box[1] + box[3] == pytest.approx(arm[1], abs=1e-6)  # and stacked, no wall between
    assert box[2] > box[3] and arm[3] > arm[2]  # the arm still runs across the box


def test_without_the_join_the_planted_l_has_no_polish() -> None:
    """The plain model of the boxes treats the arm as another room: (5.8) wants a wall
    between it and the corridor's box, so with the planted relations fixed there is no
    layout at all (what join_l_arms makes one)."""
    spec, rects = _planted_rects()
    boxes, _ = lshape.boxes_spec(spec, rects)
    model = build_model(boxes)
    warm_start_from_rects(model, boxes, rects)
    assert polish(model, SolveOptions(time_limit=20, quiet=True)).status == "infeasible"


def test_a_square_arm_starts_turned_with_its_box() -> None:
    """A 3 x 3 arm fits both orientations and its size error does not choose; the start
    must give it the orientation the turn asks (across its 6 x 2 box), else the start and
    every polish that fixes its binaries are infeasible."""
    from spec_cases import room, spec

    pair = spec("square-arm", [room("A", (4, 8, 6), (1.5, 3, 2), ar=(1, 5), rtype="C"),
                               room("R", (2, 4, 3), (2, 4, 3.5), ar=(1, 1.5))], 10, 8)
    model = build_model(pair, joins={("A", "R"): "below:lo"}, crossing={("A", "R"): True})
    start = {"A": (0.0, 0.0, 6.0, 2.0), "R": (0.0, 2.0, 3.0, 3.0)}
    warm_start_from_rects(model, pair, start)  # (it reports the joined pair's missing wall)
    assert (model.o["A"].value, model.o["R"].value) == (0, 1)
    assert polish(model, SolveOptions(time_limit=20, quiet=True)).has_solution
    box, arm = rects_from_model(model)["A"], rects_from_model(model)["R"]
    assert box[0] == pytest.approx(arm[0], abs=1e-6) and box[1] + box[3] == pytest.approx(arm[1], abs=1e-6)
    assert box[2] >= box[3] and arm[3] >= arm[2] - 1e-6  # the arm runs across its box
