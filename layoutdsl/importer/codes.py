"""Diagnostic codes of the building-XML reader and importer (E4xx errors, W4xx warnings).

Errors stop the import: the file cannot be read faithfully. Warnings say where the importer
had to depart from the plan to produce a spec that lints clean (a closet narrower than
`mindim`, a room too small for its door) or skipped something it could not use.
"""

from __future__ import annotations

from layoutdsl.diagnostics import Severity, register

MALFORMED_XML = register(
    "E400",
    Severity.ERROR,
    "malformed XML",
    "Reports a building file that is not well-formed XML (a mismatched tag, a stray `&`, "
    "a truncated file).",
    "Nothing after the first syntax error can be trusted, so no room of the plan is imported.",
    "<building>\n  <scale>\n</building>   <!-- error: mismatched tag -->",
)

FORBIDDEN_XML = register(
    "E401",
    Severity.ERROR,
    "forbidden XML construct",
    "Refuses entity declarations (`<!ENTITY ...>`) and references to external entities in a "
    "building file.",
    "Building files are untrusted input. Entity declarations are how the billion-laughs "
    "attack expands a few bytes into gigabytes, and external entities read local files or "
    "reach the network (XXE). The building format never needs them.",
    '<!DOCTYPE building [<!ENTITY lol "lol">]>   <!-- error: entity declaration -->',
)

MISSING_ELEMENT = register(
    "E402",
    Severity.ERROR,
    "missing required element",
    "Reports a building file without an element or attribute the format requires: the "
    "`<building>` root, `<scale>` with its two distances, `<floor><spaces>`, a space's `id`, "
    "a line segment's two points, a portal's `<linesegment>`.",
    "Without the scale no length can be converted to metres, and without ids the portals "
    "cannot be resolved, so the plan cannot be imported faithfully.",
    "<building>\n  <floor>...</floor>   <!-- error: no <scale> -->\n</building>",
)

INVALID_NUMBER = register(
    "E403",
    Severity.ERROR,
    "invalid number",
    "Reports a coordinate or a scale value that is not a finite number (`x=\"12a\"`, an empty "
    "`<value>`, `nan`).",
    "Every length of the spec is computed from these numbers; guessing one would silently "
    "move or resize a room.",
    '<point x="12a" y="40"/>   <!-- error: `12a` is not a number -->',
)

UNKNOWN_SPACE = register(
    "E404",
    Severity.ERROR,
    "portal names an unknown space",
    "Reports a portal whose `<target>` lists a space id that no `<space id=...>` of the "
    "floor has.",
    "The portal is an adjacency of the room graph; dropping it would change the topology "
    "the generated layout must reproduce.",
    "<target><id>A</id><id>no-such-space</id></target>   <!-- error -->",
)

DEGENERATE_POLYGON = register(
    "E405",
    Severity.ERROR,
    "space without a usable polygon",
    "Reports a space whose `<bounding_polygon>` is missing, has fewer than three points or "
    "encloses no area.",
    "A room's size in the spec comes from its polygon's area and bounding box (the thesis, §5.3.1); "
    "without them the room has no size.",
    "<bounding_polygon>\n  <point x=\"0\" y=\"0\"/>\n</bounding_polygon>   <!-- error -->",
)

INVALID_SCALE = register(
    "E406",
    Severity.ERROR,
    "invalid or implausible scale",
    "Reports a `<scale>` that cannot be right: a non-positive distance, an unknown unit, or "
    "a door (`<real_distance>`) outside 0.4-3 m, which usually means a wrong unit such as "
    "`m` where `cm` is meant.",
    "The door size converts every coordinate to metres; a unit mistake scales the whole "
    "building by 100.",
    "<real_distance><value>90</value><um>m</um></real_distance>   <!-- error: a 90 m door -->",
)

DUPLICATE_SPACE = register(
    "E407",
    Severity.ERROR,
    "duplicate space id",
    "Reports two `<space>` elements of the floor with the same `id`.",
    "Portals name spaces by id, so a repeated id makes every portal to it ambiguous.",
    '<space id="A">...</space>\n<space id="A">...</space>   <!-- error -->',
)

UNREADABLE_FILE = register(
    "E408",
    Severity.ERROR,
    "cannot read building file",
    "Reports a building file that does not exist or cannot be read (a directory, no "
    "permission).",
    "There is nothing to import.",
    "layoutdsl import no-such-plan.xml",
)

BAD_PORTAL_TARGETS = register(
    "E409",
    Severity.ERROR,
    "portal does not join two spaces",
    "Reports a `<portal>` whose `<target>` does not list exactly two space ids.",
    "An adjacency joins exactly two rooms; with one or three ids the importer cannot tell "
    "which rooms the door connects.",
    "<target><id>A</id></target>   <!-- error: one id -->",
)

NO_SPACES = register(
    "E410",
    Severity.ERROR,
    "plan without spaces",
    "Reports a building whose `<floor><spaces>` holds no `<space id=...>` element.",
    "A spec needs at least one room; an empty plan is almost always the wrong file or a "
    "truncated export.",
    "<floor><spaces/></floor>   <!-- error -->",
)

UNKNOWN_ROOM_TYPE = register(
    "W420",
    Severity.WARNING,
    "unknown room type",
    "Warns about a space whose `<labels><type>` is missing or not one of R (room), "
    "C (corridor), E (entrance); the space is imported as a generic room R.",
    "The type decides the room's id and whether it gets the corridor variance; a typo "
    "turns a corridor into a room with tight size bounds.",
    "<labels><type>X</type><label>OFFICE</label></labels>   <!-- warning: imported as R -->",
)

PORTAL_SEGMENT_MISSING = register(
    "W421",
    Severity.WARNING,
    "portal segment not found",
    "Warns about a `<portal>` whose `<linesegment>` id is not a line segment of the same "
    "space. The adjacency is still imported; only the door's position is unknown.",
    "The door's position is lost, so tools that draw the original plan cannot place it.",
    "<portal><linesegment>no-such-segment</linesegment>...</portal>   <!-- warning -->",
)

WIDENED_TO_MINDIM = register(
    "W422",
    Severity.WARNING,
    "room narrower than mindim",
    "Warns about a room whose rectangularized side is shorter than the `mindim` option: "
    "its target and maximum are raised so that minimum <= target <= maximum still holds.",
    "The generated room is larger than the original one. Lower `--mindim` to keep the "
    "original size (a robot may then not fit through it).",
    "a 0.7 m wide closet with --mindim 1.0   # warning: target widened to 1.0 m",
)

WIDENED_FOR_DOOR = register(
    "W423",
    Severity.WARNING,
    "room too small for its door",
    "Warns about a room whose longest possible side cannot hold its door plus the two "
    "wall thicknesses (the thesis, eq. 5.9); the maximum of that side is raised so that the "
    "adjacency can be satisfied.",
    "Without the change the spec has no layout at all; with it the room may be a little "
    "larger than in the original plan.",
    "a 1.0 m x 1.1 m closet with a 0.9 m door   # warning: maximum side raised to 1.3 m",
)

SELF_PORTAL = register(
    "W424",
    Severity.WARNING,
    "portal joins a space to itself",
    "Warns about a `<portal>` whose two targets are the same space; it is ignored.",
    "A room cannot be adjacent to itself; the portal is a drawing mistake in the plan.",
    "<target><id>A</id><id>A</id></target>   <!-- warning: ignored -->",
)

SKIPPED_EMPTY_SPACE = register(
    "W425",
    Severity.WARNING,
    "space without area or portal skipped",
    "Warns about a space whose `<bounding_polygon>` encloses no area and that no portal "
    "joins to any other space; it is left out of the spec. A space without area that a "
    "portal does join is still an error (E405).",
    "Such a space is a drawing artefact (a stray label or a collapsed outline, seen in real "
    "plans): it has no size and no place in the room graph, so skipping it changes neither "
    "the rooms nor the topology, while refusing it would fail the whole import.",
    "<bounding_polygon><point x=\"5\" y=\"5\"/></bounding_polygon>, no <portals>   <!-- warning: skipped -->",
)
