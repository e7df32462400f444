"""Checks whose logic is subtle: aspect-ratio reachability, planarity reduction, code-built specs."""

from __future__ import annotations

import itertools

import networkx as nx
from hypothesis import given, settings
from hypothesis import strategies as st

from layoutdsl.syntax.ast import Adjacency, Boundary, Room, Spec
from layoutdsl.check import check_spec, reachable_ratios
from layoutdsl.check.topology import _planarity_core


def _room(min_w, max_w, min_h, max_h, min_ar=1.0, max_ar=3.0, rtype="R") -> Room:
    return Room("R0", min_w, max_w, min_w, min_h, max_h, min_h, min_ar, max_ar, rtype, "ROOM")


sizes = st.floats(0.5, 20, allow_nan=False)


@settings(max_examples=300, deadline=None, derandomize=True)
@given(a=sizes, b=sizes, c=sizes, d=sizes)
def test_reachable_ratios_match_brute_force(a, b, c, d) -> None:
    min_w, max_w = sorted((a, b))
    min_h, max_h = sorted((c, d))
    lowest, highest = reachable_ratios(_room(min_w, max_w, min_h, max_h))
    steps = [i / 60 for i in range(61)]
    sampled = [
        max(w, h) / min(w, h)
        for w, h in itertools.product(
            [min_w + t * (max_w - min_w) for t in steps], [min_h + t * (max_h - min_h) for t in steps]
        )
    ]
    assert lowest <= min(sampled) + 1e-9 and max(sampled) <= highest + 1e-9
    assert abs(max(sampled) - highest) < 1e-9  # the maximum is a corner, sampled exactly
    assert min(sampled) - lowest < 0.1  # the grid gets close to the true minimum


def test_corridors_are_exempt_from_aspect_ratio() -> None:
    boundary = Boundary(60, 60)
    corridor = _room(1, 2, 20, 30, 1, 1.5, rtype="C")
    room = _room(1, 2, 20, 30, 1, 1.5)
    assert check_spec(Spec("s", (corridor,), boundary)) == []
    assert [d.code for d in check_spec(Spec("s", (room,), boundary))] == ["E205"]


def _adjacency(graph: nx.Graph) -> dict:
    return {node: set(graph.neighbors(node)) for node in graph}


def test_planarity_core_keeps_a_subdivided_k5_and_drops_trees() -> None:
    k5 = nx.complete_graph(5)
    subdivided = nx.Graph()
    for a, b in k5.edges:  # every edge becomes a path through a new degree-2 room
        subdivided.add_edges_from([(a, f"{a}-{b}"), (f"{a}-{b}", b)])
    subdivided.add_edges_from([("leaf", 0), ("leaf2", "leaf")])
    core = _planarity_core(_adjacency(subdivided))
    assert set(core) == set(range(5))
    assert all(core[n] == set(range(5)) - {n} for n in core)  # K5 again
    assert _planarity_core(_adjacency(nx.balanced_tree(3, 5))) == {}
    assert sum(map(len, _planarity_core(_adjacency(nx.cycle_graph(50))).values())) <= 2


@settings(max_examples=200, deadline=None, derandomize=True)
@given(seed=st.integers(0, 10**6), nodes=st.integers(3, 14), edges=st.integers(0, 40))
def test_planarity_core_preserves_planarity(seed: int, nodes: int, edges: int) -> None:
    graph = nx.gnm_random_graph(nodes, edges, seed=seed)
    core = _planarity_core(_adjacency(graph))
    core_graph = nx.Graph([(a, b) for a in core for b in core[a]])
    assert nx.check_planarity(graph)[0] == nx.check_planarity(core_graph)[0]


def _k5_spec() -> Spec:
    rooms = tuple(Room(f"R{i}", 3, 5, 4, 3, 5, 4, 1, 1.5, "R", "ROOM") for i in range(5))
    adjacencies = tuple(Adjacency(f"R{a}", f"R{b}", 0.9, "e") for a, b in itertools.combinations(range(5), 2))
    return Spec("k5", rooms, Boundary(30, 30), adjacencies)


def test_non_planar_spec_built_in_code_is_reported_without_spans() -> None:
    """The importer checks specs it built itself: no spans, still a located diagnostic."""
    diagnostics = check_spec(_k5_spec())
    assert [d.code for d in diagnostics] == ["E215"]
    assert diagnostics[0].span.line == 1
    assert "`R0`, `R1`, `R2`, `R3`, `R4`" in diagnostics[0].notes[0]


def test_removing_one_k5_edge_makes_it_planar() -> None:
    spec = _k5_spec()
    spec = Spec(spec.name, spec.rooms, spec.boundary, spec.adjacencies[1:])
    assert check_spec(spec) == []
