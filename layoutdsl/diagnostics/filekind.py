"""Recognise a file given to the wrong command (issue 42: "a wrong kind of file recognised").

`compile plan.xml` used to say "E002 entry before any section" and `import spec.lay`
"malformed XML": true, but neither says what to do. `sniff` looks at the first meaningful
line of a file and names its kind; `wrong_kind` turns a mismatch into one E019 diagnostic
that names the command to run instead, and nothing else is reported about that file.
"""

from __future__ import annotations

import re
from pathlib import PurePath

from layoutdsl.diagnostics import Diagnostic, Severity, register
from layoutdsl.diagnostics.source import Span

WRONG_KIND = register(
    "E019",
    Severity.ERROR,
    "wrong kind of file",
    "Reports a file that is not what the command reads: a building XML plan, a room graph or "
    "a compiled `.layout.json` given to `lint`, `fmt` or `compile`; a layoutdsl spec given "
    "to `import`; a spec, layout or graph given to `evaluate`. The help names what to run.",
    "Reading an XML plan as a spec would report a dozen syntax errors (the first one "
    "`E002 entry before any section`) that hide the real mistake: the wrong command.",
    "layoutdsl compile plan.xml -o out   # error: this is a building XML plan: run `layoutdsl import`",
)

SPEC = "spec"
BUILDING_XML = "building XML plan"
GRAPHML = "GraphML room graph"
XML = "XML file"
LAYOUT_JSON = "compiled layout (`.layout.json`)"
GRAPH_JSON = "JSON room graph"
JSON = "JSON file"
CSV = "CSV file (an adjacency matrix?)"

SECTION_WORDS = frozenset(("rooms", "boundary", "adjacencies", "positions", "connections",
                           "clusters", "hints", "settings", "arms"))
"""The section names of the spec language (layoutdsl.syntax.parser.SECTIONS; a test keeps
them equal). Repeated here because diagnostics sits below syntax in the import layering."""


def _first_line(text: str) -> tuple[int, str]:
    """(1-based number, text) of the first line that is neither blank nor a `#` comment."""
    for number, line in enumerate(text.lstrip("\ufeff").split("\n"), start=1):
        stripped = line.strip()
        if stripped and not stripped.startswith("#"):
            return number, stripped
    return 1, ""


def sniff(text: str) -> str | None:
    """The kind of a file's text, or None when it is none of the kinds layoutdsl knows."""
    head = text.lstrip("\ufeff \t\r\n")[:4096]
    if head.startswith("<"):
        if re.search(r"<graphml\b", head):
            return GRAPHML
        if re.search(r"<building\b", head):
            return BUILDING_XML
        return XML
    if head.startswith(("{", "[")):
        if '"portals"' in text[:200_000] and '"rooms"' in text[:200_000]:
            return LAYOUT_JSON
        if '"nodes"' in head:
            return GRAPH_JSON
        return JSON
    _, line = _first_line(text)
    words = line.split()
    if words and words[0] in SECTION_WORDS:
        return SPEC
    if "," in line and re.fullmatch(r"[\w .,\"'-]+", line):
        return CSV
    return None


def _a(kind: str) -> str:
    """`a building XML plan`, `an XML file`."""
    return ("an " if kind.startswith(("XML", "a", "e", "i", "o", "u")) else "a ") + kind


def _diagnostic(filename: str, text: str, message: str, label: str, help: str) -> Diagnostic:
    number, line = _first_line(text)
    return Diagnostic(WRONG_KIND, message, filename, Span(number, 1, number, max(2, len(line) + 1)),
                      label=label, help=help)


def wrong_kind_for_spec(filename: str, text: str) -> Diagnostic | None:
    """E019 when `text` (read by lint, fmt or compile) is clearly not a spec."""
    kind = sniff(text)
    if kind in (None, SPEC, CSV) and not (kind == CSV and PurePath(filename).suffix == ".csv"):
        return None
    path = PurePath(filename)
    target = path.with_suffix(".lay").name
    if kind in (BUILDING_XML, GRAPHML, GRAPH_JSON, CSV) and path.suffix == ".lay":
        real = path.with_suffix({GRAPHML: ".graphml", GRAPH_JSON: ".json", CSV: ".csv"}.get(kind, ".xml"))
        help = (f"rename it to `{real}` and run `layoutdsl import {real} -o {target}` to make a spec "
                "of it, then compile that")
    elif kind in (BUILDING_XML, GRAPHML, GRAPH_JSON, CSV):
        help = f"run `layoutdsl import {filename} -o {target}` to make a spec of it, then compile that"
    elif kind == LAYOUT_JSON:
        help = "this is what `compile` writes; compile the `.lay` spec it was made from"
    else:
        help = "layoutdsl specs are text files of sections (`rooms`, `boundary`, ...); see `layoutdsl explain E019`"
    return _diagnostic(filename, text, f"this is {_a(kind)}, not a layoutdsl spec", "not a spec", help)


def wrong_kind_for_import(filename: str, text: str) -> Diagnostic | None:
    """E019 when `text` given to `import` is a layoutdsl spec (or a compiled layout)."""
    kind = sniff(text)
    if kind == SPEC:
        return _diagnostic(
            filename, text, "this is a layoutdsl spec, not a plan to import", "a spec section",
            f"`import` turns building XML plans and room graphs into specs; compile this one "
            f"directly: `layoutdsl compile {filename} -o out`",
        )
    if kind == LAYOUT_JSON:
        return _diagnostic(filename, text, f"this is {_a(kind)}, not a plan to import", "compile's output",
                           "import the building XML plan compile wrote beside it (`NAME.xml`)")
    return None


def wrong_kind_for_plan(filename: str, text: str) -> Diagnostic | None:
    """E019 when a file given to `evaluate` as a building plan is a spec, a compiled layout
    or a room graph: evaluate compares building XML plans, the `NAME.xml` compile writes."""
    kind = sniff(text)
    stem = PurePath(filename).name.split(".")[0]
    if kind == SPEC:
        return _diagnostic(filename, text, "this is a layoutdsl spec, not a building plan", "a spec section",
                           f"evaluate compares building XML plans: compile the spec and pass the "
                           f"`{stem}.xml` it writes")
    if kind in (LAYOUT_JSON, GRAPHML, GRAPH_JSON):
        return _diagnostic(filename, text, f"this is {_a(kind)}, not a building plan", "not a plan",
                           f"evaluate compares building XML plans, such as the `{stem}.xml` compile writes")
    return None
