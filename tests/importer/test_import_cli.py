"""`layoutdsl import`: output file or stdout, options, exit codes, atomic writes."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from layoutdsl.diagnostics import exitcodes
from layoutdsl.api import lint_source
from layoutdsl.cli import main
from layoutdsl.diagnostics.source import Source

from real_plans import EXAMPLES as FIXTURES
LAMUNIERE = FIXTURES / "school_Lamuniere1.xml"


def _lint_file(path: Path):
    return lint_source(Source(str(path), path.read_text()))


def test_writes_a_spec_that_lints_clean_and_reports_on_stderr(tmp_path, capsys):
    out = tmp_path / "lamuniere.lay"
    assert main(["import", str(LAMUNIERE), "-o", str(out), "--keep-arrangement"]) == exitcodes.OK
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err == f"imported 8 rooms (1 L-shaped) and 7 adjacencies into `{out}`\n"
    spec, diagnostics = _lint_file(out)
    assert [d for d in diagnostics if d.is_error] == []
    assert spec.name == "lamuniere" and len(spec.rooms) == 8 and len(spec.hints) == 8
    text = out.read_text()
    assert text.startswith("rooms\nR0 ") and "\nboundary\n" in text and "\nadjacencies\nR0 C0 0.9 e\n" in text
    assert "settings" not in text  # a plain thesis file plus hints
    assert list(tmp_path.iterdir()) == [out]  # no temporary file left behind
    capsys.readouterr()
    assert main(["fmt", "--check", str(out)]) == exitcodes.OK  # already in canonical form


def test_stdout_output_and_options(capsys):
    # (no --no-hints: deprecated, it warns on stderr; tests/cli/test_convention.py covers it)
    argv = ["import", str(LAMUNIERE), "-o", "-", "--var-plus", "0.5", "--mindim", "0.5", "-q"]
    assert main(argv) == exitcodes.OK
    captured = capsys.readouterr()
    assert captured.err == ""
    assert "hints" not in captured.out
    spec, diagnostics = lint_source(Source("lamuniere.lay", captured.out))
    assert [d for d in diagnostics if d.is_error] == []
    classroom = spec.room("R0")
    assert classroom.max_w / classroom.target_w == pytest.approx(1 + 0.5 / 0.97, abs=0.02)


def test_stdin_input_with_a_name_for_messages(monkeypatch, capsys):
    import io

    text = LAMUNIERE.read_text().replace("<type>E</type>", "<type>Z</type>")
    monkeypatch.setattr(sys, "stdin", io.StringIO(text))
    status = main(["import", "-", "--stdin-filename", "plan.xml", "--format", "concise", "-q"])
    captured = capsys.readouterr()
    assert status == exitcodes.OK
    assert captured.err.startswith("plan.xml:") and " W420 space " in captured.err
    assert captured.out.startswith("rooms\n")
    assert "\nR5 " in captured.out and " R STAIRS\n" in captured.out  # the unknown type became R


def test_errors_exit_1_and_write_nothing(tmp_path, capsys):
    bad = tmp_path / "bad.xml"
    bad.write_text(LAMUNIERE.read_text().replace("<um>cm</um>", "<um>m</um>"))
    out = tmp_path / "bad.lay"
    out.write_text("previous content\n")
    assert main(["import", str(bad), "-o", str(out)]) == exitcodes.SPEC_ERRORS
    err = capsys.readouterr().err
    assert "error[E406]: implausible door size 90 m" in err
    assert out.read_text() == "previous content\n"  # untouched


def test_json_diagnostics(tmp_path, capsys):
    import json

    bad = tmp_path / "bad.xml"
    bad.write_text("<building>\n<scale>\n</building>\n")
    assert main(["import", str(bad), "--format", "json"]) == exitcodes.SPEC_ERRORS
    result = json.loads(capsys.readouterr().out)  # the one result object of --format json
    assert result["status"] == "errors" and result["written"] == []
    (item,) = result["diagnostics"]
    assert (item["code"], item["location"]) == ("E400", {"row": 3, "column": 3})


@pytest.mark.parametrize(
    "argv",
    [["--var-minus", "1.5"], ["--mindim", "0"], ["--var-plus", "-1"]],
)
def test_invalid_options_are_usage_errors(argv, capsys):
    assert main(["import", str(LAMUNIERE), *argv]) == exitcodes.USAGE
    assert "layoutdsl import: error:" in capsys.readouterr().err


def test_io_errors_are_exit_2(tmp_path, capsys):
    assert main(["import", str(tmp_path / "missing.xml")]) == exitcodes.USAGE
    # the one I/O error style of every command (no E408 with an invented location)
    assert capsys.readouterr().err == (f"layoutdsl import: error: cannot read `{tmp_path / 'missing.xml'}`: "
                                       "no such file or directory\n")
    (tmp_path / "a-file").write_text("")
    unwritable = tmp_path / "a-file" / "out.lay"  # a missing folder is created; one under a file cannot be
    assert main(["import", str(LAMUNIERE), "-o", str(unwritable)]) == exitcodes.USAGE
    assert "cannot write" in capsys.readouterr().err


def test_runs_as_a_program(tmp_path):
    out = tmp_path / "milano.lay"
    result = subprocess.run(
        [sys.executable, "-m", "layoutdsl", "import", str(FIXTURES / "office_Milano-1.xml"), "-o", str(out)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 0, result.stderr
    assert "imported 17 rooms (2 L-shaped) and 16 adjacencies" in result.stderr
    assert out.read_text().count("\n") > 17


def test_same_plan_gives_the_same_bytes(tmp_path):
    first, second = tmp_path / "a" / "plan.lay", tmp_path / "b" / "plan.lay"
    for out in (first, second):
        out.parent.mkdir()
        assert main(["import", str(FIXTURES / "school_VarzeaPaulistaFDE2.xml"), "-o", str(out), "-q"]) == 0
    assert first.read_bytes() == second.read_bytes()
