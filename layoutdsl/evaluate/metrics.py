"""Areas and room sizes of a plan, in square metres and metres (the thesis, §5.3.1, §6.1.1)."""

from __future__ import annotations

from dataclasses import dataclass

from layoutdsl.importer.building import Building
from layoutdsl.evaluate.topology import room_ids


@dataclass(frozen=True, slots=True)
class PlanAreas:
    """Total room area (sum of room polygons) and the area of the plan's bounding box."""

    room_area_m2: float
    bbox_area_m2: float
    bbox_width_m: float
    bbox_height_m: float


def plan_areas(building: Building) -> PlanAreas:
    """Room and bounding-box areas of a plan in m²."""
    s = building.metres_per_unit
    room_area = sum(space.area for space in building.spaces)
    xs = [p.x for space in building.spaces for p in space.polygon] or [0.0]
    ys = [p.y for space in building.spaces for p in space.polygon] or [0.0]
    width, height = (max(xs) - min(xs)) * s, (max(ys) - min(ys)) * s
    return PlanAreas(room_area * s * s, width * height, width, height)


def room_sizes(building: Building) -> dict[str, tuple[float, float]]:
    """Report id -> rectangularized (w, h) in metres (§5.3.1): the bounding box scaled by
    sqrt(polygon area / box area), the target the importer gives the room. For a
    rectangular room (every generated one) that is its own width and height."""
    s = building.metres_per_unit
    ids = room_ids(building)
    sizes = {}
    for space in building.spaces:
        ratio = space.rectangularization_ratio
        sizes[ids[space.id]] = (space.bbox.width * ratio * s, space.bbox.height * ratio * s)
    return sizes


NON_RECTANGULAR = 0.8
"""A room whose polygon covers less than this share of its bounding box counts as
non-rectangular (the importer's default L threshold, issue 14)."""


def room_shapes(building: Building) -> dict[str, tuple[float, float]]:
    """Report id -> (polygon area in m², polygon area / bounding-box area): each room's real
    shape, an L-room's included, as opposed to its rectangularized size."""
    s = building.metres_per_unit
    ids = room_ids(building)
    return {ids[space.id]: (space.area * s * s, space.rectangularization_ratio ** 2) for space in building.spaces}


def shape_deviation(original: dict[str, tuple[float, float]], generated: dict[str, tuple[float, float]]) -> dict:
    """How the rooms' real shapes compare: mean |area change| per matched room, and how many
    rooms are non-rectangular (fill below NON_RECTANGULAR) in each plan."""
    matched = [room for room in original if room in generated and original[room][0] > 0]
    changes = [abs(generated[room][0] / original[room][0] - 1) for room in matched]
    return {
        "room_area_change_mean": sum(changes) / len(changes) if changes else 0.0,
        "non_rectangular_original": sum(1 for area, fill in original.values() if fill < NON_RECTANGULAR),
        "non_rectangular_generated": sum(1 for area, fill in generated.values() if fill < NON_RECTANGULAR),
    }


@dataclass(frozen=True, slots=True)
class SizeDeviation:
    """Relative deviation of generated room sides from the original targets."""

    mean: float
    max: float
    worst_room: str | None
    per_room: dict[str, tuple[float, float]]
    """Room -> (relative deviation of the side matched to target w, of the side matched to h)."""
    unmatched: tuple[str, ...]
    """Original rooms the generated plan lacks."""


def size_deviation(original: dict[str, tuple[float, float]], generated: dict[str, tuple[float, float]]) -> SizeDeviation:
    """Orientation-agnostic: each room is compared in the orientation (w, h) or (h, w)
    that deviates least in total, as the MIQP's orientation binary allows (5.3)."""
    per_room: dict[str, tuple[float, float]] = {}
    for room, (tw, th) in original.items():
        if room not in generated:
            continue
        w, h = generated[room]
        straight = (abs(w - tw) / tw, abs(h - th) / th)
        turned = (abs(h - tw) / tw, abs(w - th) / th)
        per_room[room] = straight if sum(straight) <= sum(turned) else turned
    values = [v for pair in per_room.values() for v in pair]
    worst = max(per_room, key=lambda r: max(per_room[r]), default=None)
    return SizeDeviation(
        mean=sum(values) / len(values) if values else 0.0,
        max=max(values, default=0.0),
        worst_room=worst,
        per_room=per_room,
        unmatched=tuple(sorted(set(original) - set(generated))),
    )
