"""ast.Spec -> canonical spec text (`layoutdsl fmt`, and how imported specs are written).

The canonical form is the thesis layout (seed §5.4): the sections `rooms`, `boundary`,
`adjacencies`, `positions`, `connections`, `clusters` in that order, single spaces between
values, one blank line between sections. Extensions appear only when they carry
information: per-room weights other than 1, a `hints` section when there are hints, and a
`settings` section with the keys the spec set (or that differ from their defaults). Empty
optional sections are left out, so a spec without extensions is a plain thesis file.

Numbers are written in the shortest form that reads back to the same float (`repr`,
integers without `.0`), so `parse(format_spec(spec)) == spec` holds exactly.
"""

from __future__ import annotations

from dataclasses import fields

from layoutdsl.ast import Settings, Spec

_DEFAULT_SETTINGS = Settings()
SETTINGS_ORDER = (
    "lambda_cover", "lambda_error", "walldim", "door_utilization", "cluster_margin",
    "time_limit", "gap", "seed", "emphasis", "node_limit",
)  # fmt: skip
_UNKNOWN_PATHS = ("<spec>", "", "-", "<stdin>")


def format_number(value: float) -> str:
    """Shortest text that parses back to the same float; integers without `.0`."""
    if isinstance(value, bool):
        raise TypeError("a bool is not a spec number")
    if float(value).is_integer() and abs(value) < 1e16:
        return str(int(value))
    return repr(float(value))


def _setting_text(value) -> str:
    if value is None:
        return "none"
    if isinstance(value, str):
        return value
    if isinstance(value, int):
        return str(value)
    return format_number(value)


def _settings_lines(spec: Spec) -> list[str]:
    settings = spec.settings
    lines = []
    from layoutdsl.parser import spec_name_for  # local: parser imports build imports ast only

    name_is_default = spec.path not in _UNKNOWN_PATHS and spec.name == spec_name_for(spec.path)
    if "name" in settings.explicit or not name_is_default:
        lines.append(f"name {spec.name}")
    known = {f.name for f in fields(Settings)}
    for key in SETTINGS_ORDER:
        if key not in known:
            continue
        value = getattr(settings, key)
        if key in settings.explicit or value != getattr(_DEFAULT_SETTINGS, key):
            lines.append(f"{key} {_setting_text(value)}")
    return lines


def format_spec(spec: Spec) -> str:
    """The canonical text of a spec (ends with one newline)."""
    n = format_number
    sections: list[list[str]] = []

    rooms = ["rooms"]
    for room in spec.rooms:
        values = (room.min_w, room.max_w, room.target_w, room.min_h, room.max_h, room.target_h,
                  room.min_ar, room.max_ar)  # fmt: skip
        parts = [room.id, *(n(v) for v in values), room.rtype, room.label]
        if room.on_boundary:
            parts.append("onB")
        if room.rho_cover != 1.0:
            parts.append(f"cover={n(room.rho_cover)}")
        if room.rho_error != 1.0:
            parts.append(f"error={n(room.rho_error)}")
        rooms.append(" ".join(parts))
    sections.append(rooms)

    if spec.boundary is not None:
        boundary = ["boundary", f"{n(spec.boundary.w)} {n(spec.boundary.h)}"]
        boundary += [
            f"{o.id} {n(o.x)} {n(o.y)} {n(o.w)} {n(o.h)}" for o in spec.boundary.obstacles
        ]
        sections.append(boundary)

    if spec.adjacencies:
        sections.append(
            ["adjacencies"] + [f"{a.a} {a.b} {n(a.door)} {a.kind}" for a in spec.adjacencies]
        )
    if spec.positions:
        sections.append(["positions"] + [f"{p.room} {n(p.x)} {n(p.y)}" for p in spec.positions])
    if spec.connections:
        sections.append(
            ["connections"]
            + [f"{c.room} {n(c.x1)} {n(c.y1)} {n(c.x2)} {n(c.y2)}" for c in spec.connections]
        )
    if spec.clusters:
        lines = ["clusters"]
        for index, cluster in enumerate(spec.clusters):
            if index:
                lines.append("")  # the thesis separates clusters with a blank line
            lines.append(cluster.id)
            lines += [f"{m.room} {n(m.x)} {n(m.y)}" for m in cluster.members]
        sections.append(lines)
    if spec.hints:
        sections.append(
            ["hints"] + [f"{h.room} {n(h.x)} {n(h.y)} {n(h.w)} {n(h.h)}" for h in spec.hints]
        )
    settings = _settings_lines(spec)
    if settings:
        sections.append(["settings"] + settings)
    return "\n\n".join("\n".join(lines) for lines in sections) + "\n"
