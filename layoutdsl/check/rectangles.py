"""What rectangles can draw: a test on the room graph alone, before any geometry.

Three rectangles joined pairwise share walls only around a point, so they enclose nothing:
in any drawing of the building the triangle they form in the room graph is a face, with no
room, void or piece of the outside inside it. (Round a hole, the walls would turn four right
angles towards it, one at each place the hole's edge passes from one room to the next; three
rooms give it three such places, and a room met twice would cut the other two apart.) The
outside is one region too, and every room that must open to it (onB) touches it. The regions
of a drawing and their contacts form a plane graph, with the doors among its edges. So a room
graph can be drawn with its rectangles only if it has a planar embedding in which every
triangle of three rectangles is a face and the rooms that must open outside share a face.

The test asks networkx whether a graph built for that is planar (Boyer-Myrvold, linear time):

- each door of such a triangle gets a point in the middle of its wall (one point for the two
  triangles on either side of a wall), and each triangle a hub joined to its three rooms and
  its three wall points. Each face round the hub then touches only one of the three rooms: a
  room with doors to two of them cannot lie inside the triangle.
- one node for the outside, joined to every room that must open to it.

Nonplanar means that no drawing with these shapes exists, whatever the sizes. The converse
need not hold (sizes, and rooms with a single door, which may land in a hub's face, are not
looked at): the test never refuses a drawable graph. All 24 real plans of the development
corpus pass it, with every room a rectangle; of the 80 synthetic school graphs two fail it
with rectangles only and pass once one corridor of their triangles is an L (cml_synth_121,
cml_new_256), and two more fail it until their K4's corridor is an L (cml_new_164,
cml_new_70).

Users: `compile.structure` (a corridor that must turn a corner for the building to be drawn at
all gets its L before the search; E912 when none can) and the sampler (a graph that fails it
with every room a rectangle, as no real plan does, is drawn again).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import networkx as nx

OUTSIDE = ("outside",)
"""The outside's node in the test graph (a tuple: no room id is one)."""

Triangle = tuple[str, str, str]


@dataclass(frozen=True)
class Enclosure:
    """Why a room graph cannot be drawn with its rectangles: a fewest set of its constraints
    that still conflict (dropping any one of them leaves a graph the test passes)."""

    triangles: tuple[Triangle, ...]
    """Rooms joined pairwise in threes, all rectangles, each three meeting only at a point."""
    outside: tuple[str, ...]
    """Rooms that must open to the outside (onB); empty when the triangles alone conflict."""
    rooms: tuple[str, ...] = ()
    """The rooms whose doors close the trap, in the graph's node order: the branch nodes of
    a Kuratowski subgraph of the test graph (a hub or a wall point read as the rooms it
    stands for, the outside left out), as E215 names a non-planar graph's."""


def rectangle_triangles(graph: nx.Graph, rectangles: Iterable[str]) -> list[Triangle]:
    """Every three rooms joined pairwise that are all rectangles, each in the graph's node
    order, in the order of their nodes."""
    drawn = set(rectangles)
    order = {node: index for index, node in enumerate(graph.nodes)}
    found = set()
    for a, b in graph.edges:
        if a not in drawn or b not in drawn:
            continue
        for c in nx.common_neighbors(graph, a, b):
            if c in drawn:
                found.add(tuple(sorted((a, b, c), key=order.__getitem__)))
    return sorted(found, key=lambda triangle: [order[room] for room in triangle])


def drawable(graph: nx.Graph, rectangles: Iterable[str], outside: Iterable[str]) -> bool:
    """False when no drawing has every room of `rectangles` a rectangle and every room of
    `outside` open to the outside (see the module docstring); True may still be undrawable."""
    return _planar(graph, rectangle_triangles(graph, rectangles), list(outside))


def enclosure(graph: nx.Graph, rectangles: Iterable[str], outside: Iterable[str]) -> Enclosure | None:
    """None when `drawable`; otherwise a fewest conflicting set of triangles and rooms that
    must open outside (each constraint dropped in turn where the rest still conflict)."""
    triangles = rectangle_triangles(graph, rectangles)
    open_rooms = list(outside)
    if _planar(graph, triangles, open_rooms):
        return None
    for triangle in list(triangles):
        fewer = [kept for kept in triangles if kept != triangle]
        if not _planar(graph, fewer, open_rooms):
            triangles = fewer
    for room in list(open_rooms):
        fewer_rooms = [kept for kept in open_rooms if kept != room]
        if not _planar(graph, triangles, fewer_rooms):
            open_rooms = fewer_rooms
    return Enclosure(tuple(triangles), tuple(open_rooms), _trap(graph, triangles, open_rooms))


def _trap(graph: nx.Graph, triangles: list[Triangle], outside: list[str]) -> tuple[str, ...]:
    _planar_, certificate = nx.check_planarity(_test_graph(graph, triangles, outside), counterexample=True)
    rooms: set = set()
    for node in certificate.nodes:
        if certificate.degree(node) < 3 or node == OUTSIDE:
            continue
        if isinstance(node, tuple) and node[0] == "hub":
            rooms.update(triangles[node[1]])
        elif isinstance(node, tuple) and node[0] == "wall":
            rooms.update(node[1:])
        else:
            rooms.add(node)
    return tuple(room for room in graph.nodes if room in rooms)


def _planar(graph: nx.Graph, triangles: list[Triangle], outside: list[str]) -> bool:
    return nx.check_planarity(_test_graph(graph, triangles, outside))[0]


def _test_graph(graph: nx.Graph, triangles: list[Triangle], outside: list[str]) -> nx.Graph:
    test = nx.Graph()
    test.add_nodes_from(graph.nodes)
    walls = {frozenset((t[i], t[(i + 1) % 3])) for t in triangles for i in range(3)}
    for a, b in graph.edges:
        if frozenset((a, b)) in walls:
            point = _wall_point(a, b)
            test.add_edge(a, point)
            test.add_edge(point, b)
        else:
            test.add_edge(a, b)
    for index, triangle in enumerate(triangles):
        hub = ("hub", index)
        for i in range(3):
            test.add_edge(hub, triangle[i])
            test.add_edge(hub, _wall_point(triangle[i], triangle[(i + 1) % 3]))
    for room in outside:
        test.add_edge(OUTSIDE, room)
    return test


def _wall_point(a: str, b: str) -> tuple[str, str, str]:
    first, second = sorted((a, b))
    return ("wall", first, second)


__all__ = ["OUTSIDE", "Enclosure", "Triangle", "drawable", "enclosure", "rectangle_triangles"]
