"""Diagnostics -> text for people (full, concise) and for tools (JSON, ruff's shape).

Works for any Diagnostic, whatever stage made it: when the source text of a diagnostic's
file is not given (say, a building XML the caller did not pass), the full format simply
shows no code excerpt.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping

from layoutdsl.diagnostics import Diagnostic
from layoutdsl.diagnostics.source import Source


def _sorted(diagnostics: Iterable[Diagnostic]) -> list[Diagnostic]:
    return sorted(diagnostics, key=Diagnostic.sort_key)


def _source_lines(source: Source) -> list[str]:
    # Same line splitting as the parser (only \n ends a line), so columns agree.
    text = source.text[1:] if source.text.startswith("\ufeff") else source.text
    return [line[:-1] if line.endswith("\r") else line for line in text.split("\n")]


def _display(line: str, upto: int) -> tuple[str, int]:
    """The line with tabs expanded, and the display width of its first `upto` characters."""
    shown, width = [], 0
    prefix_width = None
    for index, char in enumerate(line):
        if index == upto:
            prefix_width = width
        if char == "\t":
            pad = 4 - width % 4
            shown.append(" " * pad)
            width += pad
        else:
            shown.append(char)
            width += 1
    if prefix_width is None:
        prefix_width = width + max(0, upto - len(line))
    return "".join(shown), prefix_width


_ANSI = {"error": "1;31", "warning": "1;33", "info": "1;32", "gutter": "1;34", "help": "1;36", "bold": "1"}


def _paint(text: str, style: str, colour: bool) -> str:
    """ANSI colour for a terminal (the caller decides: see layoutdsl.cli.output.use_colour)."""
    return f"\x1b[{_ANSI[style]}m{text}\x1b[0m" if colour and text else text


def render_one(diagnostic: Diagnostic, source: Source | None = None, *, colour: bool = False) -> str:
    """One diagnostic in ruff's full format (rustc wording), ending with a newline.
    `colour` adds ANSI colours (severity, gutter, carets, help) for a terminal."""
    d = diagnostic
    span = d.span
    tone = d.severity.value
    out = [f"{_paint(f'{tone}[{d.code}]', tone, colour)}{_paint(': ' + d.message, 'bold', colour)}"]
    gutter = " " * len(str(span.line))
    out.append(f"{gutter}{_paint('-->', 'gutter', colour)} {d.filename}:{span.line}:{span.col}")
    lines = _source_lines(source) if source is not None else []
    if 1 <= span.line <= len(lines):
        text = lines[span.line - 1]
        shown, start = _display(text, span.col - 1)
        end_col = span.end_col if span.end_line == span.line else len(text) + 1
        _, end = _display(text, max(end_col - 1, span.col))
        carets = "^" * max(1, end - start)
        bar = _paint("|", "gutter", colour)
        out.append(f"{gutter} {bar}")
        out.append(f"{_paint(str(span.line), 'gutter', colour)} {bar} {shown}".rstrip())
        marks = carets + ((" " + d.label) if d.label else "")
        out.append(f"{gutter} {bar} {' ' * start}{_paint(marks, tone, colour)}")
        out.append(f"{gutter} {bar}")
    for note in d.notes:
        out.append(f"{gutter} {_paint('=', 'gutter', colour)} {_paint('note', 'bold', colour)}: {note}")
    if d.help:
        out.append(f"{_paint('help', 'help', colour)}: {d.help}")
    return "\n".join(out) + "\n"


def render_full(diagnostics: Iterable[Diagnostic], sources: Mapping[str, Source], *, colour: bool = False) -> str:
    """Every diagnostic in full format, sorted by position, separated by blank lines."""
    return "\n".join(render_one(d, sources.get(d.filename), colour=colour) for d in _sorted(diagnostics))


def render_concise(diagnostics: Iterable[Diagnostic]) -> str:
    """One `FILE:LINE:COL: CODE message` line per diagnostic, sorted by position."""
    return "".join(
        f"{d.filename}:{d.span.line}:{d.span.col}: {d.code} {d.message}\n" for d in _sorted(diagnostics)
    )


def to_json_object(diagnostic: Diagnostic) -> dict:
    """A diagnostic as ruff's JSON object (1-based rows and columns)."""
    d = diagnostic
    return {
        "code": d.code,
        "severity": d.severity.value,
        "message": d.message,
        "filename": d.filename,
        "location": {"row": d.span.line, "column": d.span.col},
        "end_location": {"row": d.span.end_line, "column": d.span.end_col},
        "help": d.help,
    }


def render_json(diagnostics: Iterable[Diagnostic]) -> str:
    """A JSON list of ruff-shaped objects, sorted by position, ending with a newline."""
    return json.dumps([to_json_object(d) for d in _sorted(diagnostics)], indent=2, ensure_ascii=False) + "\n"


def summary(diagnostics: Iterable[Diagnostic]) -> str:
    """`found 2 errors and 1 warning`, or `no problems found`."""
    items = list(diagnostics)
    errors = sum(1 for d in items if d.is_error)
    notes = sum(1 for d in items if d.severity.value == "info")  # not problems: counted apart
    warnings = len(items) - errors - notes
    if not errors and not warnings:
        return "no problems found" + (f" ({notes} note{'s' if notes != 1 else ''})" if notes else "")
    parts = []
    if errors:
        parts.append(f"{errors} error{'s' if errors != 1 else ''}")
    if warnings:
        parts.append(f"{warnings} warning{'s' if warnings != 1 else ''}")
    return "found " + " and ".join(parts)
