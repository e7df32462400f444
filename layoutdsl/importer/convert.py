"""Convert a `Building` (a real plan) into a `Spec` following the thesis, §5.3.

Per space, in file order:
- rectangularization (§5.3.1): ratio = sqrt(polygon area / bounding-box area); the target
  sides are the bounding-box sides times ratio;
- variance (§5.3.2): w_min = max(mindim, bbox_w·(ratio − var⁻)), w_max = bbox_w·(ratio + var⁺),
  the same for h; corridors use ± var_corridor;
- aspect ratio: ar* = long/short target side, var_avg = (var⁺ + var⁻)/2 (the thesis prints
  a minus, but only the sum reproduces Figure 4.2), ar_min = max(1, ar* − α·var_avg −
  β·var_avg·(ar* − 1)²), ar_max = ar* + α·var_avg + β·var_avg·(ar* − 1)².

Two repairs keep every imported spec lint-clean and solvable, each announced by a warning:
a side shorter than `mindim` gets its target raised to the minimum (W422), and a room whose
longest possible side cannot hold its door plus two walls (eq. 5.9) gets that maximum raised
(W423). Values are rounded to millimetres outwards (minimums down, maximums up), so the
rounded target always stays a feasible witness of the room's own bounds.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from pathlib import PurePath

from layoutdsl.syntax.ast import Adjacency, Arm, Boundary, Hint, Room, Settings, Spec
from layoutdsl.importer.building import Building, Space, polygon_area, realism_of_building
from layoutdsl.importer.lshape import LFit, fit_l
from layoutdsl.diagnostics import Diagnostic, Severity
from layoutdsl.importer import codes
from layoutdsl.diagnostics.source import Span

# The label a space gets when its <label> is empty.
_DEFAULT_LABELS = {"R": "ROOM", "C": "CORRIDOR", "E": "ENTRANCE"}
_DIGITS = 3  # millimetres: fine enough for Figure 4.2's centimetres, coarse enough to read


@dataclass(frozen=True, slots=True)
class ImportOptions:
    """Parameters of the conversion (the thesis, §5.3.2). Variances are fractions of the bbox side."""

    var_plus: float = 0.2
    """variance⁺ of rooms and entrances: how much larger than the target a side may grow."""
    var_minus: float = 0.3
    """variance⁻ of rooms and entrances: how much smaller than the target a side may shrink."""
    var_corridor: float = 0.4
    """± variance of corridors. Corridors need more room to bend the layout around them;
    0.4 is what Figure 4.2's corridor rows (e.g. C3: 3.21 7.84 5.53, ar 3.11-6.84) encode."""
    mindim: float = 1.0
    """Minimum side in metres of every room: wide enough for a person or a robot to pass."""
    alpha: float = 1.5
    """α, the linear weight of the aspect-ratio margin."""
    beta: float = 0.2
    """β, the quadratic weight of the aspect-ratio margin (matters for elongated rooms)."""
    l_threshold: float = 0.8
    """A space whose polygon covers less than this share of its bounding box becomes an
    L-shaped room (issue 14), fitted to the polygon, when the L fits it better than the box
    by FIT_GAIN; 0 keeps every room rectangular."""
    rectangular_only: bool = False
    """Every room a rectangle, as the thesis imports them (§5.3.1)."""
    hints: bool = False
    """Write each room's place in the original plan as a hint for the first layout. Off by
    default: users import a plan for new buildings with its room graph (issue 11), and a
    spec's hints are its starting arrangement."""

    def __post_init__(self) -> None:
        checks = (
            ("var_plus", self.var_plus, 0.0, math.inf),
            ("var_minus", self.var_minus, 0.0, 1.0),
            ("var_corridor", self.var_corridor, 0.0, 1.0),
            ("mindim", self.mindim, 0.0, math.inf),
            ("alpha", self.alpha, 0.0, math.inf),
            ("beta", self.beta, 0.0, math.inf),
            ("l_threshold", self.l_threshold, 0.0, 1.0 + 1e-9),
        )
        for name, value, low, high in checks:
            if not (math.isfinite(value) and low <= value < high):
                bounds = f"in [{low:g}, {high:g})" if math.isfinite(high) else f">= {low:g}"
                raise ValueError(f"{name} must be {bounds}, got {value!r}")
        if self.mindim <= 0:
            # Without a positive floor a sparse polygon could give a zero or negative minimum.
            raise ValueError(f"mindim must be positive, got {self.mindim!r}")


FIT_GAIN = 0.5
"""An L replaces the rectangle only when it mismatches the polygon (area in one and not the
other) by at most this share of what the bounding box mismatches."""


def _floor(value: float) -> float:
    scale = 10**_DIGITS
    return math.floor(value * scale + 1e-6) / scale


def _ceil(value: float) -> float:
    scale = 10**_DIGITS
    return math.ceil(value * scale - 1e-6) / scale


def _round(value: float) -> float:
    return round(value, _DIGITS)


def _fit(start: float, length: float, limit: float) -> float:
    """`length`, shortened by millimetres until start + length <= limit holds in floats too."""
    while start + length > limit and length > 0:
        length = _round(length - 10**-_DIGITS)
    return length


def original_room_area(building: Building) -> float:
    """Total area of the plan's room polygons in m² (what a generated layout is compared to)."""
    scale = building.metres_per_unit**2
    return sum(polygon_area(space.polygon) for space in building.spaces) * scale


def room_ids(building: Building) -> dict[str, str]:
    """Space id -> spec room id (R0, C0, E0, ... by type, in file order; the thesis, §5.7)."""
    return building.spec_room_ids()


def spec_name(building: Building) -> str:
    """A spec name from the building's `<name>` (often a full path on the author's disk)."""
    stem = PurePath(building.name.replace("\\", "/")).name if building.name else ""
    return stem or "building"


def spec_label(label: str) -> str:
    """A plan's label made safe for a room line: it must read back as the same label.

    In a spec a word starting with `#` opens a comment, `key=value` is a room weight and a
    final `onB` is the on-boundary flag, so those words are altered; nothing else is.
    """
    words = []
    for word in label.split():
        word = word.lstrip("#")
        if re.match(r"[A-Za-z_][A-Za-z0-9_]*=", word):
            word = word.replace("=", "-")
        if word:
            words.append(word)
    if words and words[-1] == "onB":
        words[-1] = "ONB"
    return " ".join(words)


@dataclass(slots=True)
class _Sides:
    """Bounds of one room before rounding (metres)."""

    min_w: float
    max_w: float
    target_w: float
    min_h: float
    max_h: float
    target_h: float


def _space_span(space: Space) -> Span:
    line = max(space.line, 1)
    return Span(line, 1, line, 1)


def convert(
    building: Building,
    options: ImportOptions = ImportOptions(),
    *,
    name: str | None = None,
    filename: str = "<building>",
) -> tuple[Spec, list[Diagnostic]]:
    """Turn a Building into a Spec per the thesis, §5.3; warnings say where the plan was adjusted."""
    refused = _refuse_unusable(building, name, filename)
    if refused is not None:
        return refused
    diagnostics: list[Diagnostic] = []
    settings = Settings()
    door = _round(building.real_distance_m)
    ids = room_ids(building)

    adjacencies, door_rooms = _adjacencies(building, ids, door, filename, diagnostics)
    # Eq. 5.9: a room holding a door needs a side of door/utilization plus two walls.
    door_side = door / settings.door_utilization + 2 * settings.walldim
    frame = _plan_frame(building)

    rooms: list[Room] = []
    arms: list[Arm] = []
    hints: list[Hint] = []
    # entrances that must open to the outside; with hints the arrangement is the original's,
    # where an entrance in a recess of the outline opens outside without touching the
    # boundary that onB asks for, so only those on the plan's edge get it
    outside = _open_to_outside(building, on_edge_only=options.hints)
    for space in building.spaces:
        room_id = ids[space.id]
        ratio = space.rectangularization_ratio
        rtype = space.spec_type
        var_plus = options.var_corridor if rtype == "C" else options.var_plus
        var_minus = options.var_corridor if rtype == "C" else options.var_minus
        label = spec_label(space.label) or _DEFAULT_LABELS[rtype]
        fit = _l_fit(space, options, frame.mpu)
        if fit is None:
            sides = _unrounded_sides(space, ratio, var_plus, var_minus, options, frame.mpu)
        else:
            # each arm is rectangularized on its own box (§5.3.1) with the same variances;
            # the arms share the polygon's area in proportion to how much of it each covers,
            # so the room keeps its area as a rectangularized one does
            ratio, arm_ratio = _arm_ratios(space, fit)
            arm_sides = _box_sides(_width(fit.second) * frame.mpu, _height(fit.second) * frame.mpu,
                                   arm_ratio, var_plus, var_minus, options)
            _lift_to_mindim(arm_sides, arm_ratio, var_plus, options, room_id, label, space, filename,
                            diagnostics)
            arm = _rounded_room(room_id, rtype, label, arm_sides, var_plus, var_minus, options, None)
            arms.append(Arm(room_id, arm.min_w, arm.max_w, arm.target_w, arm.min_h, arm.max_h,
                            arm.target_h, arm.min_ar, arm.max_ar))
            sides = _box_sides(_width(fit.first) * frame.mpu, _height(fit.first) * frame.mpu, ratio,
                               var_plus, var_minus, options)
        _lift_to_mindim(sides, ratio, var_plus, options, room_id, label, space, filename, diagnostics)
        widened = False
        if room_id in door_rooms and max(sides.max_w, sides.max_h) < door_side:
            widened = True
            _widen_for_door(sides, door_side, door, room_id, label, space, filename, diagnostics)
        room = _rounded_room(room_id, rtype, label, sides, var_plus, var_minus, options,
                             door_side if widened else None)
        if opens_outside(rtype, label) and space.id in outside:
            # an entrance that opens to the outside in the original must in every layout
            # too: onB (the thesis' 5.12) makes the generator keep it on the boundary
            room = replace(room, on_boundary=True)
        rooms.append(room)
        if options.hints:
            hints.append(_hint(space, room_id, frame, fit.first if fit is not None else None))

    spec = Spec(
        name=name or spec_name(building),
        rooms=tuple(rooms),
        boundary=frame.boundary,
        adjacencies=tuple(adjacencies),
        hints=tuple(hints),
        arms=tuple(arms),
    )
    return spec, diagnostics


PLAN_EDGE_M = 0.5
"""Metres within which a space's box counts as touching the plan's bounding box."""


def _open_to_outside(building: Building, on_edge_only: bool = False) -> set[str]:
    """The ids of the entrances that open to the outside in the original: by the realism
    measure (layout.realism: at least a door's width of outline on space that a 0.6 m square
    reaches from beyond the plan, so an entrance in a recess of the outline counts, one in a
    closed courtyard does not), or whose bounding box reaches the plan's."""
    entrances = [space for space in building.spaces if opens_outside(space.spec_type, space.label)]
    found = {space.id for space in entrances if _on_plan_edge(space, building)}
    if on_edge_only or len(found) == len(entrances):
        return found
    opened = set(realism_of_building(building).open_entrances)
    return found | opened & {space.id for space in entrances}


def _on_plan_edge(space: Space, building: Building) -> bool:
    """Whether the space's bounding box reaches the plan's (within PLAN_EDGE_M): it opens to
    the outside there."""
    reach = PLAN_EDGE_M / building.metres_per_unit
    box = space.bbox
    return (box.min_x - min(s.bbox.min_x for s in building.spaces) <= reach
            or max(s.bbox.max_x for s in building.spaces) - box.max_x <= reach
            or box.min_y - min(s.bbox.min_y for s in building.spaces) <= reach
            or max(s.bbox.max_y for s in building.spaces) - box.max_y <= reach)


def opens_outside(rtype: str, label: str) -> bool:
    """Whether an imported room must open to the outside: an entrance (type E, labelled
    ENTRANCE; stairs and lifts, also type E, need not)."""
    return rtype == "E" and "ENTRANCE" in label.upper()


def _l_fit(space: Space, options: ImportOptions, metres_per_unit: float) -> LFit | None:
    """The L fitted to a space far from its bounding box (None: it stays a rectangle)."""
    if options.rectangular_only or space.rectangularization_ratio ** 2 >= options.l_threshold:
        return None
    fit = fit_l([(p.x, p.y) for p in space.polygon])
    if fit is None or fit.mismatch > FIT_GAIN * fit.box_mismatch:
        return None
    # an arm narrower than mindim is no part of the room a robot can enter: the polygon's
    # sliver is better absorbed by the rectangle
    mpu = metres_per_unit
    if min(_width(fit.second), _height(fit.second)) * mpu < options.mindim:
        return None
    return fit


def _arm_ratios(space: Space, fit: LFit) -> tuple[float, float]:
    """sqrt(target area / box area) of each arm, the targets adding up to the polygon's area."""
    covered = [fill * _width(box) * _height(box) for fill, box in ((fit.first_fill, fit.first),
                                                                  (fit.second_fill, fit.second))]
    scale = space.area / max(sum(covered), 1e-12)
    return tuple(math.sqrt(c * scale / (_width(box) * _height(box)))
                 for c, box in zip(covered, (fit.first, fit.second)))


def _width(box) -> float:
    return box[2] - box[0]


def _height(box) -> float:
    return box[3] - box[1]


def _refuse_unusable(building: Building, name: str | None,
                     filename: str) -> tuple[Spec, list[Diagnostic]] | None:
    """An empty Spec and the errors for a plan without spaces or with an arealess one."""
    if not building.spaces:
        # read_building never returns such a Building (E410); one built in code might.
        empty = Diagnostic(codes.NO_SPACES, "the plan has no spaces", filename, Span.point(1, 1))
        return Spec(name=name or spec_name(building), rooms=(), boundary=None), [empty]
    degenerate = [space for space in building.spaces if polygon_area(space.polygon) <= 0]
    if degenerate:
        # read_building refuses these (E405); a Building built in code might hold one.
        return Spec(name=name or spec_name(building), rooms=(), boundary=None), [
            Diagnostic(
                codes.DEGENERATE_POLYGON,
                f"the polygon of space `{space.id}` encloses no area",
                filename,
                _space_span(space),
            )
            for space in degenerate
        ]
    return None


@dataclass(frozen=True, slots=True)
class _PlanFrame:
    """The plan's bounding box (file units) and the spec's boundary around it (metres)."""

    min_x: float
    max_y: float
    mpu: float
    """Metres per file unit."""
    boundary: Boundary


def _plan_frame(building: Building) -> _PlanFrame:
    mpu = building.metres_per_unit
    plan_min_x = min(space.bbox.min_x for space in building.spaces)
    plan_max_x = max(space.bbox.max_x for space in building.spaces)
    plan_min_y = min(space.bbox.min_y for space in building.spaces)
    plan_max_y = max(space.bbox.max_y for space in building.spaces)
    boundary = Boundary(_ceil((plan_max_x - plan_min_x) * mpu), _ceil((plan_max_y - plan_min_y) * mpu))
    return _PlanFrame(plan_min_x, plan_max_y, mpu, boundary)


def _unrounded_sides(space: Space, ratio: float, var_plus: float, var_minus: float,
                     options: ImportOptions, mpu: float) -> _Sides:
    """The space's target sides (§5.3.1) and their variance bounds (§5.3.2), in metres."""
    return _box_sides(space.bbox.width * mpu, space.bbox.height * mpu, ratio, var_plus, var_minus, options)


def _box_sides(bbox_w: float, bbox_h: float, ratio: float, var_plus: float, var_minus: float,
               options: ImportOptions) -> _Sides:
    """A box's target sides (§5.3.1) and their variance bounds (§5.3.2), in metres."""
    return _Sides(
        min_w=max(options.mindim, bbox_w * (ratio - var_minus)),
        max_w=bbox_w * (ratio + var_plus),
        target_w=bbox_w * ratio,
        min_h=max(options.mindim, bbox_h * (ratio - var_minus)),
        max_h=bbox_h * (ratio + var_plus),
        target_h=bbox_h * ratio,
    )


def _rounded_room(room_id: str, rtype: str, label: str, sides: _Sides, var_plus: float,
                  var_minus: float, options: ImportOptions, door_side: float | None) -> Room:
    """The spec's room: sides rounded outwards, aspect-ratio bounds from the rounded targets.

    `door_side`: the side the room was widened to for its door (None: it was not).
    """
    # Rounding never takes a minimum below mindim (a mindim with more than three
    # decimals is kept as given) nor a target outside its rounded bounds.
    min_w = max(_floor(sides.min_w), options.mindim)
    min_h = max(_floor(sides.min_h), options.mindim)
    # ...nor a maximum below its minimum (a mindim a hair above a millimetre, rounded)
    max_w, max_h = max(_ceil(sides.max_w), min_w), max(_ceil(sides.max_h), min_h)
    target_w = min(max(_round(sides.target_w), min_w), max_w)
    target_h = min(max(_round(sides.target_h), min_h), max_h)
    # ar* from the rounded targets, so the written target is itself a feasible room.
    ar_target = max(target_w, target_h) / min(target_w, target_h)
    var_avg = (var_plus + var_minus) / 2
    margin = options.alpha * var_avg + options.beta * var_avg * (ar_target - 1) ** 2
    min_ar = max(1.0, _floor(ar_target - margin))
    max_ar = _ceil(ar_target + margin)
    if door_side is not None:
        # The door side may need to be long while the other stays short: allow that shape.
        short_max = max_h if max_w >= max_h else max_w
        max_ar = max(max_ar, _ceil(door_side / short_max))
    return Room(
        id=room_id,
        min_w=min_w,
        max_w=max_w,
        target_w=target_w,
        min_h=min_h,
        max_h=max_h,
        target_h=target_h,
        min_ar=min_ar,
        max_ar=max_ar,
        rtype=rtype,
        label=label,
    )


def _hint(space: Space, room_id: str, frame: _PlanFrame, box=None) -> Hint:
    """The space's original place, in the boundary's frame: origin bottom-left, y up; for an
    L-room the place of its first arm, `box` (x0, y0, x1, y1 in file units)."""
    mpu = frame.mpu
    if box is None:
        box = (space.bbox.min_x, space.bbox.min_y, space.bbox.max_x, space.bbox.max_y)
    x = _floor((box[0] - frame.min_x) * mpu)
    y = _floor((frame.max_y - box[3]) * mpu)
    return Hint(
        room=room_id,
        x=x,
        y=y,
        w=_fit(x, _floor(_width(box) * mpu), frame.boundary.w),
        h=_fit(y, _floor(_height(box) * mpu), frame.boundary.h),
    )


def _lift_to_mindim(sides, ratio, var_plus, options, room_id, label, space, filename, diagnostics):
    """Raise a target below mindim to the minimum, keeping the maximum's relative margin."""
    lifted = []
    for axis in ("w", "h"):
        target = getattr(sides, f"target_{axis}")
        minimum = getattr(sides, f"min_{axis}")
        if target < minimum:
            lifted.append(f"{'width' if axis == 'w' else 'height'} {target:.2f} m")
            setattr(sides, f"target_{axis}", minimum)
            upper = minimum * (ratio + var_plus) / ratio
            setattr(sides, f"max_{axis}", max(getattr(sides, f"max_{axis}"), upper))
    if lifted:
        diagnostics.append(
            Diagnostic(
                codes.WIDENED_TO_MINDIM,
                f"room `{room_id}` ({label}) has {' and '.join(lifted)}, below mindim "
                f"{options.mindim:g} m; its target is raised to {options.mindim:g} m",
                filename,
                _space_span(space),
                Severity.WARNING,
                label=f"space imported as `{room_id}`",
                help="pass a smaller `--mindim` to keep the original size",
            )
        )


def _widen_for_door(sides, door_side, door, room_id, label, space, filename, diagnostics):
    """Raise the longer possible side so the room can hold its door and two walls (5.9)."""
    axis = "w" if sides.max_w >= sides.max_h else "h"
    old = getattr(sides, f"max_{axis}")
    setattr(sides, f"max_{axis}", door_side)
    diagnostics.append(
        Diagnostic(
            codes.WIDENED_FOR_DOOR,
            f"room `{room_id}` ({label}) is at most {old:.2f} m long, too short for a "
            f"{door:g} m door between two walls; its maximum "
            f"{'width' if axis == 'w' else 'height'} is raised to {door_side:.2f} m",
            filename,
            _space_span(space),
            Severity.WARNING,
            label=f"space imported as `{room_id}`",
            help="pass a larger `--var-plus` to give small rooms more room",
        )
    )


def _adjacencies(building, ids, door, filename, diagnostics):
    """One adjacency per joined pair, explicit if any of its portals is (a door wins)."""
    order = {space.id: index for index, space in enumerate(building.spaces)}
    kinds: dict[tuple[str, str], str] = {}
    for space in building.spaces:
        for portal in space.portals:
            a, b = portal.targets
            if a == b:
                continue
            missing = [t for t in (a, b) if t not in order]
            if missing:
                # A Building from read_building never gets here; one built in code might.
                diagnostics.append(
                    Diagnostic(
                        codes.UNKNOWN_SPACE,
                        f"portal of space `{space.id}` names unknown space `{missing[0]}`",
                        filename,
                        _space_span(space),
                    )
                )
                continue
            key = (a, b) if order[a] < order[b] else (b, a)
            if kinds.get(key) != "EXPLICIT":
                kinds[key] = portal.type
    adjacencies = [
        Adjacency(ids[a], ids[b], door, "e" if kind == "EXPLICIT" else "i")
        for (a, b), kind in sorted(kinds.items(), key=lambda item: (order[item[0][0]], order[item[0][1]]))
    ]
    door_rooms = {ids[space_id] for pair in kinds for space_id in pair}
    return adjacencies, door_rooms
