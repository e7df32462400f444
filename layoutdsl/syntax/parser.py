"""Spec text -> per-line Lark parses -> ast.Spec, with named syntax errors.

The file is split into sections at header lines (a line holding only a section name);
every other line is parsed on its own with the grammar's start rule for its section. A
bad line becomes one located diagnostic and parsing goes on with the next line, so a
person sees every syntax error at once. Syntax errors are named with Lark's
`UnexpectedInput.match_examples` over SYNTAX_ERRORS (as Lark names its own grammar
errors), never shown as raw parser text.
"""

from __future__ import annotations

import difflib
import functools
import re
from collections.abc import Iterator, Mapping
from dataclasses import fields, is_dataclass, replace
from pathlib import Path
from types import MappingProxyType

from lark import Lark, Token
from lark.exceptions import UnexpectedCharacters, UnexpectedInput, UnexpectedToken
from lark.lexer import Lexer

from layoutdsl import private_api
from layoutdsl.syntax import builder as build
from layoutdsl.syntax.builder import Entry, SectionHeader
from layoutdsl.syntax.ast import Spec
from layoutdsl.diagnostics import Diagnostic, Severity, register
from layoutdsl.diagnostics.source import Source, Span

# ===== Sections and line shapes =====

SECTION_RULES = {
    "rooms": "room_line",
    "arms": "arm_line",
    "boundary": "boundary_line",
    "adjacencies": "adjacency_line",
    "positions": "position_line",
    "connections": "connection_line",
    "clusters": "cluster_line",
    "hints": "hint_line",
    "settings": "setting_line",
}
"""Section name -> the grammar's start rule for one of its lines."""

SECTIONS = tuple(SECTION_RULES)
_SECTION_OF_RULE = {rule: section for section, rule in SECTION_RULES.items()}

# The values of each line kind, in order: (field name, kind) with kind "id" or "number".
# Used to say *which* value is missing or wrong, and to generate SYNTAX_ERRORS examples.
_ROOM_FIELDS = (
    ("id", "id"), ("minw", "number"), ("maxw", "number"), ("targetw", "number"),
    ("minh", "number"), ("maxh", "number"), ("targeth", "number"), ("minar", "number"),
    ("maxar", "number"), ("rtype", "id"), ("label", "label"),
)  # fmt: skip
LINE_SHAPES: dict[str, tuple[tuple[str, str], ...]] = {
    "room_line": _ROOM_FIELDS,
    "arm_line": _ROOM_FIELDS[:9],
    "boundary_size": (("w", "number"), ("h", "number")),
    "obstacle": (("id", "id"), ("x", "number"), ("y", "number"), ("w", "number"), ("h", "number")),
    "adjacency_line": (("id1", "id"), ("id2", "id"), ("mina", "number"), ("atype", "id")),
    "position_line": (("id", "id"), ("x", "number"), ("y", "number")),
    "connection_line": (
        ("id", "id"), ("p1x", "number"), ("p1y", "number"), ("p2x", "number"), ("p2y", "number"),
    ),  # fmt: skip
    "cluster_header": (("cluster id", "id"),),
    "cluster_member": (("room", "id"), ("x", "number"), ("y", "number")),
    "hint_line": (("id", "id"), ("x", "number"), ("y", "number"), ("w", "number"), ("h", "number")),
    "setting_line": (("key", "id"), ("value", "any")),
}

LINE_SYNOPSIS = {
    "room_line": "id minw maxw targetw minh maxh targeth minar maxar rtype label [onB] [cover=W] [error=W]",
    "arm_line": "id minw maxw targetw minh maxh targeth minar maxar",
    "boundary_size": "w h",
    "obstacle": "id x y w h",
    "adjacency_line": "id1 id2 mina atype",
    "position_line": "id x y",
    "connection_line": "id p1x p1y p2x p2y",
    "cluster_header": "cluster-id",
    "cluster_member": "room x y",
    "hint_line": "id x y w h",
    "setting_line": "key value",
}

# ===== Codes =====

E_UNKNOWN_SECTION = register(
    "E001", Severity.ERROR, "unknown section",
    "Reports a line holding a single word that is not a section name where an entry line was expected.",
    "The lines after it would be read as entries of the previous section and give confusing errors.",
    "adjacency            # should be `adjacencies`\nR0 C3 0.9 e",
)  # fmt: skip
E_OUTSIDE_SECTION = register(
    "E002", Severity.ERROR, "entry outside any section",
    "Reports entry lines that come before the first section name.",
    "Without a section the line's meaning (room, adjacency, ...) is unknown.",
    "R0 4 8 6 6 10 8 1 1.7 R CLASSROOM   # no `rooms` line above",
)  # fmt: skip
E_MISSING_VALUE = register(
    "E003", Severity.ERROR, "missing value",
    "Reports a line that ends before all of its values are given.",
    "Every value of an entry is required (only `onB` and weights are optional).",
    "adjacencies\nR0 C3 0.9          # atype (e or i) is missing",
)  # fmt: skip
E_EXTRA_VALUE = register(
    "E004", Severity.ERROR, "unexpected extra value",
    "Reports a value after the last value its line takes.",
    "An extra value is usually a typo or a value meant for another line.",
    "positions\nR0 3 4 5",
)  # fmt: skip
E_EXPECTED_NUMBER = register(
    "E005", Severity.ERROR, "expected a number",
    "Reports a word where a number is required.",
    "Sizes, coordinates and door lengths are numbers in metres (`.` as decimal separator).",
    "rooms\nR0 4,6 8 6 6 10 8 1 1.7 R CLASSROOM",
)  # fmt: skip
E_EXPECTED_ID = register(
    "E006", Severity.ERROR, "expected an id",
    "Reports a number where an id or word (room id, room type, adjacency type) is required.",
    "Ids must not look like numbers, so that a missing id cannot shift every value by one.",
    "positions\n3 4 5",
)  # fmt: skip
E_DUPLICATE_SECTION = register(
    "E007", Severity.ERROR, "section opened twice",
    "Reports a section name that appears a second time.",
    "Two `rooms` (or `boundary`) sections usually mean a pasted fragment; merge them.",
    "rooms\nR0 ...\n\nrooms\nR1 ...",
)  # fmt: skip
E_NUMBER_RANGE = register(
    "E008", Severity.ERROR, "number out of range",
    "Reports a number too large to represent (it overflows to infinity).",
    "Infinite sizes or coordinates make every geometric check meaningless.",
    "boundary\n1e999 20",
)  # fmt: skip



# ===== The parser =====


def _grammar_path() -> Path:
    """The grammar file, which lives beside this module (in a checkout and when installed)."""
    return Path(__file__).resolve().parent / "layout.lark"


class LineLexer(Lexer):
    """Lark lexer for one line: the grammar's own terminals, matched by one compiled regex.

    Lark's basic lexer spends most of lint's time on a 2,000-room spec; scanning with a
    single alternation of the same patterns (in the same priority order) gives the same
    tokens several times faster.
    """

    __future_interface__ = 2

    def __init__(self, lexer_conf) -> None:
        terminals = sorted(lexer_conf.terminals, key=lambda t: -t.priority)
        self.ignore = frozenset(lexer_conf.ignore)
        self.pattern = re.compile("|".join(f"(?P<{t.name}>{t.pattern.to_regexp()})" for t in terminals))

    def tokens(self, text: str) -> Iterator[Token]:
        """The tokens of one line (columns 1-based), ignored terminals dropped."""
        position = 0
        for match in self.pattern.finditer(text):
            start, end = match.span()
            if start != position:  # a character no terminal matches
                raise UnexpectedCharacters(text, position, 1, position + 1)
            position = end
            kind = match.lastgroup
            if kind not in self.ignore:
                yield Token(kind, match.group(), start, 1, start + 1, 1, end + 1, end)
        if position != len(text):
            raise UnexpectedCharacters(text, position, 1, position + 1)

    def lex(self, lexer_state, parser_state) -> Iterator[Token]:
        return self.tokens(private_api.lexer_text(lexer_state.text))


@functools.cache
def get_parser() -> Lark:
    """The Lark LALR parser for one line, with one start rule per section (built once)."""
    return Lark(
        _grammar_path().read_text(encoding="utf-8"),
        parser="lalr",
        lexer=LineLexer,
        start=list(dict.fromkeys(SECTION_RULES.values())),
        # Build AST nodes while parsing (Lark's inline LALR transformer): no parse tree is
        # made and walked afterwards, which halves the time of a large spec.
        transformer=build.LINE_BUILDER,
        propagate_positions=False,
        maybe_placeholders=False,
    )


_parsed_lines: dict[tuple[str, str, str], tuple[object, tuple[Diagnostic, ...], int]] | None = None
_parsed_lines_limit = 0


def keep_parsed_lines(limit: int = 50_000) -> None:
    """Remember up to `limit` parsed lines, for a process that parses nearly the same text
    again and again: the language server lints the whole spec after every edit, and on a
    2,000-room spec the per-line Lark parse is 90 % of the lint's time, yet an edit changes
    one line. A line's node depends only on (rule, text, file name) and the line's number,
    which only its spans hold: a remembered line that moved (a line was inserted above it)
    is reused with its spans moved, several times faster than parsing it again. Nodes are
    frozen, so a remembered one is shared as is. Off by default: a command that parses each
    text once would only pay for the memory."""
    global _parsed_lines, _parsed_lines_limit
    _parsed_lines, _parsed_lines_limit = ({} if limit > 0 else None), limit


def _moved(value, lines: int):
    """`value` (a built line, or a part of it) with every Span in it `lines` lines further."""
    kind = type(value)
    if kind is Span:
        return Span(value.line + lines, value.col, value.end_line + lines, value.end_col)
    if kind is tuple or kind is list:
        return kind(_moved(item, lines) for item in value)
    if kind is MappingProxyType or isinstance(value, Mapping):
        return MappingProxyType({key: Span(s.line + lines, s.col, s.end_line + lines, s.end_col) if type(s) is Span
                                 else _moved(s, lines) for key, s in value.items()})  # fmt: skip
    names = _span_fields(kind) if is_dataclass(kind) else ()
    if not names:
        return value
    changed = {name: _moved(item, lines) for name in names if (item := getattr(value, name)) is not None}
    return replace(value, **changed) if changed else value


@functools.cache
def _span_fields(cls: type) -> tuple[str, ...]:
    """The fields of a node class that can hold spans (all but plain numbers and text)."""
    return tuple(f.name for f in fields(cls) if f.name in ("span", "spans") or not _plain(f.type))


def _plain(annotation) -> bool:
    text = annotation if isinstance(annotation, str) else getattr(annotation, "__name__", "")
    return text in ("str", "float", "int", "bool", "str | None", "float | None", "int | None")


def parse_line(
    rule: str, text: str, line: int = 1, filename: str = "<line>", diagnostics: list[Diagnostic] | None = None
) -> object:
    """Parse and build one entry line with a start rule; raises lark's UnexpectedInput.

    Value problems found while building (an unknown room type, say) are appended to
    `diagnostics` when it is given; a line that fails to parse leaves none behind.
    """
    memo, key = _parsed_lines, (rule, text, filename)
    # one dict operation per look-up: the server lints in worker threads, and another
    # thread may clear the memory between a membership test and a read
    hit = memo.get(key) if memo is not None else None
    if hit is not None:
        node, remembered, at = hit
        if at != line:
            node, remembered = _moved(node, line - at), _moved(remembered, line - at)
            memo[key] = (node, remembered, line)
        if diagnostics is not None:
            diagnostics.extend(remembered)
        return node
    found: list[Diagnostic] = []
    with build.building_line(filename, line, found):
        node = get_parser().parse(text, start=rule)
    if memo is not None:
        if len(memo) >= _parsed_lines_limit:
            memo.clear()  # simpler than LRU, and a whole re-parse costs well under a second
        memo[key] = (node, tuple(found), line)
    if diagnostics is not None:
        diagnostics.extend(found)
    return node


# ===== Named syntax errors =====


def _shape_examples(shape: tuple[tuple[str, str], ...]) -> tuple[list[str], list[str], list[str]]:
    """Examples for a line shape: cut short after each value, and a wrong type at each value.

    Returns (missing, expected-number, expected-id) example lines.
    """
    good = ["1" if kind == "number" else "R0" for _, kind in shape]
    missing = [" ".join(good[:k]) for k in range(1, len(good))]
    not_number = [" ".join([*good[:k], "x"]) for k, (_, kind) in enumerate(shape) if kind == "number"]
    not_id = [" ".join([*good[:k], "7"]) for k, (_, kind) in enumerate(shape) if kind == "id"]
    return missing, not_number, not_id


def _build_syntax_errors() -> dict[str, dict[str, list[str]]]:
    # Generated from LINE_SHAPES so that every (rule, position) has an example; the table
    # is still the test data: tests assert each example is named with its code.
    table: dict[str, dict[str, list[str]]] = {
        E_MISSING_VALUE: {}, E_EXPECTED_NUMBER: {}, E_EXPECTED_ID: {}, E_EXTRA_VALUE: {}
    }  # fmt: skip

    def add(code: str, rule: str, examples: list[str]) -> None:
        table[code].setdefault(rule, []).extend(e for e in examples if e)

    full = {name: " ".join("R0" if k != "number" else "1" for _, k in s) for name, s in LINE_SHAPES.items()}
    for rule in ("room_line", "arm_line", "adjacency_line", "position_line", "connection_line", "hint_line"):
        missing, not_number, not_id = _shape_examples(LINE_SHAPES[rule])
        if rule == "room_line":  # `R0 x` is a sizeless room (`id label`), not a bad number
            not_number = [e for e in not_number if e != "R0 x"]
        add(E_MISSING_VALUE, rule, missing)
        add(E_EXPECTED_NUMBER, rule, not_number)
        add(E_EXPECTED_ID, rule, not_id)
    for rule in ("arm_line", "adjacency_line", "position_line", "connection_line", "hint_line"):
        add(E_EXTRA_VALUE, rule, [full[rule] + " extra", full[rule] + " 1", full[rule] + " w=1"])
    add(E_EXTRA_VALUE, "room_line", [full["room_line"] + " cover=1 extra", full["room_line"] + " cover=1 2"])
    add(E_EXPECTED_NUMBER, "room_line", ["R0 w=1"])
    # boundary: a size line `w h` or an obstacle `id x y w h`
    add(E_MISSING_VALUE, "boundary_line", ["1", "R0", "R0 1", "R0 1 1", "R0 1 1 1"])
    add(E_EXPECTED_NUMBER, "boundary_line", ["1 x", "R0 x", "R0 1 x", "R0 1 1 x", "R0 1 1 1 x"])
    add(E_EXTRA_VALUE, "boundary_line", ["1 1 1", "1 1 x", "R0 1 1 1 1 1", "R0 1 1 1 1 x"])
    add(E_EXPECTED_ID, "boundary_line", ["w=1"])
    # clusters: `cluster-id` or `room x y`
    add(E_MISSING_VALUE, "cluster_line", ["R0 1"])
    add(E_EXPECTED_NUMBER, "cluster_line", ["R0 x", "R0 1 x"])
    add(E_EXPECTED_ID, "cluster_line", ["7", "7 1 1"])
    add(E_EXTRA_VALUE, "cluster_line", ["R0 1 1 1", "R0 1 1 x"])
    add(E_MISSING_VALUE, "setting_line", ["seed"])
    add(E_EXPECTED_ID, "setting_line", ["7 1"])
    for rule in ("arm_line", "adjacency_line", "position_line", "connection_line", "hint_line", "setting_line"):
        add(E_EXPECTED_ID, rule, ["w=1"])
    add(E_EXPECTED_ID, "room_line", ["w=1"])
    return table


SYNTAX_ERRORS: dict[str, dict[str, list[str]]] = _build_syntax_errors()
"""code -> start rule -> example lines that fail with that code (Lark GRAMMAR_ERRORS style)."""


@functools.cache
def _examples_for(rule: str) -> dict[str, list[str]]:
    return {code: by_rule[rule] for code, by_rule in SYNTAX_ERRORS.items() if rule in by_rule}


_ERROR_CODE_CACHE: dict[tuple[str, int, int, str], str | None] = {}


def name_syntax_error(rule: str, error: UnexpectedInput) -> str | None:
    """The SYNTAX_ERRORS code whose examples fail like `error` does (cached per state)."""
    token_type = error.token.type if isinstance(error, UnexpectedToken) else ""
    state = error.state
    # ParserState is unhashable; Lark compares states by stack depth and top state.
    key = (rule, len(state.state_stack), state.position, token_type)
    if key not in _ERROR_CODE_CACHE:
        _ERROR_CODE_CACHE[key] = error.match_examples(
            functools.partial(parse_line, rule), _examples_for(rule),
            token_type_match_fallback=True, use_accepts=True,
        )
    return _ERROR_CODE_CACHE[key]


def _line_tokens(text: str) -> list[Token]:
    try:
        return list(private_api.parser_lexer(get_parser()).tokens(text))
    except UnexpectedInput:  # unreachable with this grammar: NAME matches any other text
        return []


def _shape_for(rule: str, tokens: list[Token]) -> str:
    """The line shape a line of `rule` is trying to be (for alternatives like boundary)."""
    if rule == "boundary_line":
        return "boundary_size" if tokens and tokens[0].type == "NUMBER" else "obstacle"
    if rule == "cluster_line":
        return "cluster_header" if len(tokens) <= 1 else "cluster_member"
    return rule


def _describe(token: Token) -> str:
    if token.type == "NUMBER":
        return f"number `{token}`"
    return f"`{token}`"


def _syntax_diagnostic(
    filename: str, line_no: int, text: str, rule: str, error: UnexpectedInput
) -> Diagnostic:
    """Turn a Lark error on one line into a named, located diagnostic."""
    tokens = _line_tokens(text)
    shape_name = _shape_for(rule, tokens)
    shape = LINE_SHAPES[shape_name]
    synopsis = LINE_SYNOPSIS[shape_name]
    code = name_syntax_error(rule, error)
    token = error.token if isinstance(error, UnexpectedToken) else None
    at_end = token is None or token.type == "$END"
    index = len(tokens) if at_end else sum(1 for t in tokens if t.start_pos < token.start_pos)
    # match_examples may fall back to an example that failed in the same state on another
    # token (a line cut short where this one has a stray `key=value`): name it by the token
    if code is None or (code == E_MISSING_VALUE and not at_end):
        kind = shape[index][1] if index < len(shape) else None
        if at_end:
            code = E_MISSING_VALUE
        elif kind == "number":
            code = E_EXPECTED_NUMBER
        elif kind in ("id", "label"):
            code = E_EXPECTED_ID
        else:
            code = E_EXTRA_VALUE
    field_name = shape[index][0] if index < len(shape) else None
    help_text = f"a line of `{_SECTION_OF_RULE[rule]}` is `{synopsis}`"
    if shape_name in ("boundary_size", "obstacle"):
        help_text = "a line of `boundary` is `w h` (the size) or `id x y w h` (an obstacle)"
    if shape_name in ("cluster_header", "cluster_member"):
        help_text = "a line of `clusters` is a cluster id alone, or a member `room x y`"

    if at_end or code == E_MISSING_VALUE:
        col = len(text.rstrip()) + 1
        if "#" in text:
            comment_start = _comment_column(text)
            if comment_start:
                col = len(text[: comment_start - 1].rstrip()) + 1
        missing = [name for name, _ in shape[index:]] or ["value"]
        names = ", ".join(f"`{n}`" for n in missing)
        after = f" after `{shape[index - 1][0]}`" if 0 < index <= len(shape) else ""
        message = f"line ends{after}: missing {names}"
        if shape_name == "room_line" and index == 1:  # a sizeless room needs only its label
            missing = ["label"]
            message = "line ends after `id`: missing the room's `label` (and, unless the size model gives them, its eight sizes and `rtype`)"
        return Diagnostic(
            E_MISSING_VALUE, message, filename, Span(line_no, col, line_no, col + 1),
            label=f"expected `{missing[0]}`", help=help_text,
        )  # fmt: skip
    span = Span(line_no, token.column, line_no, token.end_column)
    if code == E_EXPECTED_NUMBER:
        found = str(token)
        hint = help_text
        if re.fullmatch(r"[+-]?\d+,\d+", found):
            hint = f"use `.` as the decimal separator: `{found.replace(',', '.')}`"
        elif found.lower().lstrip("+-") in ("nan", "inf", "infinity"):
            hint = "numbers must be finite"
        what = f"`{field_name}`" if field_name else "this value"
        return Diagnostic(
            code, f"expected a number for {what}, found `{found}`", filename, span,
            label="not a number", help=hint,
        )  # fmt: skip
    if code == E_EXPECTED_ID:
        what = f"`{field_name}`" if field_name else "an id"
        found = _describe(token)
        if token.type == "PAIR":
            return Diagnostic(
                code, f"expected {what}, found `{token}`", filename, span,
                label="`key=value` weights go at the end of a room line", help=help_text,
            )  # fmt: skip
        label = {"rtype": "expected R, C or E", "atype": "expected e or i"}.get(
            field_name or "", "ids must not be numbers"
        )
        return Diagnostic(
            code, f"expected {what}, found {found}", filename, span, label=label, help=help_text
        )
    # extra value
    last = shape[-1][0] if shape_name != "room_line" else "the room's weights"
    span = Span(line_no, token.column, line_no, len(_strip_comment(text)) + 1)
    return Diagnostic(
        E_EXTRA_VALUE, f"unexpected extra value `{token}` after {_tick(last)}", filename, span,
        label="extra value", help=help_text,
    )  # fmt: skip


def _tick(name: str) -> str:
    return name if name.startswith("the ") else f"`{name}`"


def _comment_column(text: str) -> int | None:
    """1-based column where a `#` comment starts (a `#` at the start of a value), or None."""
    match = re.search(r"(?:^|(?<=\s))#", text)
    return match.start() + 1 if match else None


def _strip_comment(text: str) -> str:
    col = _comment_column(text)
    return (text if col is None else text[: col - 1]).rstrip()


# ===== Whole file =====


def _split_lines(text: str) -> list[str]:
    # Only \n (and \r\n) end a line, as editors count lines; str.splitlines would also split
    # on form feeds and other separators and shift every later line number.
    if text.startswith("\ufeff"):
        text = text[1:]
    return [line[:-1] if line.endswith("\r") else line for line in text.split("\n")]


def _suggest(word: str, candidates) -> str | None:
    match = difflib.get_close_matches(word, list(candidates), n=1, cutoff=0.6)
    return match[0] if match else None


def split_sections(
    source: Source, value_diagnostics: list[Diagnostic] | None = None
) -> tuple[list[SectionHeader], list[Entry], list[Diagnostic]]:
    """Section headers, parsed entries (in file order) and line-level syntax errors.

    Value problems of lines that do parse (an unknown room type, say) go to
    `value_diagnostics` when it is given.
    """
    filename = source.path
    headers: list[SectionHeader] = []
    entries: list[Entry] = []
    diagnostics: list[Diagnostic] = []
    seen: dict[str, int] = {}
    section: str | None = None
    skipping = False  # inside an unknown section or before any: report once, then skip
    for line_no, raw in enumerate(_split_lines(source.text), start=1):
        content = _strip_comment(raw)
        words = content.split()
        if not words:
            continue
        if len(words) == 1 and words[0] in SECTION_RULES:
            name = words[0]
            col = raw.index(name) + 1
            if name in seen:
                diagnostics.append(Diagnostic(
                    E_DUPLICATE_SECTION, f"section `{name}` opened twice", filename,
                    Span(line_no, col, line_no, col + len(name)), label="second opening",
                    help="merge the two sections into one",
                    notes=(f"first opened on line {seen[name]}",),
                ))  # fmt: skip
            else:
                seen[name] = line_no
            headers.append(SectionHeader(name, line_no, raw))
            section, skipping = name, False
            continue
        if skipping:
            continue
        col = len(raw) - len(raw.lstrip()) + 1
        first = words[0]
        # A lone word is a misspelled section name, except in `clusters`, where a lone word
        # is a cluster id: there only a near miss (`hint`, `setings`) counts as a typo.
        looks_like_header = len(words) == 1 and re.fullmatch(r"[A-Za-z_]+", first) is not None
        if looks_like_header and section == "clusters":
            looks_like_header = bool(difflib.get_close_matches(first.lower(), SECTIONS, n=1, cutoff=0.8))
        if section is None or looks_like_header:
            guess = _suggest(first.lower(), SECTIONS)
            if looks_like_header and (section is None or guess is not None):
                diagnostics.append(Diagnostic(
                    E_UNKNOWN_SECTION, f"unknown section `{first}`", filename,
                    Span(line_no, col, line_no, col + len(first)), label="not a section name",
                    help=f"did you mean `{guess}`?" if guess else
                    "sections are " + ", ".join(f"`{s}`" for s in SECTIONS),
                ))  # fmt: skip
                skipping = True
                continue
            if section is None:
                diagnostics.append(Diagnostic(
                    E_OUTSIDE_SECTION, "entry before any section", filename,
                    Span(line_no, col, line_no, len(content) + 1), label="which section is this in?",
                    help="start with a section name on its own line, such as `rooms`",
                ))  # fmt: skip
                skipping = True
                continue
        rule = SECTION_RULES[section]
        try:
            node = parse_line(rule, raw, line_no, filename, value_diagnostics)
        except UnexpectedInput as error:
            if isinstance(error, UnexpectedCharacters):  # unreachable: NAME matches anything
                span = Span(line_no, error.column, line_no, error.column + 1)
                diagnostics.append(Diagnostic(
                    E_EXTRA_VALUE, "unexpected character", filename, span, label="here"
                ))  # fmt: skip
            else:
                diagnostics.append(_syntax_diagnostic(filename, line_no, raw, rule, error))
            continue
        entries.append(Entry(section, line_no, raw, node))
    return headers, entries, diagnostics


def spec_name_for(path: str) -> str:
    """The default Spec.name: the file's stem, `stdin` for standard input."""
    if path in ("-", "<stdin>"):
        return "stdin"
    stem = Path(path).stem
    return stem or "spec"


def parse_source(source: Source) -> tuple[Spec | None, list[Diagnostic]]:
    """Parse and build a spec; returns (None, errors) when any syntax or value error is found.

    Name resolution and geometry are check.py's job; this stage reports everything about
    the text itself (shape of each line, number syntax, section structure, value types).
    """
    value_diagnostics: list[Diagnostic] = []
    headers, entries, diagnostics = split_sections(source, value_diagnostics)
    diagnostics.extend(value_diagnostics)
    spec, build_diagnostics = build.build_spec(
        entries, headers, path=source.path, default_name=spec_name_for(source.path),
        had_syntax_errors=any(d.is_error for d in diagnostics),
    )
    diagnostics.extend(build_diagnostics)
    diagnostics.sort(key=Diagnostic.sort_key)
    if any(d.is_error for d in diagnostics):
        return None, diagnostics
    return spec, diagnostics
