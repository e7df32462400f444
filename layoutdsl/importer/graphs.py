"""Read room graphs that carry no geometry: adjacency-matrix CSV, node-link JSON, GraphML.

    graph, diagnostics = read_graph("cml_new_10.csv")          # format from the extension
    graph, diagnostics = read_graph("school.json", "json")

Every format gives the same networkx graph: nodes in file order with `rtype` (R, C, E) and
`label`; edges with `door` (metres) and `kind` (`e`/`i`) when the file gives them. A graph
that cannot be a building gets located diagnostics (line and column in the file) with the
codes below, and `read_graph` returns None for it: not square, not symmetric, an unknown
room code, disconnected, or non-planar (a floor plan's room graph is planar; the rooms of a
Kuratowski subgraph are named). docs/graph-formats.md shows each format.

The CSV format is the one of the room graphs sampled by Luperto and Amigoni's generative
model of school graphs: a square comma-separated matrix, one line per room, 1 off the
diagonal where two rooms are joined, the room's label code on the diagonal:

- 100 corridor, 105 hall, 110 lobby: corridor-like spaces, type C (labels CORRIDOR, HALL,
  LOBBY);
- 1000 entrance, type E (label ENTRANCE);
- 1-99 a kind of room, type R, whose name the source does not publish (label `ROOM <code>`;
  the size model knows no such label, so these rooms get the sizes of plain rooms).

Node-link JSON (networkx's `node_link_data`) and GraphML nodes give `rtype` and `label`
attributes, or a `code` attribute read as in the CSV.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import networkx as nx

from layoutdsl.diagnostics import Diagnostic, Severity, register
from layoutdsl.diagnostics.source import Span
from layoutdsl.syntax.ast import ROOM_TYPES

FORMATS = ("csv", "json", "graphml")
EXTENSIONS = {".csv": "csv", ".txt": "csv", ".json": "json", ".graphml": "graphml", ".xml": "graphml"}

CODE_LABELS = {100: ("C", "CORRIDOR"), 105: ("C", "HALL"), 110: ("C", "LOBBY"), 1000: ("E", "ENTRANCE")}
"""The named label codes of the CSV format: code -> (room type, label)."""

ROOM_CODES = range(1, 100)
"""Codes of unnamed kinds of room (R)."""

# ===== Codes =====

GRAPH_UNREADABLE = register(
    "E430", Severity.ERROR, "unreadable room graph",
    "Reports a room-graph file that cannot be read: not found, not UTF-8, not valid JSON or "
    "GraphML, a JSON that is not networkx node-link data, a CSV cell that is not a whole "
    "number, or a graph with no rooms.",
    "Nothing after the first such problem can be trusted, so no room is imported.",
    "3,0,1\n0,x,1        # error: `x` is not a number",
)  # fmt: skip
GRAPH_NOT_SQUARE = register(
    "E431", Severity.ERROR, "adjacency matrix not square",
    "Reports a CSV row whose number of cells differs from the number of rows.",
    "Row i, column j says whether rooms i and j are joined; with a missing or extra cell "
    "every later cell of the row means another pair of rooms.",
    "3,0,1\n0,3\n1,0,100      # error: row 2 has 2 cells, the matrix has 3 rows",
)  # fmt: skip
GRAPH_NOT_SYMMETRIC = register(
    "E432", Severity.ERROR, "adjacency matrix not symmetric",
    "Reports a cell (i, j) that differs from (j, i), or an off-diagonal cell other than 0 or 1.",
    "A door joins two rooms both ways; an asymmetric matrix says a door exists and does not.",
    "3,1,0\n0,3,1\n0,1,100    # error: row 1 joins room 2, row 2 does not join room 1",
)  # fmt: skip
GRAPH_DISCONNECTED = register(
    "E433", Severity.ERROR, "room graph not connected",
    "Reports a room graph with rooms that no sequence of doors reaches from the others.",
    "One building is one connected graph: a room no door reaches cannot be laid out as part "
    "of it, and a robot could never enter it.",
    "3,1,0\n1,100,0\n0,0,3    # error: room 3 is joined to no other room",
)  # fmt: skip
GRAPH_NOT_PLANAR = register(
    "E434", Severity.ERROR, "room graph not planar",
    "Reports a room graph that cannot be drawn in the plane without crossing doors; the "
    "rooms of a Kuratowski subgraph (a K5 or K3,3) are named.",
    "Rooms on one floor that share walls form a planar graph: no floor plan has this one.",
    "five rooms each joined to the four others (K5)",
)  # fmt: skip
GRAPH_UNKNOWN_CODE = register(
    "E435", Severity.ERROR, "unknown room code",
    "Reports a room whose label code (CSV diagonal, or a `code` attribute) is not 1-99 (a "
    "kind of room), 100, 105, 110 (corridor, hall, lobby) or 1000 (entrance), or whose "
    "`rtype` is not R, C or E.",
    "The code decides the room's type and size; a wrong one would silently make a corridor "
    "a closet.",
    "3,1\n1,0       # error: 0 is not a room code",
)  # fmt: skip
GRAPH_SELF_LOOP = register(
    "E436", Severity.ERROR, "room joined to itself",
    "Reports a JSON or GraphML edge from a room to itself.",
    "A door joins two different rooms.",
    '{"nodes": [{"id": 0}], "links": [{"source": 0, "target": 0}]}',
)  # fmt: skip

_FIRST = Span(1, 1, 1, 2)


def detect_format(path: str | Path, text: str | None = None) -> str | None:
    """The format named by the file's extension, else sniffed from its text, else None."""
    found = EXTENSIONS.get(Path(path).suffix.lower())
    if found is not None:
        return found
    if text is None:
        return None
    head = text.lstrip("\ufeff \t\r\n")[:2048]
    if head.startswith("<"):
        return "graphml" if "<graphml" in head else None
    if head.startswith("{"):
        return "json"
    if re.match(r"[-+0-9 ,.\r\n\t]+$", head):
        return "csv"
    return None


def read_graph(
    path: str | Path, format: str | None = None, *, text: str | None = None
) -> tuple[nx.Graph | None, list[Diagnostic]]:
    """Read and validate one room graph; (None, errors) when it is not a usable building graph.

    `format` is one of FORMATS (None: detect). `text` reads that text instead of the file
    (diagnostics still name `path`)."""
    filename = str(path)
    if text is None:
        try:
            text = Path(path).read_bytes().decode("utf-8")
        except OSError as error:
            return None, [_error(GRAPH_UNREADABLE, f"cannot read `{filename}`: {error.strerror or error}",
                                 filename, _FIRST, "unreadable")]  # fmt: skip
        except UnicodeDecodeError as error:
            return None, [_error(GRAPH_UNREADABLE, f"`{filename}` is not UTF-8 text (byte {error.start})",
                                 filename, _FIRST, "not UTF-8")]  # fmt: skip
    text = text.lstrip("\ufeff")
    if format is None:
        format = detect_format(path, text)
        if format is None:
            return None, [_error(GRAPH_UNREADABLE, f"cannot tell the format of `{filename}`", filename, _FIRST,
                                 "unknown format", help="name it: --format csv, json or graphml")]  # fmt: skip
    if format not in FORMATS:
        raise ValueError(f"unknown graph format {format!r}; known: {', '.join(FORMATS)}")
    reader = {"csv": _read_csv, "json": _read_json, "graphml": _read_graphml}[format]
    graph, diagnostics, locate = reader(text, filename)
    if graph is None or any(d.is_error for d in diagnostics):
        return None, diagnostics
    diagnostics += _check_structure(graph, filename, locate)
    return (None if any(d.is_error for d in diagnostics) else graph), diagnostics


# ===== CSV =====


def _read_csv(text: str, filename: str):
    rows: list[tuple[int, list[tuple[str, int]]]] = []  # (line, [(cell text, column)])
    for number, line in enumerate(text.split("\n"), start=1):
        line = line.rstrip("\r")
        if not line.strip():
            continue
        cells, column = [], 1
        for cell in line.split(","):
            cells.append((cell, column + len(cell) - len(cell.lstrip())))
            column += len(cell) + 1
        rows.append((number, cells))
    if not rows:
        return None, [_error(GRAPH_UNREADABLE, "the adjacency matrix has no rows", filename, _FIRST, "empty file")], None
    if len(rows) > 1 and all(len(cells) == 1 for _, cells in rows):
        line, cells = rows[0]
        separator = next((c for c in (";", "\t", " ") if c in cells[0][0].strip()), None)
        if separator is not None:
            shown = "a tab" if separator == "\t" else f"`{separator}`"
            return None, [_error(
                GRAPH_UNREADABLE, f"the cells are separated by {shown}, not by commas", filename,
                Span(line, 1, line, len(cells[0][0]) + 1), "no comma on this line",
                help="an adjacency-matrix CSV separates its cells with commas",
            )], None  # fmt: skip
    diagnostics: list[Diagnostic] = []
    size = len(rows)
    values: list[list[int]] = []
    for line, cells in rows:
        if len(cells) != size:
            if len(cells) > size:  # point at the first extra cell
                col, width = cells[size][1], max(1, len(cells[size][0].strip()))
            else:  # point just after the row's last cell
                last_text, last_col = cells[-1]
                col, width = last_col + len(last_text.strip()), 1
            diagnostics.append(_error(
                GRAPH_NOT_SQUARE, f"row has {len(cells)} cell{'s' if len(cells) != 1 else ''}, but the matrix "
                f"has {size} rows", filename, Span(line, col, line, col + width),
                "extra cell" if len(cells) > size else f"row ends after {len(cells)} cell{'s' if len(cells) != 1 else ''}",
                help="an adjacency matrix has one row and one column per room",
            ))  # fmt: skip
            continue
        row = []
        for cell, col in cells:
            word = cell.strip()
            if not re.fullmatch(r"[+-]?\d+(?:\.0*)?", word):
                hint = "cells are 0 or 1 off the diagonal and a room code on it"
                if re.search(r"[;\t ]", word):
                    hint = "cells are separated by commas"
                diagnostics.append(_error(
                    GRAPH_UNREADABLE, f"cell `{word}` is not a whole number", filename,
                    Span(line, col, line, col + max(1, len(word))), "not a number", help=hint,
                ))  # fmt: skip
                row.append(0)
                continue
            row.append(int(float(word)))
        values.append(row)
    if diagnostics:
        return None, diagnostics, None

    def cell_span(i: int, j: int) -> Span:
        line, cells = rows[i]
        cell, col = cells[j]
        return Span(line, col, line, col + max(1, len(cell.strip())))

    graph = nx.Graph()
    for i in range(size):
        code = values[i][i]
        known = _code_type(code)
        if known is None:
            diagnostics.append(_error(
                GRAPH_UNKNOWN_CODE, f"room {i + 1} has unknown code {code}", filename, cell_span(i, i),
                "not a room code", help=_CODES_HELP,
            ))  # fmt: skip
            continue
        rtype, label = known
        graph.add_node(i, rtype=rtype, label=label, code=code)
    for i in range(size):
        for j in range(i + 1, size):
            a, b = values[i][j], values[j][i]
            for value, (r, c) in ((a, (i, j)), (b, (j, i))):
                if value not in (0, 1):
                    diagnostics.append(_error(
                        GRAPH_NOT_SYMMETRIC, f"cell ({r + 1}, {c + 1}) is {value}; off the diagonal only 0 or 1",
                        filename, cell_span(r, c), "expected 0 or 1",
                        help="1 joins two rooms, 0 does not; room codes go on the diagonal",
                    ))  # fmt: skip
            if a in (0, 1) and b in (0, 1) and a != b:
                line_b = rows[j][0]
                diagnostics.append(_error(
                    GRAPH_NOT_SYMMETRIC,
                    f"rooms {i + 1} and {j + 1}: cell ({i + 1}, {j + 1}) is {a} but cell ({j + 1}, {i + 1}) is {b}",
                    filename, cell_span(i, j), f"{a} here, {b} on line {line_b}",
                    help="a door joins two rooms both ways: make both cells 1, or both 0",
                    notes=(f"the mirror cell is line {line_b}, column {cell_span(j, i).col}",),
                ))  # fmt: skip
            elif a == 1 and b == 1 and i in graph and j in graph:
                graph.add_edge(i, j)
    return graph, diagnostics, lambda node: cell_span(node, node) if isinstance(node, int) and node < size else _FIRST


_CODES_HELP = "codes are 1-99 (a kind of room), 100 corridor, 105 hall, 110 lobby, 1000 entrance"


def _code_type(code: int) -> tuple[str, str] | None:
    if code in CODE_LABELS:
        return CODE_LABELS[code]
    if code in ROOM_CODES:
        return "R", f"ROOM {code}"
    return None


# ===== JSON and GraphML =====


def _read_json(text: str, filename: str):
    try:
        data = json.loads(text)
    except json.JSONDecodeError as error:
        span = Span(error.lineno, error.colno, error.lineno, error.colno + 1)
        return None, [_error(GRAPH_UNREADABLE, f"not valid JSON: {error.msg}", filename, span, "here")], None
    help_text = "node-link data is {\"nodes\": [{\"id\": ...}, ...], \"links\": [{\"source\": ..., \"target\": ...}, ...]}"
    if not isinstance(data, dict) or not isinstance(data.get("nodes"), list):
        return None, [_error(GRAPH_UNREADABLE, "not networkx node-link data (no `nodes` list)", filename, _FIRST,
                             "no `nodes`", help=help_text)], None  # fmt: skip
    locate = _text_locator(text, lambda node: [rf'"id"\s*:\s*{re.escape(json.dumps(node))}'])
    # Read by hand rather than with networkx.node_link_graph, whose keyword for the links
    # changed in networkx 3.4: the same file reads the same with any networkx.
    graph = nx.Graph()
    diagnostics: list[Diagnostic] = []
    for node in data["nodes"]:
        if not isinstance(node, dict) or "id" not in node or isinstance(node["id"], (dict, list)):
            return None, [_error(GRAPH_UNREADABLE, f"a node without a plain `id`: {json.dumps(node)[:60]}",
                                 filename, _FIRST, "no id", help=help_text)], None  # fmt: skip
        if node["id"] in graph:
            return None, [_error(GRAPH_UNREADABLE, f"node `{node['id']}` is given twice", filename,
                                 locate(node["id"]), "second node with this id")], None  # fmt: skip
        graph.add_node(node["id"], **{k: v for k, v in node.items() if k != "id"})
    links = data.get("links", data.get("edges", []))
    if not isinstance(links, list):
        return None, [_error(GRAPH_UNREADABLE, "`links` is not a list", filename, _FIRST, "not a list",
                             help=help_text)], None  # fmt: skip
    for link in links:
        if not isinstance(link, dict) or "source" not in link or "target" not in link:
            return None, [_error(GRAPH_UNREADABLE, f"a link without `source` and `target`: {json.dumps(link)[:60]}",
                                 filename, _FIRST, "not a link", help=help_text)], None  # fmt: skip
        a, b = link["source"], link["target"]
        missing = next((n for n in (a, b) if isinstance(n, (dict, list)) or n not in graph), None)
        if missing is not None:
            span = _text_locator(text, lambda n: [rf'"(?:source|target)"\s*:\s*{re.escape(json.dumps(n))}'])(missing)
            diagnostics.append(_error(GRAPH_UNREADABLE, f"a link names node `{missing}`, which is not in `nodes`",
                                      filename, span, "no such node"))  # fmt: skip
            continue
        graph.add_edge(a, b, **{k: v for k, v in link.items() if k not in ("source", "target")})
    if diagnostics:
        return None, diagnostics, None
    return _normalized(graph, filename, locate)


def _read_graphml(text: str, filename: str):
    try:
        graph = nx.parse_graphml(text)
    except Exception as error:  # networkx raises ElementTree's ParseError, NetworkXError, ValueError...
        return None, [_error(GRAPH_UNREADABLE, f"not valid GraphML: {error}", filename, _FIRST, "unreadable")], None
    locate = _text_locator(text, lambda node: [rf'<node\b[^>]*\bid\s*=\s*"{re.escape(str(node))}"'])
    return _normalized(graph, filename, locate)


def _text_locator(text: str, patterns):
    def locate(node) -> Span:
        for pattern in patterns(node):
            match = re.search(pattern, text)
            if match:
                line = text.count("\n", 0, match.start()) + 1
                col = match.start() - (text.rfind("\n", 0, match.start()) + 1) + 1
                return Span(line, col, line, col + len(match.group()))
        return _FIRST
    return locate


def _normalized(graph: nx.Graph, filename: str, locate):
    """A read JSON/GraphML graph as the CSV reader makes them: an undirected simple Graph,
    every node with rtype and label, edges with door/kind only when given."""
    diagnostics: list[Diagnostic] = []
    if graph.is_multigraph() or graph.is_directed():
        simple = nx.Graph()
        simple.add_nodes_from(graph.nodes(data=True))
        for a, b, data in graph.edges(data=True):
            if not simple.has_edge(a, b):
                simple.add_edge(a, b, **data)
        graph = simple
    out = nx.Graph()
    for node, data in graph.nodes(data=True):
        attrs = {k: v for k, v in data.items() if k not in ("rtype", "label", "code")}
        if "code" in data:
            try:
                code = int(float(data["code"]))
            except (TypeError, ValueError):
                code = None
            known = _code_type(code) if code is not None else None
            if known is None:
                diagnostics.append(_error(GRAPH_UNKNOWN_CODE, f"room `{node}` has unknown code {data['code']!r}",
                                          filename, locate(node), "not a room code", help=_CODES_HELP))  # fmt: skip
                continue
            rtype, label = known
            attrs["code"] = code
        else:
            rtype, label = "R", ""
        if "rtype" in data:
            rtype = str(data["rtype"]).strip().upper()
            if rtype not in ROOM_TYPES:
                diagnostics.append(_error(GRAPH_UNKNOWN_CODE, f"room `{node}` has unknown type {data['rtype']!r}",
                                          filename, locate(node), "not R, C or E",
                                          help="rtype is R (room), C (corridor) or E (entrance)"))  # fmt: skip
                continue
        if "label" in data:
            label = " ".join(str(data["label"]).split()).upper()
        out.add_node(node, rtype=rtype, label=label or {"R": "ROOM", "C": "CORRIDOR", "E": "ENTRANCE"}[rtype], **attrs)
    for a, b, data in graph.edges(data=True):
        if a == b:
            diagnostics.append(_error(GRAPH_SELF_LOOP, f"room `{a}` is joined to itself", filename, locate(a),
                                      "self-loop", help="remove the edge"))  # fmt: skip
            continue
        if a in out and b in out:
            out.add_edge(a, b, **{k: v for k, v in data.items() if k in ("door", "kind")})
    if out.number_of_nodes() == 0 and not diagnostics:
        diagnostics.append(_error(GRAPH_UNREADABLE, "the graph has no rooms", filename, _FIRST, "no nodes"))
    return out, diagnostics, locate


# ===== Structure: connected and planar =====


def _check_structure(graph: nx.Graph, filename: str, locate) -> list[Diagnostic]:
    diagnostics: list[Diagnostic] = []
    if graph.number_of_nodes() == 0:
        return [_error(GRAPH_UNREADABLE, "the graph has no rooms", filename, _FIRST, "no rooms")]
    order = {node: index for index, node in enumerate(graph.nodes)}
    components = sorted((sorted(c, key=order.__getitem__) for c in nx.connected_components(graph)),
                        key=lambda c: order[c[0]])  # fmt: skip
    if len(components) > 1:
        main = max(components, key=len)
        for component in components:
            if component is main:
                continue
            names = ", ".join(_name(graph, n) for n in component[:6]) + (", ..." if len(component) > 6 else "")
            diagnostics.append(_error(
                GRAPH_DISCONNECTED,
                f"{len(component)} room{'s' if len(component) > 1 else ''} not connected to the other "
                f"{graph.number_of_nodes() - len(component)}: {names}",
                filename, locate(component[0]), "not reached from the rest",
                help="join these rooms to the rest of the building with a door (a 1 in both cells)",
                notes=(f"the graph has {len(components)} connected parts",),
            ))  # fmt: skip
    planar, certificate = nx.check_planarity(graph, counterexample=True)
    if not planar:
        rooms = sorted(certificate.nodes, key=order.__getitem__)
        degrees = sorted(d for _, d in certificate.degree())
        shape = "K5" if degrees.count(4) == 5 else "K3,3"
        diagnostics.append(_error(
            GRAPH_NOT_PLANAR,
            f"the room graph is not planar: its rooms {', '.join(_name(graph, n) for n in rooms)} "
            f"contain a subdivision of {shape}",
            filename, locate(rooms[0]), "not planar",
            help="a floor's rooms form a planar graph; remove one of these doors",
            notes=("doors of the subgraph: " + ", ".join(
                f"{_short(a)}-{_short(b)}" for a, b in sorted(
                    (tuple(sorted(e, key=order.__getitem__)) for e in certificate.edges),
                    key=lambda e: (order[e[0]], order[e[1]]))),),
        ))  # fmt: skip
    return diagnostics


def _short(node) -> str:
    return str(node + 1) if isinstance(node, int) else str(node)


def _name(graph: nx.Graph, node) -> str:
    """How a message names a room: its number (1-based row) for a CSV, else its id."""
    label = graph.nodes[node].get("label", "")
    if isinstance(node, int):
        return f"{node + 1} ({label})"
    return f"`{node}` ({label})"


def _error(code: str, message: str, filename: str, span: Span, label: str = "", *, help: str | None = None,
           notes: tuple[str, ...] = ()) -> Diagnostic:  # fmt: skip
    return Diagnostic(code, message, filename, span, Severity.ERROR, label=label, help=help, notes=notes)
