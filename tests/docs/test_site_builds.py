"""The docs site builds with `mkdocs build --strict`: no broken link, no page missing from a nav line."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_mkdocs_build_strict(tmp_path) -> None:
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1"}
    result = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--quiet", "-f", str(ROOT / "mkdocs.yml"),
         "-d", str(tmp_path / "site")],
        capture_output=True, text=True, env=env, cwd=ROOT, timeout=300,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr[-4000:]
    site = tmp_path / "site"
    # the generated reference is there: every subcommand's help, and a page per code
    cli = (site / "reference" / "cli" / "index.html").read_text(encoding="utf-8")
    from layoutdsl.cli import COMMANDS

    assert len(COMMANDS) >= 7
    for command in COMMANDS:  # every subcommand, including ones added after this test
        assert f'id="layoutdsl-{command}"' in cli, command
    assert "--stdin-filename" in cli and "--solution-limit" in cli
    assert (site / "reference" / "codes" / "E901" / "index.html").is_file()
    # the codes index links every code's page, whatever its family
    from layoutdsl.cli.explain import pages

    index = (site / "reference" / "codes" / "index.html").read_text(encoding="utf-8")
    linked = set(re.findall(r'href="([EWI]\d{3})/"', index))
    assert linked == set(pages())
    for code in pages():
        assert (site / "reference" / "codes" / code / "index.html").is_file(), code
