"""The arrangement difference (layoutdsl.layout.difference) of building XML plans.

Evaluate compares real plans, read from building XML, with generated ones; this module gives
their room centres under the report's room ids, for the measure of layoutdsl.layout.difference.
"""

from __future__ import annotations

from layoutdsl.evaluate.topology import room_ids


def building_centres(building) -> dict[str, tuple[float, float]]:
    """Room centres of a building XML plan under the report's room ids (thesis §5.7).

    The centre of a space is the centre of its bounding box: the rectangle the importer makes
    of it (and writes as its hint), so a plan redrawn from its hints scores about 0.
    """
    ids = room_ids(building)
    return {
        ids[space.id]: ((space.bbox.min_x + space.bbox.max_x) / 2, (space.bbox.min_y + space.bbox.max_y) / 2)
        for space in building.spaces
    }
