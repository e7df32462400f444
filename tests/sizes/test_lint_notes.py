"""Snapshots of `layoutdsl lint` on sizeless specs: I441 (where the sizes came from), I442
(the boundary chosen), E440 (an unknown building kind). The cases live in
tests/diagnostics/sizes/ beside their snapshots; `pytest --update-goldens` rewrites them."""

from __future__ import annotations

from pathlib import Path

import pytest

from layoutdsl.cli import main

HERE = Path(__file__).resolve().parents[1] / "diagnostics" / "sizes"
CASES = sorted(HERE.glob("*.lay"))


def lint_output(case: Path, monkeypatch, capsys, *extra: str) -> tuple[int, str]:
    monkeypatch.chdir(case.parent)
    status = main(["lint", case.name, *extra])
    return status, capsys.readouterr().out


@pytest.mark.parametrize("case", CASES, ids=[case.stem for case in CASES])
def test_snapshot(case: Path, monkeypatch, capsys, golden) -> None:
    status, out = lint_output(case, monkeypatch, capsys)
    golden(case.with_suffix(".txt"), f"{out}exit code: {status}\n")


def test_notes_name_every_sizeless_room_and_never_fail_lint(monkeypatch, capsys) -> None:
    case = HERE / "I441_I442_sizeless_rooms.lay"
    status, out = lint_output(case, monkeypatch, capsys, "--warnings-as-errors")
    assert status == 0, "notes are not problems, not even with --warnings-as-errors"
    assert "info[I441]: 4 rooms take their sizes from the school size model" in out
    for room in ("R1 (R CLASSROOM)", "R2 (R CLASSROOM)", "C1 (C CORRIDOR)", "E1 (E ENTRANCE)"):
        assert f"note: {room}: " in out, room
    assert "school, label CLASSROOM (" in out  # the group the sizes come from
    assert "corridor with 3 doors" in out  # C1 has three adjacencies
    assert "info[I442]: no `boundary` section" in out
    assert out.rstrip().endswith("no problems found (2 notes)")


def test_unknown_kind_is_an_error_at_the_setting(monkeypatch, capsys) -> None:
    status, out = lint_output(HERE / "E440_unknown_kind.lay", monkeypatch, capsys)
    assert status == 1
    assert "error[E440]: unknown building kind `hospital`" in out
    assert "E440_unknown_kind.lay:9:6" in out  # the value of `kind hospital`
