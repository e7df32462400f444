"""The building XML: well-formed, read back by the project's own reader, same graph as the layout."""

from __future__ import annotations

import math
from collections import deque
from pathlib import Path

import pytest
from _emit_support import CASES, SPEC_FILES, load_case, planted_layouts, school_layout, spec_adjacency
from defusedxml import ElementTree

from layoutdsl.emit import write_outputs
from layoutdsl.emit.xml import render_xml
from layoutdsl.importer import read_building
from layoutdsl.layout import Layout
from layoutdsl.emit.raster import rasterize_building

LAYOUTS = {**{case.name: (lambda case=case: load_case(case)) for case in CASES}, "school": lambda: school_layout(2, 4)}
TYPE = {"e": "EXPLICIT", "i": "IMPLICIT"}


@pytest.fixture(params=sorted(LAYOUTS))
def layout(request: pytest.FixtureRequest) -> Layout:
    return LAYOUTS[request.param]()


def _written(layout: Layout, tmp_path: Path) -> Path:
    (path,) = write_outputs(layout, tmp_path, "plan", ["xml"])
    return path


def test_xml_is_well_formed_with_the_real_plans_structure(layout: Layout, tmp_path: Path) -> None:
    root = ElementTree.parse(_written(layout, tmp_path)).getroot()
    assert root.tag == "building" and root.get("id")
    assert root.findtext("scale/represented_distance/value") == "90"
    assert root.findtext("scale/represented_distance/um") == "pixel"
    assert root.findtext("scale/real_distance/value") == "90"
    assert root.findtext("scale/real_distance/um") == "cm"
    spaces = root.findall("floor/spaces/space")
    assert [s.get("id") for s in spaces] == [r.id for r in layout.rooms]  # space ids = room ids (§5.7)
    for space, room in zip(spaces, layout.rooms, strict=True):
        assert space.findtext("labels/type") == room.rtype and space.findtext("labels/label") == room.label
        for tag in ("maxx", "maxy", "minx", "miny"):
            assert space.find(f"bounding_box/{tag}/point") is not None
        ids = [seg.get("id") for seg in space.findall("space_representation/linesegment")]
        assert len(ids) == len(set(ids))
        for portal in space.findall("portals/portal"):
            assert portal.findtext("linesegment") in ids
            assert portal.findtext("class") == "HORIZONTAL" and portal.findtext("direction") == "BOTH"
            assert len(portal.findall("target/id")) == 2


def test_own_reader_reads_it_back_with_the_same_rooms_and_geometry(layout: Layout, tmp_path: Path) -> None:
    building, diagnostics = read_building(_written(layout, tmp_path))
    assert building is not None, [d.message for d in diagnostics]
    assert [d for d in diagnostics if d.severity.name == "ERROR"] == []
    assert building.metres_per_unit == pytest.approx(0.01)
    assert [(s.id, s.rtype, s.label) for s in building.spaces] == [(r.id, r.rtype, r.label) for r in layout.rooms]
    for space, room in zip(building.spaces, layout.rooms, strict=True):
        s = building.metres_per_unit
        # y grows downwards in the file: y_file = (height − y) / s
        assert space.bbox.min_x * s == pytest.approx(room.x, abs=1e-3)
        assert space.bbox.max_x * s == pytest.approx(room.x2, abs=1e-3)
        assert space.bbox.min_y * s == pytest.approx(layout.height - room.y2, abs=1e-3)
        assert space.bbox.max_y * s == pytest.approx(layout.height - room.y, abs=1e-3)
        assert space.centroid is not None
        assert (space.centroid.x * s, layout.height - space.centroid.y * s) == pytest.approx(room.centre, abs=1e-3)


def test_portal_graph_is_the_layouts_with_the_same_types(layout: Layout, tmp_path: Path) -> None:
    building, _ = read_building(_written(layout, tmp_path))
    assert building is not None
    expected = {frozenset((p.a, p.b)): TYPE[p.kind] for p in layout.portals}
    assert building.portal_edges() == expected
    for space in building.spaces:
        for portal in space.portals:
            assert space.id in portal.targets  # a space lists only its own doors
            segment = portal.segment
            assert segment is not None and segment.cls == "PORTAL" and segment.type == portal.type
            # the PORTAL segment is the door: as long as the adjacency's door
            (door,) = [p for p in layout.portals if {p.a, p.b} == set(portal.targets)]
            length_m = math.dist((segment.p1.x, segment.p1.y), (segment.p2.x, segment.p2.y)) * building.metres_per_unit
            assert length_m == pytest.approx(door.width, abs=2e-3)


def test_each_room_is_closed_by_its_wall_and_portal_segments(layout: Layout, tmp_path: Path) -> None:
    building, _ = read_building(_written(layout, tmp_path))
    assert building is not None
    for space, room in zip(building.spaces, layout.rooms, strict=True):
        segments = space.segments
        for first, second in zip(segments, segments[1:] + segments[:1]):
            assert (first.p2.x, first.p2.y) == (second.p1.x, second.p1.y)  # a closed chain
        perimeter = sum(math.dist((g.p1.x, g.p1.y), (g.p2.x, g.p2.y)) for g in segments) / 100
        assert perimeter == pytest.approx(2 * (room.w + room.h), abs=1e-2)


@pytest.mark.parametrize("name", ["small_office", "school"])
def test_written_xml_rasterizes_to_the_same_room_graph(name: str, tmp_path: Path) -> None:
    """The evaluator rasterizes our XML like a real plan: doors open, other walls closed."""
    layout = LAYOUTS[name]()
    building, _ = read_building(_written(layout, tmp_path))
    assert building is not None
    grid = rasterize_building(building)
    s = building.metres_per_unit
    # which space's rectangle holds a point (frame: x = x_file·s, y = −y_file·s)
    boxes = {sp.id: (sp.bbox.min_x * s, -sp.bbox.max_y * s, sp.bbox.max_x * s, -sp.bbox.min_y * s) for sp in building.spaces}

    def space_at(point: tuple[float, float]) -> str | None:
        for sid, (x0, y0, x1, y1) in boxes.items():
            if x0 < point[0] < x1 and y0 < point[1] < y1:
                return sid
        return None

    met = set()
    for space in building.spaces:
        start = grid.world_to_cell(space.centroid.x * s, -space.centroid.y * s)
        free = ~grid.occupied
        assert free[start]
        seen, queue = {start}, deque([start])
        while queue:
            cell = queue.popleft()
            owner = space_at(grid.cell_to_world(*cell))
            if owner is not None and owner != space.id:
                met.add(frozenset((space.id, owner)))
                continue
            r, c = cell
            for nxt in ((r + 1, c), (r - 1, c), (r, c + 1), (r, c - 1)):
                if grid.contains(*nxt) and free[nxt] and nxt not in seen:
                    seen.add(nxt)
                    queue.append(nxt)
    assert met == set(building.portal_edges())


def test_ids_are_deterministic_and_text_is_escaped() -> None:
    layout = load_case(Path(__file__).parent / "single_room")
    assert render_xml(layout) == render_xml(load_case(Path(__file__).parent / "single_room"))
    root = ElementTree.fromstring(render_xml(layout).encode())
    assert root.findtext("floor/spaces/space/labels/label") == 'STUDIO "A" & <B>'


@pytest.mark.parametrize("source", ["planted", "compiled"])
@pytest.mark.parametrize("spec_file", SPEC_FILES, ids=[p.stem for p in SPEC_FILES])
def test_xml_of_every_spec_has_the_specs_graph_labels_and_types(
    spec_file: Path, source: str, tmp_path: Path, compiled_spec_layouts
) -> None:
    if source == "planted":
        layout = planted_layouts()[spec_file.stem]
    else:
        layout = compiled_spec_layouts[spec_file.stem][1]
    edges, rooms = spec_adjacency(spec_file)
    building, _ = read_building(_written(layout, tmp_path))
    assert building is not None
    assert {space.id: (space.rtype, space.label) for space in building.spaces} == rooms
    assert building.portal_edges() == {pair: TYPE[kind] for pair, kind in edges.items()}
