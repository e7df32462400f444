"""The thesis' MIQP (§5.5.1) as a Pyomo model: a pure function of the checked spec.

Every constraint family is one unit of `equations.py` that adds one named Block carrying
its equation number (`m.eq5_4_min_size` ... `m.eq5_13_cluster`), so the code can be held
against the thesis line by line. `formulation.py` holds the switches and the bounds the
units share; `warm_start.py` moves geometry in and out of a model. Nothing here solves
anything: the `solve` package owns SCIP.

Deliberate differences from the equations as printed, each exact or a valid tightening:

* Objective (5.1)-(5.3). Written as printed, one nonconvex quadratic objective made SCIP
  report numerical trouble and abort on large models (see shared/notes/solver-scouting.md).
  We use the equivalent bounded-helper form: a_i <= w_i*h_i (nonconvex, a_i bounded by the
  size bounds), e_w and e_h linear in (w, h, o) as in (5.3), q_i >= e_w^2 + e_h^2 (convex),
  and the linear objective lambda_cover*(W*H - sum rho_cover*a) + lambda_error*sum rho_error*q.
  With rho >= 0 every optimum has a_i = w_i*h_i and q_i = e_w^2 + e_h^2, so the optimal value
  and the optimal layouts are those of (5.1); nothing is convexified.
* Cover up to the target (`Formulation.cover_up_to_target`, on by default): a_i is also
  bounded by the room's target area, so E_cover rewards covering the boundary with rooms
  up to their target sizes and no further. As printed, (5.1) grows every room with space
  around it past its target until the size error balances λ_cover (a room's side settles
  about λ_cover / (2 λ_error) x its other side past its target), and generated buildings
  came out 10-17 % larger than the plans they were drawn from. `THESIS_AS_WRITTEN` counts
  the whole area, as printed.
* Orientation. As in the thesis, o_i = 0 means w_i is the long side: (5.4)/(5.5) give the
  long side the larger of the two minimum (maximum) sizes and (5.6) bounds w/h. (5.3) then
  compares the long side with the larger target and the short side with the smaller one,
  which is the printed (5.3) for rooms listed wide; for rooms listed tall the printed form
  would compare the long side with the short target, contradicting (5.4).
* Adjacency (5.9) as printed guarantees only door - walldim of shared interior wall; here the
  rooms' interiors overlap by at least door / door_utilization along the wall, and the gap
  across the wall is exactly walldim (non-overlap gives >= walldim, adjacency <= walldim).
* Big-M: one constant per constraint, from interval bounds of the variables involved (never
  looser than the boundary allows), unless `Formulation(tight_big_m=False)` asks for the
  thesis' single M.
* Long and short sides (`Formulation.long_short`, on by default): variables long_i, short_i
  equal to (w_i, h_i) when o_i = 0 and (h_i, w_i) when o_i = 1, linked by big-M rows in
  `m.orientation`. (5.4)-(5.6) hold on them too (inside their blocks), and the objective
  uses a_i <= long_i*short_i and the errors long_i - long target, short_i - short target:
  the same values as (5.3) for every o, but with narrow bounds, so SCIP's relaxation of the
  area term is tight (a 5-room spec proves its 1 % gap at the root node instead of >20 s).
* Cheap valid cuts: pairs whose bounds already separate them get no binaries, sides the
  bounds rule out are fixed to 0, interchangeable rooms are ordered by x, and each
  adjacency's α is tied to its pair's ω. `THESIS_AS_WRITTEN` switches all of this off.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace

import pyomo.environ as pyo

from layoutdsl.model.equations import UNITS, fix_relations, join_l_arms, settle_separations
from layoutdsl.model.formulation import (
    BOUNDARY_SIDES,
    OPPOSITE_SIDE,
    SIDES,
    THESIS_AS_WRITTEN,
    Formulation,
    ModelData,
    model_data,
    orientation_bounds,
    orientation_targets,
    room_bounds,
    target_area,
)
from layoutdsl.model.warm_start import (
    best_orientation,
    objective_of_rects,
    rects_from_model,
    relations_of_rects,
    warm_start_from_rects,
)
from layoutdsl.syntax.ast import Spec

__all__ = [
    "BOUNDARY_SIDES", "CONSTRAINT_FAMILIES", "OPPOSITE_SIDE", "SIDES", "THESIS_AS_WRITTEN",
    "Formulation", "ModelData", "best_orientation", "build_model", "model_data",
    "objective_of_rects", "orientation_bounds", "orientation_targets", "rects_from_model",
    "relations_of_rects", "room_bounds", "settle_separations", "target_area", "warm_start_from_rects",
]  # fmt: skip


def build_model(
    spec: Spec,
    *,
    fixed_relations: Mapping[tuple[str, str], str] | None = None,
    formulation: Formulation = Formulation(),
    joins: Mapping[tuple[str, str], str] | None = None,
    crossing: Mapping[tuple[str, str], bool] | None = None,
    defer_separations: bool = False,
) -> pyo.ConcreteModel:
    """The MIQP of the thesis, §5.5.1, for a checked spec (no solving).

    `fixed_relations` maps a pair of room or obstacle ids (a, b) to the side of b on which a
    lies ('left', 'right', 'below', 'above'); those pairs' non-overlap binaries are fixed, so
    a construction that decided the relative positions leaves SCIP an easy model.

    `joins` maps (room box, arm box) pairs of L-shaped rooms to their join option
    (`equations.join_l_arms`); the spec is then the one of their boxes
    (compile.lshape.boxes_spec), each arm a room of its own.

    `defer_separations`: the (5.8) constraints wait for equations.settle_separations, after
    a warm start has put the relations on the model (ModelData.defer_separations).
    """
    data = model_data(spec, formulation)
    if defer_separations:
        data = replace(data, defer_separations=True)
    m = pyo.ConcreteModel(name=spec.name)
    m.formulation = formulation
    for unit in UNITS:
        unit(m, data)
    fix_relations(m, fixed_relations or {})
    if joins:
        join_l_arms(m, joins, crossing)
    return m


CONSTRAINT_FAMILIES = (
    "eq5_4_min_size", "eq5_5_max_size", "eq5_6_aspect_ratio", "eq5_7_inside",
    "eq5_8_non_overlap", "eq5_9_adjacency", "eq5_10_position", "eq5_11_connection",
    "eq5_12_on_boundary", "eq5_13_cluster",
)
"""Names of the constraint blocks, one per equation of §5.5.1."""
