"""Planted layouts behind specs/*.lay: each spec is derived from rectangles placed first.

Every spec in specs/ must be feasible, so it is built from a layout that is known to
satisfy it: rooms are placed by hand below (metres, bottom-left corners, 0.2 m walls),
the spec's bounds are derived around the planted sizes, and the planted layout is checked
with the independent verifier (`layoutdsl.layout.verify`) before the spec is written. The
Figure 4.2 school keeps the thesis' numbers; only its placement and adjacencies are ours.

    python bench/planted_specs.py            # verify every planted layout
    python bench/planted_specs.py --write    # and (re)write specs/*.lay
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

from layoutdsl.syntax.ast import (
    Adjacency,
    Arm,
    Boundary,
    Cluster,
    ClusterMember,
    Connection,
    Hint,
    Obstacle,
    Position,
    Room,
    Settings,
    Spec,
)
from layoutdsl.emit.atomic import write_text_atomic
from layoutdsl.check import check_spec
from layoutdsl.syntax.format import format_spec
from layoutdsl.layout import Layout, PlacedObstacle, PlacedRoom, make_portal
from layoutdsl.layout.verify import verify

SPECS = Path(__file__).resolve().parent.parent / "specs"

# (id, type, label, x, y, w, h[, onB])
Planted = tuple


def _derived_room(rid, rtype, label, w, h, on_boundary=False, slack=0.25) -> Room:
    """Bounds ±slack around the planted size; aspect-ratio bounds that include it."""
    ratio = max(w, h) / min(w, h)
    return Room(
        rid,
        round(w * (1 - slack), 2), round(w * (1 + slack), 2), w,
        round(h * (1 - slack), 2), round(h * (1 + slack), 2), h,
        max(1.0, round(ratio * 0.8, 2)), round(ratio * 1.25 + 0.01, 2),
        rtype, label, on_boundary,
        rho_cover=0.5 if rtype == "C" else 1.0,
        rho_error=0.5 if rtype == "C" else 1.0,
    )  # fmt: skip


def _layout(name, width, height, spec: Spec, placed: list[Planted], obstacles=()) -> Layout:
    rooms = {p[0]: PlacedRoom(p[0], p[2], p[1], *p[3:7]) for p in placed}
    portals = tuple(make_portal(rooms[a.a], rooms[a.b], a.kind, a.door) for a in spec.adjacencies)
    return Layout(
        name, width, height, spec.settings.walldim, tuple(rooms.values()), portals,
        tuple(PlacedObstacle(o.id, o.x, o.y, o.w, o.h) for o in obstacles),
    )  # fmt: skip


def _adj(pairs: str, door: float = 0.9) -> tuple[Adjacency, ...]:
    """`R0-C3 R1-C3:i ...` -> adjacencies (kind e unless `:i`)."""
    out = []
    for item in pairs.split():
        pair, _, kind = item.partition(":")
        a, b = pair.split("-")
        out.append(Adjacency(a, b, door, kind or "e"))
    return tuple(out)


# ===== 1. Figure 4.2 school: the thesis' numbers, our placement =====

FIG42_ROOMS = """\
R0 4.68 8.02 6.69 6.21 10.65 8.87 1 1.71 R CLASSROOM
R1 4.68 8.02 6.69 6.21 10.65 8.87 1 1.71 R CLASSROOM
R2 3.42 5.86 4.89 5.62 9.64 8.04 1.25 2.04 R MEDIUM
R3 3.47 5.98 4.97 3.65 6.28 5.23 1 1.43 R MEDIUM
R4 3.51 6.01 5.01 4.95 8.48 7.07 1.03 1.79 R MEDIUM
R5 6.81 11.7 9.74 5.02 8.62 7.18 1 1.74 R CLASSROOM
R6 6.82 11.71 9.76 4.89 8.4 7.0 1.01 1.78 R CLASSROOM
C0 2.97 7.65 5.31 1.66 4.29 2.98 1.14 2.43 C WASHROOM
C1 3.05 7.73 5.39 1.61 4.08 2.84 1.23 2.56 C WASHROOM
R7 1.75 3.01 2.51 1.71 2.93 2.44 1 1.4 R CLOSET
R8 1.84 3.16 2.64 2.97 5.09 4.24 1.22 2.0 R MEDIUM SERVICE
E0 1.26 2.16 1.8 1.67 2.85 2.38 1 1.7 E ELEVATOR
E1 4.74 8.25 6.84 4.26 7.41 6.15 1 1.49 E STAIRS
E2 6.23 10.89 9.03 2.84 4.96 4.11 1.75 2.64 E STAIRS
C2 4.67 11.67 8.17 3.92 9.78 6.85 1 1.8 C CORRIDOR
C3 3.21 7.84 5.53 15.99 39.03 27.51 3.11 6.84 C CORRIDOR
C4 5.0 12.61 8.81 5.14 12.95 9.05 1 1.63 C LOBBY"""

FIG42_PLACED = [
    # the long corridor C3 up the middle, classrooms and medium rooms to its left
    ("C3", "C", "CORRIDOR", 8.0, 10.0, 4.0, 30.0),
    ("R0", "R", "CLASSROOM", 0.8, 10.0, 7.0, 8.0),
    ("R1", "R", "CLASSROOM", 0.8, 18.2, 7.0, 8.0),
    ("R2", "R", "MEDIUM", 2.8, 26.4, 5.0, 7.0),
    ("R3", "R", "MEDIUM", 2.8, 33.6, 5.0, 5.5),
    # service rooms and stairs to its right
    ("E2", "E", "STAIRS", 12.2, 10.0, 9.0, 4.0),
    ("E1", "E", "STAIRS", 12.2, 20.7, 6.0, 5.0),
    ("E0", "E", "ELEVATOR", 12.2, 25.9, 2.0, 2.5),
    ("R8", "R", "MEDIUM SERVICE", 12.2, 28.6, 2.5, 4.0),
    ("R4", "R", "MEDIUM", 12.2, 33.0, 5.0, 7.0),
    # the hall C2 across the top, with two classrooms, washrooms and a closet around it
    ("C2", "C", "CORRIDOR", 5.0, 40.2, 11.0, 5.0),
    ("R5", "R", "CLASSROOM", 2.0, 45.4, 9.0, 6.0),
    ("R6", "R", "CLASSROOM", 11.2, 45.4, 9.0, 6.0),
    ("R7", "R", "CLOSET", 2.3, 41.0, 2.5, 2.5),
    ("C1", "C", "WASHROOM", 16.2, 40.2, 4.5, 2.5),
    ("C0", "C", "WASHROOM", 16.2, 42.9, 4.5, 2.2),
    # the entrance lobby at the bottom
    ("C4", "C", "LOBBY", 4.0, 0.5, 12.0, 9.3),
]
FIG42_ADJ = "R0-C3 R1-C3 R2-C3 R3-C3 R4-C2 R5-C2 R6-C2 C0-C2 C1-C2 R7-C2 C2-C3:i R8-C3 E0-C3 E1-C3 C4-C3:i E2-C4"


def school_fig42() -> tuple[Spec, Layout, str]:
    """The Figure 4.2 school with our placement. Returns (spec, planted layout, header comment)."""
    rooms = []
    for line in FIG42_ROOMS.splitlines():
        parts = line.split()
        rooms.append(Room(parts[0], *map(float, parts[1:9]), parts[9], " ".join(parts[10:])))
    spec = Spec(
        "school_fig42", tuple(rooms), Boundary(21.342857142857145, 51.94285714285714), _adj(FIG42_ADJ),
        # our placement as starting rectangles: without them SCIP alone finds no layout for
        # these 17 rooms within a minute (the thesis' own experience, §5.5.2)
        hints=tuple(Hint(p[0], *p[3:7]) for p in FIG42_PLACED),
    )  # fmt: skip
    header = (
        "# The school of the thesis' Figure 4.2 (§4.1), transcribed.\n"
        "# Room numbers and boundary are the figure's; the OCR of the figure lost some ids, so the\n"
        "# two washrooms are read as C0 (2.97 ...) and C1 (3.05 ...). The figure shows only a few\n"
        "# adjacencies; the rest are ours: a tree around corridor C3 and hall C2. The hints are a\n"
        "# placement that satisfies the spec (bench/planted_specs.py verifies it); they only guide\n"
        "# the solver's first layout.\n"
    )
    return spec, _layout(spec.name, spec.boundary.w, spec.boundary.h, spec, FIG42_PLACED), header


# ===== 2. A small office: ten rooms on one corridor, a tree =====

OFFICE_PLACED = [
    ("C0", "C", "CORRIDOR", 1.0, 6.0, 20.0, 2.0),
    ("R0", "R", "OFFICE", 1.0, 1.0, 3.8, 4.8),
    ("R1", "R", "OFFICE", 5.0, 1.0, 3.8, 4.8),
    ("R2", "R", "OFFICE", 9.0, 1.0, 3.8, 4.8),
    ("R3", "R", "OFFICE", 13.0, 1.0, 3.8, 4.8),
    ("R4", "R", "OFFICE", 17.0, 1.0, 4.0, 4.8),
    ("R5", "R", "MEETING ROOM", 1.0, 8.2, 7.8, 4.8),
    ("R6", "R", "KITCHEN", 9.0, 8.2, 3.8, 4.8),
    ("R7", "R", "TOILETS", 13.0, 8.2, 2.8, 4.8),
    ("E0", "E", "ENTRANCE", 16.0, 8.2, 5.0, 5.8, True),
]
OFFICE_ADJ = "R0-C0 R1-C0 R2-C0 R3-C0 R4-C0 R5-C0 R6-C0 R7-C0 E0-C0:i"


def office_small() -> tuple[Spec, Layout, str]:
    """Ten rooms on one corridor. Returns (spec, planted layout, header comment)."""
    rooms = tuple(_derived_room(p[0], p[1], p[2], p[5], p[6], *p[7:]) for p in OFFICE_PLACED)
    spec = Spec("office_small", rooms, Boundary(22.0, 14.0), _adj(OFFICE_ADJ))
    header = (
        "# A small office: five offices, a meeting room, kitchen, toilets and an entrance on one\n"
        "# corridor. The room graph is a tree (a star around C0). Corridors weigh half in both\n"
        "# objective terms (cover=0.5 error=0.5), as the thesis suggests (§5.5.1).\n"
    )
    return spec, _layout(spec.name, 22.0, 14.0, spec, OFFICE_PLACED), header


# ===== 3. A school with a cycle: four corridors around a courtyard block =====

CYCLE_PLACED = [
    # a pinwheel of corridors: each touches the next at a corner, closing the cycle C0-C1-C2-C3
    ("C0", "C", "CORRIDOR", 3.0, 3.0, 16.0, 2.0),
    ("C1", "C", "CORRIDOR", 19.2, 3.0, 2.0, 16.0),
    ("C2", "C", "CORRIDOR", 5.2, 19.2, 16.0, 2.0),
    ("C3", "C", "CORRIDOR", 3.0, 5.2, 2.0, 16.0),
    # four classrooms inside the ring, each on one corridor
    ("R0", "R", "CLASSROOM", 5.2, 5.2, 6.8, 6.8),
    ("R1", "R", "CLASSROOM", 12.2, 5.2, 6.8, 6.8),
    ("R2", "R", "CLASSROOM", 5.2, 12.2, 6.8, 6.8),
    ("R3", "R", "CLASSROOM", 12.2, 12.2, 6.8, 6.8),
    # outside the ring
    ("E0", "E", "ENTRANCE", 8.0, 0.0, 7.0, 2.8, True),
    ("R4", "R", "TOILETS", 21.4, 7.0, 2.6, 8.0),
    ("R5", "R", "STAFF ROOM", 0.0, 8.0, 2.8, 8.0),
    ("R6", "R", "LIBRARY", 7.0, 21.4, 10.0, 3.6),
]
CYCLE_ADJ = "C0-C1:i C1-C2:i C2-C3:i C3-C0:i R0-C0 R1-C1 R3-C2 R2-C3 E0-C0:i R4-C1 R5-C3 R6-C2"


def school_cycle() -> tuple[Spec, Layout, str]:
    """Four corridors in a ring around four classrooms. Returns (spec, planted layout, header comment)."""
    rooms = tuple(_derived_room(p[0], p[1], p[2], p[5], p[6], *p[7:]) for p in CYCLE_PLACED)
    spec = Spec("school_cycle", rooms, Boundary(24.5, 25.5), _adj(CYCLE_ADJ))
    header = (
        "# A school whose corridors form a cycle: C0-C1-C2-C3 run around a block of four\n"
        "# classrooms (the thesis' hard case, §5.5.3), with an entrance, toilets, a staff room\n"
        "# and a library outside the ring.\n"
    )
    return spec, _layout(spec.name, 24.5, 25.5, spec, CYCLE_PLACED), header


# ===== 4. A campus block using every optional constraint =====

CAMPUS_PLACED = [
    ("C0", "C", "CORRIDOR", 0.5, 7.0, 23.0, 2.2),
    ("E0", "E", "ENTRANCE", 0.0, 0.0, 4.5, 6.8, True),
    ("R0", "R", "LECTURE HALL", 4.7, 0.5, 9.0, 6.3),
    ("R1", "R", "LAB", 13.9, 0.5, 5.0, 6.3),
    ("R2", "R", "LAB", 19.1, 0.5, 4.4, 6.3),
    ("R3", "R", "SEMINAR", 0.5, 9.4, 6.0, 5.0),
    ("R4", "R", "SEMINAR", 6.7, 9.4, 6.0, 5.0),
    ("R5", "R", "OFFICE", 12.9, 9.4, 3.5, 5.0),
    ("E1", "E", "STAIRS", 19.0, 9.4, 4.5, 5.0),
]
CAMPUS_OBSTACLES = (Obstacle("O1", 16.8, 10.0, 1.6, 1.6),)  # a structural column block
CAMPUS_ADJ = "E0-C0:i R0-C0 R1-C0 R2-C0 R3-C0 R4-C0 R5-C0 E1-C0:i R1-R2"


def campus_constraints() -> tuple[Spec, Layout, str]:
    """Every optional constraint on one small block. Returns (spec, planted layout, header comment)."""
    rooms = tuple(_derived_room(p[0], p[1], p[2], p[5], p[6], *p[7:]) for p in CAMPUS_PLACED)
    spec = Spec(
        "campus_constraints", rooms, Boundary(24.0, 17.0, CAMPUS_OBSTACLES), _adj(CAMPUS_ADJ),
        positions=(Position("R0", 9.0, 3.0), Position("E1", 22.0, 12.0)),
        connections=(Connection("C0", 2.0, 8.0, 22.0, 8.0),),
        # the planted rectangles themselves, as starting points for the solver
        hints=tuple(Hint(p[0], *p[3:7]) for p in CAMPUS_PLACED),
        clusters=(
            # the two labs stay side by side (centre points in the cluster's own frame)
            Cluster("LABS", (ClusterMember("R1", 0.0, 0.0), ClusterMember("R2", 5.0, 0.0))),
        ),
        settings=Settings(
            lambda_cover=0.15, walldim=0.2, door_utilization=0.9, cluster_margin=0.6,
            time_limit=30.0, seed=7,
            explicit=frozenset({"lambda_cover", "walldim", "door_utilization", "cluster_margin", "time_limit", "seed"}),
        ),
    )  # fmt: skip
    header = (
        "# A campus block that uses every optional constraint of the language: an obstacle\n"
        "# (a column block), fixed positions, a connection that makes the corridor span the\n"
        "# building, a cluster keeping the two labs side by side, an entrance on the boundary\n"
        "# (onB), hints (the rectangles this spec was derived from) and a settings section.\n"
    )
    return spec, _layout(spec.name, 24.0, 17.0, spec, CAMPUS_PLACED, CAMPUS_OBSTACLES), header


# ===== 5. An L-shaped corridor wrapping two offices (issue 14) =====

L_ROOMS = """\
C0 11 14 12 1.5 2.2 1.8 1 20 C CORRIDOR
R0 3.5 5 4.5 3.5 5 4.5 1 1.4 R OFFICE
R1 3.5 5 4.5 3.5 5 4.5 1 1.4 R OFFICE
E0 2 3 2.5 2 3 2.5 1 1.5 E ENTRANCE"""
L_ARM = Arm("C0", 1.5, 2.2, 1.8, 6, 9, 8, 1, 20)
L_PLACED = [
    # the corridor's long arm along the bottom, its second arm up the left side
    ("C0", "C", "CORRIDOR", 0.0, 0.0, 12.0, 1.8),
    # one office beside the second arm, one above the long arm: the L wraps both
    ("R0", "R", "OFFICE", 2.0, 6.7, 4.5, 3.8),
    ("R1", "R", "OFFICE", 5.3, 2.0, 4.5, 4.5),
    ("E0", "E", "ENTRANCE", 10.0, 2.0, 2.5, 2.5),
]
L_ARM_PLACED = (0.0, 1.8, 1.8, 8.0)
L_ADJ = "R0-C0 R1-C0 E0-C0:i R0-R1"


def l_corridor() -> tuple[Spec, Layout, str]:
    """An L-shaped corridor around two offices. Returns (spec, planted layout, header comment)."""
    rooms = []
    for line in L_ROOMS.splitlines():
        parts = line.split()
        rooms.append(Room(parts[0], *map(float, parts[1:9]), parts[9], " ".join(parts[10:])))
    rooms[0] = replace(rooms[0], rho_cover=0.5, rho_error=0.5)
    rooms[3] = replace(rooms[3], on_boundary=True)
    spec = Spec(
        "l_corridor", tuple(rooms), Boundary(12.5, 10.5), _adj(L_ADJ), arms=(L_ARM,),
    )  # fmt: skip
    layout = _layout(spec.name, 12.5, 10.5, spec, L_PLACED)
    corridor = replace(layout.room("C0"), arm=L_ARM_PLACED)
    placed = tuple(corridor if room.id == "C0" else room for room in layout.rooms)
    portals = tuple(make_portal(*(next(r for r in placed if r.id == i) for i in (a.a, a.b)), a.kind, a.door)
                    for a in spec.adjacencies)
    header = (
        "# An L-shaped corridor wrapping two rooms (issue 14). C0 is an L: its line in `rooms` is\n"
        "# the long arm, its line in `arms` the second arm, joined flush at a corner with no wall\n"
        "# between them; the arm line is tall where the room line is wide, so the arm runs\n"
        "# across the long arm, as in a corridor turning a corner. The two offices sit in the\n"
        "# L's inner corner (in the planted layout, bench/planted_specs.py, each has its door\n"
        "# on a different arm) and the entrance opens onto the corridor from the boundary.\n"
    )
    return spec, replace(layout, rooms=placed, portals=portals), header


BUILDERS = {
    "school_fig42": school_fig42,
    "office_small": office_small,
    "school_cycle": school_cycle,
    "campus_constraints": campus_constraints,
    "l_corridor": l_corridor,
}


def main(argv: list[str] | None = None) -> int:
    """Verify every planted layout against its spec; with --write, write specs/*.lay."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="write specs/*.lay")
    args = parser.parse_args(argv)
    failed = False
    for name, builder in BUILDERS.items():
        spec, layout, header = builder()
        spec = replace(spec, path=str(SPECS / f"{name}.lay"))
        problems = [d for d in check_spec(spec)]
        violations = verify(spec, layout)
        rooms_area = sum(r.target_w * r.target_h for r in (*spec.rooms, *spec.arms))
        ratio = spec.boundary.w * spec.boundary.h / rooms_area
        print(f"{name:20} rooms {len(spec.rooms):3}  adjacencies {len(spec.adjacencies):3}  "
              f"boundary/target area {ratio:.2f}  lint {len(problems)}  violations {len(violations)}")  # fmt: skip
        for item in [*problems, *violations]:
            print("   ", getattr(item, "code", getattr(item, "rule", "")), item.message)
        failed |= bool(problems or violations)
        if args.write and not problems and not violations:
            write_text_atomic(SPECS / f"{name}.lay", header + "\n" + format_spec(spec))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
