"""Every fenced `sh` block of the docs and the READMEs runs and exits 0, so no example goes stale.

Each Markdown file gets its own temporary folder holding copies of the repository's `specs/`
and `examples/`; its `sh` blocks run there in order (a later block may use an earlier one's
output), with the venv's `layoutdsl` first on PATH. Output shown to readers is in `console`
or `text` blocks, which are not run. The README's Quick start block (it creates a venv and
runs the whole suite) is not tagged `sh`; tests/test_readme.py checks it instead.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FENCE = re.compile(r"^(?P<indent>[ \t]*)```sh[ \t]*\n(?P<body>.*?)^(?P=indent)```[ \t]*$", re.M | re.S)
SECONDS_PER_BLOCK = 120  # a block is a few commands of about a second each; this only stops a hang


def documents() -> list[Path]:
    found = sorted((ROOT / "docs").rglob("*.md")) + [ROOT / "README.md"]
    found += sorted((ROOT / "examples").rglob("README.md"))
    return [path for path in found if path.is_file()]


def sh_blocks(text: str) -> list[tuple[int, str]]:
    """(line number, script) of every ```sh block, dedented by the fence's indent."""
    blocks = []
    for match in FENCE.finditer(text):
        indent = len(match.group("indent"))
        body = "".join(line[indent:] if line[:indent].strip() == "" else line
                       for line in match.group("body").splitlines(keepends=True))  # fmt: skip
        blocks.append((text.count("\n", 0, match.start()) + 1, body))
    return blocks


def test_the_extractor_finds_sh_blocks_only() -> None:
    text = "a\n```sh\nlayoutdsl lint x.lay\n```\n```console\n$ no\n```\n- item\n\n    ```sh\n    echo hi\n    ```\n"
    assert sh_blocks(text) == [(2, "layoutdsl lint x.lay\n"), (10, "echo hi\n")]


def test_there_are_examples_to_run() -> None:
    # a renamed fence tag or a broken regex would otherwise make the test below vacuous
    assert sum(len(sh_blocks(p.read_text(encoding="utf-8"))) for p in documents()) >= 20


@pytest.mark.parametrize("document", documents(), ids=lambda p: str(p.relative_to(ROOT)))
def test_shell_examples_run(document: Path, tmp_path: Path) -> None:
    blocks = sh_blocks(document.read_text(encoding="utf-8"))
    if not blocks:
        pytest.skip("no sh block")
    shutil.copytree(ROOT / "specs", tmp_path / "specs")
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    venv_bin = str(Path(sys.executable).parent)
    env = {**os.environ, "PATH": venv_bin + os.pathsep + os.environ.get("PATH", ""), "NO_COLOR": "1",
           "MPLBACKEND": "Agg"}  # fmt: skip
    for line, script in blocks:
        result = subprocess.run(
            ["bash", "-euo", "pipefail", "-c", script], cwd=tmp_path, env=env,
            capture_output=True, text=True, timeout=SECONDS_PER_BLOCK,
        )  # fmt: skip
        assert result.returncode == 0, (
            f"{document.relative_to(ROOT)}:{line}: exit {result.returncode}\n{script}\n"
            f"--- stdout\n{result.stdout[-3000:]}\n--- stderr\n{result.stderr[-3000:]}"
        )
