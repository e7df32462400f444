"""Layouts and checks shared by the emitter tests (no solver involved)."""

from __future__ import annotations

from collections import deque
from pathlib import Path

import numpy as np

from layoutdsl.layout import Layout, PlacedObstacle, PlacedRoom, make_portal
from layoutdsl.emit.raster import OccupancyGrid, rasterize_layout, room_cell_labels

HERE = Path(__file__).parent
CASES = sorted(path.parent for path in HERE.glob("*/layout.json"))
"""Golden cases: every folder of tests/emit holding a layout.json."""

LABELS = ("CLASSROOM", "OFFICE", "WC", "MEDIUM SERVICE", "LAB", "STORAGE", "TEACHERS ROOM")


def load_case(case: Path) -> Layout:
    return Layout.from_json((case / "layout.json").read_text())


def school_layout(bands: int = 5, per_row: int = 10, walldim: float = 0.2, name: str = "synthetic school") -> Layout:
    """A school of `bands` corridors with a row of rooms on each side and a spine corridor.

    Rooms also touch their row neighbours and the spine without a portal everywhere, so
    the topology check sees closed walls as well as open doors. 5 × 10 gives 106 rooms.
    """
    room_w, room_h, corridor_h, spine_w = 3.6, 4.0, 2.0, 2.0
    band_h = 2 * room_h + corridor_h + 3 * walldim
    row_x0 = spine_w + walldim
    height = bands * band_h - walldim
    width = row_x0 + per_row * (room_w + walldim) - walldim
    spine = PlacedRoom("C0", "CORRIDOR", "C", 0.0, 0.0, spine_w, height)
    rooms = [spine]
    portals = []
    counter = {"R": 0, "C": 1, "E": 0}

    def new_id(rtype: str) -> str:
        counter[rtype] += 1
        return f"{rtype}{counter[rtype] - 1}"

    for band in range(bands):
        y0 = band * band_h
        corridor = PlacedRoom(new_id("C"), "CORRIDOR", "C", row_x0, y0 + room_h + walldim, per_row * (room_w + walldim) - walldim, corridor_h)
        rooms.append(corridor)
        portals.append(make_portal(spine, corridor, "i" if band % 2 else "e", 1.2))
        for side, y in (("below", y0), ("above", y0 + room_h + corridor_h + 2 * walldim)):
            previous = None
            for index in range(per_row):
                rtype = "E" if (band, side, index) == (0, "below", 0) else "R"
                label = "ENTRANCE" if rtype == "E" else LABELS[(band * 7 + index + (side == "above") * 3) % len(LABELS)]
                room = PlacedRoom(new_id(rtype), label, rtype, row_x0 + index * (room_w + walldim), y, room_w, room_h)
                rooms.append(room)
                portals.append(make_portal(corridor, room, "e", 0.9))
                if previous is not None and index % 3 == 1:
                    portals.append(make_portal(previous, room, "e" if index % 2 else "i", 0.9))
                previous = room
    return Layout(name, width, height, walldim, tuple(rooms), tuple(portals))


def pair_room() -> Layout:
    """Two rooms side by side with one door."""
    a = PlacedRoom("R0", "OFFICE", "R", 0.0, 0.0, 3.0, 3.0)
    b = PlacedRoom("R1", "OFFICE", "R", 3.2, 0.0, 3.0, 3.0)
    return Layout("pair", 6.2, 3.0, 0.2, (a, b), (make_portal(a, b, "e", 0.9),))


def with_obstacle(layout: Layout) -> Layout:
    return Layout(layout.name, layout.width, layout.height, layout.walldim, layout.rooms, layout.portals, (PlacedObstacle("O0", 1.0, 1.0, 0.5, 0.5),))


def region_meetings(layout: Layout, grid: OccupancyGrid) -> set[frozenset[str]]:
    """Room pairs whose free regions meet, by flood fill from each room's centre.

    The fill runs over free cells (4-connected). A fill that reaches a cell inside another
    room's interior records a meeting and goes no further there, so meetings are direct:
    a fill never passes through a third room.
    """
    labels, origin = room_cell_labels(layout, grid.resolution)
    assert labels.shape == grid.occupied.shape and origin == grid.origin
    free = ~grid.occupied
    rows, cols = free.shape
    meetings: set[frozenset[str]] = set()
    for index, room in enumerate(layout.rooms):
        start = grid.world_to_cell(*room.centre)
        assert grid.contains(*start) and free[start], f"centre of {room.id} is not free"
        seen = np.zeros_like(free)
        seen[start] = True
        queue = deque([start])
        while queue:
            row, col = queue.popleft()
            label = labels[row, col]
            if label >= 0 and label != index:
                meetings.add(frozenset((room.id, layout.rooms[label].id)))
                continue
            for r, c in ((row + 1, col), (row - 1, col), (row, col + 1), (row, col - 1)):
                if 0 <= r < rows and 0 <= c < cols and free[r, c] and not seen[r, c]:
                    seen[r, c] = True
                    queue.append((r, c))
    return meetings


def portal_pairs(layout: Layout) -> set[frozenset[str]]:
    return {frozenset((p.a, p.b)) for p in layout.portals}


def assert_topology_matches(layout: Layout, resolution: float = 0.05) -> None:
    """Doors really open and every other wall is closed in the shared rasterization."""
    grid = rasterize_layout(layout, resolution)
    met = region_meetings(layout, grid)
    expected = portal_pairs(layout)
    assert met == expected, (
        f"regions meet without a portal: {sorted(map(sorted, met - expected))}; "
        f"portals that do not open: {sorted(map(sorted, expected - met))}"
    )


ROOT = HERE.parents[1]
SPEC_FILES = sorted((ROOT / "specs").glob("*.lay"))


def planted_layouts() -> dict[str, Layout]:
    """The verified planted layout behind each spec in specs/ (bench/planted_specs.py).

    These are layouts of exactly the specs users compile, available without a solver; a
    compiled layout of the same spec goes through the same emitters and rasterizer.
    """
    import importlib.util

    module_spec = importlib.util.spec_from_file_location("planted_specs", ROOT / "bench" / "planted_specs.py")
    planted = importlib.util.module_from_spec(module_spec)
    module_spec.loader.exec_module(planted)
    return {name: builder()[1] for name, builder in planted.BUILDERS.items()}


def spec_adjacency(path: Path) -> tuple[dict[frozenset[str], str], dict[str, tuple[str, str]]]:
    """A spec file's adjacency graph (pair -> 'e'/'i') and room id -> (type, label)."""
    from layoutdsl.api import load_spec

    spec, diagnostics = load_spec(str(path))
    assert spec is not None, [d.message for d in diagnostics]
    edges = {frozenset((a.a, a.b)): a.kind for a in spec.adjacencies}
    rooms = {room.id: (room.rtype, room.label) for room in spec.rooms}
    return edges, rooms
