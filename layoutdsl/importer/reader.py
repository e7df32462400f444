"""Read a building XML file (the thesis, §5.2) into a `Building`: the project's one XML reader.

The file is untrusted: it is parsed by defusedxml, which refuses entity declarations
(billion laughs) and external entities (XXE). Every element's line and column are recorded
while parsing, so whatever is wrong with the file becomes a located diagnostic, never a
traceback.

The `Building` stays faithful to the file (file units, y down) with two deliberate
exceptions, both because real files get them wrong:
- a space's `bbox` is the bounding box of its polygon, not the file's `<bounding_box>`
  element (the office plans write points there whose `maxy` lies above their `miny`);
- `real_distance_m` is the door size converted to metres using `<um>`.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from xml.etree.ElementTree import Element

from defusedxml import DefusedXmlException, DTDForbidden, EntitiesForbidden
from defusedxml.ElementTree import DefusedXMLParser, ParseError

from layoutdsl.importer.building import BoundingBox, Building, BuildingPortal, LineSegment, Point, Space, polygon_area
from layoutdsl.diagnostics import Diagnostic, Severity
from layoutdsl.importer import codes
from layoutdsl.diagnostics.source import Span
from layoutdsl.syntax.ast import ROOM_TYPES

PORTAL_TYPES = ("EXPLICIT", "IMPLICIT")

# Door sizes (metres) a real building can have; outside this the unit is almost surely wrong.
PLAUSIBLE_DOOR_M = (0.4, 3.0)

# Plans are drawn in pixels; a larger coordinate is a corrupted number, not a building.
MAX_COORDINATE = 1e9

_UNIT_TO_M = {"mm": 0.001, "cm": 0.01, "dm": 0.1, "m": 1.0}
_UNIT_ALIASES = {
    "": "cm",  # the thesis' default door is given in centimetres (§5.2)
    **{f"{prefix}{word}{plural}": unit
       for prefix, unit in (("milli", "mm"), ("centi", "cm"), ("deci", "dm"), ("", "m"))
       for word in ("metre", "meter") for plural in ("", "s")},
}  # fmt: skip


class _PositionedBuilder:
    """A parser target that builds an ElementTree and remembers where each element starts."""

    def __init__(self) -> None:
        self.parser: DefusedXMLParser | None = None
        self.positions: dict[int, tuple[int, int]] = {}
        self._stack: list[Element] = []
        self._root: Element | None = None
        self._text: list[str] = []

    def start(self, tag: str, attrs: dict[str, str]) -> Element:
        self._flush_text()
        element = Element(tag, dict(attrs))
        if self._stack:
            self._stack[-1].append(element)
        else:
            self._root = element
        self._stack.append(element)
        # The callback runs while expat sits on this start tag. defusedxml's parser is the
        # pure-Python one, which exposes its expat parser; without it positions are unknown.
        expat = getattr(self.parser, "parser", None)
        if expat is not None:
            self.positions[id(element)] = (expat.CurrentLineNumber, expat.CurrentColumnNumber + 1)
        return element

    def end(self, tag: str) -> Element:
        self._flush_text()
        return self._stack.pop()

    def data(self, text: str) -> None:
        self._text.append(text)

    def close(self) -> Element | None:
        return self._root

    def _flush_text(self) -> None:
        """Give collected character data to the open element (text) or its last child (tail)."""
        if not self._text:
            return
        text = "".join(self._text)
        self._text = []
        if not self._stack:
            return
        parent = self._stack[-1]
        if len(parent):
            last = parent[-1]
            last.tail = (last.tail or "") + text
        else:
            parent.text = (parent.text or "") + text


@dataclass
class _Reader:
    """Turns a parsed tree into a Building, collecting diagnostics instead of raising."""

    filename: str
    text: str
    positions: dict[int, tuple[int, int]]
    diagnostics: list[Diagnostic] = field(default_factory=list)
    space_ids: dict[str, Element] = field(default_factory=dict)
    empty_spaces: dict[str, tuple[Element, int]] = field(default_factory=dict)
    """Spaces whose polygon encloses no area and that have no portal: id -> (polygon, points)."""
    lines: list[str] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.lines = source_lines(self.text)

    # ----- locations and reporting -----

    def line_text(self, line: int) -> str:
        return self.lines[line - 1] if 1 <= line <= len(self.lines) else ""

    def span(self, element: Element, attribute: str | None = None, *, whole: bool = False) -> Span:
        """The span of an element's start tag name, of one of its attributes, or (`whole`)
        of the element up to its end tag when that is on the same line (`<id>x</id>`)."""
        line, col = self.positions.get(id(element), (1, 1))
        if whole:
            line_text = self.line_text(line)
            end = line_text.find(f"</{element.tag}>", col - 1)
            if end >= 0:
                return Span(line, col, line, end + len(element.tag) + 4)
        if attribute is not None:
            line_text = self.line_text(line)
            match = re.compile(rf"\b{re.escape(attribute)}\s*=\s*(\"[^\"]*\"|'[^']*')").search(
                line_text, col - 1
            )
            if match:
                return Span(line, match.start() + 1, line, match.end() + 1)
        return Span(line, col, line, col + 1 + len(element.tag))

    def report(
        self,
        code: str,
        message: str,
        span: Span,
        *,
        label: str = "",
        help: str | None = None,
        severity: Severity = Severity.ERROR,
    ) -> None:
        self.diagnostics.append(
            Diagnostic(code, message, self.filename, span, severity, label=label, help=help)
        )

    def warn(self, code: str, message: str, span: Span, **kwargs) -> None:
        self.report(code, message, span, severity=Severity.WARNING, **kwargs)

    # ----- small readers -----

    def child(self, parent: Element, path: str, what: str) -> Element | None:
        """The element at `path` under `parent`, or None with an E402 diagnostic."""
        element = parent.find(path)
        if element is None:
            self.report(
                codes.MISSING_ELEMENT,
                f"`<{parent.tag}>` has no `<{path}>`",
                self.span(parent),
                label=f"{what} expected here",
            )
        return element

    def number(self, element: Element, raw: str | None, where: str, attribute: str | None = None):
        """A finite float from text, or None with an E403 diagnostic."""
        if raw is None:
            self.report(
                codes.MISSING_ELEMENT,
                f"`<{element.tag}>` has no {where}",
                self.span(element),
                label=f"{where} expected",
            )
            return None
        try:
            value = float(raw.strip())
        except ValueError:
            value = math.nan
        if not math.isfinite(value):
            self.report(
                codes.INVALID_NUMBER,
                f"{where} `{raw.strip()}` is not a number",
                self.span(element, attribute, whole=attribute is None),
                label="expected a finite number",
            )
            return None
        if abs(value) > MAX_COORDINATE:
            # Areas are squares of coordinates; keep them far from float overflow.
            self.report(
                codes.INVALID_NUMBER,
                f"{where} `{raw.strip()}` is out of range",
                self.span(element, attribute, whole=attribute is None),
                label=f"at most {MAX_COORDINATE:g} in absolute value",
            )
            return None
        return value

    def point(self, element: Element) -> Point | None:
        x = self.number(element, element.get("x"), "attribute `x`", "x")
        y = self.number(element, element.get("y"), "attribute `y`", "y")
        if x is None or y is None:
            return None
        return Point(x, y)

    # ----- the document -----

    def building(self, root: Element, default_name: str) -> Building | None:
        if root.tag != "building":
            self.report(
                codes.MISSING_ELEMENT,
                f"the root element is `<{root.tag}>`, not `<building>`",
                self.span(root),
                label="expected `<building>`",
                help="is this a building XML file (the thesis, §5.2)?",
            )
            return None
        scale = self.scale(root)
        spaces = self.spaces(root)
        if spaces is not None:
            self.check_targets(spaces, self.space_ids)
            self.check_empty_spaces(spaces)
        if scale is None or spaces is None or any(d.is_error for d in self.diagnostics):
            return None
        name = (root.findtext("name") or "").strip() or default_name
        represented, real_m = scale
        return Building(name, represented, real_m, tuple(space for space, _ in spaces))

    def scale(self, root: Element) -> tuple[float, float] | None:
        scale = self.child(root, "scale", "the plan's scale")
        if scale is None:
            return None
        represented_el = self.child(scale, "represented_distance", "the door size in file units")
        real_el = self.child(scale, "real_distance", "the door size")
        if represented_el is None or real_el is None:
            return None
        represented = self.distance_value(represented_el)
        real = self.distance_value(real_el)
        if represented is None or real is None:
            return None
        ok = True
        if represented <= 0:
            self.report(
                codes.INVALID_SCALE,
                f"represented distance {represented:g} is not positive",
                self.span(represented_el),
                label="a door must span a positive number of file units",
            )
            ok = False
        unit_el = real_el.find("um")
        unit = (unit_el.text or "").strip().lower() if unit_el is not None else ""
        unit = _UNIT_ALIASES.get(unit, unit)
        if unit not in _UNIT_TO_M:
            self.report(
                codes.INVALID_SCALE,
                f"unknown unit `{unit}` for the real distance",
                self.span(unit_el if unit_el is not None else real_el, whole=True),
                label="expected mm, cm, dm or m",
            )
            return None
        real_m = real * _UNIT_TO_M[unit]
        low, high = PLAUSIBLE_DOOR_M
        if not low <= real_m <= high:
            help_text = None
            for other, factor in _UNIT_TO_M.items():
                if other != unit and low <= real * factor <= high:
                    help_text = f"did you mean `<um>{other}</um>` (a {real * factor:g} m door)?"
                    break
            self.report(
                codes.INVALID_SCALE,
                f"implausible door size {real:g} {unit}" + ("" if unit == "m" else f" ({real_m:g} m)"),
                self.span(unit_el if unit_el is not None else real_el, whole=True),
                label=f"a door is {low:g}-{high:g} m wide",
                help=help_text,
            )
            ok = False
        return (represented, real_m) if ok else None

    def distance_value(self, element: Element) -> float | None:
        """`<value>` of a distance element; a bare number as the element's text also works."""
        value_el = element.find("value")
        if value_el is not None:
            return self.number(value_el, value_el.text or "", "value")
        if (element.text or "").strip():
            return self.number(element, element.text, "value")
        self.report(
            codes.MISSING_ELEMENT,
            f"`<{element.tag}>` has no `<value>`",
            self.span(element),
            label="`<value>` expected",
        )
        return None

    def spaces(self, root: Element) -> list[tuple[Space, list[tuple[Element, list[Element]]]]] | None:
        floor = self.child(root, "floor", "the plan's rooms")
        if floor is None:
            return None
        spaces_el = self.child(floor, "spaces", "the list of rooms")
        if spaces_el is None:
            return None
        result: list[tuple[Space, list[tuple[Element, list[Element]]]]] = []
        seen: dict[str, Element] = {}
        # every id, also of spaces that failed to read: portals to them are not "unknown"
        self.space_ids = seen
        for element in spaces_el.findall("space"):
            space_id = (element.get("id") or "").strip()
            if not space_id:
                if len(element) == 0 and (element.text or "").strip():
                    continue  # a bare `<space>UUID</space>` reference, not a room
                self.report(
                    codes.MISSING_ELEMENT,
                    "`<space>` has no `id` attribute",
                    self.span(element),
                    label="portals refer to spaces by id",
                )
                continue
            if space_id in seen:
                first_line = self.positions.get(id(seen[space_id]), (0, 0))[0]
                self.report(
                    codes.DUPLICATE_SPACE,
                    f"space id `{space_id}` is used twice",
                    self.span(element, "id"),
                    label=f"first used on line {first_line}",
                )
                continue
            seen[space_id] = element
            parsed = self.space(element, space_id)
            if parsed is not None:
                result.append(parsed)
        if not seen or set(seen) == set(self.empty_spaces):
            self.report(
                codes.NO_SPACES,
                "the plan has no spaces" if not seen else "the plan has no space with an area",
                self.span(spaces_el),
                label="expected `<space id=...>` elements here",
            )
            return None
        return result

    def space(self, element: Element, space_id: str):
        """One `<space>`: the Space and, per portal, its element and target element."""
        rtype_raw = (element.findtext("labels/type") or "").strip()
        rtype = rtype_raw.upper()
        if rtype not in ROOM_TYPES:
            type_el = element.find("labels/type")
            shown = f"room type `{rtype_raw}`" if rtype_raw else "no room type"
            self.warn(
                codes.UNKNOWN_ROOM_TYPE,
                f"space `{space_id}` has {shown}; imported as a generic room",
                self.span(type_el if type_el is not None else element, whole=True),
                label="expected R, C or E",
            )
            rtype = "R"
        label = " ".join((element.findtext("labels/label") or "").split())
        centroid_el = element.find("centroid/point")
        centroid = self.point(centroid_el) if centroid_el is not None else None

        polygon = self.polygon(element, space_id)
        segments = self.segments(element)
        portals = self.portals(element, space_id, segments)
        if polygon is None or segments is None or portals is None:
            return None
        xs = [p.x for p in polygon]
        ys = [p.y for p in polygon]
        bbox = BoundingBox(min(xs), min(ys), max(xs), max(ys))
        line = self.positions.get(id(element), (0, 0))[0]
        space = Space(
            space_id,
            rtype,
            label,
            centroid,
            bbox,
            polygon,
            tuple(segments.values()),
            tuple(p for p, _ in portals),
            line=line,
        )
        return space, [elements for _, elements in portals]

    def polygon(self, element: Element, space_id: str) -> tuple[Point, ...] | None:
        polygon_el = element.find("bounding_polygon")
        if polygon_el is None:
            self.report(
                codes.DEGENERATE_POLYGON,
                f"space `{space_id}` has no `<bounding_polygon>`",
                self.span(element),
                label="its size comes from its polygon",
            )
            return None
        points = [self.point(p) for p in polygon_el.findall("point")]
        if any(p is None for p in points):
            return None
        distinct = {(p.x, p.y) for p in points}
        if len(distinct) < 3 or polygon_area(points) <= 0:
            if not element.findall("portals/portal"):
                # a drawing artefact unless another space's portal leads here: decided in
                # building(), once every portal has been read
                self.empty_spaces[space_id] = (polygon_el, len(distinct))
                return None
            self.report(
                codes.DEGENERATE_POLYGON,
                f"the polygon of space `{space_id}` encloses no area",
                self.span(polygon_el),
                label=f"{len(distinct)} distinct point(s)",
                help="a room needs at least three points not on one line",
            )
            return None
        return tuple(points)

    def segments(self, element: Element) -> dict[str, LineSegment] | None:
        segments: dict[str, LineSegment] = {}
        ok = True
        for segment_el in element.findall("space_representation/linesegment"):
            points_el = segment_el.findall("point")
            if len(points_el) != 2:
                self.report(
                    codes.MISSING_ELEMENT,
                    f"`<linesegment>` has {len(points_el)} point(s), not 2",
                    self.span(segment_el),
                    label="a segment runs between two points (equal for a door)",
                )
                ok = False
                continue
            p1, p2 = self.point(points_el[0]), self.point(points_el[1])
            if p1 is None or p2 is None:
                ok = False
                continue
            segment_id = (segment_el.get("id") or "").strip()
            cls = (segment_el.findtext("class") or "WALL").strip().upper()
            kind = (segment_el.findtext("type") or "EXPLICIT").strip().upper()
            segments[segment_id] = LineSegment(segment_id, p1, p2, cls, kind)
        return segments if ok else None

    def portals(self, element: Element, space_id: str, segments: dict[str, LineSegment] | None):
        portals: list[tuple[BuildingPortal, tuple[Element, list[Element]]]] = []
        ok = True
        for portal_el in element.findall("portals/portal"):
            ids_el = portal_el.findall("target/id")
            targets = [(i.text or "").strip() for i in ids_el]
            if len(targets) != 2 or not all(targets):
                target_el = portal_el.find("target")
                self.report(
                    codes.BAD_PORTAL_TARGETS,
                    f"portal of space `{space_id}` lists {len(targets)} target(s), not 2",
                    self.span(target_el if target_el is not None else portal_el, whole=True),
                    label="expected two `<id>` elements",
                )
                ok = False
                continue
            if targets[0] == targets[1]:
                self.warn(
                    codes.SELF_PORTAL,
                    f"portal joins space `{targets[0]}` to itself; ignored",
                    self.span(portal_el),
                    label="both targets are the same space",
                )
                continue
            segment_el = portal_el.find("linesegment")
            if segment_el is None:
                self.report(
                    codes.MISSING_ELEMENT,
                    f"portal of space `{space_id}` has no `<linesegment>`",
                    self.span(portal_el),
                    label="the door's segment expected",
                )
                ok = False
                continue
            segment_id = (segment_el.text or "").strip()
            segment = (segments or {}).get(segment_id)
            if segment is None and segments is not None:
                self.warn(
                    codes.PORTAL_SEGMENT_MISSING,
                    f"portal's line segment `{segment_id}` is not a segment of space `{space_id}`",
                    self.span(segment_el, whole=True),
                    label="the door's position is unknown",
                )
            kind = (portal_el.findtext("type") or "").strip().upper()
            if kind not in PORTAL_TYPES:
                # The portal element is what defines the adjacency; its segment is the fallback.
                kind = segment.type if segment is not None and segment.type in PORTAL_TYPES else "EXPLICIT"
            portal = BuildingPortal(segment_id, kind, (targets[0], targets[1]), segment)
            portals.append((portal, (portal_el, ids_el)))
        return portals if ok else None

    def check_empty_spaces(self, spaces) -> None:
        """Spaces without area: skipped with W425, or E405 when a portal leads to them."""
        targeted = {
            (id_el.text or "").strip()
            for _, portal_elements in spaces
            for _, ids_el in portal_elements
            for id_el in ids_el
        }
        for space_id, (polygon_el, distinct) in self.empty_spaces.items():
            if space_id in targeted:
                self.report(
                    codes.DEGENERATE_POLYGON,
                    f"the polygon of space `{space_id}` encloses no area",
                    self.span(polygon_el),
                    label=f"{distinct} distinct point(s), and a portal leads here",
                    help="a room needs at least three points not on one line",
                )
            else:
                self.warn(
                    codes.SKIPPED_EMPTY_SPACE,
                    f"space `{space_id}` encloses no area and has no portal; skipped",
                    self.span(polygon_el),
                    label=f"{distinct} distinct point(s)",
                )

    def check_targets(self, spaces, known) -> None:
        for space, portal_elements in spaces:
            for portal_el, ids_el in portal_elements:
                for id_el in ids_el:
                    target = (id_el.text or "").strip()
                    if target not in known:
                        suggestion = _closest(target, known)
                        self.report(
                            codes.UNKNOWN_SPACE,
                            f"portal of space `{space.id}` names unknown space `{target}`",
                            self.span(id_el, whole=True),
                            label="no `<space>` has this id",
                            help=f"did you mean `{suggestion}`?" if suggestion else None,
                        )


def source_lines(text: str) -> list[str]:
    """The text's lines as expat numbers them (only a newline ends a line; CR dropped)."""
    return [line[:-1] if line.endswith("\r") else line for line in text.split("\n")]


def _closest(name: str, candidates) -> str | None:
    import difflib

    matches = difflib.get_close_matches(name, sorted(candidates), n=1, cutoff=0.8)
    return matches[0] if matches else None


def _find_construct(text: str, pattern: str) -> Span:
    """Where a forbidden construct starts in the text (the parser stops past it)."""
    match = re.search(pattern, text)
    if not match:
        return Span.point(1, 1)
    line = text.count("\n", 0, match.start()) + 1
    col = match.start() - (text.rfind("\n", 0, match.start()) + 1) + 1
    length = len(match.group(0).splitlines()[0]) if match.group(0) else 1
    return Span(line, col, line, col + length)


def _parse(filename: str, data: bytes | str) -> tuple[Element | None, dict, list[Diagnostic]]:
    builder = _PositionedBuilder()
    # Entities and external references are refused (defusedxml's defaults, stated here so
    # nobody turns them off by accident); a DTD alone is harmless and so allowed.
    parser = DefusedXMLParser(
        target=builder, forbid_dtd=False, forbid_entities=True, forbid_external=True
    )
    builder.parser = parser
    text = data if isinstance(data, str) else data.decode("utf-8", errors="replace")
    try:
        parser.feed(data)
        root = parser.close()
    except EntitiesForbidden as error:
        span = _find_construct(text, rf"<!ENTITY\s+(%\s+)?{re.escape(error.name or '')}\b")
        message = f"entity declaration `{error.name}` is refused"
        kind = "external entity" if error.sysid or error.pubid else "entity expansion"
        return None, {}, [
            Diagnostic(
                codes.FORBIDDEN_XML,
                message,
                filename,
                span,
                label=f"{kind} is a known XML attack",
                help="building files never need entities: remove the DOCTYPE's entity declarations",
            )
        ]
    except DTDForbidden as error:  # only reachable if forbid_dtd is ever turned on
        span = _find_construct(text, r"<!DOCTYPE")
        return None, {}, [
            Diagnostic(codes.FORBIDDEN_XML, f"document type `{error.name}` is refused", filename, span)
        ]
    except DefusedXmlException as error:
        expat = getattr(parser, "parser", None)
        line = (expat.CurrentLineNumber or 1) if expat is not None else 1
        col = (expat.CurrentColumnNumber or 0) + 1 if expat is not None else 1
        span = Span.point(line, col)
        return None, {}, [
            Diagnostic(
                codes.FORBIDDEN_XML,
                "reference to an external entity is refused",
                filename,
                span,
                label=type(error).__name__,
            )
        ]
    except ParseError as error:
        line, col = error.position
        reason = str(error).split(":", 1)[0]
        return None, {}, [
            Diagnostic(
                codes.MALFORMED_XML,
                f"malformed XML: {reason}",
                filename,
                Span.point(max(line, 1), col + 1),
                label=reason,
            )
        ]
    if root is None:
        return None, {}, [
            Diagnostic(codes.MALFORMED_XML, "malformed XML: no element found", filename, Span.point(1, 1))
        ]
    return root, builder.positions, []


def read_building(
    source: str | Path, *, text: str | None = None
) -> tuple[Building | None, list[Diagnostic]]:
    """Parse a building XML file (or `text` named `source`) into a Building, with diagnostics.

    Returns (None, diagnostics) when any error was found; warnings may accompany a Building.
    """
    filename = str(source)
    data: bytes | str
    if text is not None:
        data = text
    else:
        try:
            data = Path(source).read_bytes()
        except OSError as error:
            reason = error.strerror or str(error)
            return None, [
                Diagnostic(
                    codes.UNREADABLE_FILE,
                    f"cannot read `{filename}`: {reason.lower()}",
                    filename,
                    Span.point(1, 1),
                )
            ]
    if isinstance(data, str) and data.startswith("\ufeff"):
        data = data[1:]  # a byte-order mark in decoded text would shift every column by one
    root, positions, diagnostics = _parse(filename, data)
    if root is None:
        return None, diagnostics
    decoded = data if isinstance(data, str) else data.decode("utf-8", errors="replace")
    reader = _Reader(filename, decoded, positions)
    building = reader.building(root, default_name=Path(filename).stem)
    return building, sorted(reader.diagnostics, key=Diagnostic.sort_key)
