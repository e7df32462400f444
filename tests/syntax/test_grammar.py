"""The grammar: thesis-format text parses verbatim, and each SYNTAX_ERRORS example is named."""

from __future__ import annotations

import pytest
from lark.exceptions import UnexpectedInput

from layoutdsl.syntax import parser
from layoutdsl.syntax.parser import SYNTAX_ERRORS, get_parser, name_syntax_error, parse_source
from layoutdsl.diagnostics.source import Source

EXAMPLES = [
    (code, rule, example)
    for code, by_rule in SYNTAX_ERRORS.items()
    for rule, examples in by_rule.items()
    for example in examples
]


def test_grammar_loads_once() -> None:
    assert get_parser() is get_parser()


@pytest.mark.parametrize(("code", "rule", "example"), EXAMPLES)
def test_syntax_error_example_is_named_with_its_code(code: str, rule: str, example: str) -> None:
    with pytest.raises(UnexpectedInput) as caught:
        parser.parse_line(rule, example)
    assert name_syntax_error(rule, caught.value) == code


def test_thesis_figure_text_parses_verbatim() -> None:
    """Figure 4.2's layout: sections, blank lines, a multi-word label, comments, CRLF, tabs."""
    text = (
        "# intermediate model\r\n"
        "rooms\r\n"
        "R0 4.68 8.02 6.69 6.21 10.65 8.87 1 1.71 R CLASSROOM\r\n"
        "R8 1.84 3.16 2.64 2.97 5.09 4.24 1.22 2.0 R MEDIUM SERVICE\r\n"
        "C3\t3.21 7.84 5.53 15.99 39.03 27.51 3.11 6.84 C CORRIDOR   \r\n"
        "\r\n"
        "boundary\r\n"
        "21.342857142857145 51.94285714285714\r\n"
        "\r\n"
        "adjacencies\r\n"
        "R0 C3 0.9 e\r\n"
        "R8 C3 0.9 e\r\n"
    )
    spec, diagnostics = parse_source(Source("fig.lay", text))
    assert diagnostics == []
    assert spec.name == "fig"
    assert [r.id for r in spec.rooms] == ["R0", "R8", "C3"]
    assert spec.rooms[1].label == "MEDIUM SERVICE"
    assert spec.rooms[1].max_ar == 2.0
    assert spec.boundary.w == 21.342857142857145
    assert [(a.a, a.b, a.door, a.kind) for a in spec.adjacencies] == [("R0", "C3", 0.9, "e"), ("R8", "C3", 0.9, "e")]


def test_extensions_parse() -> None:
    text = """rooms
R0 4 6 5 3 5 4 1 2 R BIG OFFICE onB cover=0.5 error=0.25
R1 4 6 5 3 5 4 1 2 R onB

boundary
12 14
O1 0 0 1 1

clusters
K0
R0 0 0

K1
R1 1 1

hints
R0 0 2 5 4

settings
name tower
seed 9
node_limit 100
emphasis feasibility
"""
    spec, diagnostics = parse_source(Source("x.lay", text))
    assert diagnostics == []
    big, single = spec.rooms
    assert (big.label, big.on_boundary, big.rho_cover, big.rho_error) == ("BIG OFFICE", True, 0.5, 0.25)
    # `onB` alone is the label, not the flag: a label is required
    assert (single.label, single.on_boundary) == ("onB", False)
    assert [c.id for c in spec.clusters] == ["K0", "K1"]
    assert spec.hints[0].room == "R0"
    assert spec.name == "tower"
    assert (spec.settings.seed, spec.settings.node_limit, spec.settings.emphasis) == (9, 100, "feasibility")
    assert spec.settings.explicit == {"name", "seed", "node_limit", "emphasis"}


def test_spans_point_at_each_value() -> None:
    text = "rooms\n  R0 4 6 5 3 5 4 1 2 R OFFICE\n\nboundary\n12 14\n"
    spec, _ = parse_source(Source("x.lay", text))
    room = spec.rooms[0]
    assert (room.spans["id"].line, room.spans["id"].col, room.spans["id"].end_col) == (2, 3, 5)
    assert (room.spans["max_w"].col, room.spans["max_w"].end_col) == (8, 9)
    assert spec.boundary.spans["h"].col == 4


def test_stdin_name() -> None:
    spec, _ = parse_source(Source("<stdin>", "rooms\nR0 4 6 5 3 5 4 1 2 R OFFICE\n\nboundary\n12 14\n"))
    assert spec.name == "stdin"


def test_hash_inside_a_value_is_not_a_comment() -> None:
    spec, diagnostics = parse_source(Source("x.lay", "rooms\nR0 4 6 5 3 5 4 1 2 R ROOM#3 # a comment\n\nboundary\n12 14\n"))
    assert diagnostics == []
    assert spec.rooms[0].label == "ROOM#3"


def test_every_syntax_error_is_reported_not_only_the_first() -> None:
    text = "rooms\nR0 4 6\nR1 4 6 x 3 5 4 1 2 R A\nR2 4 6 5 3 5 4 1 2 R A\n\nboundary\n12\n"
    spec, diagnostics = parse_source(Source("x.lay", text))
    assert spec is None
    assert [(d.code, d.span.line) for d in diagnostics] == [("E003", 2), ("E005", 3), ("E003", 7)]


def test_grammar_is_found_inside_an_installed_package(tmp_path) -> None:
    """A wheel has the grammar beside the parser, at layoutdsl/syntax/layout.lark."""
    import shutil
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    package = tmp_path / "site" / "layoutdsl"
    shutil.copytree(root / "layoutdsl", package, ignore=shutil.ignore_patterns("__pycache__"))
    code = (
        "import layoutdsl.syntax.parser as p, sys; from layoutdsl.diagnostics.source import Source; "
        "spec, d = p.parse_source(Source('x.lay', 'rooms\\nR0 4 6 5 3 5 4 1 2 R A\\n\\nboundary\\n12 14\\n')); "
        "print(p._grammar_path()); sys.exit(0 if spec and not d else 1)"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True,
        env={"PYTHONPATH": str(tmp_path / "site")},
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == str(package / "syntax" / "layout.lark")


def test_parsing_in_threads_keeps_each_files_lines_and_diagnostics_apart() -> None:
    """The builder's per-line state belongs to each parse call, not to the process."""
    from concurrent.futures import ThreadPoolExecutor

    def parse(index: int) -> list[tuple[str, str, int]]:
        # Each file has its bad room type on a different line, so a shared builder state
        # would put a diagnostic in the wrong file or on the wrong line.
        padding = "".join(f"R{i} 4 6 5 3 5 4 1 2 R A\n" for i in range(index))
        text = f"rooms\n{padding}BAD 4 6 5 3 5 4 1 2 X A\n\nboundary\n40 40\n"
        diagnostics = []
        for _ in range(20):
            _, diagnostics = parse_source(Source(f"f{index}.lay", text))
        return [(d.code, d.filename, d.span.line) for d in diagnostics]

    with ThreadPoolExecutor(max_workers=8) as pool:
        results = list(pool.map(parse, range(16)))
    assert results == [[("E012", f"f{i}.lay", i + 2)] for i in range(16)]


def test_a_line_parsed_alone_reports_its_value_problems_to_the_caller() -> None:
    found = []
    node = parser.parse_line("room_line", "R0 4 6 5 3 5 4 1 2 X A", line=7, filename="a.lay", diagnostics=found)
    assert node.id == "R0"
    assert [(d.code, d.filename, d.span.line) for d in found] == [("E012", "a.lay", 7)]
