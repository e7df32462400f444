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
from layoutdsl.emit.raster import rasterize_layout


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_building_xml_matches_golden(case: Path, golden) -> None:
    golden(case / "expected.xml", xml.render_xml(load_case(case)))


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_stage_world_matches_golden(case: Path, golden) -> None:
    layout = load_case(case)
    world = stage.render_world(layout, rasterize_layout(layout), case.name)
    golden(case / "expected.world", world)


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_drawing_list_matches_golden(case: Path, golden) -> None:
    data = png.drawing(load_case(case)).to_data()
    golden(case / "expected.png.json", json.dumps(data, indent=1) + "\n")


def test_there_are_golden_cases() -> None:
    assert {c.name for c in CASES} >= {"small_office", "thin_walls", "single_room"}
