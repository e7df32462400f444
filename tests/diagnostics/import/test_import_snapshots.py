"""Snapshots of what `layoutdsl import` prints for each E4xx/W4xx code.

Each case is `<CODE>-<what>.xml` (an input; E408's is a directory) next to
`<CODE>-<what>.snap`: the exit code on the first line, then the exact stderr. Rewrite the
snapshots with `LAYOUTDSL_UPDATE_GOLDENS=1` (or `--update-goldens` where the suite defines
that option) and review the diff.
"""

from __future__ import annotations

import contextlib
import io
import os
from pathlib import Path

import pytest

from layoutdsl.cli import main
from layoutdsl.diagnostics import CODES
from layoutdsl.importer import codes as import_codes

HERE = Path(__file__).parent
REPO = HERE.parents[2]
CASES = sorted(HERE.glob("*.xml"))


def _update_goldens(config) -> bool:
    try:
        if config.getoption("--update-goldens"):
            return True
    except ValueError:
        pass  # the option is defined by another part of the suite, or not at all
    return os.environ.get("LAYOUTDSL_UPDATE_GOLDENS") == "1"


def _run_import(case: Path, tmp_path: Path) -> str:
    """Run the command as a user would from the repository root; exit code + stderr."""
    stderr = io.StringIO()
    cwd = os.getcwd()
    os.chdir(REPO)
    try:
        with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            status = main(["import", str(case.relative_to(REPO)), "-o", str(tmp_path / "out.lay"), "-q"])
    finally:
        os.chdir(cwd)
    return f"exit {status}\n---\n{stderr.getvalue()}"


@pytest.mark.parametrize("case", CASES, ids=[case.stem for case in CASES])
def test_snapshot(case: Path, tmp_path: Path, request):
    actual = _run_import(case, tmp_path)
    snapshot = case.with_suffix(".snap")
    if _update_goldens(request.config) or not snapshot.exists():
        snapshot.write_text(actual)
        if not _update_goldens(request.config):
            pytest.fail(f"wrote missing snapshot {snapshot.name}; review and commit it")
    assert actual == snapshot.read_text()
    code = case.name.split("-", 1)[0]
    assert f"[{code}]" in actual, "a case must show the code it is named after"
    # an error writes nothing; a warning still writes the spec
    assert (tmp_path / "out.lay").exists() == code.startswith("W")


def test_every_import_code_has_a_snapshot():
    importer_codes = {
        value for name, value in vars(import_codes).items() if name.isupper() and value in CODES
    }
    covered = {case.name.split("-", 1)[0] for case in CASES}
    assert importer_codes, "the importer registers its codes"
    assert sorted(importer_codes - covered) == []
