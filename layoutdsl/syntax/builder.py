"""Per-line Lark trees -> ast.Spec, reporting bad values (types, keywords, settings).

A `Transformer` turns each entry line into its AST node with the span of every value;
`build_spec` then assembles the nodes section by section. Names are not resolved here
(check.py does that), so a spec with an unknown room id still builds.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from lark import Token, Transformer

from layoutdsl.syntax.ast import (
    ADJACENCY_TYPES,
    EMPHASES,
    NO_SIZE,
    ROOM_TYPES,
    SIZES_PENDING,
    SETTING_KEYS,
    Adjacency,
    Arm,
    Boundary,
    Cluster,
    ClusterMember,
    Connection,
    Hint,
    Obstacle,
    Position,
    Room,
    Settings,
    Spec,
)
from layoutdsl.diagnostics import Diagnostic, Severity, register
from layoutdsl.diagnostics.source import Span

E_NUMBER_RANGE = "E008"  # registered in parser.py, where numbers are first met
E_EXPECTED_NUMBER = "E005"  # registered in parser.py too

_SIZE_FIELDS = ("minw", "maxw", "targetw", "minh", "maxh", "targeth", "minar", "maxar")
_NUMBERS_OF_A_BROKEN_SIZED_LINE = 4
"""A sizeless room line with this many numbers among its words is a sized line with a typo
in its first number (`R0 4,6 8 6 6 10 8 1 1.7 R CLASSROOM`), not a label."""

E_BAD_WEIGHT = register(
    "E009", Severity.ERROR, "invalid room weight",
    "Reports a `key=value` token on a room line whose key is not `cover` or `error`, whose "
    "value is not a non-negative number, or whose key is given twice.",
    "Per-room weights scale the room's terms of the objective (ρ_cover, ρ_error in 5.2-5.3); "
    "a misspelled key would otherwise be silently ignored.",
    "R0 4 8 6 6 10 8 1 1.7 R CLASSROOM covr=0.5",
)  # fmt: skip
E_UNKNOWN_SETTING = register(
    "E010", Severity.ERROR, "unknown setting",
    "Reports a `settings` key that layoutdsl does not know.",
    "A misspelled setting would silently keep its default value.",
    "settings\nlamda_cover 0.2",
)  # fmt: skip
E_BAD_SETTING = register(
    "E011", Severity.ERROR, "invalid setting value",
    "Reports a setting whose value has the wrong type, is out of range or has the wrong count.",
    "The solver would reject it later, or (worse) accept a meaningless value.",
    "settings\ndoor_utilization 1.5     # must be in (0, 1]",
)  # fmt: skip
E_BAD_ROOM_TYPE = register(
    "E012", Severity.ERROR, "unknown room type",
    "Reports a room type other than R (room), C (corridor) or E (entrance).",
    "The type decides which constraints apply (corridors have no aspect-ratio limit).",
    "R0 4 8 6 6 10 8 1 1.7 X CLASSROOM",
)  # fmt: skip
E_BAD_ADJACENCY_TYPE = register(
    "E013", Severity.ERROR, "unknown adjacency type",
    "Reports an adjacency type other than e (explicit portal, a door) or i (implicit portal).",
    "The type decides whether the portal is a door or an opening in the generated plan.",
    "adjacencies\nR0 C3 0.9 d",
)  # fmt: skip
E_DUPLICATE_SETTING = register(
    "E014", Severity.ERROR, "setting given twice",
    "Reports a settings key that appears more than once.",
    "Only one value can win; which one was meant is unclear.",
    "settings\nseed 1\nseed 2",
)  # fmt: skip
E_BOUNDARY_SIZE_TWICE = register(
    "E015", Severity.ERROR, "boundary size given twice",
    "Reports a second `w h` line in the `boundary` section.",
    "The boundary is one rectangle; a second size line is ambiguous.",
    "boundary\n20 50\n21 52",
)  # fmt: skip
E_NO_BOUNDARY = register(
    "E016", Severity.ERROR, "missing boundary",
    "Reports a `boundary` section without its `w h` line. (A spec may leave the whole section "
    "out: the tool then chooses the boundary, docs/sizes.md.)",
    "The obstacles of the section are placed in the boundary's frame; without its size they "
    "have none (the thesis, §5.4).",
    "boundary\nO1 2 2 1 1     # obstacle but no size line",
)  # fmt: skip
E_NO_ROOMS = register(
    "E017", Severity.ERROR, "missing rooms",
    "Reports a spec without a `rooms` section or with an empty one.",
    "There is nothing to lay out.",
    "boundary\n20 50",
)  # fmt: skip
E_MEMBER_BEFORE_CLUSTER = register(
    "E018", Severity.ERROR, "cluster member before any cluster id",
    "Reports a `room x y` line in `clusters` before the first cluster id line.",
    "Each member belongs to the cluster named above it; here there is none.",
    "clusters\nR0 0 0      # add a line `K0` above",
)  # fmt: skip

WEIGHT_KEYS = {"cover": "rho_cover", "error": "rho_error"}
"""Per-room weight token key -> Room field."""


@dataclass(frozen=True, slots=True)
class Entry:
    """One parsed entry line: its section, 1-based line number, text and built node."""

    section: str
    line: int
    text: str
    node: object
    """What LineBuilder made of the line (an AST node, or a marker tuple)."""


@dataclass(frozen=True, slots=True)
class SectionHeader:
    """Where a section was opened."""

    name: str
    line: int
    text: str


@dataclass(slots=True)
class LineContext:
    """Where the line being built is, and where its value problems go (one per parse call)."""

    filename: str
    line: int
    diagnostics: list[Diagnostic] = field(default_factory=list)


# Lark calls the builder inline while it parses (see parser.get_parser), so the builder cannot
# be told which line it is building through the call; the parse call sets this instead. A
# context variable is private to each thread (and asyncio task), so parsing is thread-safe.
_CURRENT_LINE: ContextVar[LineContext] = ContextVar("layoutdsl_current_line")


@contextmanager
def building_line(filename: str, line: int, diagnostics: list[Diagnostic]) -> Iterator[None]:
    """While inside, LINE_BUILDER builds line `line` of `filename` into `diagnostics`."""
    token = _CURRENT_LINE.set(LineContext(filename, line, diagnostics))
    try:
        yield
    finally:
        _CURRENT_LINE.reset(token)


@dataclass(frozen=True, slots=True)
class _Num:
    value: float
    span: Span
    text: str


@dataclass(frozen=True, slots=True)
class _Word:
    value: str
    span: Span


class LineBuilder(Transformer):
    """Lark Transformer from one entry line to its AST node (or a marker tuple).

    Lark runs it inline while parsing (see parser.get_parser), so it cannot take the line
    number from the tree: it reads the line, file name and diagnostics list of the current
    parse call from `building_line`. The instance itself holds no state, so the one
    LINE_BUILDER serves every thread.
    """

    def __init__(self) -> None:
        super().__init__(visit_tokens=False)

    # -- helpers
    def _span(self, token: Token) -> Span:
        line = _CURRENT_LINE.get().line
        return Span(line, token.column, line, token.end_column)

    def _word(self, token: Token) -> _Word:
        return _Word(str(token), self._span(token))

    def _error(self, code: str, message: str, span: Span, label: str = "", help: str | None = None):
        context = _CURRENT_LINE.get()
        context.diagnostics.append(Diagnostic(code, message, context.filename, span, label=label, help=help))

    def _line_span(self, first: Span, last: Span) -> Span:
        return Span(first.line, first.col, first.line, last.end_col)

    # -- rules
    def number(self, children: list[Token]) -> _Num:
        token = children[0]
        value = float(token)
        span = self._span(token)
        if not math.isfinite(value):
            self._error(
                E_NUMBER_RANGE, f"number `{token}` is too large", span, label="overflows to infinity",
                help="use a finite number of metres",
            )  # fmt: skip
        return _Num(value, span, str(token))

    def label(self, children: list[Token]) -> list[_Word]:
        return [self._word(t) for t in children]

    def weight(self, children: list[Token]) -> _Word:
        return self._word(children[0])

    def sizeless_label(self, children: list[Token]) -> list[tuple[_Word, bool]]:
        return [(self._word(t), t.type == "NUMBER") for t in children]

    def sizeless_room_line(self, children: list[Any]) -> Room:
        """`id [rtype] label... [onB] [weights]`: a room whose sizes the size model gives."""
        rid = self._word(children[0])
        tagged: list[tuple[_Word, bool]] = children[1]
        weights: list[_Word] = children[2:]
        numbers = sum(1 for _, is_number in tagged if is_number)
        first = tagged[0][0]
        if numbers >= _NUMBERS_OF_A_BROKEN_SIZED_LINE or re.match(r"[+\-.\d]", first.value):
            # the eight sizes with a typo, not a label: say which number is wrong
            index = next((i for i, (_, is_number) in enumerate(tagged) if not is_number), 0)
            word = tagged[index][0]
            field_name = _SIZE_FIELDS[index] if index < len(_SIZE_FIELDS) else "rtype"
            hint = "a room line is `id minw maxw targetw minh maxh targeth minar maxar rtype label`, or `id [rtype] label` for sizes from the model"
            if re.fullmatch(r"[+-]?\d+,\d+", word.value):
                hint = f"use `.` as the decimal separator: `{word.value.replace(',', '.')}`"
            if field_name == "rtype":
                self._error("E012", f"unknown room type `{word.value}`", word.span, label="expected R, C or E",
                            help="use R (room), C (corridor) or E (entrance)")  # fmt: skip
            else:
                self._error(E_EXPECTED_NUMBER, f"expected a number for `{field_name}`, found `{word.value}`",
                            word.span, label="not a number", help=hint)  # fmt: skip
        words = [word for word, _ in tagged]
        spans: dict[str, Span] = {"id": rid.span}
        on_boundary = False
        if len(words) > 1 and words[-1].value == "onB":
            on_boundary, spans["on_boundary"] = True, words[-1].span
            words = words[:-1]
        rtype = ""
        if words[0].value in ROOM_TYPES:
            rtype, spans["rtype"] = words[0].value, words[0].span
            words = words[1:]
        label = " ".join(w.value for w in words) or {"R": "ROOM", "C": "CORRIDOR", "E": "ENTRANCE"}[rtype]
        if words:
            spans["label"] = self._line_span(words[0].span, words[-1].span)
        rho = self._weights(weights, spans)
        last = weights[-1].span if weights else spans.get("on_boundary") or (words[-1].span if words else spans.get("rtype", rid.span))
        return Room(
            rid.value, *(NO_SIZE,) * 8, rtype, label, on_boundary, rho["rho_cover"], rho["rho_error"],
            span=self._line_span(rid.span, last), spans=MappingProxyType(spans), sizes_from=SIZES_PENDING,
        )  # fmt: skip

    def room_line(self, children: list[Any]) -> Room:
        rid = self._word(children[0])
        nums: list[_Num] = children[1:9]
        rtype = self._word(children[9])
        words: list[_Word] = children[10]
        weights: list[_Word] = children[11:]
        on_boundary = False
        onb_span = None
        if len(words) > 1 and words[-1].value == "onB":
            on_boundary, onb_span = True, words[-1].span
            words = words[:-1]
        label = " ".join(w.value for w in words)
        if rtype.value not in ROOM_TYPES:
            help_text = "use R (room), C (corridor) or E (entrance)"
            if rtype.value.upper() in ROOM_TYPES:
                help_text = f"room types are upper case: `{rtype.value.upper()}`"
            self._error(E_BAD_ROOM_TYPE, f"unknown room type `{rtype.value}`", rtype.span,
                        label="expected R, C or E", help=help_text)  # fmt: skip
        spans = {
            "id": rid.span, "rtype": rtype.span,
            "label": self._line_span(words[0].span, words[-1].span),
        }  # fmt: skip
        names = ("min_w", "max_w", "target_w", "min_h", "max_h", "target_h", "min_ar", "max_ar")
        spans.update({name: num.span for name, num in zip(names, nums)})
        if onb_span:
            spans["on_boundary"] = onb_span
        rho = self._weights(weights, spans)
        return Room(
            rid.value, *(n.value for n in nums), rtype.value, label, on_boundary,
            rho["rho_cover"], rho["rho_error"],
            span=self._line_span(rid.span, (weights[-1].span if weights else (onb_span or words[-1].span))),
            spans=MappingProxyType(spans),
        )  # fmt: skip

    def _weights(self, weights: list[_Word], spans: dict[str, Span]) -> dict[str, float]:
        """The `cover=W error=W` tokens of a room line (bad ones reported), their spans into `spans`."""
        rho = {"rho_cover": 1.0, "rho_error": 1.0}
        seen: set[str] = set()
        for weight in weights:
            key, _, text = weight.value.partition("=")
            field_name = WEIGHT_KEYS.get(key)
            if field_name is None:
                guess = difflib.get_close_matches(key, list(WEIGHT_KEYS), n=1)
                self._error(E_BAD_WEIGHT, f"unknown room weight `{key}`", weight.span,
                            label="not a weight",
                            help=f"did you mean `{guess[0]}`?" if guess else
                            "room weights are `cover=W` and `error=W`")  # fmt: skip
                continue
            if key in seen:
                self._error(E_BAD_WEIGHT, f"room weight `{key}` given twice", weight.span,
                            label="second value", help=f"keep one `{key}=` token")  # fmt: skip
                continue
            seen.add(key)
            value = _parse_float(text)
            if value is None or value < 0:
                self._error(E_BAD_WEIGHT, f"room weight `{key}` must be a non-negative number, found `{text}`",
                            weight.span, label="invalid weight", help=f"for example `{key}=0.5`")  # fmt: skip
                continue
            rho[field_name] = value
            spans[field_name] = weight.span
        return rho

    def arm_line(self, children: list[Any]) -> Arm:
        room = self._word(children[0])
        nums: list[_Num] = children[1:9]
        names = ("min_w", "max_w", "target_w", "min_h", "max_h", "target_h", "min_ar", "max_ar")
        spans = {"room": room.span, **{name: num.span for name, num in zip(names, nums)}}
        return Arm(
            room.value, *(n.value for n in nums), span=self._line_span(room.span, nums[-1].span),
            spans=MappingProxyType(spans),
        )  # fmt: skip

    def boundary_size(self, children: list[_Num]) -> tuple[str, _Num, _Num]:
        return ("size", children[0], children[1])

    def obstacle(self, children: list[Any]) -> Obstacle:
        oid = self._word(children[0])
        x, y, w, h = children[1:]
        return Obstacle(
            oid.value, x.value, y.value, w.value, h.value, span=self._line_span(oid.span, h.span),
            spans=MappingProxyType({"id": oid.span, "x": x.span, "y": y.span, "w": w.span, "h": h.span}),
        )  # fmt: skip

    def adjacency_line(self, children: list[Any]) -> Adjacency:
        a, b = self._word(children[0]), self._word(children[1])
        door: _Num = children[2]
        kind = self._word(children[3])
        if kind.value not in ADJACENCY_TYPES:
            help_text = "use e (explicit portal: a door) or i (implicit portal: an opening)"
            if kind.value.lower() in ADJACENCY_TYPES:
                help_text = f"adjacency types are lower case: `{kind.value.lower()}`"
            self._error(E_BAD_ADJACENCY_TYPE, f"unknown adjacency type `{kind.value}`", kind.span,
                        label="expected e or i", help=help_text)  # fmt: skip
        return Adjacency(
            a.value, b.value, door.value, kind.value, span=self._line_span(a.span, kind.span),
            spans=MappingProxyType({"a": a.span, "b": b.span, "door": door.span, "kind": kind.span}),
        )  # fmt: skip

    def position_line(self, children: list[Any]) -> Position:
        room = self._word(children[0])
        x, y = children[1:]
        return Position(
            room.value, x.value, y.value, span=self._line_span(room.span, y.span),
            spans=MappingProxyType({"room": room.span, "x": x.span, "y": y.span}),
        )  # fmt: skip

    def connection_line(self, children: list[Any]) -> Connection:
        room = self._word(children[0])
        x1, y1, x2, y2 = children[1:]
        return Connection(
            room.value, x1.value, y1.value, x2.value, y2.value, span=self._line_span(room.span, y2.span),
            spans=MappingProxyType(
                {"room": room.span, "x1": x1.span, "y1": y1.span, "x2": x2.span, "y2": y2.span}
            ),
        )  # fmt: skip

    def cluster_header(self, children: list[Token]) -> tuple[str, _Word]:
        return ("cluster", self._word(children[0]))

    def cluster_member(self, children: list[Any]) -> ClusterMember:
        room = self._word(children[0])
        x, y = children[1:]
        return ClusterMember(
            room.value, x.value, y.value, span=self._line_span(room.span, y.span),
            spans=MappingProxyType({"room": room.span, "x": x.span, "y": y.span}),
        )  # fmt: skip

    def hint_line(self, children: list[Any]) -> Hint:
        room = self._word(children[0])
        x, y, w, h = children[1:]
        return Hint(
            room.value, x.value, y.value, w.value, h.value, span=self._line_span(room.span, h.span),
            spans=MappingProxyType({"room": room.span, "x": x.span, "y": y.span, "w": w.span, "h": h.span}),
        )  # fmt: skip

    def setting_line(self, children: list[Token]) -> tuple[str, _Word, list[_Word]]:
        return ("setting", self._word(children[0]), [self._word(t) for t in children[1:]])


LINE_BUILDER = LineBuilder()
"""The builder Lark calls while parsing a line (parser.get_parser)."""


def _parse_float(text: str) -> float | None:
    if not re.fullmatch(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?", text):
        return None
    value = float(text)
    return value if math.isfinite(value) else None


# ===== Settings =====

def _setting_value(key: str, text: str) -> tuple[Any, str | None]:
    """(value, None) or (None, what-is-wrong) for one setting's text."""
    if key == "name":
        # outputs are written as OUTDIR/NAME.*: a name must not reach outside OUTDIR
        if re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.\-]*", text):
            return text, None
        return None, "must be a plain file name (letters, digits, `_`, `-`, `.`)"
    if key == "kind":
        if re.fullmatch(r"[A-Za-z][A-Za-z0-9_\-]*", text):
            return text, None
        return None, "must be a building kind such as `school` or `office`"
    if key == "emphasis":
        if text in EMPHASES:
            return text, None
        return None, "must be one of " + ", ".join(f"`{v}`" for v in EMPHASES)
    if key in ("seed", "node_limit"):
        if key == "node_limit" and text == "none":
            return None, None
        if not re.fullmatch(r"\+?\d+", text):
            return None, "must be a whole number"
        value = int(text)
        if key == "seed" and value > 2**31 - 1:
            return None, "must be at most 2147483647 (SCIP's largest seed)"
        if key == "node_limit" and value < 1:
            return None, "must be at least 1 (or `none`)"
        return value, None
    value = _parse_float(text)
    if value is None:
        return None, "must be a finite number"
    if key == "door_utilization" and not 0 < value <= 1:
        return None, "must be in (0, 1]"
    if key == "time_limit" and value <= 0:
        return None, "must be positive (seconds)"
    if value < 0:
        return None, "must not be negative"
    return value, None


def _build_settings(
    lines: list[tuple[_Word, list[_Word], int]], filename: str, header_span: Span | None
) -> tuple[Settings, str | None, list[Diagnostic]]:
    diagnostics: list[Diagnostic] = []
    values: dict[str, Any] = {}
    spans: dict[str, Span] = {}
    name: str | None = None
    for key, words, _line in lines:
        if key.value not in SETTING_KEYS:
            guess = difflib.get_close_matches(key.value, SETTING_KEYS, n=1)
            diagnostics.append(Diagnostic(
                E_UNKNOWN_SETTING, f"unknown setting `{key.value}`", filename, key.span,
                label="not a setting",
                help=f"did you mean `{guess[0]}`?" if guess else "settings are " + ", ".join(SETTING_KEYS),
            ))  # fmt: skip
            continue
        if key.value in spans:
            diagnostics.append(Diagnostic(
                E_DUPLICATE_SETTING, f"setting `{key.value}` given twice", filename, key.span,
                label="second value", help="remove one of the two lines",
                notes=(f"first given on line {spans[key.value].line}",),
            ))  # fmt: skip
            continue
        value_span = Span(words[0].span.line, words[0].span.col, words[-1].span.end_line, words[-1].span.end_col)
        spans[key.value] = value_span
        if len(words) != 1:
            diagnostics.append(Diagnostic(
                E_BAD_SETTING, f"setting `{key.value}` takes one value, found {len(words)}", filename,
                value_span, label="one value expected", help=f"write `{key.value} VALUE`",
            ))  # fmt: skip
            continue
        value, problem = _setting_value(key.value, words[0].value)
        if problem:
            diagnostics.append(Diagnostic(
                E_BAD_SETTING, f"setting `{key.value}` {problem}, found `{words[0].value}`", filename,
                value_span, label="invalid value",
            ))  # fmt: skip
            continue
        if key.value == "name":
            name = value
        else:
            values[key.value] = value
    settings = Settings(
        **values, explicit=frozenset(spans), span=header_span, spans=MappingProxyType(spans)
    )
    return settings, name, diagnostics


# ===== Assembly =====


@dataclass(slots=True)
class _Sections:
    """The built entry lines, sorted by what they are, before assembly into a Spec."""

    rooms: list[Room] = field(default_factory=list)
    arms: list[Arm] = field(default_factory=list)
    obstacles: list[Obstacle] = field(default_factory=list)
    size: tuple[_Num, _Num] | None = None
    size_span: Span | None = None
    adjacencies: list[Adjacency] = field(default_factory=list)
    positions: list[Position] = field(default_factory=list)
    connections: list[Connection] = field(default_factory=list)
    clusters: list[tuple[_Word, list[ClusterMember]]] = field(default_factory=list)
    hints: list[Hint] = field(default_factory=list)
    setting_lines: list[tuple[_Word, list[_Word], int]] = field(default_factory=list)


_NODE_LISTS = {Room: "rooms", Arm: "arms", Obstacle: "obstacles", Adjacency: "adjacencies", Position: "positions",
               Connection: "connections", Hint: "hints"}  # fmt: skip


def _sort_entries(entries: list[Entry], path: str, diagnostics: list[Diagnostic]) -> _Sections:
    """Each entry's node into its list; cluster members under the cluster id above them."""
    found = _Sections()
    for entry in entries:
        node = entry.node
        if type(node) in _NODE_LISTS:
            getattr(found, _NODE_LISTS[type(node)]).append(node)
        elif isinstance(node, ClusterMember):
            if not found.clusters:
                diagnostics.append(Diagnostic(
                    E_MEMBER_BEFORE_CLUSTER, f"cluster member `{node.room}` before any cluster id", path,
                    node.span, label="belongs to no cluster",
                    help="add a line with the cluster's id (for example `K0`) above its rooms",
                ))  # fmt: skip
            else:
                found.clusters[-1][1].append(node)
        elif node[0] == "cluster":
            found.clusters.append((node[1], []))
        elif node[0] == "size":
            span = Span(entry.line, node[1].span.col, entry.line, node[2].span.end_col)
            if found.size is not None:
                diagnostics.append(Diagnostic(
                    E_BOUNDARY_SIZE_TWICE, "boundary size given twice", path, span, label="second size",
                    help="keep one `w h` line", notes=(f"first given on line {found.size_span.line}",),
                ))  # fmt: skip
            else:
                found.size, found.size_span = (node[1], node[2]), span
        elif node[0] == "setting":
            found.setting_lines.append((node[1], node[2], entry.line))
    return found


def _header_spans(headers: list[SectionHeader]) -> dict[str, Span]:
    """Section name -> the span of its (first) header word."""
    spans: dict[str, Span] = {}
    for header in headers:
        if header.name not in spans:
            col = header.text.index(header.name) + 1
            spans[header.name] = Span(header.line, col, header.line, col + len(header.name))
    return spans


def _missing_sections(found: _Sections, header_spans: dict[str, Span], path: str) -> list[Diagnostic]:
    """E016 (no boundary size) and E017 (no rooms), located at the section's header if any."""
    diagnostics = []
    if found.size is None:
        # No `boundary` section at all: the tool chooses one (layoutdsl.sizes.boundary).
        # A section without its size line is still an error: its obstacles need a frame.
        span = header_spans.get("boundary")
        if span is not None:
            diagnostics.append(Diagnostic(
                E_NO_BOUNDARY, "`boundary` section has no size line", path, span,
                label="no `w h` line", help="add a line `w h` (metres) under `boundary`",
            ))  # fmt: skip
    if not found.rooms:
        span = header_spans.get("rooms")
        diagnostics.append(Diagnostic(
            E_NO_ROOMS, "spec has no rooms" if span else "spec has no `rooms` section", path,
            span or Span(1, 1, 1, 2), label="no rooms",
            help="add a section `rooms` with one line per room",
        ))  # fmt: skip
    return diagnostics


def build_spec(
    entries: list[Entry],
    headers: list[SectionHeader],
    *,
    path: str,
    default_name: str,
    had_syntax_errors: bool = False,
) -> tuple[Spec, list[Diagnostic]]:
    """Assemble the parsed entry lines into a Spec, reporting value errors."""
    diagnostics: list[Diagnostic] = []
    found = _sort_entries(entries, path, diagnostics)
    header_spans = _header_spans(headers)
    settings, name, setting_diagnostics = _build_settings(found.setting_lines, path, header_spans.get("settings"))
    diagnostics.extend(setting_diagnostics)
    if not had_syntax_errors:  # after a syntax error the missing line may be the broken one
        diagnostics.extend(_missing_sections(found, header_spans, path))
    boundary = None
    if found.size is not None:
        w, h = found.size
        boundary = Boundary(
            w.value, h.value, tuple(found.obstacles), span=found.size_span,
            spans=MappingProxyType({"w": w.span, "h": h.span}),
        )  # fmt: skip
    spec = Spec(
        name=name if name is not None else default_name,
        rooms=tuple(found.rooms),
        boundary=boundary,
        adjacencies=tuple(found.adjacencies),
        positions=tuple(found.positions),
        connections=tuple(found.connections),
        clusters=tuple(
            Cluster(word.value, tuple(members), span=word.span, spans=MappingProxyType({"id": word.span}))
            for word, members in found.clusters
        ),
        hints=tuple(found.hints),
        settings=settings,
        path=path,
        arms=tuple(found.arms),
    )
    return spec, diagnostics
