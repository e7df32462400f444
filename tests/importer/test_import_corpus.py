"""Acceptance over the 24 real plans of ../shared/floorplans (issue 5).

Every plan imports, its spec lints with no errors and reads back equal, and its adjacency
graph equals the plan's portal graph. The expected graph is computed here independently of
the importer, with the standard library's ElementTree (the corpus is trusted data), and its
size is also held against the counts published in the corpus' INDEX.md.
"""

from __future__ import annotations

import re
import time
import xml.etree.ElementTree as ElementTree
from dataclasses import replace
from pathlib import Path

import networkx as nx
import pytest

from layoutdsl.api import lint_source
from layoutdsl.diagnostics import has_errors
from layoutdsl.syntax.format import format_spec
from layoutdsl.importer import ImportOptions, import_building, original_room_area, read_building
from layoutdsl.diagnostics.source import Source

from real_plans import CORPUS, CORPUS_SIZE, corpus_plans, needs_corpus

PLANS = corpus_plans()
pytestmark = needs_corpus


def _index_counts() -> dict[str, tuple[int, int, int]]:
    """file name -> (spaces, edges, components) from the corpus' INDEX.md table."""
    counts = {}
    for line in (CORPUS / "INDEX.md").read_text().splitlines():
        match = re.match(r"\|\s*(\S+\.xml)\s*\|\s*(\d+)\s*\|\s*(\d+)\s*\|\s*\d+\s*\|\s*(\d+)\s*\|", line)
        if match:
            counts[match.group(1)] = (int(match.group(2)), int(match.group(3)), int(match.group(4)))
    return counts


def _expected_graph(path: Path):
    """Rooms (id, type, label) in file order and {frozenset(ids): 'e'|'i'} from the XML."""
    root = ElementTree.parse(path).getroot()
    spaces = root.findall("floor/spaces/space")
    counters: dict[str, int] = {}
    ids: dict[str, str] = {}
    rooms = []
    for space in spaces:
        rtype = space.findtext("labels/type").strip()
        ids[space.get("id")] = f"{rtype}{counters.get(rtype, 0)}"
        counters[rtype] = counters.get(rtype, 0) + 1
        rooms.append((ids[space.get("id")], rtype, " ".join(space.findtext("labels/label").split())))
    edges: dict[frozenset, str] = {}
    for space in spaces:
        for portal in space.findall("portals/portal"):
            a, b = (ids[t.text.strip()] for t in portal.findall("target/id"))
            kind = "e" if portal.findtext("type").strip() == "EXPLICIT" else "i"
            key = frozenset((a, b))
            edges[key] = "e" if "e" in (kind, edges.get(key)) else "i"
    return rooms, edges


def test_the_corpus_is_there():
    assert len(PLANS) == CORPUS_SIZE, f"expected the {CORPUS_SIZE} real plans in {CORPUS}"


@pytest.mark.parametrize("plan", PLANS, ids=[plan.stem for plan in PLANS])
def test_real_plan_imports_lints_clean_and_keeps_its_portal_graph(plan: Path):
    started = time.perf_counter()
    spec, diagnostics = import_building(plan, ImportOptions(hints=True))
    elapsed = time.perf_counter() - started
    assert spec is not None and not has_errors(diagnostics), diagnostics
    assert {d.code for d in diagnostics} <= {"W422"}, "real plans only need the mindim repair"
    assert elapsed < 2.0

    text = format_spec(replace(spec, path=f"{plan.stem}.lay"))
    linted, lint_diagnostics = lint_source(Source(f"{plan.stem}.lay", text))
    assert [d for d in lint_diagnostics if d.is_error] == []
    assert linted == spec, "the written spec reads back as the imported one"
    assert text.startswith("rooms\n") and "\nsettings\n" not in text  # a plain thesis file + hints

    rooms, edges = _expected_graph(plan)
    assert [(r.id, r.rtype, r.label) for r in spec.rooms] == rooms
    assert {frozenset((a.a, a.b)): a.kind for a in spec.adjacencies} == edges
    assert len(spec.adjacencies) == len(edges)  # one adjacency per pair, however many doors
    assert {a.door for a in spec.adjacencies} == {0.9}
    graph = nx.Graph()
    graph.add_nodes_from(spec.room_ids)
    graph.add_edges_from((a.a, a.b) for a in spec.adjacencies)
    components = nx.number_connected_components(graph)
    assert (len(spec.rooms), len(spec.adjacencies), components) == _index_counts()[plan.name]
    assert [h.room for h in spec.hints] == [r.id for r in spec.rooms]

    # Rectangularization keeps each room's area (only the mindim repair adds a little).
    target_area = sum(room.target_w * room.target_h for room in (*spec.rooms, *spec.arms))
    assert target_area == pytest.approx(original_room_area(read_building(plan)[0]), rel=0.003)
