"""The room graph of a spec as networkx reads it: one leaf module that the stages share.

`structure` (what rectangles can draw) and `initial` (the spring embedding) both read the
graph; neither can import the other (structure -> explain -> generator -> initial is the
pipeline's direction, and initial loads numba), so it lives here, below both. `explain`
reads the corridors' rings from here too.
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


def corridor_skeleton(spec: Spec) -> nx.Graph:
    """The corridor-like rooms (type C) as nodes, in sorted order, and the doors between two
    of them as edges."""
    corridors = {room.id for room in spec.rooms if room.is_corridor}
    skeleton = nx.Graph()
    skeleton.add_nodes_from(sorted(corridors))
    skeleton.add_edges_from(sorted((adj.a, adj.b) for adj in spec.adjacencies
                                   if adj.a in corridors and adj.b in corridors and adj.a != adj.b))
    return skeleton


def rings(graph: nx.Graph) -> int:
    """Independent cycles of a graph (edges - nodes + components): of the corridor
    skeleton, its rings of corridors, each of which must close round the rooms inside it.
    The formula of `layoutdsl.sample.stats.cycle_rank`, not imported from there: loading
    the sample package would add 0.4 s to every compile's start-up for one subtraction."""
    return graph.number_of_edges() - graph.number_of_nodes() + nx.number_connected_components(graph)
