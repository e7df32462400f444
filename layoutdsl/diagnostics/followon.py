"""Follow-on warnings: a warning another reported error causes is not shown beside it.

An adjacency naming an unknown room (E102) cannot join its two rooms, so the room graph
falls apart and W301 ("the rooms form 2 separate parts") fires too, printed first because
it points at an earlier line. The fix of E102 removes both, so W301 then only distracts
from the real mistake (issue 42). Only warnings are suppressed, never errors, and only
when their cause is reported in the same file: once the error is fixed, a warning that
still holds is reported on the next run.
"""

from __future__ import annotations

from collections.abc import Iterable

from layoutdsl.diagnostics import Diagnostic

FOLLOW_ONS: dict[str, frozenset[str]] = {
    # several components: an adjacency dropped because a room id is unknown or ambiguous
    "W301": frozenset({"E101", "E102"}),
    # target areas exceed the boundary: a room that cannot fit, or minimum areas that cannot
    "W304": frozenset({"E206", "E207"}),
}
"""Warning code -> the error codes that cause it."""


def without_follow_ons(diagnostics: Iterable[Diagnostic]) -> list[Diagnostic]:
    """The diagnostics minus each warning whose cause (FOLLOW_ONS) is reported in its file."""
    items = list(diagnostics)
    reported = {(d.filename, d.code) for d in items if d.is_error}
    return [
        d for d in items
        if d.is_error or not any((d.filename, cause) in reported for cause in FOLLOW_ONS.get(d.code, ()))
    ]
