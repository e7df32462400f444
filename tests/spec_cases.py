"""Small specs, one per constraint family of §5.5.1, whose optimum breaks that family if the
family's block is dropped. Each case names the block and an independent geometric check."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from layoutdsl.syntax.ast import Adjacency, Boundary, Cluster, ClusterMember, Connection, Obstacle, Position, Room, Settings, Spec

Rect = tuple[float, float, float, float]


def room(rid: str, w: tuple[float, float, float], h: tuple[float, float, float], *, ar=(1.0, 4.0),
         rtype: str = "R", on_boundary: bool = False, rho_cover: float = 1.0, rho_error: float = 1.0) -> Room:
    """A room from (min, max, target) per side."""
    return Room(rid, w[0], w[1], w[2], h[0], h[1], h[2], ar[0], ar[1], rtype, rid,
                on_boundary=on_boundary, rho_cover=rho_cover, rho_error=rho_error)


def spec(name: str, rooms, width: float, height: float, *, obstacles=(), adjacencies=(), positions=(),
         connections=(), clusters=(), **settings) -> Spec:
    return Spec(name, tuple(rooms), Boundary(width, height, tuple(obstacles)), tuple(adjacencies),
                tuple(positions), tuple(connections), tuple(clusters), settings=Settings(**settings))


def separation(a: Rect, b: Rect) -> float:
    """The larger of the x and y gaps between two rectangles (negative: they overlap)."""
    gap_x = max(b[0] - (a[0] + a[2]), a[0] - (b[0] + b[2]))
    gap_y = max(b[1] - (a[1] + a[3]), a[1] - (b[1] + b[3]))
    return max(gap_x, gap_y)


def covers(r: Rect, x: float, y: float, tol: float = 1e-6) -> bool:
    return r[0] - tol <= x <= r[0] + r[2] + tol and r[1] - tol <= y <= r[1] + r[3] + tol


# Five rooms around a corridor; small enough to solve to a 1 % gap in about a second.
FIVE = spec(
    "five",
    [room("A", (3.2, 4.8, 4), (2.4, 3.6, 3)), room("B", (2.4, 3.6, 3), (2.4, 3.6, 3)),
     room("C", (6.4, 9.6, 8), (1.6, 2.4, 2), ar=(1, 6), rtype="C"),
     room("D", (2.4, 3.6, 3), (3.2, 4.8, 4), on_boundary=True), room("E", (2.4, 3.6, 3), (2.4, 3.6, 3))],
    15, 10,
    adjacencies=[Adjacency("A", "C", 0.9, "e"), Adjacency("B", "C", 0.9, "e"), Adjacency("D", "C", 0.9, "i"),
                 Adjacency("A", "B", 0.9, "e"), Adjacency("E", "C", 0.9, "e")],
)

# A feasible geometry for FIVE: C across the middle, A, B above it, D, E below.
FIVE_RECTS = {
    "C": (1.0, 4.0, 8.0, 2.0),
    "A": (1.0, 6.2, 4.0, 3.0),
    "B": (5.2, 6.2, 3.0, 3.0),
    "D": (1.0, 0.0, 3.0, 3.8),
    "E": (4.2, 0.8, 3.0, 3.0),
}



@dataclass(frozen=True)
class Case:
    """A spec, the block whose constraint it exercises, and that constraint checked on the rects."""

    name: str
    block: str
    spec: Spec
    holds: Callable[[dict[str, Rect]], bool]
    why: str


TOL = 1e-5


def _shared_along(a: Rect, b: Rect) -> tuple[float, float]:
    """(gap across the facing wall, length the interiors face each other)."""
    gap_x = max(b[0] - (a[0] + a[2]), a[0] - (b[0] + b[2]))
    gap_y = max(b[1] - (a[1] + a[3]), a[1] - (b[1] + b[3]))
    if gap_x >= gap_y:
        return gap_x, min(a[1] + a[3], b[1] + b[3]) - max(a[1], b[1])
    return gap_y, min(a[0] + a[2], b[0] + b[2]) - max(a[0], b[0])


def _cluster_ok(rects: dict[str, Rect], members: dict[str, tuple[float, float]], margin: float) -> bool:
    lo_x = max(rects[r][0] - margin - p[0] for r, p in members.items())
    hi_x = min(rects[r][0] + rects[r][2] + margin - p[0] for r, p in members.items())
    lo_y = max(rects[r][1] - margin - p[1] for r, p in members.items())
    hi_y = min(rects[r][1] + rects[r][3] + margin - p[1] for r, p in members.items())
    return lo_x <= hi_x + TOL and lo_y <= hi_y + TOL


CASES = [
    Case(
        "min_size", "eq5_4_min_size",
        # A and B compete for 10.4 m of width (too low to stack); B's size error weighs 10x,
        # so without (5.4) A would shrink far below its 5 m minimum to let B reach 9 m.
        spec("min_size", [room("A", (5, 7, 6), (3, 4, 3.5)),
                          room("B", (5, 9, 9), (3, 4, 3.5), rho_error=10)], 10.4, 4.0, lambda_cover=0.0),
        lambda r: min(r["A"][2], r["A"][3]) >= 3 - TOL and max(r["A"][2], r["A"][3]) >= 5 - TOL,
        "A keeps its 5 m minimum on the long side",
    ),
    Case(
        "max_size", "eq5_5_max_size",
        # a strong cover weight pulls the room to fill the 10 x 10 boundary; its sides may
        # reach 6 m, but only one of them (the short side stays within 4 m)
        spec("max_size", [room("A", (2, 4, 4), (2, 6, 6), ar=(1, 2))], 10, 10, lambda_cover=10.0),
        lambda r: min(r["A"][2], r["A"][3]) <= 4 + TOL and max(r["A"][2], r["A"][3]) <= 6 + TOL,
        "A stays within 4 x 6",
    ),
    Case(
        "aspect_ratio", "eq5_6_aspect_ratio",
        # filling the 10 x 4 boundary needs aspect ratio 2.5; the room allows 1.5 at most
        spec("aspect_ratio", [room("A", (2, 10, 5), (2, 10, 4), ar=(1, 1.5)),
                              room("K", (2, 10, 5), (2, 10, 4), ar=(1, 1.5), rtype="C")],
             10, 8.2, lambda_cover=10.0),
        lambda r: max(r["A"][2], r["A"][3]) <= 1.5 * min(r["A"][2], r["A"][3]) + TOL,
        "A's long side is at most 1.5 times its short side",
    ),
    Case(
        "inside", "eq5_7_inside",
        # two 6 m rooms side by side need 12.2 m; the boundary has 10
        spec("inside", [room("A", (3, 7, 6), (3, 4, 3.5), rho_error=10),
                        room("B", (3, 7, 6), (3, 4, 3.5), rho_error=10)], 10, 4, lambda_cover=0.0),
        lambda r: all(x >= -TOL and y >= -TOL and x + w <= 10 + TOL and y + h <= 4 + TOL for x, y, w, h in r.values()),
        "every room inside 10 x 4",
    ),
    Case(
        "non_overlap", "eq5_8_non_overlap",
        # both rooms want to fill the whole boundary
        spec("non_overlap", [room("A", (2, 8, 6), (2, 8, 6)), room("B", (2, 8, 6), (2, 8, 6))],
             8, 8, lambda_cover=5.0),
        lambda r: separation(r["A"], r["B"]) >= 0.2 - TOL,
        "A and B are at least one wall (0.2 m) apart",
    ),
    Case(
        "obstacle", "eq5_8_non_overlap",
        # a column in the middle of the only room's space
        spec("obstacle", [room("A", (2, 10, 8), (2, 10, 8), ar=(1, 3))], 10, 10,
             obstacles=[Obstacle("P", 4, 4, 1, 1)], lambda_cover=5.0),
        lambda r: separation(r["A"], (4, 4, 1, 1)) >= 0.2 - TOL,
        "A keeps a wall's thickness from the obstacle",
    ),
    Case(
        "adjacency", "eq5_9_adjacency",
        # A and B sit in opposite corners; the adjacency makes them reach each other with
        # door / door_utilization = 1.8 m of shared wall, exactly one wall apart
        spec("adjacency", [room("A", (2, 6, 3), (2, 6, 3)), room("B", (2, 6, 3), (2, 6, 3))], 10, 10,
             adjacencies=[Adjacency("A", "B", 0.9, "e")],
             positions=[Position("A", 1, 1), Position("B", 9, 9)], door_utilization=0.5),
        lambda r: abs(_shared_along(r["A"], r["B"])[0] - 0.2) <= TOL and _shared_along(r["A"], r["B"])[1] >= 1.8 - TOL,
        "A and B face each other across exactly 0.2 m along at least 1.8 m",
    ),
    Case(
        "position", "eq5_10_position",
        spec("position", [room("A", (2, 4, 3), (2, 4, 3))], 10, 10, positions=[Position("A", 8.5, 8.5)]),
        lambda r: covers(r["A"], 8.5, 8.5),
        "A covers (8.5, 8.5)",
    ),
    Case(
        "connection", "eq5_11_connection",
        # covering both points needs a room 7 m wide
        spec("connection", [room("A", (2, 9, 3), (2, 9, 3))], 10, 10,
             connections=[Connection("A", 1, 1, 8, 2)]),
        lambda r: covers(r["A"], 1, 1) and covers(r["A"], 8, 2),
        "A covers (1, 1) and (8, 2)",
    ),
    Case(
        "on_boundary", "eq5_12_on_boundary",
        # A must cover the centre and still touch a side of the boundary
        spec("on_boundary", [room("A", (2, 6, 3), (2, 6, 3), on_boundary=True)], 10, 10,
             positions=[Position("A", 5, 5)]),
        lambda r: min(r["A"][0], r["A"][1], 10 - r["A"][0] - r["A"][2], 10 - r["A"][1] - r["A"][3]) <= TOL,
        "A touches a side of the boundary",
    ),
    Case(
        "cluster", "eq5_13_cluster",
        # the cluster keeps A and B 7 m apart along x, within the 0.5 m margin
        spec("cluster", [room("A", (2, 4, 3), (2, 4, 3)), room("B", (2, 4, 3), (2, 4, 3))], 12, 12,
             clusters=[Cluster("K", (ClusterMember("A", 0, 0), ClusterMember("B", 7, 0)))]),
        lambda r: _cluster_ok(r, {"A": (0, 0), "B": (7, 0)}, 0.5),
        "one cluster offset keeps A and B within 0.5 m of their cluster points",
    ),
]


SMALL_LAY = """\
rooms
A 3.2 4.8 4 2.4 3.6 3 1 3 R OFFICE
B 2.4 3.6 3 2.4 3.6 3 1 3 R OFFICE
C 6.4 9.6 8 1.6 2.4 2 1 6 C CORRIDOR onB

boundary
14 10

adjacencies
A C 0.9 e
B C 0.9 e
A B 0.9 e

settings
time_limit 20
gap 0.02
"""
"""Three rooms around a corridor, as a spec file: small enough to compile in seconds."""
