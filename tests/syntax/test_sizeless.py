"""Sizeless room lines (`R1 R CLASSROOM`, `R2 CLASSROOM`), the `kind` setting and a spec
without a boundary: parsing, the size model filling them in, fmt, lint, and compile."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from layoutdsl.api import lint_source
from layoutdsl.cli import main
from layoutdsl.diagnostics.source import Source
from layoutdsl.sizes import load_model
from layoutdsl.sizes.boundary import choose_boundary
from layoutdsl.sizes.resolve import resolve_spec
from layoutdsl.syntax.format import format_source, format_spec
from layoutdsl.syntax.parser import parse_source

ROOT = Path(__file__).resolve().parents[2]
MODEL = load_model()

LABELS_ONLY = """\
# rooms with labels only: types and sizes from the size model, boundary chosen by the tool
rooms
C1 CORRIDOR
R1 CLASSROOM
R2 CLASSROOM
R3 LAB
R4 BATHROOM
E1 ENTRANCE onB

adjacencies
R1 C1 0.9 e
R2 C1 0.9 e
R3 C1 0.9 e
R4 C1 0.9 e
E1 C1 0.9 e
"""


def parse(text: str, path: str = "s.lay"):
    spec, diagnostics = parse_source(Source(path, text))
    assert spec is not None, diagnostics
    return spec


def test_the_forms_of_a_sizeless_line() -> None:
    spec = parse("rooms\nR1 R CLASSROOM\nR2 CLASSROOM onB\nC1 C\nE1 E ENTRANCE onB cover=2\nR9 R MEDIUM SERVICE\n")
    r1, r2, c1, e1, r9 = spec.rooms
    assert (r1.rtype, r1.label, r1.sizeless, r1.has_sizes) == ("R", "CLASSROOM", True, False)
    assert (r2.rtype, r2.label, r2.on_boundary) == ("", "CLASSROOM", True)  # type from the model later
    assert (c1.rtype, c1.label) == ("C", "CORRIDOR")  # a type alone gets its default label
    assert (e1.on_boundary, e1.rho_cover) == (True, 2.0)
    assert r9.label == "MEDIUM SERVICE"
    assert spec.boundary is None


@pytest.mark.parametrize(("line", "code", "col"), [
    ("R0 4,6 8 6 6 10 8 1 1.7 R CLASSROOM", "E005", 4),  # a typo in the first number
    ("R0 x 8 6 6 10 8 1 1.7 R CLASSROOM", "E005", 4),
    ("R0 4 8 6 6 10 8 1 R CLASSROOM", "E005", 19),        # one number short, as before
    ("R0", "E003", 3),
    ("R0 CLASSROOM covr=1", "E009", 14),
])  # fmt: skip
def test_sized_lines_with_mistakes_are_not_taken_for_labels(line: str, code: str, col: int) -> None:
    spec, diagnostics = parse_source(Source("s.lay", f"rooms\n{line}\n"))
    assert spec is None
    assert (diagnostics[0].code, diagnostics[0].span.line, diagnostics[0].span.col) == (code, 2, col)


def bundled_specs() -> list[Path]:
    found = {*ROOT.glob("specs/**/*.lay"), *ROOT.glob("examples/**/*.lay"), *ROOT.glob("tests/**/*.lay")}
    # written in the new syntax on purpose
    sizeless_cases = (ROOT / "tests" / "diagnostics" / "sizes", ROOT / "examples" / "sizeless")
    return sorted(p for p in found if not any(folder in p.parents for folder in sizeless_cases))


def test_no_existing_spec_changes_meaning() -> None:
    specs = bundled_specs()
    assert len(specs) >= 50
    for path in specs:
        spec, diagnostics = parse_source(Source(str(path), path.read_text(encoding="utf-8")))
        if spec is None:
            continue  # the deliberately broken examples
        assert not any(room.sizeless for room in spec.rooms), path
        assert spec.boundary is not None, path


def test_resolving_fills_sizes_types_and_the_boundary() -> None:
    spec, notes = resolve_spec(parse(LABELS_ONLY))
    assert [d.code for d in notes] == ["I441", "I442"] and not any(d.is_error for d in notes)
    rooms = {room.id: room for room in spec.rooms}
    # the types come from the labels
    assert [rooms[r].rtype for r in ("C1", "R1", "R2", "R3", "R4", "E1")] == ["C", "R", "R", "R", "R", "E"]
    expected = MODEL.room_sizes("school", "R", "CLASSROOM")
    assert (rooms["R1"].target_w, rooms["R1"].target_h, rooms["R1"].max_ar) == (
        expected.target_w, expected.target_h, expected.max_ar)
    corridor = MODEL.room_sizes("school", "C", "CORRIDOR", doors=5)
    assert rooms["C1"].target_w == corridor.target_w
    assert (spec.boundary.w, spec.boundary.h) == choose_boundary(spec.rooms) and spec.boundary.chosen
    assert len(notes[0].notes) == 6 and notes[0].notes[1].startswith("R1 (R CLASSROOM): 9.87 x 8.2 m")


def test_the_kind_setting_picks_the_model() -> None:
    office, _ = resolve_spec(parse(LABELS_ONLY + "\nsettings\nkind office\n"))
    school, _ = resolve_spec(parse(LABELS_ONLY))
    assert office.settings.kind == "office"
    assert office.room("R4").target_w == MODEL.room_sizes("office", "R", "BATHROOM").target_w
    assert office.room("R4").target_w != school.room("R4").target_w


def test_a_given_boundary_is_kept_and_sized_rooms_untouched() -> None:
    text = "rooms\nR1 R CLASSROOM\nR2 4 8 6 6 10 8 1 1.7 R OFFICE\n\nboundary\n30 20\n"
    spec, notes = resolve_spec(parse(text))
    assert [d.code for d in notes] == ["I441"]
    assert (spec.boundary.w, spec.boundary.h, spec.boundary.chosen) == (30, 20, False)
    assert spec.room("R2").target_w == 6 and spec.room("R2").sizes_from is None


def test_fmt_keeps_sizeless_lines_and_fill_sizes_writes_the_numbers() -> None:
    source = Source("s.lay", LABELS_ONLY)
    kept = format_source(source)
    assert "R1 CLASSROOM\n" in kept and "C1 CORRIDOR\n" in kept and "\nboundary\n" not in kept
    assert kept.startswith("# rooms with labels only")  # comments stay
    filled = format_source(source, resolve=resolve_spec)
    assert "\nboundary\n" in filled and "R2 CLASSROOM" not in filled
    # the filled spec is the resolved one, number for number
    resolved, _ = resolve_spec(parse(LABELS_ONLY))
    again = parse(filled)
    assert again.rooms == resolved.rooms
    assert (again.boundary.w, again.boundary.h) == (resolved.boundary.w, resolved.boundary.h)
    assert not any(room.sizeless for room in again.rooms)


def test_format_spec_round_trips_a_sizeless_spec() -> None:
    spec = parse(LABELS_ONLY + "\nsettings\nkind office\n")
    assert parse(format_spec(spec)) == spec
    resolved, _ = resolve_spec(spec)
    assert resolve_spec(parse(format_spec(resolved)))[0] == resolved


def test_the_fmt_command_fills_in_place(tmp_path: Path, capsys) -> None:
    path = tmp_path / "s.lay"
    path.write_text(LABELS_ONLY)
    assert main(["fmt", "--fill-sizes", "--write", str(path), "-q"]) == 0
    text = path.read_text()
    assert "R1 6.909 11.844 9.87 " in text and "\nboundary\n" in text
    assert main(["lint", str(path), "-q"]) == 0


def test_lint_without_sizes_reports_notes_and_no_error() -> None:
    spec, diagnostics = lint_source(Source("s.lay", LABELS_ONLY))
    assert spec is not None and spec.boundary is not None
    assert [d.severity.value for d in diagnostics] == ["info", "info"]


def test_a_boundary_section_without_size_is_still_an_error() -> None:
    spec, diagnostics = parse_source(Source("s.lay", "rooms\nR1 R CLASSROOM\n\nboundary\nO1 1 1 2 2\n"))
    assert spec is None and [d.code for d in diagnostics] == ["E016"]


def test_a_spec_of_labels_only_compiles_to_a_verified_layout(tmp_path: Path) -> None:
    spec_path = tmp_path / "labels.lay"
    spec_path.write_text(LABELS_ONLY)
    out = tmp_path / "out"
    assert main(["compile", str(spec_path), "-o", str(out), "--emit", "xml", "-q"]) == 0
    layout = json.loads((out / "labels.layout.json").read_text())
    width, height, wall = layout["width"], layout["height"], layout["walldim"]
    resolved, _ = resolve_spec(parse(LABELS_ONLY))
    # the layout lies in the boundary the tool chose (compile may report it trimmed to the rooms)
    assert width <= resolved.boundary.w + 1e-6 and height <= resolved.boundary.h + 1e-6
    rects = {r["id"]: (r["x"], r["y"], r["w"], r["h"]) for r in layout["rooms"]}
    assert set(rects) == set(resolved.room_ids)
    eps = 1e-6
    for rid, (x, y, w, h) in rects.items():
        room = resolved.room(rid)
        assert -eps <= x and -eps <= y and x + w <= width + eps and y + h <= height + eps, rid
        assert min(room.min_w, room.min_h) - eps <= min(w, h) and max(w, h) <= max(room.max_w, room.max_h) + eps, rid
    ids = sorted(rects)
    for i, a in enumerate(ids):  # no two rooms overlap
        for b in ids[i + 1:]:
            ax, ay, aw, ah = rects[a]
            bx, by, bw, bh = rects[b]
            assert ax + aw <= bx + eps or bx + bw <= ax + eps or ay + ah <= by + eps or by + bh <= ay + eps, (a, b)
    for adjacency in resolved.adjacencies:  # adjacent rooms share a wall long enough for the door
        ax, ay, aw, ah = rects[adjacency.a]
        bx, by, bw, bh = rects[adjacency.b]
        side_by_side = min(abs(ax + aw - bx), abs(bx + bw - ax)) <= wall + eps
        stacked = min(abs(ay + ah - by), abs(by + bh - ay)) <= wall + eps
        overlap_y = min(ay + ah, by + bh) - max(ay, by)
        overlap_x = min(ax + aw, bx + bw) - max(ax, bx)
        assert (side_by_side and overlap_y >= adjacency.door - eps) or (stacked and overlap_x >= adjacency.door - eps), adjacency
    x, y, w, h = rects["E1"]  # the entrance opens to the outside
    assert min(x, y, width - x - w, height - y - h) <= eps
