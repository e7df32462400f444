"""specs/*.lay are exactly what bench/planted_specs.py derives from verified planted layouts."""

from __future__ import annotations

import importlib.util
from dataclasses import replace
from pathlib import Path

import pytest

from layoutdsl.check import check_spec
from layoutdsl.syntax.format import format_spec
from layoutdsl.layout.verify import verify

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("planted_specs", ROOT / "bench" / "planted_specs.py")
planted = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(planted)


@pytest.mark.parametrize("name", sorted(planted.BUILDERS))
def test_spec_file_comes_from_a_verified_planted_layout(name: str) -> None:
    spec, layout, header = planted.BUILDERS[name]()
    path = ROOT / "specs" / f"{name}.lay"
    spec = replace(spec, path=str(path))
    assert verify(spec, layout) == []
    assert check_spec(spec) == []
    assert path.read_text(encoding="utf-8") == header + "\n" + format_spec(spec)
    rooms_area = sum(r.target_w * r.target_h for r in (*spec.rooms, *spec.arms))
    assert 1.3 <= spec.boundary.w * spec.boundary.h / rooms_area <= 1.6


def test_the_verifier_would_catch_a_broken_planted_layout() -> None:
    """Guard against a vacuous check: move one room onto another and verify must object."""
    spec, layout, _ = planted.office_small()
    first, second, *rest = layout.rooms
    on_top = replace(second, x=first.x, y=first.y)
    moved = replace(layout, rooms=(first, on_top, *rest))
    assert any(v.rule == "overlap" for v in verify(spec, moved))
