"""Import real floor plans: building XML -> `Building` -> `Spec` (the thesis, §5.2, §5.3).

`read_building` is the project's one building-XML reader (safe against XML attacks, every
problem a located diagnostic); `convert` applies the thesis' rectangularization and variance
rules; `import_building` chains the two.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from layoutdsl.syntax.ast import Spec
from layoutdsl.diagnostics import Diagnostic, has_errors
from layoutdsl.importer.convert import ImportOptions, convert, original_room_area, room_ids, spec_name
from layoutdsl.importer.reader import polygon_area, read_building, source_lines
from layoutdsl.diagnostics.source import Span

__all__ = [
    "ImportOptions",
    "convert",
    "import_building",
    "original_room_area",
    "polygon_area",
    "read_building",
    "room_ids",
    "spec_name",
]


def import_building(
    source: str | Path,
    options: ImportOptions = ImportOptions(),
    *,
    text: str | None = None,
    name: str | None = None,
) -> tuple[Spec | None, list[Diagnostic]]:
    """Read a building XML file and convert it to a Spec; (None, diagnostics) on errors.

    The spec is named `name`, else after the file's stem (else the building's `<name>`).
    """
    building, diagnostics = read_building(source, text=text)
    if building is None or has_errors(diagnostics):
        return None, diagnostics
    filename = str(source)
    if name is None and text is None:
        name = Path(filename).stem
    spec, converted = convert(building, options, name=name, filename=filename)
    source_text = text if text is not None else _read_text(Path(filename))
    converted = [_point_at_tag(d, source_text) for d in converted]
    diagnostics = sorted(diagnostics + converted, key=Diagnostic.sort_key)
    return (None if has_errors(diagnostics) else spec), diagnostics


def _read_text(path: Path) -> str:
    try:
        return path.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return ""


def _point_at_tag(diagnostic: Diagnostic, text: str) -> Diagnostic:
    """Give a line-only diagnostic from `convert` the column of the element on that line."""
    span = diagnostic.span
    lines = source_lines(text)
    if not (1 <= span.line <= len(lines)) or span.end_col != span.col:
        return diagnostic
    line_text = lines[span.line - 1]
    start = line_text.find("<")
    if start < 0:
        return replace(diagnostic, span=Span(span.line, 1, span.line, 2))
    end = start + 1
    while end < len(line_text) and not line_text[end].isspace() and line_text[end] not in ">/":
        end += 1
    return replace(diagnostic, span=Span(span.line, start + 1, span.line, end + 1))
