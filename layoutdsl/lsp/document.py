"""A lexical index of a spec's text: its lines, their sections and words, and every room id.

The parser (`layoutdsl.syntax.parser`) gives no spec at all while any line has a syntax
error, which is most of the time while someone types. The editor features need less than a
spec: which section a line is in, which of its words is a room id, and where each id is
defined. This module reads that off the text with the spec language's own lexical rules
(README, "The spec language"): a line holding only a section name opens a section, values
are separated by blanks, and `#` at the start of a value begins a comment.

Positions here are 0-based lines and 0-based code-point columns, as the Language Server
Protocol counts lines; the server converts columns to the client's encoding.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import cached_property
from typing import NamedTuple

from layoutdsl.syntax.ast import ROOM_TYPES
from layoutdsl.syntax.parser import SECTIONS

_COMMENT = re.compile(r"(?:^|(?<=\s))#")
"""A `#` at the start of a value starts a comment; inside a value (`ROOM#3`) it does not."""
_WORD = re.compile(r"[^\s]+")
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")

ROOM_ID_SLOTS = {
    "rooms": (0,),
    "arms": (0,),
    "adjacencies": (0, 1),
    "positions": (0,),
    "connections": (0,),
    "hints": (0,),
}
"""Section -> which words of an entry line are room ids (`clusters` is handled apart: a
member line `room x y` names a room, a line of one word is a cluster id)."""


def is_number(word: str) -> bool:
    """Does the word read as a spec number (`4`, `4.68`, `.5`, `-1`, `1e3`)?"""
    return _NUMBER.fullmatch(word) is not None


def split_lines(text: str) -> list[str]:
    """The text's lines as the parser counts them: only `\\n` (or `\\r\\n`) ends a line."""
    if text.startswith("\ufeff"):
        text = text[1:]
    return [line[:-1] if line.endswith("\r") else line for line in text.split("\n")]


class Word(NamedTuple):
    """A blank-separated value on a line: its text and 0-based [start, end) columns.

    A NamedTuple rather than a frozen dataclass: a 2,000-room spec has 40,000 words, and a
    tuple is made three times faster."""

    text: str
    line: int
    start: int
    end: int

    def contains(self, line: int, column: int) -> bool:
        """Is (line, column) on this word (its end included, where a cursor after it sits)?"""
        return line == self.line and self.start <= column <= self.end


class SpecLine:
    """One line of the text: the section it belongs to and its words before any comment.

    The words are found when first asked for: indexing a 2,000-room spec needs only the
    one or two room ids of each line, and making all 40,000 words up front would double
    the time the server takes to index it after each edit."""

    __slots__ = ("number", "text", "section", "is_header", "comment_start", "content", "_words")

    def __init__(self, number: int, text: str, section: str | None, content: str, is_header: bool,
                 comment_start: int | None) -> None:  # fmt: skip
        self.number = number
        self.text = text
        self.section = section
        """The section the line is in (for a header line, the section it opens)."""
        self.content = content
        """The text before any comment."""
        self.is_header = is_header
        self.comment_start = comment_start
        """0-based column of a `#` comment, if the line has one."""
        self._words: tuple[Word, ...] | None = None

    @property
    def words(self) -> tuple[Word, ...]:
        if self._words is None:
            self._words = tuple(Word(m.group(), self.number, m.start(), m.end()) for m in _WORD.finditer(self.content))
        return self._words


@dataclass(frozen=True, slots=True)
class RoomUse:
    """A word that names a room: its definition (the id of a `rooms` line) or a reference."""

    word: Word
    section: str
    is_definition: bool


@dataclass
class SpecDocument:
    """The lexical index of one spec text."""

    text: str
    lines: list[SpecLine] = field(init=False)
    room_uses: list[RoomUse] = field(init=False)
    definitions: dict[str, Word] = field(init=False)
    """Room id -> the id word of its first `rooms` line (a duplicate is lint's E101)."""
    room_lines: dict[str, SpecLine] = field(init=False)

    def __post_init__(self) -> None:
        self.lines = []
        self.room_uses = []
        self.definitions = {}
        self.room_lines = {}
        section: str | None = None
        for number, raw in enumerate(split_lines(self.text)):
            comment = _COMMENT.search(raw) if "#" in raw else None
            content = raw if comment is None else raw[: comment.start()]
            values = content.split()
            header = len(values) == 1 and values[0] in SECTIONS
            if header:
                section = values[0]
            line = SpecLine(number, raw, section, content, header, comment.start() if comment else None)
            self.lines.append(line)
            if header or not values or section is None:
                continue
            for word in self._room_words(section, values, content, number):
                use = RoomUse(word, section, section == "rooms")
                self.room_uses.append(use)
                if use.is_definition and word.text not in self.definitions:
                    self.definitions[word.text] = word
                    self.room_lines[word.text] = line

    @staticmethod
    def _room_words(section: str, values: list[str], content: str, number: int) -> list[Word]:
        """The words of a line that name rooms (see ROOM_ID_SLOTS)."""
        if section == "clusters":
            slots: tuple[int, ...] = (0,) if len(values) > 1 else ()
        else:
            slots = ROOM_ID_SLOTS.get(section, ())
        found = []
        end = 0
        for slot, value in enumerate(values[: max(slots, default=-1) + 1]):
            start = content.index(value, end)  # values are in order, separated by blanks
            end = start + len(value)
            if slot in slots and not is_number(value):
                found.append(Word(value, number, start, end))
        return found

    # ----------------------------------------------------------------- look-ups

    def line(self, number: int) -> SpecLine | None:
        return self.lines[number] if 0 <= number < len(self.lines) else None

    def room_use_at(self, line: int, column: int) -> RoomUse | None:
        """The room id under the cursor, if any."""
        spec_line = self.line(line)
        if spec_line is None:
            return None
        for use in self._uses_by_line.get(line, ()):
            if use.word.contains(line, column):
                return use
        return None

    @cached_property
    def _uses_by_line(self) -> dict[int, list[RoomUse]]:
        by_line: dict[int, list[RoomUse]] = {}
        for use in self.room_uses:
            by_line.setdefault(use.word.line, []).append(use)
        return by_line

    def uses_of(self, room_id: str) -> list[RoomUse]:
        """Every word naming the room, definition first, then in text order."""
        uses = [use for use in self.room_uses if use.word.text == room_id]
        uses.sort(key=lambda use: (not use.is_definition, use.word.line, use.word.start))
        return uses

    def labels(self, except_line: int | None = None) -> list[str]:
        """The labels the file's rooms use, each once, in first-use order (leaving out the
        room on `except_line`: the line being typed)."""
        seen: dict[str, None] = {}
        for room_id in self.definitions:
            if self.room_lines[room_id].number == except_line:
                continue
            label = self.room_entry(room_id).label
            if label:
                seen.setdefault(label, None)
        return list(seen)

    def sections(self) -> list[str]:
        """The sections the text opens, in order."""
        return [line.section for line in self.lines if line.is_header and line.section]

    def setting_keys(self) -> list[str]:
        """The keys the `settings` section sets."""
        return [line.words[0].text for line in self.lines
                if line.section == "settings" and not line.is_header and line.words]  # fmt: skip

    def room_entry(self, room_id: str) -> RoomEntry:
        """What the room's line says, read word by word."""
        return RoomEntry.from_line(self.room_lines[room_id])

    def adjacencies_of(self, room_id: str) -> list[tuple[str, str, str, int]]:
        """(other room, door, atype, 0-based line) of every adjacency line naming the room."""
        found = []
        for line in self.lines:
            if line.section != "adjacencies" or line.is_header or len(line.words) < 2:
                continue
            a, b = line.words[0].text, line.words[1].text
            if room_id not in (a, b):
                continue
            other = b if a == room_id else a
            door = line.words[2].text if len(line.words) > 2 else "?"
            kind = line.words[3].text if len(line.words) > 3 else "?"
            found.append((other, door, kind, line.number))
        return found


@dataclass(frozen=True, slots=True)
class RoomEntry:
    """A `rooms` line as written: `id [8 numbers] [rtype] label... [onB] [cover=W] [error=W]`.

    Read lexically so that hover works on a spec that does not parse yet; the numbers are
    the words after the id that read as numbers (none for a room whose sizes the size model
    chooses).
    """

    id: str
    numbers: tuple[str, ...]
    rtype: str | None
    label: str
    on_boundary: bool
    weights: tuple[str, ...]

    @staticmethod
    def from_line(line: SpecLine) -> RoomEntry:
        words = [w.text for w in line.words]
        room_id, rest = words[0], words[1:]
        numbers: list[str] = []
        while rest and is_number(rest[0]):
            numbers.append(rest.pop(0))
        # after the sizes the next word is the room type, whatever it is; a sizeless line
        # (`id [rtype] label...`) has one only if that word is R, C or E (as the parser reads it)
        rtype = None
        if rest and (numbers or rest[0] in ROOM_TYPES):
            rtype = rest.pop(0)
        weights = []
        while rest and "=" in rest[-1]:
            weights.insert(0, rest.pop())
        on_boundary = len(rest) > 1 and rest[-1] == "onB"
        if on_boundary:
            rest.pop()
        return RoomEntry(room_id, tuple(numbers), rtype, " ".join(rest), on_boundary, tuple(weights))
