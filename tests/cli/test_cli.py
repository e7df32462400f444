"""`layoutdsl lint` and `layoutdsl fmt` as a user runs them (subprocess)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DIAGNOSTICS = ROOT / "tests" / "diagnostics"
GOOD = "rooms\nR0 4 6 5 3 5 4 1 2 R OFFICE\nR1 4 6 5 3 5 4 1 2 R OFFICE\n\nboundary\n12 14\n\nadjacencies\nR0 R1 0.9 e\n"


def run(*args: str, stdin: str | None = None, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "layoutdsl", *args], input=stdin, capture_output=True, text=True, cwd=cwd
    )


def test_lint_specs_exit_zero() -> None:
    result = run("lint", *sorted(str(p) for p in (ROOT / "specs").glob("*.lay")))
    assert result.returncode == 0, result.stdout
    assert result.stdout == "no problems found\n"


def test_lint_errors_exit_one_and_print_to_stdout() -> None:
    result = run("lint", "E102_unknown_adjacent_room.lay", cwd=DIAGNOSTICS)
    assert result.returncode == 1
    assert "error[E102]: room `R0` is adjacent to unknown room `C1`" in result.stdout
    assert result.stderr == ""


def test_warnings_exit_zero_unless_warnings_as_errors() -> None:
    assert run("lint", "W301_several_components.lay", cwd=DIAGNOSTICS).returncode == 0
    assert run("lint", "--warnings-as-errors", "W301_several_components.lay", cwd=DIAGNOSTICS).returncode == 1


def test_concise_format() -> None:
    result = run("lint", "--format", "concise", "several_errors_at_once.lay", cwd=DIAGNOSTICS)
    lines = result.stdout.splitlines()
    assert lines[0] == "several_errors_at_once.lay:3:21: E003 line ends after `rtype`: missing `label`"
    assert lines[-1] == "found 4 errors"


def test_json_format_has_ruff_shape() -> None:
    result = run("lint", "--format", "json", "E005_expected_number.lay", cwd=DIAGNOSTICS)
    document = json.loads(result.stdout)  # one result object, its diagnostics in ruff's shape
    assert document["command"] == "lint" and document["status"] == "errors" and document["exit_code"] == 1
    items = document["diagnostics"]
    assert result.returncode == 1
    assert set(items[0]) == {"code", "severity", "message", "filename", "location", "end_location", "help"}
    assert items[0]["location"] == {"row": 2, "column": 8}
    assert items[0]["end_location"] == {"row": 2, "column": 12}
    assert [i["code"] for i in items] == ["E005", "E005", "E005"]


def test_stdin_with_filename() -> None:
    result = run("lint", "--format", "concise", "--stdin-filename", "mine.lay", "-",
                 stdin=GOOD.replace("R0 R1", "R0 R9"))  # fmt: skip
    assert result.returncode == 1
    assert "mine.lay:9:4: E102 room `R0` is adjacent to unknown room `R9`" in result.stdout


def test_missing_file_is_exit_two() -> None:
    result = run("lint", "does-not-exist.lay")
    assert result.returncode == 2
    assert result.stderr == "layoutdsl lint: error: cannot read `does-not-exist.lay`: no such file or directory\n"
    assert "no problems found" not in result.stdout


def test_binary_file_is_exit_two_not_a_traceback(tmp_path: Path) -> None:
    path = tmp_path / "bin.lay"
    path.write_bytes(b"rooms\n\xff\xfe\x00")
    result = run("lint", str(path))
    assert result.returncode == 2
    assert "Traceback" not in result.stderr


def test_no_command_and_bad_flag_are_usage_errors() -> None:
    assert run().returncode == 2
    assert run("lint", "--format", "xml", "x.lay").returncode == 2


def test_help_lists_exit_codes() -> None:
    out = run("lint", "--help").stdout
    assert "exit codes:" in out and "1  the input has errors" in out
    assert "\n  3  " not in out  # lint cannot return 3 (no layout)


def test_fmt_prints_check_and_write(tmp_path: Path) -> None:
    messy = "rooms\nR0   4.0 6 5 3 5 4 1 2 R  OFFICE  # big\nR1 4 6 5 3 5 4 1 2 R OFFICE\n\nadjacencies\nR0 R1 .9 e\n\nboundary\n12 14\n"
    path = tmp_path / "messy.lay"
    path.write_text(messy)
    printed = run("fmt", str(path))
    assert printed.returncode == 0
    assert printed.stdout.splitlines()[1] == "R0 4 6 5 3 5 4 1 2 R OFFICE  # big"
    assert run("fmt", "--check", str(path)).returncode == 1
    written = run("fmt", "--write", str(path))
    assert written.returncode == 0
    assert path.read_text() == printed.stdout
    assert run("fmt", "--check", str(path)).returncode == 0


def test_fmt_refuses_a_spec_with_errors(tmp_path: Path) -> None:
    path = tmp_path / "bad.lay"
    path.write_text("rooms\nR0 4 6\n")
    result = run("fmt", "--write", str(path))
    assert result.returncode == 1
    assert "E003" in result.stderr
    assert path.read_text() == "rooms\nR0 4 6\n"  # untouched


def test_an_internal_error_is_one_clear_line_and_exit_2(monkeypatch, capsys):
    from layoutdsl import cli
    from layoutdsl.cli import lint

    def broken(_args):
        raise RuntimeError("boom")

    monkeypatch.delenv("LAYOUTDSL_TRACEBACK", raising=False)
    monkeypatch.setattr(lint, "run", broken)
    assert cli.main(["lint", "specs/office_small.lay"]) == 2
    err = capsys.readouterr().err
    assert "internal error: RuntimeError: boom" in err
    assert "Traceback" not in err
