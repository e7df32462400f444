"""The README documents the language truthfully: its example lints clean, its code table is current."""

from __future__ import annotations

import re
from pathlib import Path

from layoutdsl.api import lint_source
from layoutdsl.diagnostics import load_all_codes
from layoutdsl.syntax.format import format_source
from layoutdsl.diagnostics.source import Source

README = Path(__file__).resolve().parents[1] / "README.md"
START, END = "<!-- codes:start -->", "<!-- codes:end -->"


def _cell(text: str) -> str:
    return " ".join(text.split()).replace("|", "\\|")


def codes_table() -> str:
    """The README's table of every registered code, generated from CODES."""
    rows = ["| code | severity | title | what it does | why is this bad? |", "|---|---|---|---|---|"]
    for code, doc in sorted(load_all_codes().items()):
        rows.append(f"| {code} | {doc.severity.value} | {_cell(doc.title)} | {_cell(doc.what_it_does)} | "
                    f"{_cell(doc.why_bad)} |")  # fmt: skip
    return "\n".join(rows)


def test_code_table_is_current(golden) -> None:
    # the README itself is the golden file; only its generated code table may differ
    text = README.read_text(encoding="utf-8")
    before, rest = text.split(START)
    _, after = rest.split(END)
    golden(README, f"{before}{START}\n{codes_table()}\n{END}{after}")


def test_complete_example_lints_clean_and_is_canonical() -> None:
    text = README.read_text(encoding="utf-8")
    section = text.split("### A complete example", 1)[1]
    example = re.search(r"```\n(.*?)```", section, re.S).group(1)
    source = Source("example.lay", example)
    spec, diagnostics = lint_source(source)
    assert diagnostics == []
    assert spec.positions and spec.connections and spec.clusters and spec.hints and spec.boundary.obstacles
    assert any(r.on_boundary for r in spec.rooms) and any(r.rho_cover != 1 for r in spec.rooms)
    assert format_source(source) == example


def test_readme_opens_with_two_commands_and_ci_runs_the_second():
    root = Path(__file__).resolve().parents[1]
    readme = (root / "README.md").read_text(encoding="utf-8")
    quick_start = readme.split("## Quick start", 1)[1]
    block = quick_start.split("```", 2)[1].strip().splitlines()
    assert len(block) == 2
    setup_and_compile, setup_and_test = block
    assert setup_and_compile.startswith("python3 -m venv .venv && ")
    spec = setup_and_compile.split("layoutdsl compile ", 1)[1].split()[0]
    assert (root / spec).is_file()
    assert setup_and_test.startswith("python3 -m venv .venv && ")
    ci_lines = (root / ".ci" / "run").read_text(encoding="utf-8").strip().splitlines()
    assert ci_lines[-1] == setup_and_test
