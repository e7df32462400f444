"""The cost: one number per packed state, in metres, that the schedule drives to zero.

    violation = OVERFLOW_WEIGHT   x extent of the packing beyond the outline
              + ADJACENCY_WEIGHT  x sum over doors of (gap between the two rooms
                                                     + shortfall of their shared wall
                                                     + FLUSH_WEIGHT x, for an L-room's
                                                       box and arm, how far the arm is
                                                       from the nearer end of the box)
              + BOUNDARY_WEIGHT   x sum over rooms that must open to the outside (onB)
                                    of their distance from the outer boundary
    cost      = violation
              + COMPACT_WEIGHT    x bounding-box area / outline area   (few enclosed voids)
              + RESIZE_WEIGHT     x metres the sides are from their targets (schedule.py)

A violation of 0 is a packing that meets every door inside the outline with every entrance
on the outside: the relation LP of the sizing stage (layoutdsl.solve.relations) is then
feasible from its first round. The outer boundary is the spec's outline when it has one,
else the packing's own bounding box (the boundary the tool chooses is drawn round it).
"""

from __future__ import annotations

from numba import njit

ADJACENCY_WEIGHT = 1.0
"""Per metre of gap between a door's rooms, or of missing shared wall."""

FLUSH_WEIGHT = 0.3
"""Per metre an L-room's arm lies from the nearer end of its box. The sizing stage joins the
arm at an end (an L, layout.lshape.JOIN_OPTIONS), so an arm met along the box's middle (a
T) is moved there, over the rooms beside it: measured on office_324-Elm (95 % of its outline
filled), the annealer reached a violation of 0 with four such Ts and every sizing failed.
With 1.0 the search lost plans it drew before (school_hendersonhighschool); 0.3 drew them
and 324-Elm."""

OVERFLOW_WEIGHT = 2.0
"""Per metre the packing sticks out of the spec's outline."""

CHOSEN_OVERFLOW_WEIGHT = 0.1
"""...of the outline the tool chose (a spec without a boundary): a guide towards its size
and shape, not a limit, since the boundary is drawn round the layout afterwards."""

BOUNDARY_WEIGHT = 1.0
"""Per metre a room that must open to the outside (onB) is from the outer boundary."""

COMPACT_WEIGHT = 0.02
"""Per (bounding box area / outline area): compact buildings, with few enclosed voids."""

RESIZE_WEIGHT = 0.05
"""Per metre a side is from its target length: rooms stay near their target sizes."""


@njit(cache=True, inline="always")
def distance_to_outside(x, y, w, h, outer_w, outer_h):
    """Metres from a room (x, y, w, h) to the nearest side of the outer boundary."""
    return min(min(x, y), min(max(0.0, outer_w - x - w), max(0.0, outer_h - y - h)))


@njit(cache=True)
def violation(work, edge_a, edge_b, need, join, group_end, on_boundary, width, height, wall, outline_given,
              per_edge):
    """(score, violation in metres, bounding box area) of a packing (representation.pack_state's
    `work`); per_edge[k] gets door k's share, which the moves read to pick unmet doors.
    A door of an L-room is a group of alternative edges (its box's, its arm's; group_end):
    the best of them counts. join[k]: edge k joins an L-room's box and arm.
    `outline_given`: onB is measured to the outline (width x height), else to the packing's
    bounding box, the boundary the tool will draw round it.

    Sticking out of an outline the spec gives is violation; sticking out of a guide (an
    outline the tool chose, or one `--grow-boundary` may grow) is not, since the boundary is
    drawn round the packing. The search minimises `score`, the violation plus what sticks out
    of a guide, which steers it towards the guide's size and shape; `violation` alone says
    how far a packing is from a layout. Counted as violation, the guide kept a packing with
    every door met but 20 m beyond a grown outline over repair_max_violation_m, never sized
    (office_floorplanMAIN with --grow-boundary, seed 1: every door met from round 5 on, no
    layout in 60 s)."""
    n = work.x.shape[0]
    pos_p, pos_q = work.pos_p, work.pos_q
    x, y, w, h = work.x, work.y, work.w, work.h
    right = 0.0
    top = 0.0
    for i in range(n):
        right = max(right, x[i] + w[i])
        top = max(top, y[i] + h[i])
    for k in range(edge_a.shape[0]):
        a = edge_a[k]
        b = edge_b[k]
        if pos_q[a] > pos_q[b]:
            a, b = b, a
        # now a comes first in Q: a is left of b or below it
        if pos_p[a] < pos_p[b]:
            gap = x[b] - (x[a] + w[a] + wall)
            overlap = min(y[a] + h[a], y[b] + h[b]) - max(y[a], y[b])
        else:
            gap = y[b] - (y[a] + h[a] + wall)
            overlap = min(x[a] + w[a], x[b] + w[b]) - max(x[a], x[b])
        per_edge[k] = abs(gap) + max(0.0, need[k] - overlap)
        if join[k]:
            # the two boxes of an L: the arm is flush with one end of the box
            if pos_p[a] < pos_p[b]:
                per_edge[k] += FLUSH_WEIGHT * min(abs(y[a] - y[b]), abs(y[a] + h[a] - y[b] - h[b]))
            else:
                per_edge[k] += FLUSH_WEIGHT * min(abs(x[a] - x[b]), abs(x[a] + w[a] - x[b] - w[b]))
    doors = 0.0
    start = 0
    for g in range(group_end.shape[0]):
        best = per_edge[start]
        for k in range(start + 1, group_end[g]):
            best = min(best, per_edge[k])
        doors += best
        start = group_end[g]
    outer_w = width if outline_given else right
    outer_h = height if outline_given else top
    away = 0.0
    for i in range(n):
        if on_boundary[i]:
            away += distance_to_outside(x[i], y[i], w[i], h[i], outer_w, outer_h)
    overflow = max(0.0, right - width) + max(0.0, top - height)
    overflow_weight = OVERFLOW_WEIGHT if outline_given else CHOSEN_OVERFLOW_WEIGHT
    # the sum in this order, so the search's arithmetic does not change with the split
    score = overflow_weight * overflow + ADJACENCY_WEIGHT * doors + BOUNDARY_WEIGHT * away
    if outline_given:
        return score, score, right * top
    return score, ADJACENCY_WEIGHT * doors + BOUNDARY_WEIGHT * away, right * top
