"""Snapshots of the E9xx diagnostics (tests/diagnostics/solve/): the exact text and exit code.

Each `X.lay` is compiled with `layoutdsl compile -q` plus the flags of its `# compile-args:`
line, and stderr is compared with `X.snap` ("exit N", "---", the diagnostics). A spec with a
sibling `X.layout.json` instead shows what compile reports when a layout fails verification
(E903), which a correct solver never produces on purpose. Set LAYOUTDSL_UPDATE_GOLDENS=1 (or
pass --update-goldens when the suite defines it) to rewrite the snapshots.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from layoutdsl.compile import explain
from layoutdsl.diagnostics import exitcodes
from layoutdsl.api import lint_source, read_source
from layoutdsl.layout import Layout
from layoutdsl.diagnostics.render import render_full
from layoutdsl.layout.verify import verify

ROOT = Path(__file__).resolve().parents[2]
SNAPSHOTS = Path("tests/diagnostics/solve")
SPECS = sorted((ROOT / SNAPSHOTS).glob("*.lay"))


def _compile_args(path: Path) -> list[str]:
    for line in path.read_text().splitlines():
        if line.startswith("# compile-args:"):
            return line.split(":", 1)[1].split()
    return []


def _run(relative: Path, tmp_path: Path) -> tuple[int, str]:
    layout_json = ROOT / relative.with_suffix(".layout.json")
    if layout_json.exists():
        source = read_source(str(relative))
        spec, diagnostics = lint_source(source)
        assert spec is not None and not diagnostics
        violations = verify(spec, Layout.from_json(layout_json.read_text()))
        assert violations, "the E903 example layout must fail verification"
        text = render_full([explain.verification_failed(spec, violations)], {source.path: source})
        return exitcodes.NO_LAYOUT, text
    command = [sys.executable, "-m", "layoutdsl", "compile", str(relative), "-o", str(tmp_path), "-q",
               *_compile_args(ROOT / relative)]
    done = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=120)
    return done.returncode, done.stderr


@pytest.mark.parametrize("path", SPECS, ids=[p.stem for p in SPECS])
def test_solver_diagnostic_snapshot(path: Path, tmp_path: Path, golden):
    relative = SNAPSHOTS / path.name
    code, stderr = _run(relative, tmp_path)
    golden(path.with_suffix(".snap"), f"exit {code}\n---\n{stderr}")
    assert code == exitcodes.NO_LAYOUT
    assert not any(tmp_path.iterdir()), "no output may be written without a layout"


def test_every_solver_code_has_a_snapshot():
    codes = {c for c in explain.__dict__.values() if isinstance(c, str) and c[:2] == "E9" and len(c) == 4}
    shown = {p.stem.split("-")[0] for p in SPECS}
    assert codes == {"E901", "E902", "E903", "E904"}
    assert codes <= shown
