"""A room graph without geometry (networkx) -> a Spec with sizes from the model.

Nodes carry `rtype` (R, C or E) and `label`; edges may carry `door` (metres) and `kind`
(`e` a door, `i` an opening). Each room gets the model's sizes for its kind, type and label
(a corridor is sized by its door count, its degree in the graph), typical ones when `rng` is
None and drawn ones otherwise. The boundary is `choose_boundary` of the rooms, and
entrances (type E labelled ENTRANCE, or any node whose `onB`/`exterior` attribute is true)
must touch it (`onB`): an entrance opens to the outside.

Room ids: the graph's own node ids when every one of them is a spec id (a word that is not
a number, e.g. `R1`, `hall_2`); otherwise R0, R1, ..., C0, ..., E0, ... by type in node
order, as the XML importer numbers rooms (the thesis, §5.7). Rooms and adjacencies keep the
graph's node and edge order, so the same graph in two file formats gives the same spec.
"""

from __future__ import annotations

import random
import re
from types import MappingProxyType

import networkx as nx

from layoutdsl.sizes.boundary import choose_boundary
from layoutdsl.sizes.model import SizeModel, load_model
from layoutdsl.syntax.ast import ROOM_TYPES, Adjacency, Boundary, Room, Spec

_DEFAULT_LABELS = {"R": "ROOM", "C": "CORRIDOR", "E": "ENTRANCE"}
_SPEC_ID = re.compile(r"[A-Za-z_][A-Za-z0-9_.\-]*")
_TRUE = {"1", "true", "yes", "on"}


def room_ids_for(graph: nx.Graph) -> dict:
    """Node -> room id (see the module doc)."""
    nodes = list(graph.nodes)
    if all(isinstance(n, str) and _SPEC_ID.fullmatch(n) and n not in ("onB",) for n in nodes):
        return {n: n for n in nodes}
    counters: dict[str, int] = {}
    ids = {}
    for node in nodes:
        rtype = node_type(graph, node)
        number = counters.get(rtype, 0)
        counters[rtype] = number + 1
        ids[node] = f"{rtype}{number}"
    return ids


def node_type(graph: nx.Graph, node) -> str:
    rtype = str(graph.nodes[node].get("rtype", "R")).strip().upper()
    return rtype if rtype in ROOM_TYPES else "R"


def node_label(graph: nx.Graph, node) -> str:
    label = " ".join(str(graph.nodes[node].get("label", "")).split()).upper()
    return label or _DEFAULT_LABELS[node_type(graph, node)]


def opens_outside(graph: nx.Graph, node) -> bool:
    """Must this room touch the boundary? Entrances do, and nodes that say so."""
    data = graph.nodes[node]
    for key in ("onB", "exterior"):
        if key in data:
            value = data[key]
            return value is True or str(value).strip().lower() in _TRUE
    return node_type(graph, node) == "E" and node_label(graph, node) == "ENTRANCE"


def spec_from_graph(
    graph: nx.Graph,
    kind: str = "school",
    model: SizeModel | None = None,
    rng: random.Random | None = None,
    *,
    name: str = "graph",
) -> Spec:
    """The spec of a room graph (see the module doc). Raises ModelError for an unknown kind
    and ValueError for a graph with no rooms."""
    model = model if model is not None else load_model()
    model.kind(kind)  # an unknown kind fails before any work
    if graph.number_of_nodes() == 0:
        raise ValueError("the graph has no rooms")
    ids = room_ids_for(graph)
    rooms = []
    for node in graph.nodes:
        rtype, label = node_type(graph, node), node_label(graph, node)
        doors = graph.degree(node)
        if rng is None:
            size = model.room_sizes(kind, rtype, label, doors=doors)
        else:
            size = model.sample_room_sizes(kind, rtype, label, rng, doors=doors)
        rooms.append(Room(ids[node], *size.as_tuple(), rtype, label, opens_outside(graph, node)))
    order = {node: index for index, node in enumerate(graph.nodes)}
    adjacencies = []
    default_door = model.door(kind)
    for a, b, data in graph.edges(data=True):
        if order[a] > order[b]:
            a, b = b, a
        door = _positive(data.get("door"), default_door)
        portal = str(data.get("kind", "")).strip().lower()
        if portal not in ("e", "i"):
            portal = model.adjacency_kind(kind, node_type(graph, a), node_type(graph, b))
        adjacencies.append((order[a], order[b], Adjacency(ids[a], ids[b], door, portal)))
    adjacencies.sort(key=lambda item: item[:2])
    w, h = choose_boundary(rooms)
    return Spec(
        name=name,
        rooms=tuple(rooms),
        boundary=Boundary(w, h, spans=MappingProxyType({}), chosen=True),
        adjacencies=tuple(adjacency for *_, adjacency in adjacencies),
    )


def _positive(value, default: float) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        return default
    return number if number > 0 and number != float("inf") else default
