"""`layoutdsl sizes fit` and `sizes show`."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from layoutdsl.cli import main
from layoutdsl.sizes import load_model
from layoutdsl.sizes.fit import fit_folder

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "floorplans"


def test_fit_writes_the_model_fit_folder_gives_and_it_loads(tmp_path: Path) -> None:
    out = tmp_path / "model.json"
    assert main(["sizes", "fit", str(EXAMPLES), "-o", str(out), "-q"]) == 0
    assert out.read_text() == fit_folder(EXAMPLES).dumps()
    model = load_model(out)
    assert model.corpus == "floorplans" and set(model.kinds) == {"school", "office"}


def test_fit_skips_a_plan_that_does_not_import_and_says_so(tmp_path: Path, capsys) -> None:
    folder = tmp_path / "plans"
    folder.mkdir()
    shutil.copy(EXAMPLES / "school_Sabadell3.xml", folder)
    (folder / "school_broken.xml").write_text("<building>")
    assert main(["sizes", "fit", str(folder), "-o", str(tmp_path / "m.json"), "--format", "json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["skipped"] == ["school_broken.xml"] and result["kinds"]["school"]["plans"] == 1


def test_fit_without_plans_is_a_usage_error(tmp_path: Path, capsys) -> None:
    assert main(["sizes", "fit", str(tmp_path)]) == 2
    assert "no *.xml plan" in capsys.readouterr().err
    assert main(["sizes", "fit", str(tmp_path / "missing")]) == 2
    assert main(["sizes", "fit"]) == 2


def test_show_lists_every_label_with_its_typical_size(capsys) -> None:
    assert main(["sizes", "show", "--like", "school"]) == 0
    out = capsys.readouterr().out
    model = load_model()
    for label in model.kind("school").by_label:
        assert f"\n{label} " in out
    classroom = model.room_sizes("school", "R", "CLASSROOM")
    assert f"{classroom.target_w:g} x {classroom.target_h:g}" in out
    assert main(["sizes", "show", "--like", "castle"]) == 2
