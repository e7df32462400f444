"""One page per diagnostic code (layoutdsl/diagnostics/pages/), and `layoutdsl explain` prints it."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

from layoutdsl.cli import main
from layoutdsl.cli.explain import pages, severity, suggestion, title
from layoutdsl.diagnostics import load_all_codes

PACKAGE = Path(__file__).resolve().parents[2] / "layoutdsl"
CODE_LITERAL = re.compile(r"""["']([EWI]\d{3})["']""")


def codes_in_source() -> set[str]:
    """Every code the code base can emit: each quoted `E123`/`W123` in the package's Python."""
    found: set[str] = set()
    for path in PACKAGE.rglob("*.py"):
        found |= set(CODE_LITERAL.findall(path.read_text(encoding="utf-8")))
    return found


def test_the_source_scan_finds_codes_of_every_family() -> None:
    # guards the regex: a scan that found nothing would pass the next test vacuously
    families = {code[:2] for code in codes_in_source()}
    assert {"E0", "E1", "E2", "W3", "E4", "W4", "E9", "W9"} <= families


def test_every_code_the_code_base_can_emit_has_a_page() -> None:
    missing = sorted(codes_in_source() - set(pages()))
    assert not missing, f"codes without a page in layoutdsl/diagnostics/pages/: {missing}"


def test_every_page_is_a_code_the_code_base_has() -> None:
    orphans = sorted(set(pages()) - codes_in_source() - set(load_all_codes()))
    assert not orphans, f"pages of codes nothing emits or registers: {orphans}"


def test_each_page_agrees_with_the_registry() -> None:
    for code, doc in load_all_codes().items():
        page = pages()[code]
        assert page.startswith(f"# {code}: {doc.title}\n"), code
        assert severity(page) == doc.severity.value, code
        for heading in ("## What it does", "## Why is this bad?", "## Example"):
            assert heading in page, (code, heading)


def test_explain_prints_the_page(capsys) -> None:
    assert main(["explain", "e102"]) == 0
    out = capsys.readouterr().out
    assert out == pages()["E102"]
    assert "adjacency names an unknown room" in out


def test_explain_a_wrong_code_suggests_one_and_exits_2(capsys) -> None:
    assert main(["explain", "W102"]) == 2
    captured = capsys.readouterr()
    assert captured.err == "layoutdsl explain: error: no diagnostic code `W102`; did you mean `E102`?\n"
    assert captured.out == ""
    assert suggestion("E2O1", list(pages())) == "E201"
    assert suggestion("nonsense-words", list(pages())) is None


def test_explain_json_and_listing(capsys) -> None:
    assert main(["explain", "W301", "--format", "json"]) == 0
    record = json.loads(capsys.readouterr().out)
    assert record["command"] == "explain" and record["status"] == "ok" and record["exit_code"] == 0
    assert record["code"] == "W301" and record["severity"] == "warning"
    assert record["title"] == load_all_codes()["W301"].title and record["page"] == pages()["W301"]
    assert main(["explain"]) == 0
    listed = capsys.readouterr().out.splitlines()
    assert len(listed) == len(pages()) and listed[0].startswith("E001  error")
    assert title(pages()["E001"]) in listed[0]
    assert main(["explain", "--format", "json"]) == 0
    assert len(json.loads(capsys.readouterr().out)["codes"]) == len(pages())
    assert main(["explain", "nonsense", "--format", "json"]) == 2
    failed = json.loads(capsys.readouterr().out)
    assert failed["status"] == "usage_or_io_error" and failed["suggestion"] is None and failed["errors"]


def test_pages_ship_in_the_wheel_as_package_data() -> None:
    # explain reads them through importlib.resources, as an installed wheel would
    out = subprocess.run([sys.executable, "-m", "layoutdsl", "explain", "E901"], capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.startswith("# E901: ")
