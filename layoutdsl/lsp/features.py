"""What the language server answers, as plain functions of a spec's text.

Lines are 0-based and columns are 0-based code points here (`layoutdsl.lsp.document`); the
server converts them to the client's position encoding. Diagnostics come from exactly what
`layoutdsl lint` runs (`layoutdsl.api.lint_source`: the parser, then every check), so the
editor and the command line never disagree.
"""

from __future__ import annotations

import re
from dataclasses import MISSING, dataclass, fields

from layoutdsl.api import lint_source
from layoutdsl.diagnostics import Diagnostic
from layoutdsl.diagnostics.source import Source
from layoutdsl.lsp.document import RoomEntry, SpecDocument, Word, is_number
from layoutdsl.syntax.ast import (
    ADJACENCY_TYPES, EMPHASES, ROOM_TYPE_NAMES, ROOM_TYPES, SETTING_KEYS, Room, Settings, Spec,
)  # fmt: skip
from layoutdsl.syntax.format import format_source
from layoutdsl.syntax.parser import LINE_SYNOPSIS, SECTION_RULES, SECTIONS


@dataclass(frozen=True, slots=True)
class Range:
    """0-based, end-exclusive (start_line, start_col) - (end_line, end_col), code points."""

    start_line: int
    start_col: int
    end_line: int
    end_col: int

    @staticmethod
    def of_word(word: Word) -> Range:
        return Range(word.line, word.start, word.line, word.end)


@dataclass(frozen=True, slots=True)
class Fix:
    """A quick fix: replace `range` with `new_text`; `title` is what the editor's menu says."""

    title: str
    range: Range
    new_text: str


@dataclass(frozen=True, slots=True)
class EditorDiagnostic:
    """A lint diagnostic placed in the editor, with the quick fix its hint spells out."""

    diagnostic: Diagnostic
    range: Range
    message: str
    fix: Fix | None


# ----------------------------------------------------------------------------- diagnostics


@dataclass(frozen=True, slots=True)
class Linted:
    """A lint's result: the spec when it parsed (sizeless rooms sized by the size model), and
    the diagnostics placed in the editor."""

    spec: Spec | None
    diagnostics: list[EditorDiagnostic]


def lint(text: str, path: str) -> Linted:
    """Lint a text as `layoutdsl lint` does and place each diagnostic in the editor."""
    spec, diagnostics = lint_source(Source(path, text))
    lines = text.split("\n")
    placed = []
    for diagnostic in diagnostics:
        span = diagnostic.span
        start_line, end_line = span.line - 1, span.end_line - 1
        rng = Range(start_line, span.col - 1, end_line, span.end_col - 1)
        if start_line >= len(lines):  # a whole-file problem reported past the end
            rng = Range(len(lines) - 1, 0, len(lines) - 1, 0)
        fix = fix_for(diagnostic, rng, len(lines))
        placed.append(EditorDiagnostic(diagnostic, rng, editor_message(diagnostic), fix))
    return Linted(spec, placed)


def editor_message(diagnostic: Diagnostic) -> str:
    """The message as an editor shows it: the message, its caret label, notes and help."""
    parts = [diagnostic.message]
    if diagnostic.label:
        parts[0] += f" ({diagnostic.label})"
    parts.extend(f"note: {note}" for note in diagnostic.notes)
    if diagnostic.help:
        parts.append(f"help: {diagnostic.help}")
    return "\n".join(parts)


# The hints that spell out an exact replacement for the diagnostic's span. Diagnostics carry
# their hint as text only (layoutdsl.diagnostics.Diagnostic.help), so a fix is recognised by
# the hint's wording; tests/lsp/test_features.py lints one example of each so that a
# rewording shows up as a failing test, not as a quick fix that silently disappears.
_REPLACEMENT_HINTS = (
    re.compile(r"did you mean `(?P<text>[^`]+)`\?"),  # unknown room, section, setting, weight
    re.compile(r"room types are upper case: `(?P<text>[^`]+)`"),  # E012 `r` -> `R`
    re.compile(r"use `\.` as the decimal separator: `(?P<text>[^`]+)`"),  # E005 `4,5` -> `4.5`
)


_REMOVE_LINE_HINTS = (
    "remove one of the two lines",  # E111 adjacency listed twice, a setting given twice
    "keep one hint per room",  # E113
    "keep one point per room",  # E112, a room twice in one cluster
)
"""Hints of diagnostics that point at the second of two lines saying the same thing: the fix
removes that line (the first stays, as the hint's note says where)."""


def fix_for(diagnostic: Diagnostic, rng: Range, line_count: int) -> Fix | None:
    """The quick fix a diagnostic's hint names, if it names one."""
    if not diagnostic.help or rng.start_line != rng.end_line:
        return None
    for pattern in _REPLACEMENT_HINTS:
        match = pattern.search(diagnostic.help)
        if match:
            text = match.group("text")
            return Fix(f"Replace with `{text}` ({diagnostic.code})", rng, text)
    if diagnostic.help in _REMOVE_LINE_HINTS:
        line = rng.start_line
        # the line and its end of line; the last line takes the end of the line before it
        if line + 1 < line_count:
            whole = Range(line, 0, line + 1, 0)
        elif line > 0:
            whole = Range(line - 1, _END_OF_LINE, line, _END_OF_LINE)
        else:
            whole = Range(line, 0, line, _END_OF_LINE)
        return Fix(f"Remove line {line + 1} ({diagnostic.code})", whole, "")
    return None


_END_OF_LINE = 1 << 30
"""A column past any line's end: the server clamps it to the line's length."""


# ----------------------------------------------------------------------------- navigation


def definition(document: SpecDocument, line: int, column: int) -> Range | None:
    """Where the room id under the cursor is defined (its `rooms` line)."""
    use = document.room_use_at(line, column)
    if use is None or use.word.text not in document.definitions:
        return None
    return Range.of_word(document.definitions[use.word.text])


def references(document: SpecDocument, line: int, column: int, include_declaration: bool = True) -> list[Range]:
    """Every place the room id under the cursor is named (its definition first)."""
    use = document.room_use_at(line, column)
    if use is None:
        return []
    return [Range.of_word(u.word) for u in document.uses_of(use.word.text)
            if include_declaration or not u.is_definition]  # fmt: skip


class RenameError(ValueError):
    """A rename the spec cannot take (the message says why, for the editor to show)."""


def rename(document: SpecDocument, line: int, column: int, new_name: str) -> list[Range]:
    """Where to write `new_name` to rename the room id under the cursor: its definition and
    every use. Raises RenameError for a name that is not an id or is taken."""
    use = document.room_use_at(line, column)
    if use is None:
        raise RenameError("not a room id")
    if not new_name or any(ch.isspace() for ch in new_name) or new_name.startswith("#") or is_number(new_name):
        raise RenameError(f"`{new_name}` is not an id: one word, not a number, not starting with `#`")
    if "=" in new_name or new_name in SECTIONS:
        raise RenameError(f"`{new_name}` would read as a weight or a section name")
    if new_name != use.word.text and new_name in document.definitions:
        raise RenameError(f"a room `{new_name}` is already defined on line {document.definitions[new_name].line + 1}")
    return [Range.of_word(u.word) for u in document.uses_of(use.word.text)]


@dataclass(frozen=True, slots=True)
class Symbol:
    """An outline entry: a section (with its rooms, for `rooms`)."""

    name: str
    kind: str
    """`section` or `room`."""
    range: Range
    detail: str = ""
    children: tuple[Symbol, ...] = ()


def outline(document: SpecDocument) -> list[Symbol]:
    """The sections in order, each spanning its lines; `rooms` lists its rooms."""
    headers = [line for line in document.lines if line.is_header]
    symbols = []
    for index, header in enumerate(headers):
        last = headers[index + 1].number - 1 if index + 1 < len(headers) else len(document.lines) - 1
        while last > header.number and not document.lines[last].content.strip():
            last -= 1
        children: tuple[Symbol, ...] = ()
        if header.section == "rooms":
            children = tuple(
                Symbol(room_id, "room", Range(word.line, 0, word.line, len(document.lines[word.line].text)),
                       f"{document.room_entry(room_id).rtype or ''} {document.room_entry(room_id).label}".strip())
                for room_id, word in document.definitions.items()
                if header.number < word.line <= last
            )  # fmt: skip
        span = Range(header.number, 0, last, len(document.lines[last].text))
        symbols.append(Symbol(header.section, "section", span, children=children))
    return symbols


# ----------------------------------------------------------------------------- hover

_SIZE_ROWS = (("width", 0), ("height", 3))


def hover(document: SpecDocument, line: int, column: int, spec: Spec | None = None) -> tuple[str, Range] | None:
    """Markdown about the room id under the cursor: type, label, size bounds, adjacencies.
    `spec` (the last one that parsed) gives the sizes the size model chose for a sizeless room.
    On a section name, the shape of its lines; on a setting's key, its default."""
    use = document.room_use_at(line, column)
    if use is None:
        return _keyword_hover(document, line, column)
    room_id = use.word.text
    if room_id not in document.room_lines:
        return f"`{room_id}`: no room with this id is defined in `rooms`", Range.of_word(use.word)
    parsed = spec.room(room_id) if spec is not None else None
    return room_markdown(document, document.room_entry(room_id), parsed), Range.of_word(use.word)


_SECTION_SHAPES = {
    "boundary": ("boundary_size", "obstacle"),
    "clusters": ("cluster_header", "cluster_member"),
}
"""Sections whose lines come in two shapes (parser.LINE_SYNOPSIS names each)."""


def _keyword_hover(document: SpecDocument, line: int, column: int) -> tuple[str, Range] | None:
    spec_line = document.line(line)
    word = next((w for w in spec_line.words if w.contains(line, column)), None) if spec_line else None
    if word is None:
        return None
    if spec_line.is_header:
        shapes = _SECTION_SHAPES.get(word.text, (SECTION_RULES[word.text],))
        lines = "\n".join(LINE_SYNOPSIS[shape] for shape in shapes)
        return f"section `{word.text}`: one entry per line\n\n```\n{lines}\n```", Range.of_word(word)
    if spec_line.section == "settings" and word is spec_line.words[0] and word.text in SETTING_KEYS:
        default = _SETTING_DEFAULTS.get(word.text)
        text = f"setting `{word.text}`" + (f", default `{default}`" if default is not None else "")
        if word.text == "emphasis":
            text += "; one of " + ", ".join(f"`{value}`" for value in EMPHASES)
        return text, Range.of_word(word)
    return None


_SETTING_DEFAULTS = {f.name: ("none" if f.default is None else f.default)
                     for f in fields(Settings) if f.name in SETTING_KEYS and f.default is not MISSING}  # fmt: skip


def _size_table(numbers: tuple[str, ...]) -> list[str]:
    n = numbers
    out = ["| | min | max | target |", "|---|---|---|---|"]
    out += [f"| {name} (m) | {n[i]} | {n[i + 1]} | {n[i + 2]} |" for name, i in _SIZE_ROWS]
    return [*out, "", f"aspect ratio {n[6]} to {n[7]}"]


def room_markdown(document: SpecDocument, room: RoomEntry, parsed: Room | None = None) -> str:
    kind = ROOM_TYPE_NAMES.get(room.rtype or "", f"type `{room.rtype}`" if room.rtype else "no type given")
    defined = document.definitions[room.id].line + 1
    out = [f"**{room.id}**: {kind} `{room.label}` (line {defined})", ""]
    if len(room.numbers) >= 8:
        out += _size_table(room.numbers)
    elif not room.numbers and parsed is not None and parsed.sizes_from:
        chosen = (parsed.min_w, parsed.max_w, parsed.target_w, parsed.min_h, parsed.max_h, parsed.target_h,
                  parsed.min_ar, parsed.max_ar)  # fmt: skip
        out += [f"sizes from the size model ({parsed.sizes_from}), at the last lint:", ""]
        out += _size_table(tuple(f"{value:g}" for value in chosen))
    elif not room.numbers:
        out.append("sizes: none written (the size model chooses them)")
    else:
        out.append("sizes: " + " ".join(room.numbers) + " (incomplete line)")
    arm = next((line for line in document.lines if line.section == "arms" and not line.is_header
                and line.words and line.words[0].text == room.id), None)  # fmt: skip
    if arm is not None:
        numbers = tuple(word.text for word in arm.words[1:9])
        out += ["", f"L-shaped: its second rectangle is on line {arm.number + 1} (`arms`)"]
        if len(numbers) == 8 and all(is_number(n) for n in numbers):
            out += ["", *_size_table(numbers)]
    extras = []
    if room.on_boundary:
        extras.append("on the boundary (`onB`)")
    extras.extend(f"`{weight}`" for weight in room.weights)
    if extras:
        out += ["", ", ".join(extras)]
    adjacent = document.adjacencies_of(room.id)
    out.append("")
    if adjacent:
        out.append("adjacent to:")
        for other, door, kind_letter, _ in adjacent:
            what = {"e": "door", "i": "opening"}.get(kind_letter, kind_letter)
            out.append(f"- `{other}` ({what}, {door} m)")
    else:
        out.append("adjacent to no room")
    return "\n".join(out)


# ----------------------------------------------------------------------------- completion


@dataclass(frozen=True, slots=True)
class Completion:
    label: str
    kind: str
    """`section`, `room`, `label`, `setting`, `value` or `flag`: the server maps it to an icon."""
    detail: str = ""


def completions(document: SpecDocument, line: int, column: int) -> list[Completion]:
    """What may be typed at the cursor, from the line's section and the word's place in it."""
    spec_line = document.line(line)
    if spec_line is None:
        return [Completion(name, "section") for name in SECTIONS]
    if spec_line.comment_start is not None and column > spec_line.comment_start:
        return []
    before = [w for w in spec_line.words if w.start < column]
    typing = bool(before) and before[-1].end >= column  # the cursor is on a word, not after a blank
    index = len(before) - 1 if typing else len(before)
    previous = [w.text for w in before[: index]]
    section = spec_line.section if not spec_line.is_header else _section_before(document, line)
    items: list[Completion] = []
    if index == 0:
        opened = set(document.sections())
        items += [Completion(name, "section") for name in SECTIONS if name not in opened or spec_line.is_header]
    if section is None:
        return items
    if section == "rooms":
        items += _room_line_completions(document, previous, index, line)
    elif section == "adjacencies":
        if index in (0, 1):
            items += _room_ids(document, exclude=previous[:1])
        elif index == 3:
            items += [Completion(kind, "value", {"e": "door (explicit portal)", "i": "opening (implicit portal)"}[kind])
                      for kind in ADJACENCY_TYPES]  # fmt: skip
    elif section in ("arms", "positions", "connections", "hints", "clusters") and index == 0:
        items += _room_ids(document)
    elif section == "settings":
        if index == 0:
            chosen = set(document.setting_keys())
            items += [Completion(key, "setting") for key in SETTING_KEYS if key not in chosen]
        elif index == 1 and previous[0] == "emphasis":
            items += [Completion(value, "value", "SCIP emphasis") for value in EMPHASES]
    return items


def _section_before(document: SpecDocument, line: int) -> str | None:
    previous = document.line(line - 1)
    return previous.section if previous else None


def _room_ids(document: SpecDocument, exclude: list[str] = ()) -> list[Completion]:
    items = []
    for room_id in document.definitions:
        if room_id in exclude:
            continue
        entry = document.room_entry(room_id)
        items.append(Completion(room_id, "room", f"{entry.rtype or '?'} {entry.label}".strip()))
    return items


def _room_line_completions(document: SpecDocument, previous: list[str], index: int, line: int) -> list[Completion]:
    if index == 0:
        return []  # a new room's id: nothing to offer but the section names
    after_id = previous[1:]
    types = [Completion(t, "value", ROOM_TYPE_NAMES[t]) for t in ROOM_TYPES]
    if not after_id:
        # the eight sizes, or a sizeless line: a room type or the label straight away
        return types + [Completion(label, "label") for label in document.labels(except_line=line)]
    if all(is_number(word) for word in after_id):
        # still among the sizes; the room type comes after the eighth
        return types if len(after_id) == 8 else []
    items = [Completion(label, "label") for label in document.labels(except_line=line)]
    if len(after_id) > 1 + sum(is_number(w) for w in after_id):  # a label word is written
        items += [Completion("onB", "flag", "the room touches the boundary (the thesis, 5.12)")]
        items += [Completion("cover=", "flag", "weight of its area in E_cover"),
                  Completion("error=", "flag", "weight of its size error in E_error")]  # fmt: skip
    return items


# ----------------------------------------------------------------------------- formatting


def formatted(text: str, path: str) -> str | None:
    """The text as `layoutdsl fmt` writes it, or None when it has errors (fmt refuses then)."""
    return format_source(Source(path, text))
