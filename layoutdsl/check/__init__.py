"""The linter: pure checks over a parsed Spec, each yielding located Diagnostics.

CHECKS is an ordered tuple of `check_*(spec)` functions (sqlglot's optimizer RULES). A
check reports every problem it finds, never only the first. Later checks skip what an
earlier one already reported (an unknown room has no size to compare), so one mistake
gives one message. Geometry follows the thesis model (§5.5.1): rooms may be rotated,
corridors have no aspect-ratio limit (5.6), a shared wall must be at least
door / door_utilization long (5.9).
"""

from __future__ import annotations

from dataclasses import replace

from layoutdsl.check.geometry import (
    check_boundary,
    check_doors,
    check_fit,
    check_points,
    check_room_sizes,
    check_shared_points,
    reachable_ratios,
)
from layoutdsl.check.names import check_duplicate_ids, check_references, check_repeats
from layoutdsl.check.shapes import check_arms
from layoutdsl.check.topology import check_components, check_planarity
from layoutdsl.diagnostics import Diagnostic
from layoutdsl.diagnostics.followon import without_follow_ons
from layoutdsl.syntax.ast import Spec

__all__ = ["CHECKS", "check_spec", "reachable_ratios"]

CHECKS = (
    check_duplicate_ids,
    check_references,
    check_repeats,
    check_arms,
    check_room_sizes,
    check_boundary,
    check_fit,
    check_doors,
    check_points,
    check_shared_points,
    check_planarity,
    check_components,
)
"""Every check, in order. Each is pure: Spec -> iterator of Diagnostic."""


SIZE_CHECKS = frozenset((check_arms, check_room_sizes, check_boundary, check_fit, check_doors, check_points,
                         check_shared_points))  # fmt: skip
"""The checks that read rooms' sizes: a sizeless room the size model has not sized yet
(a spec straight from parse_source, not through api.lint_source) is left out of them."""


def check_spec(spec: Spec) -> list[Diagnostic]:
    """Run every check and return all diagnostics sorted by position."""
    diagnostics: list[Diagnostic] = []
    sized = spec
    if not all(room.has_sizes for room in spec.rooms):
        sized = replace(spec, rooms=tuple(room for room in spec.rooms if room.has_sizes))
    for check in CHECKS:
        diagnostics.extend(check(sized if check in SIZE_CHECKS else spec))
    diagnostics = without_follow_ons(diagnostics)  # no W301 beside the E102 that causes it
    diagnostics.sort(key=Diagnostic.sort_key)
    return diagnostics

