"""The real floor plans the bench scripts run over, and what their `--only` selects.

One place for both, so that every script finds the plans in the same folder and an `--only`
value picks the same plans whichever script it is given to. Scripts import it as
`from plans import ...` (a script's own folder is on sys.path when run as python bench/X.py).
"""

from __future__ import annotations

from fnmatch import fnmatch
from pathlib import Path

DEFAULT_FOLDER = Path(__file__).resolve().parents[2] / "shared" / "floorplans"
"""../shared/floorplans beside the repo: the building XML files of the real plans."""

ONLY_HELP = "comma-separated fnmatch patterns or substrings of plan names; default: every plan"


def matches(stem: str, only: str | None) -> bool:
    """Whether the plan `stem` is selected by `only`: one of its comma-separated parts is an
    fnmatch pattern of the stem or a substring of it. A part may also be (a pattern or a
    substring of) the file name, stem + .xml. Empty parts are ignored (`a,b,` is `a,b`); no
    parts at all (None, "") select every plan."""
    parts = [part for part in (only or "").split(",") if part]
    name = stem + ".xml"
    return not parts or any(part in name or fnmatch(stem, part) or fnmatch(name, part) for part in parts)


def plan_files(folder: Path | str, only: str | None = None) -> list[Path]:
    """The building XML files of `folder` that `only` selects, sorted."""
    return [path for path in sorted(Path(folder).glob("*.xml")) if matches(path.stem, only)]
