"""Where the tests find real floor plans: the examples shipped in the repository, and the
24-plan corpus CI provides beside it.

Tests over one or a few plans use `EXAMPLES` and always run. Tests over the whole corpus use
`corpus_plans()` and `needs_corpus`, which skips with a reason naming the missing folder;
the session header says whether the corpus was found, so a fresh clone never loses those
tests silently.
"""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples" / "floorplans"
CORPUS = ROOT.parent / "shared" / "floorplans"
CORPUS_SIZE = 24

CORPUS_MISSING = (
    f"the {CORPUS_SIZE}-plan corpus is not at {CORPUS} (CI provides it beside the repository); "
    "the examples/floorplans tests ran instead"
)


def corpus_plans() -> list[Path]:
    """The corpus' plans, sorted; empty when the corpus is not beside the repository."""
    return sorted(CORPUS.glob("*.xml"))


needs_corpus = pytest.mark.skipif(not corpus_plans(), reason=CORPUS_MISSING)
"""Marks a test that needs the whole corpus."""
