"""Snapshots of what `layoutdsl import` prints for each E4xx/W4xx code.

Each case is `<CODE>_<what>.xml` (an input; E408's is a directory) next to
`<CODE>_<what>.txt`: the exact stderr of `layoutdsl import <CODE>_<what>.xml -o OUT -q` run
from this folder, followed by the exit code, as the spec snapshots in ../ hold them.
`pytest --update-goldens` rewrites them; review the diff.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from layoutdsl.cli import main
from layoutdsl.diagnostics import CODES
from layoutdsl.importer import codes as import_codes

HERE = Path(__file__).resolve().parent
CASES = sorted(HERE.glob("*.xml"))


def import_output(case: Path, out: Path, monkeypatch, capsys) -> str:
    monkeypatch.chdir(case.parent)
    status = main(["import", case.name, "-o", str(out), "-q"])
    return f"{capsys.readouterr().err}exit code: {status}\n"


@pytest.mark.parametrize("case", CASES, ids=[case.stem for case in CASES])
def test_snapshot(case: Path, tmp_path: Path, monkeypatch, capsys, golden):
    out = tmp_path / "out.lay"
    actual = import_output(case, out, monkeypatch, capsys)
    golden(case.with_suffix(".txt"), actual)
    code = re.match(r"([EW]\d{3})_", case.name).group(1)
    if code == import_codes.UNREADABLE_FILE:
        # the CLI reports an unreadable input in the one I/O error style of every command
        # (exit 2, no invented location); E408 is what the API (read_building) returns
        assert actual.startswith("layoutdsl import: error: cannot read `E408_directory.xml`: is a directory\n")
        return
    assert f"[{code}]" in actual, "a case must show the code it is named after"
    # an error writes nothing; a warning still writes the spec
    assert out.exists() == code.startswith("W")


def test_e408_from_the_api(monkeypatch, golden):
    """read_building's own diagnostic for an unreadable file, which the CLI never shows."""
    from layoutdsl.diagnostics.render import render_full
    from layoutdsl.importer import read_building

    monkeypatch.chdir(HERE)
    building, diagnostics = read_building("E408_directory.xml")
    assert building is None and [d.code for d in diagnostics] == ["E408"]
    golden(HERE / "E408_directory.api.txt", render_full(diagnostics, {}))


def test_every_import_code_has_a_snapshot():
    importer_codes = {
        value for name, value in vars(import_codes).items() if name.isupper() and value in CODES
    }
    covered = {case.name.split("_", 1)[0] for case in CASES}
    assert len(importer_codes) == 17
    assert sorted(importer_codes - covered) == []
