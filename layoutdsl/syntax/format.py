"""ast.Spec -> canonical spec text (`layoutdsl fmt`, and how imported specs are written).

The canonical form is the thesis layout (the thesis, §5.4): the sections `rooms`, `boundary`,
`adjacencies`, `positions`, `connections`, `clusters` in that order, single spaces between
values, one blank line between sections. Extensions appear only when they carry
information: per-room weights other than 1, an `arms` section (right after `rooms`) when
there are L-shaped rooms, a `hints` section when there are hints, and a
`settings` section with the keys the spec set (or that differ from their defaults). Empty
optional sections are left out, so a spec without extensions is a plain thesis file.

`format_source` does the same for a source text and keeps its `#` comments (the `fmt`
command uses it). Numbers are written in the shortest form that reads back to the same float (`repr`,
integers without `.0`), so `parse(format_spec(spec)) == spec` holds exactly.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import fields

from layoutdsl.syntax.ast import SETTING_KEYS, Settings, Spec
from layoutdsl.diagnostics.source import Source

_DEFAULT_SETTINGS = Settings()
_UNKNOWN_PATHS = ("<spec>", "")  # a Spec built in code, not read from a file


def format_number(value: float) -> str:
    """Shortest text that parses back to the same float; integers without `.0`."""
    if isinstance(value, bool):
        raise TypeError("a bool is not a spec number")
    if float(value).is_integer() and abs(value) < 1e16:
        return str(int(value))
    return repr(float(value))


_WEIGHT_LIKE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*=")


def safe_label(label: str) -> str:
    """The label as words that read back as a label (labels from imported plans can be odd).

    A word starting with `#` would start a comment and a `key=value` word would read as a
    room weight, so `#` becomes `No.` and `=` becomes `-`; a last word `onB` would read as
    the on-boundary flag, so it is written `onb`; an empty label becomes `ROOM`.
    """
    words = label.split()
    out = []
    for word in words:
        if word.startswith("#"):
            word = "No." + word[1:]
        if _WEIGHT_LIKE.match(word):
            word = word.replace("=", "-")
        out.append(word)
    if len(out) > 1 and out[-1] == "onB":
        out[-1] = "onb"
    return " ".join(out) or "ROOM"


def _setting_text(value) -> str:
    if value is None:
        return "none"
    if isinstance(value, str):
        return value
    if isinstance(value, int):
        return str(value)
    return format_number(value)


def _settings_lines(spec: Spec) -> list[tuple[str, int | None]]:
    settings = spec.settings
    spans = settings.spans or {}
    lines: list[tuple[str, int | None]] = []
    from layoutdsl.syntax.parser import spec_name_for  # local: the parser imports this module's users

    def origin(key: str) -> int | None:
        span = spans.get(key)
        return span.line if span else None

    name_is_default = spec.path not in _UNKNOWN_PATHS and spec.name == spec_name_for(spec.path)
    if "name" in settings.explicit or not name_is_default:
        lines.append((f"name {spec.name}", origin("name")))
    known = {f.name for f in fields(Settings)}
    for key in SETTING_KEYS:
        if key not in known:
            continue
        value = getattr(settings, key)
        if key in settings.explicit or value != getattr(_DEFAULT_SETTINGS, key):
            lines.append((f"{key} {_setting_text(value)}", origin(key)))
    return lines


def _line(node) -> int | None:
    return node.span.line if node.span is not None else None


def format_lines(
    spec: Spec, header_lines: Mapping[str, int] | None = None, *, fill_sizes: bool = False
) -> list[tuple[str, int | None]]:
    """The canonical lines, each with the source line it came from (None for new lines).

    A sizeless room (`R1 R CLASSROOM`) stays sizeless unless `fill_sizes`: then it is written
    with the numbers the size model gave (the spec must have been through
    layoutdsl.sizes.resolve). A boundary is written whenever the spec has one, chosen by
    the tool or not: a spec without a `boundary` section gets one only from resolving."""
    n = format_number
    headers = header_lines or {}
    sections: list[list[tuple[str, int | None]]] = []

    def header(name: str) -> tuple[str, int | None]:
        return (name, headers.get(name))

    rooms = [header("rooms")]
    for room in spec.rooms:
        values = (room.min_w, room.max_w, room.target_w, room.min_h, room.max_h, room.target_h,
                  room.min_ar, room.max_ar)  # fmt: skip
        if room.sizeless and not (fill_sizes and room.has_sizes):
            # sizes from the size model: `id [rtype] label`, the type once it is known
            parts = [room.id, *([room.rtype] if room.rtype else []), safe_label(room.label)]
        else:
            parts = [room.id, *(n(v) for v in values), room.rtype, safe_label(room.label)]
        if room.on_boundary:
            parts.append("onB")
        if room.rho_cover != 1.0:
            parts.append(f"cover={n(room.rho_cover)}")
        if room.rho_error != 1.0:
            parts.append(f"error={n(room.rho_error)}")
        rooms.append((" ".join(parts), _line(room)))
    sections.append(rooms)
    if spec.arms:
        sections.append([header("arms")] + [
            (" ".join([arm.room, *(n(v) for v in (arm.min_w, arm.max_w, arm.target_w, arm.min_h,
                                                  arm.max_h, arm.target_h, arm.min_ar, arm.max_ar))]),
             _line(arm))
            for arm in spec.arms
        ])  # fmt: skip

    boundary = spec.boundary
    if boundary is not None:
        lines = [header("boundary"), (f"{n(boundary.w)} {n(boundary.h)}", _line(boundary))]
        lines += [(f"{o.id} {n(o.x)} {n(o.y)} {n(o.w)} {n(o.h)}", _line(o)) for o in boundary.obstacles]
        sections.append(lines)
    if spec.adjacencies:
        sections.append([header("adjacencies")] + [
            (f"{a.a} {a.b} {n(a.door)} {a.kind}", _line(a)) for a in spec.adjacencies
        ])  # fmt: skip
    if spec.positions:
        sections.append([header("positions")] + [
            (f"{p.room} {n(p.x)} {n(p.y)}", _line(p)) for p in spec.positions
        ])  # fmt: skip
    if spec.connections:
        sections.append([header("connections")] + [
            (f"{c.room} {n(c.x1)} {n(c.y1)} {n(c.x2)} {n(c.y2)}", _line(c)) for c in spec.connections
        ])  # fmt: skip
    if spec.clusters:
        lines = [header("clusters")]
        for index, cluster in enumerate(spec.clusters):
            if index:
                lines.append(("", None))  # the thesis separates clusters with a blank line
            lines.append((cluster.id, _line(cluster)))
            lines += [(f"{m.room} {n(m.x)} {n(m.y)}", _line(m)) for m in cluster.members]
        sections.append(lines)
    if spec.hints:
        sections.append([header("hints")] + [
            (f"{h.room} {n(h.x)} {n(h.y)} {n(h.w)} {n(h.h)}", _line(h)) for h in spec.hints
        ])  # fmt: skip
    settings = _settings_lines(spec)
    if settings:
        sections.append([header("settings")] + settings)
    out: list[tuple[str, int | None]] = []
    for index, lines in enumerate(sections):
        if index:
            out.append(("", None))
        out += lines
    return out


def format_spec(spec: Spec, *, fill_sizes: bool = False) -> str:
    """The canonical text of a spec (ends with one newline); comments are not part of a Spec.
    `fill_sizes`: see format_lines."""
    return "\n".join(text for text, _ in format_lines(spec, fill_sizes=fill_sizes)) + "\n"


def format_source(source: Source, *, resolve=None) -> str | None:
    """The canonical text of a source, keeping its comments; None if it has errors.

    The comment block that opens the file (followed by a blank line) stays at the top; any
    other comment line travels with the next line that has content (so a comment above a
    room stays above it when sections are reordered); a comment after the values of a line stays
    at the end of that line. Comments after the last line stay at the end of the file.
    """
    from layoutdsl.syntax.parser import _comment_column, _split_lines, parse_source, split_sections

    spec, diagnostics = parse_source(source)
    if spec is None or any(d.is_error for d in diagnostics):
        return None
    if resolve is not None:  # `fmt --fill-sizes`: the sizes and boundary the model gives
        spec, resolved = resolve(spec)
        if any(d.is_error for d in resolved):
            return None
    headers, _, _ = split_sections(source)
    header_lines: dict[str, int] = {}
    for h in headers:
        header_lines.setdefault(h.name, h.line)
    leading: dict[int, list[str]] = {}
    trailing: dict[int, str] = {}
    pending: list[str] = []
    file_header: list[str] = []
    seen_content = False
    for line_no, raw in enumerate(_split_lines(source.text), start=1):
        stripped = raw.strip()
        if not stripped:
            if pending and not seen_content and not file_header:
                file_header, pending = pending, []  # the file's opening comment block
            continue
        column = _comment_column(raw)
        if column is not None and not raw[: column - 1].strip():
            pending.append(raw[column - 1 :].rstrip())
            continue
        seen_content = True
        if pending:
            leading[line_no] = pending
            pending = []
        if column is not None:
            trailing[line_no] = raw[column - 1 :].rstrip()
    out: list[str] = [*file_header, ""] if file_header else []
    for text, origin in format_lines(spec, header_lines, fill_sizes=resolve is not None):
        if origin is not None and origin in leading:
            out += leading.pop(origin)
        if origin is not None and origin in trailing:
            text = f"{text}  {trailing.pop(origin)}"
        out.append(text)
    # comments whose line is not written (a duplicate header, say) are kept, not lost
    for comments in leading.values():
        out += comments
    out += trailing.values()
    if pending:
        out += ["", *pending]
    return "\n".join(out) + "\n"
