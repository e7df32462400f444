"""docs/reference/spec-language.md describes the language the parser reads, with nothing missing."""

from __future__ import annotations

import re
from pathlib import Path

from layoutdsl.api import lint_source
from layoutdsl.diagnostics.source import Source
from layoutdsl.syntax.ast import SETTING_KEYS
from layoutdsl.syntax.format import format_source
from layoutdsl.syntax.parser import SECTIONS

PAGE = Path(__file__).resolve().parents[2] / "docs" / "reference" / "spec-language.md"


def test_complete_example_lints_clean_and_is_canonical() -> None:
    text = PAGE.read_text(encoding="utf-8")
    section = text.split("## A complete example", 1)[1]
    example = re.search(r"```[a-z]*\n(.*?)```", section, re.S).group(1)
    source = Source("example.lay", example)
    spec, diagnostics = lint_source(source)
    assert diagnostics == []
    assert spec.positions and spec.connections and spec.clusters and spec.hints and spec.boundary.obstacles
    assert any(r.on_boundary for r in spec.rooms) and any(r.rho_cover != 1 for r in spec.rooms)
    assert format_source(source) == example


def test_every_section_has_a_heading() -> None:
    headings = re.findall(r"^## `(\w+)`", PAGE.read_text(encoding="utf-8"), re.M)
    assert set(SECTIONS) <= set(headings), set(SECTIONS) - set(headings)


def test_every_setting_is_in_the_table() -> None:
    table = PAGE.read_text(encoding="utf-8").split("## `settings`", 1)[1].split("\n## ", 1)[0]
    documented = set(re.findall(r"^\| `(\w+)` \|", table, re.M))
    assert set(SETTING_KEYS) <= documented, set(SETTING_KEYS) - documented


def test_the_settings_table_gives_the_real_defaults() -> None:
    from layoutdsl.syntax.ast import Settings

    table = PAGE.read_text(encoding="utf-8").split("## `settings`", 1)[1].split("\n## ", 1)[0]
    rows = dict(re.findall(r"^\| `(\w+)` \| ([^|]+?) \|", table, re.M))
    defaults = Settings()
    checked = 0
    for key, written in rows.items():
        if key == "name":
            continue  # the file's stem: not a constant
        actual = getattr(defaults, key)
        if actual is None:
            assert written == "none", key
        elif isinstance(actual, str):
            assert written == actual, key
        else:
            assert float(written) == actual, key
        checked += 1
    assert checked >= 10
