"""Checks of L-shaped rooms (the `arms` section): each arm belongs to one known room."""

from __future__ import annotations

from collections.abc import Iterator

from layoutdsl.check.common import diag, did_you_mean, node_span, rooms_by_id
from layoutdsl.diagnostics import Diagnostic, Severity, register
from layoutdsl.syntax.ast import ARM_SUFFIX, Spec

E_UNKNOWN_ARMED = register(
    "E114", Severity.ERROR, "arm names an unknown room",
    "Reports an `arms` line whose room id is not defined in `rooms`.",
    "The arm would make no room L-shaped; usually the id is misspelled.",
    "arms\nC9 1.5 2.5 2 6 10 8 1 20",
)  # fmt: skip
E_TWO_ARMS = register(
    "E115", Severity.ERROR, "room has two arms",
    "Reports a room with more than one `arms` line.",
    "An L-shaped room is two rectangles: its room line and one arm. A room of three "
    "rectangles is not supported.",
    "arms\nC0 1.5 2.5 2 6 10 8 1 20\nC0 1.5 2.5 2 4 6 5 1 20",
)  # fmt: skip
E_ARM_NAME_TAKEN = register(
    "E116", Severity.ERROR, "room id ends like an arm's name",
    f"Reports a room id ending in `{ARM_SUFFIX}` while the spec has L-shaped rooms.",
    f"An L-room's second rectangle is called `ID{ARM_SUFFIX}` in messages and in the "
    "construction's geometry; a room of that name would be confused with it.",
    f"rooms\nC0{ARM_SUFFIX} 4 8 6 6 10 8 1 1.7 R CLASSROOM",
)  # fmt: skip


def check_arms(spec: Spec) -> Iterator[Diagnostic]:
    """E114-E116: every arm names a known room, at most one arm per room, no name clash."""
    known = rooms_by_id(spec)
    first_line: dict[str, int] = {}
    for arm in spec.arms:
        if arm.room not in known:
            yield diag(spec, E_UNKNOWN_ARMED, f"arm for unknown room `{arm.room}`", node_span(arm, "room"),
                       "not defined", did_you_mean(arm.room, known) or
                       "an arm's line starts with the id of the room it makes L-shaped")  # fmt: skip
        elif arm.room in first_line:
            yield diag(spec, E_TWO_ARMS, f"room `{arm.room}` has two arms", node_span(arm, "room"),
                       "second arm", "an L-shaped room has one arm; keep one line",
                       (f"first arm on line {first_line[arm.room]}",))  # fmt: skip
        else:
            first_line[arm.room] = node_span(arm).line
    if not spec.arms:
        return
    for room in spec.rooms:
        if room.id.endswith(ARM_SUFFIX):
            yield diag(spec, E_ARM_NAME_TAKEN, f"room id `{room.id}` ends in `{ARM_SUFFIX}`",
                       node_span(room, "id"), "reserved ending",
                       f"rename the room: `{room.id[:-len(ARM_SUFFIX)]}{ARM_SUFFIX}` names the "
                       "second rectangle of an L-shaped room")  # fmt: skip
