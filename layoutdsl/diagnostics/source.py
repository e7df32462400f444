"""Source text and positions: what every diagnostic points into."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class Span:
    """A 1-based, end-exclusive range of a source text (line, column)."""

    line: int
    col: int
    end_line: int
    end_col: int

    @staticmethod
    def point(line: int, col: int) -> Span:
        return Span(line, col, line, col + 1)


@dataclass(frozen=True, slots=True)
class Source:
    """A spec's text and the name messages call it by (a path, or `<stdin>`)."""

    path: str
    text: str

    def line_text(self, line: int) -> str:
        """The text of a 1-based line, without its newline ('' past the end)."""
        lines = self.text.splitlines()
        return lines[line - 1] if 1 <= line <= len(lines) else ""
