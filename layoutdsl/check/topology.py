"""Checks of the room graph: planarity (E215) and connectedness (W301)."""

from __future__ import annotations

from collections.abc import Iterator

from layoutdsl.check.common import diag, node_span, rooms_by_id
from layoutdsl.diagnostics import Diagnostic, Severity, register
from layoutdsl.syntax.ast import Adjacency, Spec

E_NOT_PLANAR = register(
    "E215", Severity.ERROR, "room graph is not planar",
    "Reports adjacencies that no arrangement of rectangles can realise because the room graph "
    "is not planar (for example five mutually adjacent rooms, K5).",
    "Rooms that touch form a planar graph; the solver would search in vain until its time limit.",
    "adjacencies: every pair of R0 R1 R2 R3 R4",
)  # fmt: skip
W_COMPONENTS = register(
    "W301", Severity.WARNING, "room graph has several components",
    "Reports rooms with no chain of adjacencies to the rest of the building.",
    "A robot could never reach them: a generated plan would contain unreachable rooms.",
    "rooms R0 R1 R2 with only `R0 R1` adjacent: R2 is unreachable",
)  # fmt: skip


Graph = dict[str, set[str]]
"""Room id -> ids of the rooms it is adjacent to (undirected, no self loops)."""


def _room_graph(spec: Spec) -> tuple[Graph, dict[frozenset[str], Adjacency]]:
    rooms = rooms_by_id(spec)
    graph: Graph = {room_id: set() for room_id in rooms}
    edges: dict[frozenset[str], Adjacency] = {}
    for adjacency in spec.adjacencies:
        if adjacency.a in rooms and adjacency.b in rooms and adjacency.a != adjacency.b:
            graph[adjacency.a].add(adjacency.b)
            graph[adjacency.b].add(adjacency.a)
            edges.setdefault(frozenset((adjacency.a, adjacency.b)), adjacency)
    return graph, edges


def _planarity_core(graph: Graph) -> Graph:
    """The graph with rooms of degree <= 1 removed and rooms of degree 2 smoothed away.

    Both steps keep (non-)planarity, and real plans are mostly trees around corridors, so
    the core left for the planarity test is usually empty.
    """
    core = {node: set(neighbours) for node, neighbours in graph.items()}
    queue = [node for node, neighbours in core.items() if len(neighbours) <= 2]
    while queue:
        node = queue.pop()
        if node not in core or len(core[node]) > 2:
            continue
        neighbours = core.pop(node)
        for other in neighbours:
            core[other].discard(node)
        if len(neighbours) == 2:
            a, b = neighbours  # a path through a degree-2 room acts as one edge
            core[a].add(b)
            core[b].add(a)
        queue.extend(n for n in neighbours if len(core[n]) <= 2)
    return core


def _edge_count(graph: Graph) -> int:
    return sum(len(neighbours) for neighbours in graph.values()) // 2


def check_planarity(spec: Spec) -> Iterator[Diagnostic]:
    """E215: rooms that touch form a planar graph; name a Kuratowski subgraph if not."""
    graph, edges = _room_graph(spec)
    core = _planarity_core(graph)
    if _edge_count(core) <= 8:  # K5 has 10 edges and K3,3 has 9
        return
    import networkx as nx  # imported only for the rare non-trivial core: it is slow to load

    planar, certificate = nx.check_planarity(nx.Graph([(a, b) for a in core for b in core[a]]), counterexample=True)
    if planar:
        return
    names = sorted(certificate.nodes)
    offending = [edges[frozenset(e)] for e in certificate.edges if frozenset(e) in edges]
    if not offending:  # every certificate edge stands for a smoothed path
        offending = [a for key, a in edges.items() if key & certificate.nodes]
    last = max(offending, key=lambda a: (node_span(a).line, node_span(a).col))
    kind = "five mutually adjacent rooms (K5)" if len(names) == 5 and certificate.number_of_edges() == 10 else (
        "two groups of three rooms each adjacent to all of the other group (K3,3)"
        if len(names) == 6 and certificate.number_of_edges() == 9 else "a subdivided K5 or K3,3")  # fmt: skip
    yield diag(spec, E_NOT_PLANAR,
                "the adjacencies cannot all be realised by touching rectangles: the room graph is not planar",
                node_span(last), "closes a non-planar subgraph",
                "drop or reroute an adjacency among the rooms in the note (e.g. through a corridor)",
                (f"rooms {', '.join(f'`{n}`' for n in names)} form {kind}",))  # fmt: skip


def check_components(spec: Spec) -> Iterator[Diagnostic]:
    """W301: every room is reachable from every other through adjacencies."""
    graph, _ = _room_graph(spec)
    if len(graph) < 2:
        return
    components: list[set[str]] = []
    unseen = set(graph)
    for start in graph:  # depth-first search from each room not yet reached, in file order
        if start not in unseen:
            continue
        component, stack = {start}, [start]
        unseen.discard(start)
        while stack:
            for other in graph[stack.pop()]:
                if other in unseen:
                    unseen.discard(other)
                    component.add(other)
                    stack.append(other)
        components.append(component)
    if len(components) < 2:
        return
    rooms = rooms_by_id(spec)
    order = {room_id: index for index, room_id in enumerate(rooms)}
    components.sort(key=lambda c: min(order[r] for r in c))

    def shown(component) -> str:
        members = sorted(component, key=order.__getitem__)
        return ", ".join(f"`{m}`" for m in members[:8]) + (", ..." if len(members) > 8 else "")

    first_cut_off = rooms[min(components[1], key=order.__getitem__)]
    notes = tuple(f"part {i}: {shown(c)}" for i, c in enumerate(components, start=1))
    yield diag(spec, W_COMPONENTS,
                f"the rooms form {len(components)} separate parts with no adjacency between them",
                node_span(first_cut_off, "id"), "first room not connected to the first part",
                "add adjacencies joining the parts, so every room can be reached", notes,
                warning=True)  # fmt: skip
