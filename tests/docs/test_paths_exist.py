"""Files the docs and the README name (`bench/batch.py`, `layoutdsl/emit/walls.py`, ...) exist."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PATH = re.compile(r"\b(?:bench|layoutdsl|specs|tests|examples|docs)/[\w./-]*\w")
PLACEHOLDER = re.compile(r"[A-Z]{4,}")  # NAME, CODE, CASE: a pattern the text explains, not a file


def documents() -> list[Path]:
    return sorted((ROOT / "docs").rglob("*.md")) + [ROOT / "README.md"] + sorted((ROOT / "examples").rglob("*.md"))


HISTORY = re.compile(r"^## Where the old modules went\n.*?(?=^## |\Z)", re.M | re.S)
"""architecture.md's map from the paths before the restructure of issue 10: they are gone on purpose."""


def named_paths(text: str) -> set[str]:
    text = HISTORY.sub("", text)
    return {p.rstrip(".") for p in PATH.findall(text) if not PLACEHOLDER.search(p)}


def test_the_scan_finds_paths() -> None:
    assert named_paths("see `bench/batch.py` and layoutdsl/emit/walls.py, not NAME/x") == {
        "bench/batch.py", "layoutdsl/emit/walls.py"}  # fmt: skip
    assert sum(len(named_paths(p.read_text(encoding="utf-8"))) for p in documents()) >= 20


def test_every_named_path_exists() -> None:
    missing = []
    for document in documents():
        for path in sorted(named_paths(document.read_text(encoding="utf-8"))):
            if not (ROOT / path).exists():
                missing.append(f"{document.relative_to(ROOT)}: {path}")
    assert not missing, "\n".join(missing)
