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

DIAGNOSTICS = Path(__file__).resolve().parent
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


def rendered_codes(text: str) -> set[str]:
    """Codes shown as diagnostics in a snapshot (full, concise or JSON rendering), not codes
    merely mentioned, say in a comment of the spec echoed in a source excerpt."""
    full = re.findall(r"^(?:error|warning|info)\[([EWI]\d{3})\]", text, re.M)
    concise = re.findall(r"^\S+:\d+:\d+: ([EWI]\d{3}) ", text, re.M)
    json = re.findall(r'"code": "([EWI]\d{3})"', text)
    return {*full, *concise, *json}


def test_every_code_has_a_snapshot() -> None:
    """A documented code that no snapshot under tests/diagnostics/ renders fails."""
    shown: set[str] = set()
    for path in DIAGNOSTICS.rglob("*"):
        if path.suffix in (".txt", ".snap", ".json"):
            shown |= rendered_codes(path.read_text(encoding="utf-8", errors="replace"))
    missing = sorted(set(load_all_codes()) - shown)
    assert not missing, f"codes no snapshot under tests/diagnostics/ renders: {missing}"


def test_a_code_only_mentioned_does_not_count_as_a_snapshot() -> None:
    mentioned = "# E205 would be reported here\n 3 | R0 1 2  # not E206\n"
    assert rendered_codes(mentioned) == set()
    shown = 'error[E102]: x\nwarning[W301]: y\na.lay:1:2: E205 z\n[{"code": "E206"}]'
    assert rendered_codes(shown) == {"E102", "W301", "E205", "E206"}


def test_every_code_is_documented() -> None:
    for code, doc in load_all_codes().items():
        assert doc.title and doc.what_it_does and doc.why_bad and doc.example, code
