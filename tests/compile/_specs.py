"""Small synthetic specs for the generator tests (feasible by construction)."""

from __future__ import annotations

from layoutdsl.syntax.ast import Adjacency, Boundary, Room, Spec


def room(room_id: str, w: float, h: float, *, rtype: str = "R", var: float = 0.3,
         on_boundary: bool = False) -> Room:
    """A room of target w x h whose sides may vary by `var` (a fraction) either way."""
    long, short = max(w, h), min(w, h)
    return Room(
        id=room_id,
        min_w=w * (1 - var),
        max_w=w * (1 + var),
        target_w=w,
        min_h=h * (1 - var),
        max_h=h * (1 + var),
        target_h=h,
        min_ar=1.0,
        max_ar=max(1.5, 1.6 * long / short),
        rtype=rtype,
        label="CORRIDOR" if rtype == "C" else "ROOM",
        on_boundary=on_boundary,
    )


def adjacent(a: str, b: str, door: float = 0.9, kind: str = "e") -> Adjacency:
    return Adjacency(a, b, door, kind)


def tree_spec() -> Spec:
    """A corridor with six rooms hung on it and a second corridor with two more (a tree)."""
    rooms = [room("C0", 14.0, 2.0, rtype="C", var=0.4), room("C1", 2.0, 8.0, rtype="C", var=0.4)]
    rooms += [room(f"R{i}", 4.0, 3.5) for i in range(8)]
    adjacencies = [adjacent("C0", f"R{i}") for i in range(6)]
    adjacencies += [adjacent("C0", "C1", kind="i"), adjacent("C1", "R6"), adjacent("C1", "R7")]
    return Spec("tree", tuple(rooms), Boundary(24.0, 18.0), tuple(adjacencies))


def cycle_spec() -> Spec:
    """Five rooms in a ring plus two rooms hanging off it: one independent cycle."""
    ring = ["A", "B", "C", "D", "E"]
    rooms = [room(name, 4.0, 4.0) for name in ring] + [room("F", 3.0, 3.0), room("G", 3.0, 3.0)]
    adjacencies = [adjacent(a, b) for a, b in zip(ring, ring[1:] + ring[:1])]
    adjacencies += [adjacent("A", "F"), adjacent("C", "G")]
    return Spec("ring", tuple(rooms), Boundary(20.0, 20.0), tuple(adjacencies))


def ladder_spec() -> Spec:
    """Two long corridors joined by three short ones (a ladder: two independent cycles),
    with an office on each rung."""
    rooms = [room("A", 20.0, 2.0, rtype="C", var=0.4), room("B", 20.0, 2.0, rtype="C", var=0.4)]
    rooms += [room(f"K{i}", 2.0, 8.0 + i, rtype="C", var=0.4) for i in range(3)]
    rooms += [room(f"R{i}", 4.0, 3.5) for i in range(3)]
    adjacencies = [adjacent(rail, f"K{i}", kind="i") for rail in "AB" for i in range(3)]
    adjacencies += [adjacent(f"K{i}", f"R{i}") for i in range(3)]
    return Spec("ladder", tuple(rooms), Boundary(30.0, 30.0), tuple(adjacencies))


def ring_block_spec() -> Spec:
    """A ring of twelve rooms, a triangle of rooms beside it
    (a small block), rooms hanging off both (H3 on the boundary), and a room with no door."""
    ring = [f"K{i}" for i in range(12)]
    rooms = [room(name, 4.0, 4.0) for name in ring]
    rooms += [room(name, 3.0, 3.0) for name in ("T1", "T2", "H1", "H2", "LONE")]
    rooms.append(room("H3", 3.0, 3.0, on_boundary=True))
    adjacencies = [adjacent(a, b) for a, b in zip(ring, ring[1:] + ring[:1])]
    adjacencies += [adjacent("K0", "T1"), adjacent("T1", "T2"), adjacent("T2", "K0"),
                    adjacent("K5", "H1"), adjacent("H1", "H2"), adjacent("T2", "H3")]
    return Spec("ring-block", tuple(rooms), Boundary(40.0, 40.0), tuple(adjacencies))
