"""The editor features as plain functions (no protocol): the lexical index, completion
contexts, quick fixes, and the parsed-line memory the server turns on."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from layoutdsl.api import lint_source
from layoutdsl.diagnostics.source import Source
from layoutdsl.lsp import features
from layoutdsl.lsp.document import SpecDocument
from layoutdsl.syntax import parser

ROOT_SPECS = Path(__file__).resolve().parents[2] / "specs"

SPEC = """\
rooms
hall 10 20 15 2 3 2.5 4 10 C HALL   # the spine
kitchen 3 5 4 3 5 4 1 1.67 R KITCHEN onB cover=0.5
ROOM#3 3 5 4 3 5 4 1 1.67 R STORE ROOM

boundary
20 12
O1 0 0 1 1

adjacencies
kitchen hall 0.9 e
ROOM#3 hall 0.9 i # kitchen is not named here

clusters
K0
kitchen 0 0
ROOM#3 4 0
"""


def test_the_index_finds_definitions_and_references_but_not_comments_obstacles_or_clusters() -> None:
    document = SpecDocument(SPEC)
    assert list(document.definitions) == ["hall", "kitchen", "ROOM#3"]
    uses = [(u.word.text, u.word.line, u.word.start, u.is_definition) for u in document.uses_of("kitchen")]
    assert uses == [("kitchen", 2, 0, True), ("kitchen", 10, 0, False), ("kitchen", 15, 0, False)]
    assert [u.word.line for u in document.uses_of("ROOM#3")] == [3, 11, 16]
    assert document.uses_of("K0") == [] and document.uses_of("O1") == []


def test_a_room_line_is_read_word_by_word() -> None:
    entry = SpecDocument(SPEC).room_entry("kitchen")
    assert entry.numbers == ("3", "5", "4", "3", "5", "4", "1", "1.67")
    assert (entry.rtype, entry.label, entry.on_boundary, entry.weights) == ("R", "KITCHEN", True, ("cover=0.5",))
    assert SpecDocument(SPEC).room_entry("ROOM#3").label == "STORE ROOM"
    sizeless = SpecDocument("rooms\nlobby E ENTRANCE HALL onB\n").room_entry("lobby")
    assert (sizeless.numbers, sizeless.rtype, sizeless.label, sizeless.on_boundary) == ((), "E", "ENTRANCE HALL", True)
    untyped = SpecDocument("rooms\nR10 CLASSROOM\n").room_entry("R10")
    assert (untyped.rtype, untyped.label) == (None, "CLASSROOM")  # only R, C or E is a type there


def _completions(text: str, line: int, column: int) -> list[str]:
    return [c.label for c in features.completions(SpecDocument(text), line, column)]


def test_completion_follows_the_words_place_on_its_line() -> None:
    rooms = "rooms\nhall 10 20 15 2 3 2.5 4 10 C HALL\nx 1 2 1 1 2 1 1 2 "
    assert _completions(rooms, 2, len("x 1 2 1 1 2 1 1 2 ")) == ["R", "C", "E"]
    assert _completions(rooms, 2, len("x 1 2 1 ")) == []  # among the sizes
    typed_label = rooms + "R STORE "
    assert _completions(typed_label, 2, len(typed_label.split("\n")[2])) == ["HALL", "onB", "cover=", "error="]
    adjacency = SPEC + "\nadjacencies\nhall kitchen 1 "
    last = adjacency.split("\n")
    assert _completions(adjacency, len(last) - 1, len(last[-1])) == ["e", "i"]
    # in a comment, nothing
    assert _completions(SPEC, 1, len("hall 10 20 15 2 3 2.5 4 10 C HALL   # th")) == []


def test_fixes_are_read_from_the_hints_that_name_a_replacement() -> None:
    text = "rooms\nhall 10 20 15 2 3 2,5 4 10 C HALL\nstore 1 2 1 1 2 1 1 2 c STORE\n\nboundary\n20 12\n\nadjacencys\n"
    found = {d.diagnostic.code: d.fix for d in features.lint(text, "fix.lay").diagnostics}
    assert found["E005"] == features.Fix("Replace with `2.5` (E005)", features.Range(1, 18, 1, 21), "2.5")
    assert text.split("\n")[1][18:21] == "2,5"
    assert found["E012"].new_text == "C" and found["E001"].new_text == "adjacencies"


VALUE_ERROR = SPEC.replace("R KITCHEN", "r KITCHEN")


@pytest.mark.parametrize(("before", "edited"), [
    (SPEC, SPEC),
    (SPEC, SPEC.replace("kitchen hall 0.9 e", "kitchen hall 0.9 x")),     # a value error on a line that parses
    (SPEC, VALUE_ERROR),                                                  # another one
    (SPEC, SPEC.replace("20 12\n", "20 12\n\n").replace("O1 0", "O1 0 0")),  # lines moved, one broken
    (SPEC, "# a new first line\n" + SPEC),                              # every line moved: spans compared
    (VALUE_ERROR, "# a new first line\n" + VALUE_ERROR),                # every line moved, value error too
    (VALUE_ERROR, VALUE_ERROR.replace("rooms\n", "rooms\nnew 1 2 1 1 2 1 1 2 R NEW\n", 1)),
])  # fmt: skip
def test_remembered_lines_give_the_same_spec_and_diagnostics(before: str, edited: str) -> None:
    def lint(text: str):
        spec, diagnostics = lint_source(Source("memo.lay", text))
        nodes = () if spec is None else (*spec.rooms, *spec.adjacencies, *spec.clusters, *spec.hints)
        spans = [(node.span, dict(node.spans)) for node in nodes]  # spans take no part in ==
        return spec, spans, [(d.code, d.message, d.span, d.help, d.notes) for d in diagnostics]

    parser.keep_parsed_lines(0)
    fresh = lint(edited)
    if edited == "# a new first line\n" + SPEC:
        assert fresh[0] is not None  # the case that compares moved spans needs a spec that parses
    try:
        parser.keep_parsed_lines()
        lint(before)  # remember the lines before the edit, as the server does
        assert lint(edited) == fresh
        assert lint(edited) == fresh  # and again, entirely from memory
    finally:
        parser.keep_parsed_lines(0)


def test_a_repeated_last_line_is_removed_with_the_end_of_the_line_before_it() -> None:
    text = "rooms\nhall 10 20 15 2 3 2.5 4 10 C HALL\n\nboundary\n20 12\n\nsettings\nseed 1\nseed 2"
    (found,) = [d for d in features.lint(text, "last.lay").diagnostics if d.diagnostic.code == "E014"]
    assert found.fix.range == features.Range(7, features._END_OF_LINE, 8, features._END_OF_LINE)
    # applied as a client does, columns clamped to the line: `seed 2` and the newline before it go
    lines = text.split("\n")
    offset = [sum(len(line) + 1 for line in lines[:n]) for n in range(len(lines))]
    start = offset[7] + min(found.fix.range.start_col, len(lines[7]))
    end = offset[8] + min(found.fix.range.end_col, len(lines[8]))
    assert text[:start] + text[end:] == text.removesuffix("\nseed 2")


def test_hover_on_a_section_name_or_a_setting_key() -> None:
    text = "rooms\nhall 10 20 15 2 3 2.5 4 10 C HALL\n\nboundary\n20 12\n\nsettings\nwalldim 0.3\nemphasis default\n"
    document = SpecDocument(text)
    markdown, where = features.hover(document, 3, 2)
    assert "section `boundary`" in markdown and "w h\nid x y w h" in markdown
    assert where == features.Range(3, 0, 3, 8)
    assert features.hover(document, 7, 1)[0] == "setting `walldim`, default `0.2`"
    assert "`feasibility`" in features.hover(document, 8, 1)[0]
    assert features.hover(document, 7, 9) is None  # a setting's value


def test_hover_on_an_l_room_shows_its_arm() -> None:
    text = (ROOT_SPECS / "l_corridor.lay").read_text(encoding="utf-8")
    document = SpecDocument(text)
    room_id = next(line.words[0].text for line in document.lines if line.section == "arms" and not line.is_header and line.words)
    word = document.definitions[room_id]
    markdown, _ = features.hover(document, word.line, word.start)
    arm_line = next(n for n, line in enumerate(text.split("\n")) if line.split()[:1] == [room_id] and n != word.line)
    assert f"L-shaped: its second rectangle is on line {arm_line + 1} (`arms`)" in markdown
    assert markdown.count("| width (m) |") == 2


_EDITS = st.lists(
    st.tuples(st.sampled_from(["delete", "duplicate", "swap", "retype"]), st.integers(0, 10_000), st.integers(0, 10_000)),
    min_size=1, max_size=6,
)  # fmt: skip


@settings(max_examples=40, deadline=None)
@given(edits=_EDITS)
def test_remembered_lines_agree_with_a_fresh_parse_through_any_edits(edits) -> None:
    # the server's lints, one per edit, with the parsed lines remembered all along, against a
    # fresh parse of each text (specs, their spans, and the diagnostics)
    def lint(text: str):
        spec, diagnostics = lint_source(Source("edits.lay", text))
        nodes = () if spec is None else (*spec.rooms, *spec.arms, *spec.adjacencies, *spec.positions,
                                          *spec.connections, *spec.clusters, *spec.hints)  # fmt: skip
        return spec, [(n.span, dict(n.spans)) for n in nodes], [(d.code, d.message, d.span, d.notes) for d in diagnostics]

    lines = (ROOT_SPECS / "campus_constraints.lay").read_text(encoding="utf-8").split("\n")
    try:
        parser.keep_parsed_lines()
        lint("\n".join(lines))
        for kind, i, j in edits:
            i, j = i % len(lines), j % len(lines)
            if kind == "delete" and len(lines) > 1:
                del lines[i]
            elif kind == "duplicate":
                lines.insert(j, lines[i])
            elif kind == "swap":
                lines[i], lines[j] = lines[j], lines[i]
            else:  # a keystroke: the line's last character typed again, or a letter
                lines[i] = lines[i] + (lines[i][-1:] or "x")
            text = "\n".join(lines)
            remembered = lint(text)
            parser.keep_parsed_lines(0)
            assert remembered == lint(text)
            parser.keep_parsed_lines()
            lint(text)  # as the server left it
    finally:
        parser.keep_parsed_lines(0)
