"""Diagnostics: what layoutdsl tells a person about a spec, and the registry of codes.

Every code is registered once in CODES with ruff-style documentation; a code is never
reused. Ranges: E0xx syntax, E1xx names and references, E2xx geometry, W3xx warnings,
E4xx imported building XML, E9xx solver (no layout, failed verification).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

from layoutdsl.diagnostics.source import Span


class Severity(str, Enum):
    ERROR = "error"
    WARNING = "warning"
    INFO = "info"
    """Not a problem: a note on what the tool decided for the spec (where a sizeless room's
    sizes came from, the boundary it chose). Never fails a command, not even with
    `--warnings-as-errors`."""


@dataclass(frozen=True, slots=True)
class CodeDoc:
    """Documentation of one diagnostic code, in ruff's shape."""

    code: str
    severity: Severity
    title: str
    what_it_does: str
    why_bad: str
    example: str


@dataclass(frozen=True, slots=True)
class Diagnostic:
    """One located problem. Wording follows rustc: lower case, no final period."""

    code: str
    message: str
    filename: str
    span: Span
    severity: Severity = Severity.ERROR
    label: str = ""
    """Short text under the caret (`not defined`)."""
    help: str | None = None
    """What to do next, when it can be guessed."""
    notes: tuple[str, ...] = field(default=())

    @property
    def is_error(self) -> bool:
        return self.severity is Severity.ERROR

    def sort_key(self) -> tuple:
        return (self.filename, self.span.line, self.span.col, self.code, self.message)


CODES: dict[str, CodeDoc] = {}
"""Every documented code. Modules register their codes with `register` at import time."""


def register(
    code: str, severity: Severity, title: str, what_it_does: str, why_bad: str, example: str
) -> str:
    """Document a code once; registering the same code twice is a programming error."""
    if code in CODES:
        raise ValueError(f"diagnostic code {code} registered twice")
    CODES[code] = CodeDoc(code, severity, title, what_it_does, why_bad, example)
    return code


def has_errors(diagnostics: list[Diagnostic] | tuple[Diagnostic, ...]) -> bool:
    return any(d.is_error for d in diagnostics)


CODE_MODULES = ("layoutdsl.syntax.parser", "layoutdsl.syntax.builder", "layoutdsl.check", "layoutdsl.importer", "layoutdsl.compile.explain", "layoutdsl.diagnostics.filekind",
                "layoutdsl.importer.graphs", "layoutdsl.sizes.resolve")
"""Modules that register codes at import time; `load_all_codes` imports them all."""


def load_all_codes() -> dict[str, CodeDoc]:
    """Import every module that registers codes, so CODES is complete; returns CODES."""
    import importlib

    for name in CODE_MODULES:
        importlib.import_module(name)
    return CODES
