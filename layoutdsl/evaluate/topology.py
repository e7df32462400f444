"""Room graphs of two plans and how they differ (the thesis, §6.4, compares plans of the same topology).

Rooms are paired by the ids the thesis gives them (§5.7): type letter + order of the room
among the spaces of that type in the file (R0, R1, ..., C0, ..., E0). A generated plan's
spaces already carry those ids; an original's get them from their order.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import networkx as nx

from layoutdsl.importer.building import Building

_SPEC_ID = re.compile(r"^([A-Z])(\d+)$")


def room_ids(building: Building) -> dict[str, str]:
    """Space id -> report id: the space's own id when the file already uses spec ids
    (`R0`, `E1`, ... matching the space type), else the importer's ids: type letter and
    order within that type (the thesis, §5.7), so report rows name the rooms as the spec does."""
    own = [space.id for space in building.spaces]
    if len(set(own)) == len(own) and all(
        (m := _SPEC_ID.match(space.id)) and m.group(1) == space.rtype for space in building.spaces
    ):
        return {space.id: space.id for space in building.spaces}
    return building.spec_room_ids()


def room_graph(building: Building) -> nx.Graph:
    """The plan's room graph under report ids; nodes carry rtype and label, edges the portal kind."""
    ids = room_ids(building)
    graph = nx.Graph()
    for space in building.spaces:
        graph.add_node(ids[space.id], rtype=space.rtype, label=space.label, kind=f"{space.rtype}:{space.label}")
    for pair, kind in sorted(building.portal_edges().items(), key=lambda item: sorted(item[0])):
        a, b = sorted(pair)
        if a in ids and b in ids:
            graph.add_edge(ids[a], ids[b], kind=kind)
    return graph


def _edge_key(a: str, b: str) -> tuple[str, str]:
    return (a, b) if _sort_key(a) <= _sort_key(b) else (b, a)


def _sort_key(room: str) -> tuple:
    m = _SPEC_ID.match(room)
    return (m.group(1), int(m.group(2)), room) if m else ("~", 0, room)


def sorted_rooms(rooms) -> list[str]:
    """Room ids in report order: by type letter, then number (R2 before R10)."""
    return sorted(rooms, key=_sort_key)


@dataclass(frozen=True, slots=True)
class TopologyDifference:
    """How a generated plan's room graph compares with the original's."""

    isomorphic: bool
    """Isomorphic respecting each room's type and label (a relabelling of rooms is allowed)."""
    missing_rooms: tuple[str, ...] = ()
    extra_rooms: tuple[str, ...] = ()
    relabelled_rooms: tuple[tuple[str, str, str], ...] = ()
    """(room, original type:label, generated type:label)."""
    missing_edges: tuple[tuple[str, str], ...] = ()
    """Adjacencies of the original absent in the generated plan (e.g. a closed door)."""
    extra_edges: tuple[tuple[str, str], ...] = ()
    changed_portals: tuple[tuple[str, str, str, str], ...] = ()
    """(room, room, original kind, generated kind) for EXPLICIT/IMPLICIT changes."""

    @property
    def identical(self) -> bool:
        """True when the graphs are equal room for room, portal kinds included."""
        return not (
            self.missing_rooms or self.extra_rooms or self.relabelled_rooms
            or self.missing_edges or self.extra_edges or self.changed_portals
        )

    def summary(self) -> str:
        """One line a person reads: what differs, by room."""
        if self.identical:
            return "identical"
        parts = []
        if self.missing_rooms:
            parts.append("missing rooms " + ", ".join(self.missing_rooms))
        if self.extra_rooms:
            parts.append("extra rooms " + ", ".join(self.extra_rooms))
        for room, old, new in self.relabelled_rooms:
            parts.append(f"{room} is {new} (was {old})")
        if self.missing_edges:
            parts.append("missing adjacencies " + ", ".join(f"{a}-{b}" for a, b in self.missing_edges))
        if self.extra_edges:
            parts.append("extra adjacencies " + ", ".join(f"{a}-{b}" for a, b in self.extra_edges))
        for a, b, old, new in self.changed_portals:
            parts.append(f"portal {a}-{b} {old.lower()} -> {new.lower()}")
        prefix = "isomorphic; " if self.isomorphic else ""
        return prefix + "; ".join(parts)


def compare_topology(original: nx.Graph, generated: nx.Graph) -> TopologyDifference:
    """Isomorphism (type- and label-respecting) and the room-by-room difference."""
    orig_nodes, gen_nodes = set(original.nodes), set(generated.nodes)
    relabelled = tuple(
        (room, original.nodes[room]["kind"], generated.nodes[room]["kind"])
        for room in sorted_rooms(orig_nodes & gen_nodes)
        if original.nodes[room]["kind"] != generated.nodes[room]["kind"]
    )
    orig_edges = {_edge_key(a, b): d["kind"] for a, b, d in original.edges(data=True)}
    gen_edges = {_edge_key(a, b): d["kind"] for a, b, d in generated.edges(data=True)}
    order = lambda edges: sorted(edges, key=lambda e: (_sort_key(e[0]), _sort_key(e[1])))  # noqa: E731
    missing = tuple(order(set(orig_edges) - set(gen_edges)))
    extra = tuple(order(set(gen_edges) - set(orig_edges)))
    changed = tuple(
        (a, b, orig_edges[(a, b)], gen_edges[(a, b)])
        for a, b in order(set(orig_edges) & set(gen_edges))
        if orig_edges[(a, b)] != gen_edges[(a, b)]
    )
    same_by_id = not (orig_nodes ^ gen_nodes) and not relabelled and not missing and not extra
    if same_by_id:
        isomorphic = True  # the identity pairing already is an isomorphism
    elif original.number_of_nodes() != generated.number_of_nodes() or original.number_of_edges() != generated.number_of_edges():
        isomorphic = False
    else:
        isomorphic = nx.vf2pp_is_isomorphic(original, generated, node_label="kind")
    return TopologyDifference(
        isomorphic=isomorphic,
        missing_rooms=tuple(sorted_rooms(orig_nodes - gen_nodes)),
        extra_rooms=tuple(sorted_rooms(gen_nodes - orig_nodes)),
        relabelled_rooms=relabelled,
        missing_edges=missing,
        extra_edges=extra,
        changed_portals=changed,
    )
