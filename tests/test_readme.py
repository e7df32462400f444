"""The README is a short landing page that opens with the two commands CI runs, and its links work.

Its `sh` examples run in tests/docs/test_shell_examples.py; the language reference it used to
hold is docs/reference/spec-language.md (tested in tests/docs/test_spec_language.py), and its
code table became one page per code (tests/docs/test_diagnostic_pages.py).
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"


def test_readme_opens_with_two_commands_and_ci_runs_the_second():
    readme = README.read_text(encoding="utf-8")
    assert readme.index("## Quick start") < readme.index("## What it is")
    quick_start = readme.split("## Quick start", 1)[1]
    fenced = quick_start.split("```", 2)[1]
    info, _, body = fenced.partition("\n")
    assert info.strip() != "sh"  # it creates a venv and runs the suite: not a docs example to run
    block = body.strip().splitlines()
    assert len(block) == 2
    setup_and_compile, setup_and_test = block
    assert setup_and_compile.startswith("python3 -m venv .venv && ")
    spec = setup_and_compile.split("layoutdsl compile ", 1)[1].split()[0]
    assert (ROOT / spec).is_file()
    assert setup_and_test.startswith("python3 -m venv .venv && ")
    ci_lines = (ROOT / ".ci" / "run").read_text(encoding="utf-8").strip().splitlines()
    assert ci_lines[-1] == setup_and_test


def test_readme_is_a_landing_page():
    lines = README.read_text(encoding="utf-8").splitlines()
    assert len(lines) <= 200
    text = "\n".join(lines)
    # what it is and the picture come before any reference material
    assert text.index("## What it is") < text.index("![") < text.index("## Install")
    assert "Procedural generation of realistic building layouts from graphs" in text
    assert "Politecnico di Milano" in text and "2019" in text


def test_readme_links_and_images_point_at_files():
    text = README.read_text(encoding="utf-8")
    targets = re.findall(r"\]\(([^)\s]+)\)", text)
    local = [t.split("#", 1)[0] for t in targets if not re.match(r"[a-z]+://", t)]
    assert len(local) >= 10
    missing = [t for t in local if not (ROOT / t).exists()]
    assert not missing, f"README links to missing files: {missing}"
