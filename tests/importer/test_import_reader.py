"""read_building: the safe building-XML reader (located diagnostics, never a traceback)."""

from __future__ import annotations


import pytest
from _import_plans import PlanSpace, plan_xml, rect
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from layoutdsl.importer.building import Point
from layoutdsl.diagnostics import CODES
from layoutdsl.importer import import_building, read_building

from real_plans import EXAMPLES as FIXTURES

BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE building [
  <!ENTITY lol "lol">
  <!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
  <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
  <!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
  <!ENTITY lol9 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">
]>
<building><name>&lol9;</name></building>
"""


def _codes(diagnostics) -> list[str]:
    return [d.code for d in diagnostics]


def _two_rooms(**kwargs) -> str:
    spaces = [
        PlanSpace("a", "R", "ROOM", rect(0, 0, 300, 300), [("d", "a", "b", "EXPLICIT")], {"d": (300, 100)}),
        PlanSpace("b", "C", "CORRIDOR", rect(300, 0, 600, 300), [("e", "b", "a", "EXPLICIT")], {"e": (300, 100)}),
    ]
    return plan_xml(spaces, **kwargs)


def test_billion_laughs_is_refused_with_a_located_diagnostic(tmp_path):
    path = tmp_path / "laughs.xml"
    path.write_text(BILLION_LAUGHS)
    building, diagnostics = read_building(path)
    assert building is None
    (diagnostic,) = diagnostics
    assert diagnostic.code == "E401"
    assert "entity declaration `lol` is refused" in diagnostic.message
    assert (diagnostic.filename, diagnostic.span.line, diagnostic.span.col) == (str(path), 3, 3)


def test_external_entity_is_refused_and_the_file_is_never_read(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("TOP-SECRET")
    xxe = (
        '<?xml version="1.0"?>\n'
        f'<!DOCTYPE building [<!ENTITY xxe SYSTEM "file://{secret}">]>\n'
        "<building><name>&xxe;</name></building>\n"
    )
    building, diagnostics = read_building("xxe.xml", text=xxe)
    assert building is None
    assert _codes(diagnostics) == ["E401"]
    assert diagnostics[0].span.line == 2
    assert "external entity" in diagnostics[0].label
    assert "TOP-SECRET" not in repr(diagnostics)


def test_malformed_xml_points_at_the_error():
    building, diagnostics = read_building("bad.xml", text="<building>\n  <scale>\n</building>\n")
    assert building is None
    assert [(d.code, d.span.line, d.span.col) for d in diagnostics] == [("E400", 3, 3)]
    assert diagnostics[0].message == "malformed XML: mismatched tag"


def test_empty_file_is_malformed_xml_not_a_crash():
    assert _codes(read_building("empty.xml", text="")[1]) == ["E400"]


def test_missing_scale_is_reported_at_the_building_element():
    xml = _two_rooms().replace("  <scale>", "  <nothing>").replace("  </scale>", "  </nothing>")
    building, diagnostics = read_building("plan.xml", text=xml)
    assert building is None
    assert [(d.code, d.message, d.span.line, d.span.col) for d in diagnostics] == [
        ("E402", "`<building>` has no `<scale>`", 2, 1)
    ]


def test_portal_naming_an_unknown_space_is_an_error_with_a_guess():
    xml = _two_rooms().replace("<id>b</id><id>a</id>", "<id>corridor-1</id><id>a</id>")
    xml = xml.replace('space id="b"', 'space id="corridor-2"')
    building, diagnostics = read_building("plan.xml", text=xml)
    assert building is None
    unknown = [d for d in diagnostics if d.code == "E404"]
    assert [d.message for d in unknown] == [
        "portal of space `a` names unknown space `b`",
        "portal of space `corridor-2` names unknown space `corridor-1`",
    ]
    assert unknown[1].help == "did you mean `corridor-2`?"
    line = xml.splitlines()[unknown[1].span.line - 1]
    assert line[unknown[1].span.col - 1 :].startswith("<id>corridor-1")


def test_space_without_polygon_is_an_error():
    xml = _two_rooms()
    start = xml.index("<bounding_polygon>")
    end = xml.index("</bounding_polygon>") + len("</bounding_polygon>")
    building, diagnostics = read_building("plan.xml", text=xml[:start] + xml[end:])
    assert building is None
    assert [(d.code, d.message) for d in diagnostics] == [("E405", "space `a` has no `<bounding_polygon>`")]


FLAT = [(0, 0), (100, 0), (200, 0), (0, 0)]
"""A polygon on one line: no area."""


def test_zero_area_polygon_a_portal_leads_to_is_an_error():
    xml = plan_xml([
        PlanSpace("a", "R", "ROOM", FLAT),
        PlanSpace("b", "C", "CORRIDOR", rect(0, 100, 400, 200), portals=[("d1", "a", "b", "EXPLICIT")]),
    ])
    building, diagnostics = read_building("plan.xml", text=xml)
    assert building is None
    empty = [d for d in diagnostics if d.code == "E405"]
    assert len(empty) == 1 and "portal leads here" in empty[0].label


def test_zero_area_space_without_portal_is_skipped_with_a_warning():
    xml = plan_xml([
        PlanSpace("artefact", "R", "ROOM", FLAT),
        PlanSpace("b", "C", "CORRIDOR", rect(0, 100, 400, 200)),
    ])
    building, diagnostics = read_building("plan.xml", text=xml)
    assert _codes(diagnostics) == ["W425"]
    assert building is not None and [s.id for s in building.spaces] == ["b"]


def test_a_plan_of_nothing_but_empty_spaces_has_no_spaces():
    xml = plan_xml([PlanSpace("a", "R", "ROOM", FLAT)])
    building, diagnostics = read_building("plan.xml", text=xml)
    assert building is None
    assert _codes(diagnostics) == ["E410"]
    assert "no space with an area" in diagnostics[0].message


def test_non_numeric_coordinate_points_at_the_attribute():
    xml = _two_rooms().replace('<point x="300" y="100"/>', '<point x="3OO" y="100"/>', 1)
    building, diagnostics = read_building("plan.xml", text=xml)
    assert building is None
    (diagnostic,) = diagnostics
    assert (diagnostic.code, diagnostic.message) == ("E403", "attribute `x` `3OO` is not a number")
    line = xml.splitlines()[diagnostic.span.line - 1]
    assert line[diagnostic.span.col - 1 : diagnostic.span.end_col - 1] == 'x="3OO"'


@pytest.mark.parametrize(
    "real, unit, help_text",
    [("90", "m", "did you mean `<um>cm</um>` (a 0.9 m door)?"), ("0.9", "cm", "did you mean `<um>m</um>` (a 0.9 m door)?")],
)
def test_implausible_door_size_is_an_error_that_guesses_the_unit(real, unit, help_text):
    building, diagnostics = read_building("plan.xml", text=_two_rooms(real=real, unit=unit))
    assert building is None
    (diagnostic,) = diagnostics
    assert diagnostic.code == "E406"
    assert diagnostic.help == help_text


def test_non_positive_represented_distance_is_an_error():
    assert _codes(read_building("plan.xml", text=_two_rooms(represented="0"))[1]) == ["E406"]


def test_duplicate_space_ids_and_bad_portal_targets_are_errors():
    xml = _two_rooms().replace('space id="b"', 'space id="a"').replace("<id>b</id><id>a</id>", "<id>a</id>")
    _, diagnostics = read_building("plan.xml", text=xml)
    assert sorted(_codes(diagnostics)) == ["E404", "E407"]
    xml = _two_rooms().replace("<id>b</id><id>a</id>", "<id>b</id>")
    assert _codes(read_building("plan.xml", text=xml)[1]) == ["E409"]


def test_every_problem_is_reported_not_only_the_first():
    xml = _two_rooms().replace('<point x="300" y="100"/>', '<point x="?" y="100"/>', 1)
    xml = xml.replace("<id>b</id><id>a</id>", "<id>zzz</id><id>a</id>")
    xml = xml.replace("<type>C</type>", "<type>Q</type>")
    _, diagnostics = read_building("plan.xml", text=xml)
    assert _codes(diagnostics) == ["E403", "W420", "E404"]


def test_unreadable_file_is_a_diagnostic(tmp_path):
    building, diagnostics = read_building(tmp_path / "missing.xml")
    assert building is None
    assert _codes(diagnostics) == ["E408"]
    assert _codes(read_building(tmp_path)[1]) == ["E408"]  # a directory


def test_accepts_miny_spelling_zero_length_portals_and_bare_space_references():
    extra = "    <groups><group_features><space>a</space><space>b</space></group_features></groups>"
    for tag in ("miny", "minY"):
        building, diagnostics = read_building("plan.xml", text=_two_rooms(miny_tag=tag, extra=extra))
        assert diagnostics == []
        assert [s.id for s in building.spaces] == ["a", "b"]
    portal = building.space("a").portals[0]
    assert portal.targets == ("a", "b") and portal.type == "EXPLICIT"
    assert portal.segment.p1 == portal.segment.p2 == Point(300, 100)
    assert portal.segment.cls == "PORTAL"


def test_unknown_room_type_and_missing_portal_segment_are_warnings():
    xml = _two_rooms().replace("<type>C</type>", "<type>X</type>").replace(
        "<linesegment>e</linesegment>", "<linesegment>nope</linesegment>"
    )
    building, diagnostics = read_building("plan.xml", text=xml)
    assert building is not None
    assert _codes(diagnostics) == ["W420", "W421"]
    assert building.space("b").rtype == "R"
    assert building.space("b").portals[0].segment is None


def test_self_portal_is_ignored_with_a_warning():
    xml = _two_rooms().replace("<id>b</id><id>a</id>", "<id>b</id><id>b</id>")
    building, diagnostics = read_building("plan.xml", text=xml)
    assert _codes(diagnostics) == ["W424"]
    assert building.space("b").portals == ()
    # the door is still known from the other side
    assert building.portal_edges() == {frozenset({"a", "b"}): "EXPLICIT"}


def test_real_plan_keeps_file_units_and_y_down_and_bboxes_come_from_polygons():
    building, diagnostics = read_building(FIXTURES / "office_Milano-1.xml")
    assert diagnostics == []
    assert (building.represented_distance, building.real_distance_m) == (14, 0.9)
    assert len(building.spaces) == 17  # the `<groups>` references are not spaces
    first = building.spaces[0]
    xs = [p.x for p in first.polygon]
    ys = [p.y for p in first.polygon]
    # the file's own <bounding_box> is broken here (maxy above miny); the polygon is not
    assert (first.bbox.min_x, first.bbox.min_y, first.bbox.max_x, first.bbox.max_y) == (
        min(xs), min(ys), max(xs), max(ys)
    )
    assert first.line == 21


def test_reader_never_raises_on_mangled_real_plans():
    """Truncating a real plan anywhere gives diagnostics, never an exception."""
    text = (FIXTURES / "school_Lamuniere1.xml").read_text()
    for cut in range(0, len(text), 997):
        building, diagnostics = read_building("cut.xml", text=text[:cut])
        assert building is not None or diagnostics
        spec, diagnostics = import_building("cut.xml", text=text[:cut])
        assert spec is not None or any(d.is_error for d in diagnostics)


_SMALL_PLAN = _two_rooms()


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    edits=st.lists(
        st.tuples(
            st.integers(0, len(_SMALL_PLAN)),
            st.integers(0, 40),
            st.sampled_from(["", "<", ">", "&", '"', "x", "-1", "1e999", "nan", "</space>", "<point/>", "\x00", "é", "\n"]),
        ),
        min_size=1,
        max_size=4,
    )
)
def test_mutated_plans_give_diagnostics_or_a_spec_never_an_exception(edits):
    text = _SMALL_PLAN
    for start, length, replacement in edits:
        text = text[:start] + replacement + text[start + length :]
    spec, diagnostics = import_building("fuzz.xml", text=text)
    assert spec is not None or any(d.is_error for d in diagnostics)
    for diagnostic in diagnostics:
        assert diagnostic.span.line >= 1 and diagnostic.span.col >= 1
        assert diagnostic.code in CODES
    if spec is not None:
        for room in spec.rooms:
            assert room.min_w <= room.target_w <= room.max_w
            assert room.min_h <= room.target_h <= room.max_h


@pytest.mark.parametrize(
    "real, unit, door",
    [("90", "cm", 0.9), ("90", "centimeters", 0.9), ("90", "", 0.9), ("1.2", "m", 1.2), ("800", "mm", 0.8)],
)
def test_door_size_units(real, unit, door):
    building, diagnostics = read_building("plan.xml", text=_two_rooms(real=real, unit=unit))
    assert diagnostics == []
    assert building.real_distance_m == pytest.approx(door)
    assert building.metres_per_unit == pytest.approx(door / 90)


def test_unknown_unit_is_an_error():
    _, diagnostics = read_building("plan.xml", text=_two_rooms(unit="inch"))
    assert [(d.code, d.message) for d in diagnostics] == [("E406", "unknown unit `inch` for the real distance")]


def test_portal_without_linesegment_is_incomplete():
    xml = _two_rooms().replace("            <linesegment>e</linesegment>\n", "", 1)
    building, diagnostics = read_building("plan.xml", text=xml)
    assert building is None
    assert [(d.code, d.message) for d in diagnostics] == [("E402", "portal of space `b` has no `<linesegment>`")]
