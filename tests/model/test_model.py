"""model.py without a solver: component names and counts, big-M values, pruning, symmetry."""

from __future__ import annotations

import pyomo.environ as pyo
from pyomo.repn import generate_standard_repn

from layoutdsl.syntax.ast import Adjacency, Position
from layoutdsl.model import CONSTRAINT_FAMILIES, THESIS_AS_WRITTEN, build_model

from spec_cases import room, spec

SPEC = spec(
    "model",
    [room("A", (2, 4, 3), (2, 4, 3)), room("B", (2, 4, 3), (2, 4, 3)), room("C", (6, 9, 8), (1.5, 2.5, 2), rtype="C"),
     room("D", (3, 5, 4), (3, 5, 4), on_boundary=True)],
    12, 8,
    adjacencies=[Adjacency("A", "C", 0.9, "e"), Adjacency("B", "C", 0.9, "e"), Adjacency("D", "C", 1.2, "i")],
)


def _binary_coefficient(constraint, binary) -> float:
    repn = generate_standard_repn(constraint.body)
    for var, coef in zip(repn.linear_vars, repn.linear_coefs):
        if var is binary:
            return abs(coef)
    return 0.0


def test_every_family_is_a_block_named_after_its_equation():
    model = build_model(SPEC)
    for name in CONSTRAINT_FAMILIES:
        block = getattr(model, name)
        number = name.split("_")[0][2:] + "." + name.split("_")[1]  # eq5_10_position -> 5.10
        assert isinstance(block, pyo.Block) and f"({number})" in block.doc, name
    assert "(5.1)" in model.eq5_1_objective.doc


def test_sets_and_variables_follow_the_spec():
    model = build_model(SPEC)
    assert list(model.rooms) == ["A", "B", "C", "D"]
    assert list(model.room_pairs) == [("A", "B"), ("A", "C"), ("A", "D"), ("B", "C"), ("B", "D"), ("C", "D")]
    assert list(model.adjacencies) == [("A", "C"), ("B", "C"), ("D", "C")]
    assert list(model.onb_rooms) == ["D"]
    assert len(model.eq5_8_non_overlap.side) == 4 * len(model.eq5_8_non_overlap.pairs)
    assert len(model.eq5_9_adjacency.stacked) == 3
    assert len(model.eq5_12_on_boundary.side) == 4
    assert set(model.eq5_6_aspect_ratio.rooms) == {"A", "B", "D"}  # not the corridor


def test_big_m_is_as_tight_as_the_boundary_allows():
    wall = SPEC.settings.walldim
    tight, loose = build_model(SPEC), build_model(SPEC, formulation=THESIS_AS_WRITTEN)
    for model, limit_x, limit_y in ((tight, 12 + wall, 8 + wall), (loose, None, None)):
        block = model.eq5_8_non_overlap
        for (a, b) in block.pairs:
            for side in ("left", "right", "below", "above"):
                coef = _binary_coefficient(block.separate[a, b, side], block.side[a, b, side])
                if limit_x is None:
                    assert coef > 12 + wall  # one global M, larger than any pair needs
                else:
                    assert 0 < coef <= (limit_x if side in ("left", "right") else limit_y) + 1e-9


def test_pairs_that_positions_keep_apart_get_no_binaries():
    far = spec("far", [room("A", (2, 4, 3), (2, 4, 3)), room("B", (2, 4, 3), (2, 4, 3))], 20, 8,
               positions=[Position("A", 1, 4), Position("B", 19, 4)])
    assert list(build_model(far).eq5_8_non_overlap.pairs) == []
    assert list(build_model(far, formulation=THESIS_AS_WRITTEN).eq5_8_non_overlap.pairs) == [("A", "B")]


def test_interchangeable_rooms_are_ordered_by_x():
    model = build_model(SPEC)
    assert model.interchangeable_groups == [["A", "B"]]  # same line, same neighbour and door
    assert list(model.symmetry.chain) == [("A", "B")]
    assert build_model(SPEC, formulation=THESIS_AS_WRITTEN).interchangeable_groups == []
