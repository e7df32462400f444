"""Every bad spec in tests/diagnostics/ renders exactly its snapshot, and every code has one.

A snapshot `<name>.txt` beside `<name>.lay` holds what `layoutdsl lint <name>.lay` prints
(run from that folder) followed by the exit code. `pytest --update-goldens` rewrites them.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from layoutdsl.cli import main
from layoutdsl.diagnostics import load_all_codes

DIAGNOSTICS = Path(__file__).resolve().parent.parent / "diagnostics"
CASES = sorted(DIAGNOSTICS.glob("*.lay"))


def lint_output(case: Path, monkeypatch, capsys) -> str:
    monkeypatch.chdir(case.parent)
    code = main(["lint", case.name])
    out = capsys.readouterr().out
    return f"{out}exit code: {code}\n"


def test_there_are_at_least_thirty_bad_specs() -> None:
    assert len(CASES) >= 30


@pytest.mark.parametrize("case", CASES, ids=[c.stem for c in CASES])
def test_snapshot(case: Path, monkeypatch, capsys, golden) -> None:
    golden(case.with_suffix(".txt"), lint_output(case, monkeypatch, capsys))


@pytest.mark.parametrize("case", CASES, ids=[c.stem for c in CASES])
def test_bad_spec_is_reported(case: Path, monkeypatch, capsys) -> None:
    """A bad spec never lints clean: it gets at least one diagnostic."""
    output = lint_output(case, monkeypatch, capsys)
    assert "no problems found" not in output


def test_named_codes_appear_in_their_snapshot(monkeypatch, capsys) -> None:
    """`E205_...lay` really produces E205 (so a file name cannot lie about its case)."""
    for case in CASES:
        match = re.match(r"([EW]\d{3})_", case.name)
        if match:
            assert f"[{match.group(1)}]" in lint_output(case, monkeypatch, capsys), case.name


def test_every_code_has_a_snapshot() -> None:
    """A documented code without a snapshot anywhere under tests/diagnostics/ fails."""
    texts = [
        path.read_text(encoding="utf-8", errors="replace")
        for path in DIAGNOSTICS.rglob("*")
        if path.is_file() and path.suffix not in (".lay", ".xml")
    ]
    corpus = "\n".join(texts)
    missing = [code for code in sorted(load_all_codes()) if not re.search(rf"\b{code}\b", corpus)]
    assert not missing, f"codes with no snapshot under tests/diagnostics/: {missing}"


def test_every_code_is_documented() -> None:
    for code, doc in load_all_codes().items():
        assert doc.title and doc.what_it_does and doc.why_bad and doc.example, code
