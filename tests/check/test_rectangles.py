"""layoutdsl.check.rectangles: room graphs that no drawing with rectangles realises.

The test must never refuse a drawable graph: every contact graph of a real rectangle
dissection passes (checked against dissections built here, and against the real plans), and
the graphs it refuses are the ones the geometric argument forbids.
"""

from __future__ import annotations

import random
from pathlib import Path

import networkx as nx
import pytest

from layoutdsl.check.rectangles import Enclosure, drawable, enclosure, rectangle_triangles

ROOT = Path(__file__).resolve().parents[2]
FLOORPLANS = ROOT.parent / "shared" / "floorplans"


def _graph(edges) -> nx.Graph:
    graph = nx.Graph()
    graph.add_edges_from(edges)
    return graph


RING_WITH_CROSSING_ENTRANCES = _graph([
    ("C0", "C1"), ("C1", "C2"), ("C2", "C3"), ("C3", "C0"),
    ("C0", "E0"), ("C2", "E0"), ("C1", "E1"), ("C3", "E1"),
])
"""Four corridors in a ring, an entrance joining C0 to C2 and one joining C1 to C3: the two
cross the ring's inside or outside, and one of them is shut in either way."""

TWO_TRIANGLES_ON_A_WALL = _graph([
    ("C0", "C1"), ("C1", "C2"), ("C1", "C3"), ("C0", "C3"), ("C2", "C3"),
    ("C0", "C5"), ("C2", "C5"), ("C1", "E0"), ("C3", "E1"),
])
"""The core of the synthetic school graph cml_synth_121: C1 and C3 share a wall with C0 at
one end and C2 at the other (two triangles, each meeting at a point); C5 joins C0 to C2
round one of them, so C1 or C3 is shut in, and each has an entrance."""


def test_a_ring_crossed_by_two_entrances_shuts_one_in():
    rooms = list(RING_WITH_CROSSING_ENTRANCES)
    assert not drawable(RING_WITH_CROSSING_ENTRANCES, rooms, ["E0", "E1"])
    reason = enclosure(RING_WITH_CROSSING_ENTRANCES, rooms, ["E0", "E1"])
    # the rooms named are the branch rooms of the trap: the ring and both entrances
    assert reason == Enclosure((), ("E0", "E1"), ("C0", "C1", "C2", "C3", "E0", "E1"))
    # either entrance alone can face outwards, and no shape changes that
    assert drawable(RING_WITH_CROSSING_ENTRANCES, rooms, ["E0"])
    assert not drawable(RING_WITH_CROSSING_ENTRANCES, [], ["E0", "E1"])


def test_three_rectangles_joined_pairwise_enclose_nothing():
    # a triangle with two rooms each joined to all three of it: one is inside the triangle
    # in every embedding (K5 less an edge has one), which three rectangles cannot hold
    graph = _graph([("A", "B"), ("B", "C"), ("C", "A")] + [(x, t) for x in "XY" for t in "ABC"])
    assert rectangle_triangles(graph, "ABC") == [("A", "B", "C")]
    assert not drawable(graph, list(graph), [])
    assert enclosure(graph, list(graph), []) == Enclosure((("A", "B", "C"),), (), ("A", "B", "C", "X", "Y"))
    # an L (A not a rectangle) can wrap round one of them
    assert drawable(graph, ["B", "C", "X", "Y"], [])
    # one room joined to all three sits outside the triangle: drawable
    graph.remove_node("Y")
    assert drawable(graph, list(graph), [])


def test_two_triangles_on_a_wall_and_their_entrances():
    graph = TWO_TRIANGLES_ON_A_WALL
    reason = enclosure(graph, list(graph), ["E0", "E1"])
    assert reason.triangles == (("C0", "C1", "C3"), ("C1", "C2", "C3")) and reason.outside == ("E0", "E1")
    assert set(reason.rooms) <= {"C0", "C1", "C2", "C3", "C5", "E0", "E1"}
    # any one of the four rooms of the two triangles as an L is enough
    for bent in ("C0", "C1", "C2", "C3"):
        assert drawable(graph, [room for room in graph if room != bent], ["E0", "E1"]), bent
    # C5 is in no triangle: its L changes nothing
    assert not drawable(graph, [room for room in graph if room != "C5"], ["E0", "E1"])
    # without an entrance to keep outside, C1 or C3 may be shut in
    assert drawable(graph, list(graph), ["E0"])


def _dissection(rng: random.Random, rooms: int) -> dict[str, tuple[float, float, float, float]]:
    """A rectangle cut by random guillotine cuts into `rooms` rectangles, plus a few rooms
    merged away (so not every wall runs the full width): (x, y, w, h) each."""
    boxes = [(0.0, 0.0, 40.0, 30.0)]
    while len(boxes) < rooms:
        boxes.sort(key=lambda box: -box[2] * box[3])
        x, y, w, h = boxes.pop(rng.randrange(min(3, len(boxes))))
        share = rng.uniform(0.25, 0.75)
        if w >= h:
            boxes += [(x, y, w * share, h), (x + w * share, y, w * (1 - share), h)]
        else:
            boxes += [(x, y, w, h * share), (x, y + h * share, w, h * (1 - share))]
    return {f"R{i}": box for i, box in enumerate(boxes)}


def _contacts(boxes) -> nx.Graph:
    """Rooms that share a wall of positive length (independent of the code under test)."""
    graph = nx.Graph()
    graph.add_nodes_from(boxes)
    names = sorted(boxes)
    for i, a in enumerate(names):
        ax, ay, aw, ah = boxes[a]
        for b in names[i + 1:]:
            bx, by, bw, bh = boxes[b]
            touch_x = abs(ax + aw - bx) < 1e-9 or abs(bx + bw - ax) < 1e-9
            touch_y = abs(ay + ah - by) < 1e-9 or abs(by + bh - ay) < 1e-9
            overlap_x = min(ax + aw, bx + bw) - max(ax, bx)
            overlap_y = min(ay + ah, by + bh) - max(ay, by)
            if (touch_x and overlap_y > 1e-6) or (touch_y and overlap_x > 1e-6):
                graph.add_edge(a, b)
    return graph


@pytest.mark.parametrize("seed", range(60))
def test_every_drawn_building_passes(seed):
    # rectangles that tile a box, some removed (voids and a ragged outline), doors on a
    # random subset of the walls they share, and every room on the outline allowed to be
    # one that must open outside: a drawing exists, so the test must not refuse it
    rng = random.Random(seed)
    boxes = _dissection(rng, rng.randrange(6, 40))
    for name in rng.sample(sorted(boxes), k=len(boxes) // 6):
        del boxes[name]
    contacts = _contacts(boxes)
    doors = nx.Graph()
    doors.add_nodes_from(contacts)
    doors.add_edges_from(edge for edge in contacts.edges if rng.random() < 0.8)
    on_outline = [name for name, (x, y, w, h) in sorted(boxes.items())
                  if x < 1e-9 or y < 1e-9 or x + w > 40 - 1e-9 or y + h > 30 - 1e-9]
    outside = [name for name in on_outline if rng.random() < 0.5]
    assert drawable(doors, list(doors), outside)
    assert drawable(contacts, list(contacts), on_outline)


@pytest.mark.skipif(not FLOORPLANS.is_dir(), reason="needs ../shared/floorplans beside the repository")
def test_every_real_plan_passes_with_every_room_a_rectangle():
    from layoutdsl.importer import import_building

    plans = sorted(FLOORPLANS.glob("*.xml"))
    assert len(plans) >= 20
    for path in plans:
        spec, _ = import_building(path)
        assert spec is not None, path.stem
        graph = nx.Graph()
        graph.add_nodes_from(room.id for room in spec.rooms)
        graph.add_edges_from((adj.a, adj.b) for adj in spec.adjacencies)
        outside = [room.id for room in spec.rooms if room.on_boundary]
        assert enclosure(graph, list(graph), outside) is None, path.stem
