"""Golden files: the XML, world and drawing written for fixed, hand-made layouts.

Each folder beside this file with a `layout.json` is a case; `pytest --update-goldens`
rewrites its expected files after a deliberate change.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from _emit_support import CASES, load_case

from layoutdsl.emit import png, stage, xml
from layoutdsl.raster import rasterize_layout


def _check(path: Path, actual: str, update: bool) -> None:
    if update or not path.exists():
        if not update:
            pytest.fail(f"missing golden {path}; run pytest --update-goldens to create it")
        path.write_text(actual, encoding="utf-8")
        return
    assert actual == path.read_text(encoding="utf-8"), f"{path} differs (pytest --update-goldens to accept)"


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_building_xml_matches_golden(case: Path, update_goldens: bool) -> None:
    _check(case / "expected.xml", xml.render_xml(load_case(case)), update_goldens)


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_stage_world_matches_golden(case: Path, update_goldens: bool) -> None:
    layout = load_case(case)
    world = stage.render_world(layout, rasterize_layout(layout), case.name)
    _check(case / "expected.world", world, update_goldens)


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_drawing_list_matches_golden(case: Path, update_goldens: bool) -> None:
    data = png.drawing(load_case(case)).to_data()
    _check(case / "expected.png.json", json.dumps(data, indent=1) + "\n", update_goldens)


def test_there_are_golden_cases() -> None:
    assert {c.name for c in CASES} >= {"small_office", "thin_walls", "single_room"}
