"""The layering rule of docs/architecture.md: no import cycle, every edge points down."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from layoutdsl.devtools.imports import import_graph, violations

ROOT = Path(__file__).resolve().parents[2]


def _tree(tmp_path: Path, files: dict[str, str]) -> Path:
    package = tmp_path / "layoutdsl"
    for name, text in files.items():
        path = package / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return package


def test_the_package_has_no_cycle_and_no_upward_import() -> None:
    problems = violations(import_graph())
    assert not problems, "the import graph breaks the layering:\n" + "\n".join(map(str, problems))


def test_an_upward_edge_is_reported(tmp_path) -> None:
    package = _tree(tmp_path, {
        "__init__.py": "",
        "syntax/__init__.py": "",
        "syntax/ast.py": "from layoutdsl.model import build_model\n",
        "model/__init__.py": "from layoutdsl.syntax.ast import Spec\n",
    })  # fmt: skip
    graph = import_graph(package)
    assert graph["layoutdsl.syntax.ast"] == {"layoutdsl.model"}
    kinds = [(v.kind, v.modules) for v in violations(graph)]
    assert ("upward", ("layoutdsl.syntax.ast", "layoutdsl.model")) in kinds
    assert ("cycle", ("layoutdsl.model", "layoutdsl.syntax.ast")) in kinds


def test_a_cycle_inside_one_package_hidden_in_a_function_is_reported(tmp_path) -> None:
    package = _tree(tmp_path, {
        "__init__.py": "",
        "compile/__init__.py": "",
        "compile/pipeline.py": "from layoutdsl.compile import construct\n",
        "compile/construct.py": "def f():\n    from .pipeline import g\n",
    })  # fmt: skip
    graph = import_graph(package)
    assert graph["layoutdsl.compile.construct"] == {"layoutdsl.compile.pipeline"}
    assert [(v.kind, v.modules) for v in violations(graph)] == [
        ("cycle", ("layoutdsl.compile.construct", "layoutdsl.compile.pipeline"))
    ]


def test_the_command_prints_the_graph_and_exits_zero() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "layoutdsl.devtools.imports", "--packages"],
        cwd=ROOT, capture_output=True, text=True,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    edges = dict(line.split(" -> ") for line in result.stdout.splitlines())
    assert set(edges["check"].split(", ")) == {"diagnostics", "syntax"}
    assert "no cycle, every edge points down the layers" in result.stderr
