"""`layoutdsl evaluate` as a user runs it: exit codes, diagnostics, report files."""

from __future__ import annotations

import json
import subprocess
import sys

from real_plans import EXAMPLES

SMALL_PLAN = EXAMPLES / "school_Lamuniere1.xml"


def _run(*args, cwd=None):
    return subprocess.run(
        [sys.executable, "-m", "layoutdsl", "evaluate", *map(str, args)],
        capture_output=True, text=True, cwd=cwd, timeout=300,
    )  # fmt: skip


def test_unreadable_xml_gives_a_located_diagnostic_and_exit_1(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text("<building>\n  <floor>\n</building>\n")
    out = tmp_path / "report"
    result = _run(bad, bad, "-o", out)
    assert result.returncode == 1
    assert "Traceback" not in result.stderr
    assert f"{bad}:3:" in result.stderr and "malformed XML" in result.stderr
    assert not out.exists()


def test_missing_file_is_a_diagnostic_not_a_traceback(tmp_path):
    result = _run(tmp_path / "nope.xml", tmp_path / "nope.xml", "-o", tmp_path / "r")
    assert result.returncode == 2  # the one I/O exit code of every command (issue 42)
    assert result.stderr.startswith(f"layoutdsl evaluate: error: cannot read `{tmp_path / 'nope.xml'}`: ")
    assert "Traceback" not in result.stderr


def test_bad_options_are_usage_errors(tmp_path):
    result = _run(SMALL_PLAN, SMALL_PLAN, "-o", tmp_path / "r", "--resolution", "-1")
    assert result.returncode == 2 and "positive" in result.stderr


def test_real_plan_against_itself_end_to_end(tmp_path):
    out = tmp_path / "report"
    result = _run(SMALL_PLAN, SMALL_PLAN, "-o", out, "--seed", "1", "-q")
    assert result.returncode == 0, result.stderr
    report = json.loads((out / "report.json").read_text())
    assert report["original"]["rooms"] == 8
    (generated,) = report["generated"]
    assert generated["topology"]["identical"]
    assert generated["deviation"]["room_area"] == 0
    exploration = report["original"]["exploration"]
    assert exploration["reached_target"] and exploration["final_coverage"] >= 0.99
    assert "| school_Lamuniere1 (original) | 8 | 7 |" in (out / "report.md").read_text()
    assert (out / "exploration.png").read_bytes()[:4] == b"\x89PNG"


def test_unknown_start_room_is_a_usage_error(tmp_path):
    result = _run(SMALL_PLAN, SMALL_PLAN, "-o", tmp_path / "r", "--start-room", "E9")
    assert result.returncode == 2 and "E9" in result.stderr


def test_the_realism_of_every_plan_is_printed_and_in_the_json_result(tmp_path):
    result = _run(SMALL_PLAN, SMALL_PLAN, "-o", tmp_path / "r", "--format", "json")
    assert result.returncode == 0, result.stderr
    payload = json.loads(result.stdout)
    # the same plan twice: both rows carry the same measures
    measures = list(payload["realism"].values())
    assert measures and measures[0]["rooms"] == 8 and measures[0]["void_share"] >= 0
    report = json.loads((tmp_path / "r" / "report.json").read_text())
    assert report["original"]["realism"] == measures[0]
    text = _run(SMALL_PLAN, SMALL_PLAN, "-o", tmp_path / "r2")
    assert "entrances open" in text.stderr and "rooms with an outside wall" in text.stderr
