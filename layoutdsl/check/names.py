"""Checks of names and references (E1xx): duplicates, unknown rooms, repeated lines."""

from __future__ import annotations

from collections.abc import Iterator

from layoutdsl.check.common import diag, node_span, rooms_by_id
from layoutdsl.diagnostics.suggest import did_you_mean
from layoutdsl.diagnostics import Diagnostic, Severity, register
from layoutdsl.syntax.ast import Adjacency, Room, Spec

# ===== Codes: E1xx names and references =====

E_DUPLICATE_ROOM = register(
    "E101", Severity.ERROR, "duplicate room id",
    "Reports a room id defined by more than one room line.",
    "Adjacencies, positions and clusters refer to rooms by id; a duplicate makes them ambiguous.",
    "rooms\nR0 4 8 6 6 10 8 1 1.7 R CLASSROOM\nR0 3 5 4 5 9 8 1 2 R MEDIUM",
)  # fmt: skip
E_UNKNOWN_ADJACENT = register(
    "E102", Severity.ERROR, "adjacency names an unknown room",
    "Reports an adjacency whose room id is not defined in `rooms`.",
    "The adjacency cannot be enforced; usually the id is misspelled.",
    "adjacencies\nR0 C33 0.9 e     # no room C33",
)  # fmt: skip
E_UNKNOWN_POSITIONED = register(
    "E103", Severity.ERROR, "position names an unknown room",
    "Reports a `positions` line whose room id is not defined in `rooms`.",
    "The position would be silently dropped.",
    "positions\nR9 3 4",
)  # fmt: skip
E_UNKNOWN_CONNECTED = register(
    "E104", Severity.ERROR, "connection names an unknown room",
    "Reports a `connections` line whose room id is not defined in `rooms`.",
    "The connection would be silently dropped.",
    "connections\nC9 1 1 1 10",
)  # fmt: skip
E_UNKNOWN_MEMBER = register(
    "E105", Severity.ERROR, "cluster names an unknown room",
    "Reports a cluster member whose room id is not defined in `rooms`.",
    "The cluster would silently lose a member.",
    "clusters\nK0\nR9 0 0",
)  # fmt: skip
E_UNKNOWN_HINTED = register(
    "E106", Severity.ERROR, "hint names an unknown room",
    "Reports a `hints` line whose room id is not defined in `rooms`.",
    "The hint would be silently ignored; usually the id is misspelled.",
    "hints\nR9 0 0 4 4",
)  # fmt: skip
E_DUPLICATE_OBSTACLE = register(
    "E107", Severity.ERROR, "duplicate obstacle id",
    "Reports an obstacle id used twice, or also used by a room.",
    "Ids name things in diagnostics and outputs; a shared id makes them ambiguous.",
    "boundary\n20 50\nO1 0 0 1 1\nO1 5 5 1 1",
)  # fmt: skip
E_DUPLICATE_CLUSTER = register(
    "E108", Severity.ERROR, "duplicate cluster id",
    "Reports a cluster id used by two clusters.",
    "Two clusters with one name cannot be told apart in messages; usually a copy-paste slip.",
    "clusters\nK0\nR0 0 0\n\nK0\nR1 0 0",
)  # fmt: skip
E_TWO_POSITIONS = register(
    "E109", Severity.ERROR, "room has two positions",
    "Reports a room with more than one `positions` line.",
    "The thesis allows at most one position per room (5.10); use `connections` for two points.",
    "positions\nR0 3 4\nR0 5 6",
)  # fmt: skip
E_SELF_ADJACENT = register(
    "E110", Severity.ERROR, "room adjacent to itself",
    "Reports an adjacency between a room and itself.",
    "A room cannot share a wall with itself; usually the second id is a typo.",
    "adjacencies\nR0 R0 0.9 e",
)  # fmt: skip
E_DUPLICATE_ADJACENCY = register(
    "E111", Severity.ERROR, "duplicate adjacency",
    "Reports an adjacency listed twice (in either order).",
    "Adjacencies are symmetric; a second line either repeats the first or contradicts its door.",
    "adjacencies\nR0 C3 0.9 e\nC3 R0 0.9 e",
)  # fmt: skip
E_DUPLICATE_MEMBER = register(
    "E112", Severity.ERROR, "room twice in one cluster",
    "Reports a room listed twice in the same cluster.",
    "A room has one point in its cluster's frame; two points contradict each other.",
    "clusters\nK0\nR0 0 0\nR0 4 0",
)  # fmt: skip
E_TWO_HINTS = register(
    "E113", Severity.ERROR, "room has two hints",
    "Reports a room with more than one `hints` line.",
    "A hint is the room's one starting rectangle; two are ambiguous.",
    "hints\nR0 0 0 4 4\nR0 5 5 4 4",
)  # fmt: skip
W_EMPTY_CLUSTER = register(
    "W302", Severity.WARNING, "empty cluster",
    "Reports a cluster id with no member lines under it.",
    "An empty cluster constrains nothing; usually its members were forgotten or misplaced.",
    "clusters\nK0\n\nK1\nR0 0 0",
)  # fmt: skip


def check_duplicate_ids(spec: Spec) -> Iterator[Diagnostic]:
    """E101, E107, E108: ids defined twice."""
    first: dict[str, Room] = {}
    for room in spec.rooms:
        if room.id in first:
            yield diag(spec, E_DUPLICATE_ROOM, f"room `{room.id}` is defined twice", node_span(room, "id"),
                        "second definition", "rename one of the two rooms",
                        (f"first defined on line {node_span(first[room.id]).line}",))  # fmt: skip
        else:
            first[room.id] = room
    seen_obstacles: dict[str, int] = {}
    for obstacle in spec.boundary.obstacles if spec.boundary else ():
        if obstacle.id in first:
            yield diag(spec, E_DUPLICATE_OBSTACLE, f"obstacle `{obstacle.id}` has the id of a room",
                        node_span(obstacle, "id"), "also a room id", "give the obstacle its own id",
                        (f"room `{obstacle.id}` is defined on line {node_span(first[obstacle.id]).line}",))  # fmt: skip
        elif obstacle.id in seen_obstacles:
            yield diag(spec, E_DUPLICATE_OBSTACLE, f"obstacle `{obstacle.id}` is defined twice",
                        node_span(obstacle, "id"), "second definition", "rename one of the two obstacles",
                        (f"first defined on line {seen_obstacles[obstacle.id]}",))  # fmt: skip
        else:
            seen_obstacles[obstacle.id] = node_span(obstacle).line
    seen_clusters: dict[str, int] = {}
    for cluster in spec.clusters:
        if cluster.id in seen_clusters:
            yield diag(spec, E_DUPLICATE_CLUSTER, f"cluster `{cluster.id}` is defined twice",
                        node_span(cluster, "id"), "second definition", "rename one of the two clusters",
                        (f"first defined on line {seen_clusters[cluster.id]}",))  # fmt: skip
        else:
            seen_clusters[cluster.id] = node_span(cluster).line


def check_references(spec: Spec) -> Iterator[Diagnostic]:
    """E102-E106: every room id used outside `rooms` is defined there."""
    known = rooms_by_id(spec)

    def unknown(code: str, node, field: str, room_id: str, what: str, other: str | None = None) -> Diagnostic:
        # always a way forward: the closest id (never the adjacency's other room, which
        # would make it adjacent to itself), else the ids there are
        shown = list(known)[:8]
        listing = ", ".join(f"`{room}`" for room in shown) + (", ..." if len(known) > len(shown) else "")
        help_text = did_you_mean(room_id, [room for room in known if room != other]) or (
            f"define `{room_id}` in `rooms`, or use one of its rooms: {listing}" if known
            else f"define `{room_id}` in `rooms`")
        return diag(spec, code, f"{what} unknown room `{room_id}`", node_span(node, field), "not defined",
                     help_text)  # fmt: skip

    for adjacency in spec.adjacencies:
        for field, room_id in (("a", adjacency.a), ("b", adjacency.b)):
            if room_id not in known:
                other = adjacency.b if field == "a" else adjacency.a
                yield unknown(E_UNKNOWN_ADJACENT, adjacency, field, room_id, f"room `{other}` is adjacent to", other)
    for position in spec.positions:
        if position.room not in known:
            yield unknown(E_UNKNOWN_POSITIONED, position, "room", position.room, "position for")
    for connection in spec.connections:
        if connection.room not in known:
            yield unknown(E_UNKNOWN_CONNECTED, connection, "room", connection.room, "connection for")
    for cluster in spec.clusters:
        for member in cluster.members:
            if member.room not in known:
                yield unknown(E_UNKNOWN_MEMBER, member, "room", member.room, f"cluster `{cluster.id}` has")
    for hint in spec.hints:
        if hint.room not in known:
            yield unknown(E_UNKNOWN_HINTED, hint, "room", hint.room, "hint for")


def check_repeats(spec: Spec) -> Iterator[Diagnostic]:
    """E109-E113: self/duplicate adjacencies, second positions or hints, repeated members."""
    pairs: dict[frozenset[str], Adjacency] = {}
    for adjacency in spec.adjacencies:
        if adjacency.a == adjacency.b:
            yield diag(spec, E_SELF_ADJACENT, f"room `{adjacency.a}` is adjacent to itself",
                        node_span(adjacency, "b"), "same room", "name two different rooms")  # fmt: skip
            continue
        pair = frozenset((adjacency.a, adjacency.b))
        if pair in pairs:
            first = pairs[pair]
            yield diag(spec, E_DUPLICATE_ADJACENCY,
                        f"adjacency between `{adjacency.a}` and `{adjacency.b}` is listed twice",
                        node_span(adjacency), "second listing", "remove one of the two lines",
                        (f"first listed on line {node_span(first).line}",))  # fmt: skip
        else:
            pairs[pair] = adjacency
    for nodes, code, what in ((spec.positions, E_TWO_POSITIONS, "position"), (spec.hints, E_TWO_HINTS, "hint")):
        first_line: dict[str, int] = {}
        for node in nodes:
            if node.room in first_line:
                help_text = ("to make the room cover two points use one `connections` line"
                             if what == "position" else "keep one hint per room")  # fmt: skip
                yield diag(spec, code, f"room `{node.room}` has two {what}s", node_span(node, "room"),
                            f"second {what}", help_text, (f"first {what} on line {first_line[node.room]}",))  # fmt: skip
            else:
                first_line[node.room] = node_span(node).line
    for cluster in spec.clusters:
        if not cluster.members:
            yield diag(spec, W_EMPTY_CLUSTER, f"cluster `{cluster.id}` has no rooms", node_span(cluster, "id"),
                        "empty", "list its rooms as `room x y` lines under the cluster id, or remove it",
                        warning=True)  # fmt: skip
        member_line: dict[str, int] = {}
        for member in cluster.members:
            if member.room in member_line:
                yield diag(spec, E_DUPLICATE_MEMBER,
                            f"room `{member.room}` is listed twice in cluster `{cluster.id}`",
                            node_span(member, "room"), "second listing", "keep one point per room",
                            (f"first listed on line {member_line[member.room]}",))  # fmt: skip
            else:
                member_line[member.room] = node_span(member).line
