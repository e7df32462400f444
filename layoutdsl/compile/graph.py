"""The room graph of a spec as networkx reads it: one leaf module that the stages share.

`structure` (what rectangles can draw) and `initial` (the spring embedding) both read the
graph; neither can import the other (structure -> explain -> generator -> initial is the
pipeline's direction, and initial loads numba), so it lives here, below both.
"""

from __future__ import annotations

import networkx as nx

from layoutdsl.syntax.ast import Spec


def room_graph(spec: Spec) -> nx.Graph:
    """The spec's rooms as nodes (in the spec's order), its adjacencies as edges."""
    graph = nx.Graph()
    graph.add_nodes_from(room.id for room in spec.rooms)
    graph.add_edges_from((adj.a, adj.b) for adj in spec.adjacencies)
    return graph
