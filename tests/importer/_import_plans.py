"""Small synthetic building XML plans for the importer tests (file units, y down)."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class PlanSpace:
    id: str
    rtype: str
    label: str
    polygon: list[tuple[float, float]]
    # (segment id, target a, target b, EXPLICIT/IMPLICIT)
    portals: list[tuple[str, str, str, str]] = field(default_factory=list)
    door_points: dict[str, tuple[float, float]] = field(default_factory=dict)


def rect(x: float, y: float, w: float, h: float) -> list[tuple[float, float]]:
    """A closed rectangle polygon with its top-left corner at (x, y) (y grows downwards)."""
    return [(x, y), (x + w, y), (x + w, y + h), (x, y + h), (x, y)]


def plan_xml(
    spaces: list[PlanSpace],
    *,
    represented: str = "90",
    real: str = "90",
    unit: str = "cm",
    miny_tag: str = "miny",
    extra: str = "",
) -> str:
    """The text of a building XML file with these spaces, in the real files' layout."""
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<building id="test">',
        "  <name>test plan</name>",
        "  <scale>",
        f"    <represented_distance><value>{represented}</value><um>pixel</um></represented_distance>",
        f"    <real_distance><value>{real}</value><um>{unit}</um></real_distance>",
        "  </scale>",
        "  <floor>",
        "    <spaces>",
    ]
    for space in spaces:
        xs = [p[0] for p in space.polygon]
        ys = [p[1] for p in space.polygon]
        out += [
            f'      <space id="{space.id}">',
            f"        <labels><type>{space.rtype}</type><label>{space.label}</label></labels>",
            "        <bounding_box>",
            f'          <maxx><point x="{max(xs):g}" y="{min(ys):g}"/></maxx>',
            f'          <maxy><point x="{max(xs):g}" y="{max(ys):g}"/></maxy>',
            f'          <minx><point x="{min(xs):g}" y="{min(ys):g}"/></minx>',
            f'          <{miny_tag}><point x="{min(xs):g}" y="{min(ys):g}"/></{miny_tag}>',
            "        </bounding_box>",
            "        <bounding_polygon>",
            *(f'          <point x="{x:g}" y="{y:g}"/>' for x, y in space.polygon),
            "        </bounding_polygon>",
            "        <space_representation>",
        ]
        for segment_id, (x, y) in space.door_points.items():
            out += [
                f'          <linesegment id="{segment_id}">',
                f'            <point x="{x:g}" y="{y:g}"/>',
                f'            <point x="{x:g}" y="{y:g}"/>',
                "            <class>PORTAL</class>",
                "            <type>EXPLICIT</type>",
                "          </linesegment>",
            ]
        out += ["        </space_representation>", "        <portals>"]
        for segment_id, a, b, kind in space.portals:
            out += [
                "          <portal>",
                f"            <linesegment>{segment_id}</linesegment>",
                "            <class>HORIZONTAL</class>",
                f"            <type>{kind}</type>",
                "            <direction>BOTH</direction>",
                f"            <target><id>{a}</id><id>{b}</id></target>",
                "          </portal>",
            ]
        out += ["        </portals>", "      </space>"]
    out += ["    </spaces>", extra, "  </floor>", "</building>", ""]
    return "\n".join(out)
