"""fmt: parse(format(spec)) == spec for every clean spec in specs/ and tests/, and fmt is stable."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from layoutdsl.api import lint_source, read_source
from layoutdsl.syntax.ast import Adjacency, Boundary, Room, Settings, Spec
from layoutdsl.syntax.format import format_number, format_source, format_spec, safe_label
from layoutdsl.syntax.parser import parse_source
from layoutdsl.diagnostics.source import Source

ROOT = Path(__file__).resolve().parents[2]
SPEC_FILES = sorted((ROOT / "specs").glob("*.lay")) + sorted((ROOT / "tests").rglob("*.lay"))


def _clean(path: Path):
    source = read_source(str(path))
    spec, diagnostics = parse_source(source)
    return source, spec if spec is not None and not diagnostics else None


CLEAN = [p for p in SPEC_FILES if _clean(p)[1] is not None]


def test_specs_folder_is_lint_and_fmt_clean() -> None:
    specs = sorted((ROOT / "specs").glob("*.lay"))
    assert len(specs) >= 4
    for path in specs:
        source = read_source(str(path))
        spec, diagnostics = lint_source(source)
        assert diagnostics == [], path.name
        assert format_source(source) == source.text, f"{path.name} is not in canonical form"


@pytest.mark.parametrize("path", CLEAN, ids=[str(p.relative_to(ROOT)) for p in CLEAN])
def test_parse_format_parse_is_identity(path: Path) -> None:
    source, spec = _clean(path)
    again, diagnostics = parse_source(Source(source.path, format_spec(spec)))
    assert diagnostics == []
    assert again == spec
    # and with comments kept, the text is a fixed point
    once = format_source(source)
    assert format_source(Source(source.path, once)) == once


@pytest.mark.parametrize(
    "value", [0.0, 1.0, 2.5, 0.1, 1 / 3, 21.342857142857145, 1e-7, 123456789.125, 1e20, -4.0, 5e-324]
)
def test_numbers_round_trip_exactly(value: float) -> None:
    text = format_number(value)
    assert float(text) == value
    if value.is_integer() and abs(value) < 1e16:
        assert "." not in text and "e" not in text


def test_format_spec_of_a_spec_built_in_code() -> None:
    """The importer's path: a Spec made in code, written, read back equal (name included)."""
    spec = Spec(
        "Lamuniere1",
        (Room("R0", 3, 5, 4, 3, 5, 4, 1, 1.5, "R", "OFFICE #1 A=B", rho_cover=0.3),),
        Boundary(10, 10),
        (Adjacency("R0", "R0", 0.9, "i"),),
        settings=Settings(walldim=0.15),
    )
    text = format_spec(spec)
    assert "name Lamuniere1" in text and "walldim 0.15" in text and "cover=0.3" in text
    assert "lambda_cover" not in text  # defaults are not written
    again, diagnostics = parse_source(Source("imported.lay", text))
    assert [d.code for d in diagnostics] == []
    # a label word that would read as a comment or a weight is escaped, nothing else changes
    assert again.rooms[0].label == "OFFICE No.1 A-B"
    assert again == replace(spec, rooms=(replace(spec.rooms[0], label="OFFICE No.1 A-B"),))


def test_plain_labels_are_kept() -> None:
    assert safe_label("MEDIUM SERVICE") == "MEDIUM SERVICE"
    assert safe_label("") == "ROOM"
    assert safe_label("X onB") == "X onb"


def test_thesis_sections_come_first_in_thesis_order() -> None:
    source = Source("x.lay", "settings\nseed 3\n\nadjacencies\nR0 R1 1 e\n\nboundary\n10 10\n\nrooms\n"
                    "R0 3 5 4 3 5 4 1 1.5 R A\nR1 3 5 4 3 5 4 1 1.5 R B\n")  # fmt: skip
    text = format_source(source)
    headers = [line for line in text.splitlines() if line in ("rooms", "boundary", "adjacencies", "settings")]
    assert headers == ["rooms", "boundary", "adjacencies", "settings"]


def test_comments_travel_with_their_lines() -> None:
    source = Source("x.lay", "# file header\n\nadjacencies\n# the door\nR0 R1 1 e  # wide\n\nrooms\n"
                    "R0 3 5 4 3 5 4 1 1.5 R A\nR1 3 5 4 3 5 4 1 1.5 R B\n\nboundary\n10 10\n# end\n")  # fmt: skip
    lines = format_source(source).splitlines()
    assert lines[0] == "# file header"
    assert lines[lines.index("R0 R1 1 e  # wide") - 1] == "# the door"
    assert lines[-1] == "# end"


# ===== Generated specs: any numbers, ids and labels survive format -> parse =====

from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from layoutdsl.syntax.ast import ClusterMember, Cluster, Connection, Hint, Obstacle, Position  # noqa: E402
from layoutdsl.syntax.ast import NO_SIZE, SIZES_PENDING  # noqa: E402

_SIZE_FIELDS = ("min_w", "max_w", "target_w", "min_h", "max_h", "target_h", "min_ar", "max_ar")

_numbers = st.floats(allow_nan=False, allow_infinity=False, width=64)
_weights = st.floats(0, 1e6)  # the language accepts only non-negative weights
_ids = st.from_regex(r"[A-Za-z_][A-Za-z0-9_\-.]{0,6}", fullmatch=True)
_words = st.from_regex(r"[A-Za-z0-9][A-Za-z0-9#=.\-]{0,5}", fullmatch=True)


@st.composite
def _specs(draw) -> Spec:
    ids = draw(st.lists(_ids, min_size=1, max_size=4, unique=True))
    rooms = tuple(
        Room(rid, *draw(st.lists(_numbers, min_size=8, max_size=8)), draw(st.sampled_from("RCE")),
             safe_label(" ".join(draw(st.lists(_words, min_size=1, max_size=3)))),
             draw(st.booleans()), draw(_weights), draw(_weights))
        for rid in ids
    )  # fmt: skip
    # some rooms sizeless (`id rtype label`): their sizes are the size model's to give
    rooms = tuple(
        replace(room, **dict.fromkeys(_SIZE_FIELDS, NO_SIZE), sizes_from=SIZES_PENDING)
        if draw(st.booleans()) else room for room in rooms
    )  # fmt: skip
    pick = st.sampled_from(ids)
    return Spec(
        "generated",
        rooms,
        Boundary(draw(_numbers), draw(_numbers), tuple(
            Obstacle(f"O{i}", *draw(st.lists(_numbers, min_size=4, max_size=4))) for i in range(draw(st.integers(0, 2)))
        )),
        tuple(Adjacency(draw(pick), draw(pick), draw(_numbers), draw(st.sampled_from("ei")))
              for _ in range(draw(st.integers(0, 3)))),
        tuple(Position(draw(pick), draw(_numbers), draw(_numbers)) for _ in range(draw(st.integers(0, 2)))),
        tuple(Connection(draw(pick), *draw(st.lists(_numbers, min_size=4, max_size=4)))
              for _ in range(draw(st.integers(0, 2)))),
        tuple(Cluster(f"K{i}", tuple(ClusterMember(draw(pick), draw(_numbers), draw(_numbers))
                                     for _ in range(draw(st.integers(1, 3)))))
              for i in range(draw(st.integers(0, 2)))),
        tuple(Hint(draw(pick), *draw(st.lists(_numbers, min_size=4, max_size=4))) for _ in range(draw(st.integers(0, 2)))),
        Settings(lambda_cover=draw(st.floats(0, 10)), seed=draw(st.integers(0, 2**31 - 1)),
                 kind=draw(st.sampled_from(["school", "office"])),
                 node_limit=draw(st.none() | st.integers(1, 10**6)),
                 emphasis=draw(st.sampled_from(["default", "heuristics", "easycip"]))),
    )  # fmt: skip


@settings(max_examples=300, deadline=None, derandomize=True)
@given(spec=_specs())
def test_generated_specs_round_trip(spec: Spec) -> None:
    """Structure only: the values need not make a sensible building, just survive the text."""
    again, diagnostics = parse_source(Source("generated.lay", format_spec(spec)))
    assert [d.message for d in diagnostics] == []
    assert again == spec


def test_arms_are_written_right_after_rooms() -> None:
    """An L-room's arm line reads next to its room line, whatever order the file used."""
    text = (
        "boundary\n14 12\n\narms\nC0 1.5 2.2 1.8 6 9 8 1 20\n\n"
        "rooms\nC0 11 14 12 1.5 2.2 1.8 1 20 C CORRIDOR\n"
    )
    spec, diagnostics = parse_source(Source("l.lay", text))
    assert diagnostics == []
    assert spec.arm("C0") is not None and spec.arm("C0").target_h == 8
    assert format_spec(spec).split("\n\n")[:2] == [
        "rooms\nC0 11 14 12 1.5 2.2 1.8 1 20 C CORRIDOR",
        "arms\nC0 1.5 2.2 1.8 6 9 8 1 20",
    ]
    assert parse_source(Source("l.lay", format_spec(spec)))[0] == spec
