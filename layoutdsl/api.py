"""The front end's stages as plain functions: each can be called alone (hcl2's api.py).

    spec, diagnostics = load_spec("specs/office_small.lay")
    if spec is not None and not has_errors(diagnostics): ...

`load_spec` raises OSError (and UnicodeDecodeError, a ValueError) when the file cannot be
read: reading is I/O, not a property of the spec, so the CLI turns it into exit code 2.
"""

from __future__ import annotations

from pathlib import Path

from layoutdsl.syntax.ast import Spec
from layoutdsl.check import check_spec
from layoutdsl.diagnostics import Diagnostic, has_errors
from layoutdsl.syntax.format import format_spec
from layoutdsl.sizes.resolve import resolve_spec
from layoutdsl.syntax.parser import parse_source
from layoutdsl.diagnostics.source import Source

__all__ = ["parse_source", "lint_source", "load_spec", "read_source", "format_spec", "has_errors"]


def lint_source(source: Source) -> tuple[Spec | None, list[Diagnostic]]:
    """Parse and check a source; the spec is None when it has syntax or value errors.

    Semantic checks run only on a spec that parsed cleanly, so a typo on one line does not
    also appear as a cascade of "unknown room" errors elsewhere. Between the two, what the
    spec leaves to the tool is filled in (layoutdsl.sizes.resolve): the sizes of sizeless
    rooms and a boundary, each reported by an info diagnostic.
    """
    spec, diagnostics = parse_source(source)
    if spec is not None:
        spec, resolved = resolve_spec(spec)
        diagnostics = diagnostics + resolved
        if not has_errors(resolved):
            diagnostics = diagnostics + check_spec(spec)
    diagnostics.sort(key=Diagnostic.sort_key)
    return spec, diagnostics


def read_source(path: str) -> Source:
    """Read a spec file as UTF-8 (raises OSError / UnicodeDecodeError)."""
    data = Path(path).read_bytes()
    return Source(path, data.decode("utf-8"))


def load_spec(path: str) -> tuple[Spec | None, list[Diagnostic]]:
    """Read, parse and check a spec file; I/O problems raise OSError (see module doc)."""
    return lint_source(read_source(path))
