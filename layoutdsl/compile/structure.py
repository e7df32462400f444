"""What cannot be drawn: room graphs no arrangement of the spec's room shapes realises.

Checked before the generator runs, from the room graph alone (rooms as nodes, doors as
edges). A non-planar graph never gets here: the checks before compile reject it (E215,
layoutdsl.check, naming the rooms of a Kuratowski subgraph). What is left is what the
spec's room shapes cannot draw:

- four rooms joined pairwise (a K4) none of which is L-shaped (E908): no four rectangles
  pairwise share a wall of positive length (three meet pairwise only around a point, and
  the fourth cannot touch all three), while one L-room wrapping two of the others can.

A K4 with a corridor-like room (type C: corridors, halls, lobbies) is drawn instead: that
room gets an arm (`with_l_rooms`), an L that wraps two of the others, its area shared
between its box (BOX_SHARE of its long side) and its arm (ARM_SHARE, across the box).

Separating triangles (three rooms joined pairwise with rooms both inside and outside the
triangle) are drawable with rectangles when the triangle's rooms may meet around a point;
they are left to the generator.
"""

from __future__ import annotations

from dataclasses import replace
from itertools import combinations

import networkx as nx

from layoutdsl.compile.explain import E908
from layoutdsl.compile.graph import room_graph
from layoutdsl.diagnostics import Diagnostic
from layoutdsl.diagnostics.source import Span
from layoutdsl.syntax.ast import Arm, Room, Spec

_FALLBACK_SPAN = Span(1, 1, 1, 2)


BOX_SHARE = 0.7
ARM_SHARE = 0.4
"""Shares of a corridor-like room's long side (targets and bounds) its box keeps and its
new arm gets when it becomes an L (`with_l_rooms`): 110 % of its length in all."""


def with_l_rooms(spec: Spec) -> tuple[Spec, list[str]]:
    """The spec with one corridor-like room of every four rooms joined pairwise (and none
    L-shaped yet) made an L, and the rooms made so; rooms of type C only, first the one with
    the most doors (then spec order)."""
    graph = room_graph(spec)
    rooms = {room.id: room for room in spec.rooms}
    made: list[str] = []
    armed = {arm.room for arm in spec.arms}
    for four in rectangle_k4s(graph, armed):
        if armed & set(four):
            continue  # an earlier group's L already covers this one
        corridors = [r for r in four if rooms[r].rtype == "C"]
        if not corridors:
            continue
        chosen = max(corridors, key=lambda r: (graph.degree(r), -list(rooms).index(r)))
        armed.add(chosen)
        made.append(chosen)
    if not made:
        return spec, []
    new_rooms, arms = [], list(spec.arms)
    for room in spec.rooms:
        if room.id in made:
            box, arm = _split_into_l(room)
            new_rooms.append(box)
            arms.append(arm)
        else:
            new_rooms.append(room)
    return replace(spec, rooms=tuple(new_rooms), arms=tuple(arms)), made


def _split_into_l(room: Room) -> tuple[Room, Arm]:
    """The room's box (its long side shortened to BOX_SHARE) and an arm across it, as wide
    as the room and ARM_SHARE of its long side long."""
    wide = room.target_w >= room.target_h
    if wide:
        box = replace(room, min_w=room.min_w * BOX_SHARE, max_w=room.max_w * BOX_SHARE,
                      target_w=room.target_w * BOX_SHARE)
        arm = Arm(room.id, room.min_h, room.max_h, room.target_h, room.min_w * ARM_SHARE,
                  room.max_w * ARM_SHARE, room.target_w * ARM_SHARE, 1.0, 1e3)
    else:
        box = replace(room, min_h=room.min_h * BOX_SHARE, max_h=room.max_h * BOX_SHARE,
                      target_h=room.target_h * BOX_SHARE)
        arm = Arm(room.id, room.min_h * ARM_SHARE, room.max_h * ARM_SHARE, room.target_h * ARM_SHARE,
                  room.min_w, room.max_w, room.target_w, 1.0, 1e3)
    return box, arm


def undrawable(spec: Spec) -> list[Diagnostic]:
    """An E908 diagnostic for every four rooms joined pairwise that must all be rectangles;
    empty when the room graph may be drawable."""
    l_rooms = {arm.room for arm in spec.arms}
    return [_k4_diagnostic(spec, group) for group in rectangle_k4s(room_graph(spec), l_rooms)]


def rectangle_k4s(graph: nx.Graph, l_rooms: set[str]) -> list[tuple[str, ...]]:
    """Every four rooms joined pairwise none of which may be L-shaped (node order of the
    graph): cliques of four or more give each of their four-room subsets."""
    order = {node: i for i, node in enumerate(graph.nodes)}
    found: set[tuple[str, ...]] = set()
    for clique in nx.find_cliques(graph):
        if len(clique) < 4:
            continue
        for four in combinations(sorted(clique, key=order.__getitem__), 4):
            if not l_rooms & set(four):
                found.add(four)
    return sorted(found, key=lambda four: [order[r] for r in four])


def _k4_diagnostic(spec: Spec, four: tuple[str, ...]) -> Diagnostic:
    return Diagnostic(
        code=E908,
        message=f"rooms {', '.join(four)} are joined pairwise: four rectangles cannot all share walls",
        filename=spec.path, span=_adjacency_span(spec, list(four)),
        label="four rooms joined pairwise",
        help=f"give one of them an L shape (an `arms` line, e.g. `{four[0]} ...` for a corridor), "
             "or remove one of their six adjacencies")


def _adjacency_span(spec: Spec, rooms: list[str]) -> Span:
    """The first adjacency line between two of the rooms, else the first room's line."""
    wanted = set(rooms)
    for adj in spec.adjacencies:
        if adj.a in wanted and adj.b in wanted and getattr(adj, "span", None) is not None:
            return adj.span
    for room in spec.rooms:
        if room.id in wanted and getattr(room, "span", None) is not None:
            return room.span
    return _FALLBACK_SPAN
