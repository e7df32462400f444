"""Issue 42's diagnostics: suggestions for short ids, follow-on warnings, wrong kinds of file."""

from __future__ import annotations

from pathlib import Path

import pytest

from layoutdsl.api import lint_source
from layoutdsl.diagnostics import Diagnostic, Severity
from layoutdsl.diagnostics.filekind import (
    BUILDING_XML, GRAPH_JSON, GRAPHML, LAYOUT_JSON, SECTION_WORDS, SPEC, sniff, wrong_kind_for_import,
    wrong_kind_for_spec,
)
from layoutdsl.diagnostics.followon import FOLLOW_ONS, without_follow_ons
from layoutdsl.diagnostics.source import Source, Span
from layoutdsl.diagnostics.suggest import edit_distance, suggest

HERE = Path(__file__).resolve().parent
ROOMS = ["R0", "R1", "C0", "E0", "KITCHEN"]


# ----------------------------------------------------------------- suggestions


@pytest.mark.parametrize("typed, expected", [
    ("C9", "C0"),       # one substitution: difflib's 0.6 cutoff rejected it (ratio 0.5)
    ("CO", "C0"),       # letter O for digit 0
    ("C1", "C0"),       # equally close to R1: the shared first letter (the room's kind) wins
    ("c0", "C0"),       # case
    ("0C", "C0"),       # two characters swapped
    ("R01", "R0"),      # one extra character
    ("KITCHN", "KITCHEN"),
    ("E", "E0"),
])
def test_short_ids_get_a_suggestion(typed, expected):
    assert suggest(typed, ROOMS) == expected


@pytest.mark.parametrize("typed", ["X7", "LOBBY", "Q", "R123"])
def test_nothing_close_gets_no_suggestion(typed):
    assert suggest(typed, ROOMS) is None


def test_edit_distance_counts_lookalikes_and_case_as_half():
    assert edit_distance("CO", "C0") == 0.5
    assert edit_distance("c0", "C0") == 0.5
    assert edit_distance("C9", "C0") == 1
    assert edit_distance("ab", "ba") == 1
    assert edit_distance("", "abc") == 3


def lint(text: str, name: str = "t.lay") -> list[Diagnostic]:
    return lint_source(Source(name, text))[1]


GOOD = ("rooms\nR0 4 6 5 3 5 4 1 2 R OFFICE\nR1 4 6 5 3 5 4 1 2 R OFFICE\nC0 1.5 2.5 2 8 14 10 3 10 C CORRIDOR\n\n"
        "boundary\n12 14\n\nadjacencies\nR0 C0 0.9 e\nR1 C0 0.9 e\n")


def test_an_unknown_room_gets_a_suggestion_in_every_section():
    text = GOOD.replace("R1 C0 0.9 e", "R1 C9 0.9 e") + "\npositions\nCO 1 1\n\nhints\nr1 0 0 4 4\n"
    helps = {(d.code, d.help) for d in lint(text)}
    assert ("E102", "did you mean `C0`?") in helps
    assert ("E103", "did you mean `C0`?") in helps
    assert ("E106", "did you mean `R1`?") in helps


def test_an_unknown_room_far_from_every_id_gets_the_list_of_rooms():
    (found,) = [d for d in lint(GOOD.replace("R1 C0 0.9 e", "R1 LOBBY 0.9 e")) if d.code == "E102"]
    assert found.help == "define `LOBBY` in `rooms`, or use one of its rooms: `R0`, `R1`, `C0`"


def test_the_suggestion_is_never_the_other_room_of_the_adjacency():
    # `R0 R2`: R0 would be one edit away, but R0 adjacent to R0 is E110; R1 is the guess
    (found,) = [d for d in lint(GOOD + "R0 R2 0.9 e\n") if d.code == "E102"]
    assert found.help == "did you mean `R1`?"


# ----------------------------------------------------------------- follow-on warnings


def test_w301_is_not_reported_beside_the_e102_that_causes_it():
    broken = GOOD.replace("R1 C0 0.9 e", "R1 C9 0.9 e")  # R1 falls off the graph because of the typo
    assert [d.code for d in lint(broken)] == ["E102"]
    # fixed typo: no W301 either; a genuinely separate room still gets its W301
    assert lint(GOOD) == []
    separate = GOOD.replace("R1 C0 0.9 e\n", "")
    assert [d.code for d in lint(separate)] == ["W301"]


def test_only_warnings_caused_by_an_error_of_the_same_file_are_dropped():
    def make(code: str, filename: str, severity=Severity.ERROR) -> Diagnostic:
        return Diagnostic(code, "m", filename, Span.point(1, 1), severity)

    w301_a = make("W301", "a.lay", Severity.WARNING)
    w301_b = make("W301", "b.lay", Severity.WARNING)
    w302_a = make("W302", "a.lay", Severity.WARNING)
    e102_a = make("E102", "a.lay")
    assert without_follow_ons([w301_a, w301_b, w302_a, e102_a]) == [w301_b, w302_a, e102_a]
    assert all(code.startswith("W") for code in FOLLOW_ONS)  # errors are never suppressed


# ----------------------------------------------------------------- wrong kind of file


def test_section_words_are_the_parsers_sections():
    from layoutdsl.syntax.parser import SECTIONS

    assert SECTION_WORDS == frozenset(SECTIONS)


@pytest.mark.parametrize("text, kind", [
    ('<?xml version="1.0"?>\n<building>\n', BUILDING_XML),
    ("\ufeff  <building><scale/>", BUILDING_XML),
    ('<?xml version="1.0"?>\n<graphml xmlns="http://graphml.graphdrawing.org/xmlns">', GRAPHML),
    ('{"directed": false, "nodes": [], "links": []}', GRAPH_JSON),
    ('{"name": "x", "rooms": [], "portals": []}', LAYOUT_JSON),
    ("# a comment\n\nrooms\nR0 1 2 3 4 5 6 1 2 R OFFICE\n", SPEC),
    ("boundary\n10 10\n", SPEC),
])
def test_sniff(text, kind):
    assert sniff(text) == kind


def test_a_spec_with_typos_is_still_read_as_a_spec():
    # a broken spec gets its real diagnostics, never E019
    assert wrong_kind_for_spec("x.lay", "rooms\nR0 4 6\n") is None
    assert wrong_kind_for_spec("x.lay", "romos\nR0 4 6 5 3 5 4 1 2 R OFFICE\n") is None
    assert wrong_kind_for_spec("x.lay", "") is None


def test_a_plan_given_for_a_spec_names_import():
    found = wrong_kind_for_spec("plan.xml", '<?xml version="1.0"?>\n<building>\n</building>\n')
    assert found is not None and found.code == "E019"
    assert found.message == "this is a building XML plan, not a layoutdsl spec"
    assert found.help == "run `layoutdsl import plan.xml -o plan.lay` to make a spec of it, then compile that"
    layout = wrong_kind_for_spec("out/x.layout.json", '{"rooms": [], "portals": []}')
    assert "compile the `.lay` spec" in layout.help


def test_a_spec_given_to_import_says_so():
    found = wrong_kind_for_import("office.lay", (HERE.parents[1] / "specs" / "office_small.lay").read_text())
    assert found is not None and found.code == "E019"
    assert found.message == "this is a layoutdsl spec, not a plan to import"
    assert wrong_kind_for_import("plan.xml", "<building/>") is None
    assert wrong_kind_for_import("graph.csv", "0,1\n1,0\n") is None


def test_a_spec_or_a_layout_given_to_evaluate_as_a_plan_says_so():
    from layoutdsl.diagnostics.filekind import wrong_kind_for_plan

    spec = wrong_kind_for_plan("specs/office.lay", "rooms\nR0 4 6 5 3 5 4 1 2 R OFFICE\n")
    assert spec.code == "E019" and spec.message == "this is a layoutdsl spec, not a building plan"
    assert "`office.xml`" in spec.help
    layout = wrong_kind_for_plan("out/office-v1.layout.json", '{"rooms": [], "portals": []}')
    assert layout.message == "this is a compiled layout (`.layout.json`), not a building plan"
    assert "`office-v1.xml`" in layout.help
    assert wrong_kind_for_plan("plan.xml", '<?xml version="1.0"?><building/>') is None


def test_other_xml_is_an_xml_file():
    assert wrong_kind_for_spec("a.lay", "<rooms>\n").message == "this is an XML file, not a layoutdsl spec"
