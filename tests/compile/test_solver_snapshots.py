"""Snapshots of the E9xx and W9xx diagnostics (tests/diagnostics/solve/): the exact text and
exit code.

Each `X.lay` is compiled with `layoutdsl compile -q` plus the flags of its `# compile-args:`
line, and stderr is compared with `X.snap` ("exit N", "---", the diagnostics). A spec with a
sibling `X.layout.json` shows what compile reports when a layout fails verification (E903),
which a correct solver never produces on purpose: the compile command runs in-process with
the solver's result replaced by that layout's rectangles, so the whole path (compile,
verify, E903, exit code, nothing written) is the real one. `pytest --update-goldens`
rewrites the snapshots.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from layoutdsl.api import lint_source, read_source
from layoutdsl.cli import main
from layoutdsl.compile import explain, pipeline
from layoutdsl.diagnostics import exitcodes
from layoutdsl.layout import Layout
from layoutdsl.layout.verify import verify

ROOT = Path(__file__).resolve().parents[2]
SNAPSHOTS = Path("tests/diagnostics/solve")
SPECS = sorted((ROOT / SNAPSHOTS).glob("*.lay"))


def _compile_args(path: Path) -> list[str]:
    for line in path.read_text().splitlines():
        if line.startswith("# compile-args:"):
            return line.split(":", 1)[1].split()
    return []


def _run(relative: Path, tmp_path: Path, monkeypatch, capsys) -> tuple[int, str]:
    args = ["compile", str(relative), "-o", str(tmp_path), "-q", *_compile_args(ROOT / relative)]
    layout_json = ROOT / relative.with_suffix(".layout.json")
    if layout_json.exists():
        return _compile_with_a_broken_solution(args, relative, layout_json, monkeypatch, capsys)
    done = subprocess.run([sys.executable, "-m", "layoutdsl", *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)  # fmt: skip
    return done.returncode, done.stderr


def _compile_with_a_broken_solution(args, relative: Path, layout_json: Path, monkeypatch, capsys) -> tuple[int, str]:
    """Run compile, with every solution SCIP finds replaced by the layout in `layout_json`."""
    spec, diagnostics = lint_source(read_source(str(ROOT / relative)))
    assert spec is not None and not diagnostics
    broken = Layout.from_json(layout_json.read_text())
    assert verify(spec, broken), "the E903 example layout must fail verification"
    rects = {room.id: (room.x, room.y, room.w, room.h) for room in broken.rooms}
    # no construction (its start would be a correct answer), and SCIP's answer is the broken one
    monkeypatch.setattr(pipeline, "default_start_provider", lambda spec, options: None)
    monkeypatch.setattr(pipeline, "rects_from_model", lambda model: dict(rects))
    monkeypatch.chdir(ROOT)
    capsys.readouterr()
    code = main(args)
    return code, capsys.readouterr().err


@pytest.mark.parametrize("path", SPECS, ids=[p.stem for p in SPECS])
def test_solver_diagnostic_snapshot(path: Path, tmp_path: Path, golden, monkeypatch, capsys):
    relative = SNAPSHOTS / path.name
    code, stderr = _run(relative, tmp_path, monkeypatch, capsys)
    golden(path.with_suffix(".snap"), f"exit {code}\n---\n{stderr}")
    if path.stem.startswith(("E", "I")):  # an error, or a note that comes with one
        assert code == exitcodes.NO_LAYOUT
        assert not any(tmp_path.iterdir()), "no output may be written without a layout"
    else:  # a warning: the layouts are written all the same
        assert code == exitcodes.OK
        assert any(p.suffix == ".xml" for p in tmp_path.iterdir())


def test_every_solver_code_has_a_snapshot():
    codes = {c for c in explain.__dict__.values() if isinstance(c, str) and c[1:2] == "9" and len(c) == 4}
    shown = {p.stem.split("-")[0] for p in SPECS}
    assert codes == {"E901", "E902", "E903", "E904", "E905", "W906", "E908", "I909", "I910", "I911", "E912", "I912"}
    assert codes <= shown
