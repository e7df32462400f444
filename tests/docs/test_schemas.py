"""docs/schemas/*.json describe the real outputs: a real batch's manifest and layouts validate."""

from __future__ import annotations

import copy
import dataclasses
import json
import subprocess
import sys
from pathlib import Path

import pytest

jsonschema = pytest.importorskip("jsonschema", reason="the `test` extra installs jsonschema")

from layoutdsl.batch.manifest import RECORD_FIELDS  # noqa: E402
from layoutdsl.layout import Layout, PlacedRoom, Portal, SolveInfo  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
SCHEMAS = ROOT / "docs" / "schemas"
# A spec no layout satisfies (two rooms that must touch but must cover points 17 m apart):
# batch records it as failed, so the manifest has both kinds of record.
INFEASIBLE = """rooms
A 2 3 2.5 2 3 2.5 1 1.5 R OFFICE
B 2 3 2.5 2 3 2.5 1 1.5 R OFFICE

boundary
20 10

adjacencies
A B 0.9 e

positions
A 1 1
B 18 8
"""


def schema(name: str) -> dict:
    loaded = json.loads((SCHEMAS / f"{name}.schema.json").read_text(encoding="utf-8"))
    jsonschema.Draft202012Validator.check_schema(loaded)
    return loaded


def errors(name: str, instance) -> list[str]:
    validator = jsonschema.Draft202012Validator(schema(name))
    return [f"{list(e.absolute_path)}: {e.message}" for e in validator.iter_errors(instance)]


@pytest.fixture(scope="module")
def batch_output(tmp_path_factory) -> Path:
    """A real batch: an L-room spec, a spec with obstacles and hints, and one that fails."""
    folder = tmp_path_factory.mktemp("batch")
    (folder / "tight.lay").write_text(INFEASIBLE, encoding="utf-8")
    outdir = folder / "out"
    result = subprocess.run(
        [sys.executable, "-m", "layoutdsl", "batch", str(ROOT / "specs" / "l_corridor.lay"),
         str(ROOT / "specs" / "campus_constraints.lay"), str(folder / "tight.lay"),
         "-o", str(outdir), "--variants", "1", "-q"],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert result.returncode == 3, result.stderr  # one building failed, on purpose
    return outdir


def test_a_real_manifest_validates(batch_output: Path) -> None:
    records = [json.loads(line) for line in (batch_output / "manifest.jsonl").read_text().splitlines()]
    assert sorted(r["status"] for r in records) == ["done", "done", "failed"]
    for record in records:
        assert errors("manifest", record) == [], record["building"]


def test_real_layouts_validate(batch_output: Path) -> None:
    layouts = sorted(batch_output.rglob("*.layout.json"))
    assert len(layouts) == 2
    seen_arm = seen_obstacle = False
    for path in layouts:
        data = json.loads(path.read_text(encoding="utf-8"))
        assert errors("layout", data) == [], path.name
        seen_arm |= any("arm" in room for room in data["rooms"])
        seen_obstacle |= bool(data["obstacles"])
    assert seen_arm and seen_obstacle  # the optional parts of the schema were exercised


def test_the_schemas_reject_what_is_not_an_output(batch_output: Path) -> None:
    layout = json.loads(next(batch_output.rglob("*.layout.json")).read_text(encoding="utf-8"))
    for breakage in (lambda d: d.pop("rooms"), lambda d: d["rooms"][0].update(rtype="X"),
                     lambda d: d["portals"].append({"a": "R0"}), lambda d: d.update(extra=1)):  # fmt: skip
        broken = copy.deepcopy(layout)
        breakage(broken)
        assert errors("layout", broken)
    record = json.loads((batch_output / "manifest.jsonl").read_text().splitlines()[0])
    for breakage in (lambda r: r.update(status="ok"), lambda r: r.pop("seed"), lambda r: r.update(reason="x")):
        broken = copy.deepcopy(record)
        breakage(broken)
        assert errors("manifest", broken), breakage


def test_the_schemas_name_exactly_the_fields_the_code_writes() -> None:
    # catches a field added to the code and not to the schema without running a batch
    assert list(schema("manifest")["required"]) == list(RECORD_FIELDS)
    layout = schema("layout")["properties"]
    assert set(layout) == {f.name for f in dataclasses.fields(Layout)}
    assert set(layout["rooms"]["items"]["properties"]) == {f.name for f in dataclasses.fields(PlacedRoom)}
    assert set(layout["portals"]["items"]["properties"]) == {f.name for f in dataclasses.fields(Portal)}
    assert set(layout["solve"]["properties"]) == {f.name for f in dataclasses.fields(SolveInfo)}
