"""Every spec in specs/ compiles to a layout the independent verifier accepts."""

from __future__ import annotations

from pathlib import Path

import pytest

from layoutdsl.layout.verify import verify

SPECS_DIR = Path(__file__).resolve().parents[2] / "specs"
SPEC_NAMES = sorted(path.stem for path in SPECS_DIR.glob("*.lay"))


def test_specs_folder_has_the_four_worked_examples():
    assert {"school_fig42", "office_small", "school_cycle", "campus_constraints"} <= set(SPEC_NAMES)


@pytest.mark.parametrize("name", SPEC_NAMES)
def test_bundled_spec_compiles_to_a_verified_layout(name, compiled_spec_layouts):
    spec, layout = compiled_spec_layouts[name]
    assert verify(spec, layout) == []
    assert {room.id for room in layout.rooms} == set(spec.room_ids)
    assert {frozenset((p.a, p.b)): p.kind for p in layout.portals} == {
        frozenset((a.a, a.b)): a.kind for a in spec.adjacencies
    }
