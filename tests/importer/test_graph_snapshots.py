"""Snapshots of what `layoutdsl import` prints for each malformed room graph (E430-E436).

Each case in tests/diagnostics/graphs/ is `<CODE>_<what>.csv|.json` next to `<CODE>_<what>.txt`:
the exact stderr of `layoutdsl import CASE -o OUT -q` run from that folder, then the exit
code. `pytest --update-goldens` rewrites them; review the diff.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from layoutdsl.cli import main

HERE = Path(__file__).resolve().parents[1] / "diagnostics" / "graphs"
CASES = sorted(p for p in HERE.iterdir() if p.suffix in (".csv", ".json", ".graphml"))


def test_every_graph_code_has_a_case() -> None:
    codes = {re.match(r"(E\d{3})_", case.name).group(1) for case in CASES}
    assert codes == {"E430", "E431", "E432", "E433", "E434", "E435", "E436"}


@pytest.mark.parametrize("case", CASES, ids=[case.stem for case in CASES])
def test_snapshot(case: Path, tmp_path: Path, monkeypatch, capsys, golden) -> None:
    out = tmp_path / "out.lay"
    monkeypatch.chdir(case.parent)
    status = main(["import", case.name, "-o", str(out), "-q"])
    actual = f"{capsys.readouterr().err}exit code: {status}\n"
    golden(case.with_suffix(".txt"), actual)
    code = case.name[:4]
    assert f"error[{code}]" in actual, "a case must show the code it is named after"
    assert status == 1 and not out.exists(), "a malformed graph writes nothing"
    assert "Traceback" not in actual
