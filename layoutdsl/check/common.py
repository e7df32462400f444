"""What the checks share: the span of a node's field, and building a Diagnostic."""

from __future__ import annotations

from collections.abc import Iterable

from layoutdsl.diagnostics import Diagnostic, Severity
from layoutdsl.diagnostics.source import Span
from layoutdsl.diagnostics.suggest import did_you_mean as suggest_by_edits
from layoutdsl.syntax.ast import Room, Spec

FALLBACK_SPAN = Span(1, 1, 1, 2)


def node_span(node, field: str | None = None) -> Span:
    """The span of a node's field, else of the node; programmatic specs may have none."""
    if field is not None and node.spans:
        span = node.spans.get(field)
        if span is not None:
            return span
    return node.span or FALLBACK_SPAN


def pair_span(node, first: str, last: str) -> Span:
    """From the start of one field to the end of another (a point's `x y`)."""
    a, b = node_span(node, first), node_span(node, last)
    return Span(a.line, a.col, b.end_line, b.end_col) if (a.line, a.col) <= (b.line, b.col) else a


def diag(spec: Spec, code: str, message: str, span: Span, label: str = "", help: str | None = None,
         notes: tuple[str, ...] = (), warning: bool = False) -> Diagnostic:  # fmt: skip
    """A Diagnostic in the spec's file (an error unless `warning`)."""
    return Diagnostic(
        code, message, spec.path, span, Severity.WARNING if warning else Severity.ERROR,
        label=label, help=help, notes=notes,
    )  # fmt: skip


def did_you_mean(word: str, candidates: Iterable[str]) -> str | None:
    """A help line naming the closest candidate, or None (by edit distance: difflib's ratio
    cutoff rejected every two-letter room id; see layoutdsl.diagnostics.suggest)."""
    return suggest_by_edits(word, candidates)


def rooms_by_id(spec: Spec) -> dict[str, Room]:
    """Room id -> its first room (a duplicate id is check_duplicate_ids' to report)."""
    rooms: dict[str, Room] = {}
    for room in spec.rooms:
        rooms.setdefault(room.id, room)
    return rooms
