"""What cannot be drawn: room graphs no arrangement of the spec's room shapes realises.

Checked before the generator runs, from the room graph alone (rooms as nodes, doors as
edges). A non-planar graph never gets here: the checks before compile reject it (E215,
layoutdsl.check, naming the rooms of a Kuratowski subgraph). What is left is what the
spec's room shapes cannot draw:

- four rooms joined pairwise (a K4) none of which is L-shaped (E908): no four rectangles
  pairwise share a wall of positive length (three meet pairwise only around a point, and
  the fourth cannot touch all three), while one L-room wrapping two of the others can.

A K4 with a corridor-like room (type C: corridors, halls, lobbies) is drawn instead: that
room gets an arm (`with_l_rooms`), an L that wraps two of the others (shapes.py): the
longest such room, since its legs must reach round the two it wraps.

Separating triangles (three rooms joined pairwise with rooms both inside and outside the
triangle) are drawable with rectangles when the triangle's rooms may meet around a point;
they are left to the generator.

The generator also turns corridors: of each door between two corridor-like rooms that its
best arrangement still leaves unmet, one gets an arm, the same L (shapes.py), for the rounds
that follow.
"""

from __future__ import annotations

from itertools import combinations

import networkx as nx

from layoutdsl.compile.explain import E908, I911
from layoutdsl.compile.graph import room_graph
from layoutdsl.compile.shapes import with_corridor_arms
from layoutdsl.diagnostics import Diagnostic, Severity
from layoutdsl.diagnostics.source import Span
from layoutdsl.syntax.ast import Spec

_FALLBACK_SPAN = Span(1, 1, 1, 2)


def with_l_rooms(spec: Spec) -> tuple[Spec, list[str]]:
    """The spec with one corridor-like room of every four rooms joined pairwise (and none
    L-shaped yet) made an L, and the rooms made so; rooms of type C only, the one with the
    longest target side first (then the most doors, then spec order). The L has to wrap two
    of the others: a long corridor's legs reach round them where a hall's do not (a hall
    with more doors than three corridors, made the L, found no layout for two seeds of
    four; the longest corridor, four of four)."""
    armed = {arm.room for arm in spec.arms}
    return with_corridor_arms(spec, rectangle_k4s(room_graph(spec), armed), longest=True)


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


def not_placed(spec: Spec) -> list[Diagnostic]:
    """An I911 note for every four rooms joined pairwise with an L among them: said when the
    generator found no layout for such a graph (E908 is for four that must be rectangles)."""
    l_rooms = {arm.room for arm in spec.arms}
    fours = [four for four in rectangle_k4s(room_graph(spec), set()) if l_rooms & set(four)]
    return [_not_placed_diagnostic(spec, four, l_rooms) for four in fours]


def _k4_diagnostic(spec: Spec, four: tuple[str, ...]) -> Diagnostic:
    return Diagnostic(
        code=E908,
        message=f"rooms {', '.join(four)} are joined pairwise: four rectangles cannot all share walls",
        filename=spec.path, span=_adjacency_span(spec, list(four)),
        label="four rooms joined pairwise",
        help=f"give one of them an L shape (an `arms` line, e.g. `{four[0]} ...` for a corridor), "
             "or remove one of their six adjacencies")


def _not_placed_diagnostic(spec: Spec, four: tuple[str, ...], l_rooms: set[str]) -> Diagnostic:
    ls = [room for room in four if room in l_rooms]
    named = " and ".join(ls)
    return Diagnostic(
        code=I911,
        message=f"rooms {', '.join(four)} are joined pairwise: with {named} L-shaped they draw only as "
                f"three around a point and {'an L' if len(ls) > 1 else named} wrapping two of them, "
                "and the generator's arrangements did not reach it",
        filename=spec.path, span=_adjacency_span(spec, list(four)), severity=Severity.INFO,
        label="four rooms joined pairwise",
        help="another `--seed`; an `arms` line for a second of the four; or one of their six "
             "adjacencies removed (then rectangles draw them)")


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
