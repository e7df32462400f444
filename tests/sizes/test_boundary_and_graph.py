"""choose_boundary's rule, and spec_from_graph: ids, entrances outside, doors, drawn sizes."""

from __future__ import annotations

import random

import networkx as nx
import pytest

from layoutdsl.api import lint_source
from layoutdsl.diagnostics.source import Source
from layoutdsl.sizes import load_model, spec_from_graph
from layoutdsl.sizes.boundary import ASPECT, FILL, choose_boundary
from layoutdsl.syntax.ast import Room
from layoutdsl.syntax.format import format_spec


def room(w: float, h: float) -> Room:
    return Room("R", w, w, w, h, h, h, 1, 10, "R", "X")


def test_the_boundary_holds_the_target_area_at_the_fill_ratio() -> None:
    rooms = [room(6, 4)] * 10  # 240 m²
    w, h = choose_boundary(rooms)
    assert w * h >= 240 / FILL
    assert w * h <= 240 / FILL * 1.05  # rounding up to 10 cm adds little
    assert w / h == pytest.approx(ASPECT, rel=0.02)
    assert round(w * 10) == pytest.approx(w * 10) and round(h * 10) == pytest.approx(h * 10)


def test_the_boundary_grows_to_fit_its_longest_room() -> None:
    w, h = choose_boundary([room(40, 2), room(3, 3)])
    assert w >= 40 and h >= 3
    w, h = choose_boundary([room(9, 9)], fill=1.0, aspect=4)
    assert w >= 9 and h >= 9  # the square room fits the short side too


def test_choose_boundary_refuses_nonsense() -> None:
    with pytest.raises(ValueError, match="no rooms"):
        choose_boundary([])
    with pytest.raises(ValueError, match="fill"):
        choose_boundary([room(1, 1)], fill=0)
    with pytest.raises(ValueError, match="not a positive"):
        choose_boundary([room(float("nan"), 1)])


def school_graph() -> nx.Graph:
    graph = nx.Graph()
    graph.add_node("hall", rtype="C", label="CORRIDOR")
    graph.add_node("class_a", rtype="R", label="CLASSROOM")
    graph.add_node("class_b", rtype="R", label="CLASSROOM")
    graph.add_node("door", rtype="E", label="ENTRANCE")
    graph.add_node("stairs", rtype="E", label="STAIRS")
    graph.add_node("yard", rtype="R", label="GYM", exterior=True)
    for node in ("class_a", "class_b", "door", "stairs", "yard"):
        graph.add_edge("hall", node)
    graph.edges["hall", "door"]["door"] = 1.8
    return graph


def test_spec_from_graph_keeps_ids_sizes_rooms_and_flags_the_outside() -> None:
    spec = spec_from_graph(school_graph(), name="mini")
    assert spec.name == "mini" and spec.room_ids == ("hall", "class_a", "class_b", "door", "stairs", "yard")
    outside = {r.id for r in spec.rooms if r.on_boundary}
    assert outside == {"door", "yard"}  # entrances open outside; stairs need not; `exterior` asks for it
    model = load_model()
    classroom = model.room_sizes("school", "R", "CLASSROOM")
    assert spec.room("class_a").target_w == classroom.target_w
    assert spec.room("hall").target_w == model.room_sizes("school", "C", "CORRIDOR", doors=5).target_w
    doors = {(a.a, a.b): a.door for a in spec.adjacencies}
    assert doors[("hall", "door")] == 1.8 and doors[("hall", "class_a")] == model.door("school")
    assert (spec.boundary.w, spec.boundary.h) == choose_boundary(spec.rooms) and spec.boundary.chosen
    _, diagnostics = lint_source(Source("mini.lay", format_spec(spec)))
    assert not [d for d in diagnostics if d.is_error]


def test_spec_from_graph_numbers_rooms_by_type_when_ids_are_not_spec_ids() -> None:
    graph = nx.convert_node_labels_to_integers(school_graph())
    spec = spec_from_graph(graph)
    assert spec.room_ids == ("C0", "R0", "R1", "E0", "E1", "R2")


def test_drawn_sizes_are_seeded_and_typical_ones_fixed() -> None:
    graph = school_graph()
    typical = spec_from_graph(graph)
    assert spec_from_graph(graph) == typical
    drawn = spec_from_graph(graph, rng=random.Random(5))
    assert drawn == spec_from_graph(graph, rng=random.Random(5))
    assert drawn != typical and drawn != spec_from_graph(graph, rng=random.Random(6))
    office = spec_from_graph(graph, kind="office")
    assert office.room("hall") != typical.room("hall")


def test_spec_from_graph_refuses_an_empty_graph_and_an_unknown_kind() -> None:
    with pytest.raises(ValueError, match="no rooms"):
        spec_from_graph(nx.Graph())
    from layoutdsl.sizes import ModelError

    with pytest.raises(ModelError):
        spec_from_graph(school_graph(), kind="castle")


def test_a_chosen_boundary_contains_the_points_the_spec_places() -> None:
    from layoutdsl.api import lint_source
    from layoutdsl.diagnostics.source import Source

    text = ("rooms\nR1 R CLASSROOM\nC1 C\n\nadjacencies\nR1 C1 0.9 e\n\n"
            "positions\nC1 3 17\n\nhints\nR1 40 0 5 5\n")  # fmt: skip
    spec, diagnostics = lint_source(Source("p.lay", text))
    assert not [d for d in diagnostics if d.is_error], diagnostics
    assert spec.boundary.w >= 45 and spec.boundary.h >= 17
    assert choose_boundary([room(2, 2)], contains=[(30, 12)]) == (30.1, 12.1)
