"""Generated plans read back: the XML emitter's golden files go through the same reader.

A layout written as building XML and imported again must give back its rooms (as hints, at
their places; as targets, at their sizes) and its portal graph. This ties the importer's
frame conversion (y down in the file, y up in specs) to the emitter's.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from layoutdsl.importer import ImportOptions, import_building, read_building, room_ids
from layoutdsl.layout import Layout

EMIT_CASES = sorted(p.parent for p in (Path(__file__).parents[1] / "emit").glob("*/expected.xml"))


def test_there_are_emitted_plans_to_read():
    assert EMIT_CASES, "tests/emit/*/expected.xml are the XML emitter's golden files"


@pytest.mark.parametrize("case", EMIT_CASES, ids=[case.name for case in EMIT_CASES])
def test_emitted_plan_imports_back_to_its_layout(case: Path):
    layout = Layout.from_json((case / "layout.json").read_text())
    building, diagnostics = read_building(case / "expected.xml")
    assert diagnostics == []
    spec, diagnostics = import_building(case / "expected.xml", ImportOptions(hints=True))
    assert spec is not None and not any(d.is_error for d in diagnostics)
    ids = room_ids(building)  # emitted space ids are the layout's room ids
    origin_x = min(room.x for room in layout.rooms)
    origin_y = min(room.y for room in layout.rooms)
    hints = {hint.room: hint for hint in spec.hints}
    for placed in layout.rooms:
        room = spec.room(ids[placed.id])
        assert (room.rtype, room.label) == (placed.rtype, placed.label)
        assert (room.target_w, room.target_h) == pytest.approx((placed.w, placed.h), abs=0.011)
        hint = hints[room.id]
        assert (hint.x, hint.y, hint.w, hint.h) == pytest.approx(
            (placed.x - origin_x, placed.y - origin_y, placed.w, placed.h), abs=0.011
        )
    expected = {frozenset((ids[p.a], ids[p.b])): p.kind for p in layout.portals}
    assert {frozenset((a.a, a.b)): a.kind for a in spec.adjacencies} == expected
