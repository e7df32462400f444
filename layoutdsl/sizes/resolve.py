"""Give a parsed spec what it leaves to the tool: sizes of sizeless rooms, and a boundary.

    spec, diagnostics = resolve_spec(spec)     # between parsing and the checks (api.lint_source)

A sizeless room line (`R1 R CLASSROOM`, `R2 CLASSROOM`) gets the size model's typical sizes
for the spec's building kind (the `kind` setting, default school), its type and label; a
room line without a type takes the type its label has most often in the corpus (R for a
label the corpus never saw). A CORRIDOR's length follows its number of adjacencies. A spec
without a `boundary` section gets `choose_boundary` of its rooms, marked `chosen`.

Nothing here is a problem of the spec, so the diagnostics are notes (severity info): I441
lists where each room's sizes came from, I442 the boundary chosen. The only error is E440,
a `kind` the model does not know.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import replace

from layoutdsl.diagnostics import Diagnostic, Severity, register
from layoutdsl.diagnostics.source import Span
from layoutdsl.sizes.boundary import ASPECT, FILL, choose_boundary
from layoutdsl.sizes.model import ModelError, SizeModel, load_model
from layoutdsl.syntax.ast import Boundary, Spec
from layoutdsl.syntax.format import format_number

UNKNOWN_KIND = register(
    "E440", Severity.ERROR, "unknown building kind",
    "Reports a `kind` setting that the room-size model does not know.",
    "Sizeless rooms take their sizes from the model of the spec's building kind; with an "
    "unknown kind they would have none.",
    "settings\nkind hospital      # the shipped model knows school and office",
)  # fmt: skip
SIZES_FROM_MODEL = register(
    "I441", Severity.INFO, "sizes from the size model",
    "Lists, for every sizeless room line (`R1 R CLASSROOM`), the sizes the room-size model "
    "gave it and the group of real rooms they come from (its label, else its type, else "
    "its building kind).",
    "Nothing is wrong: it says where numbers the spec does not show come from. "
    "`layoutdsl fmt --fill-sizes` writes them into the spec.",
    "rooms\nR1 R CLASSROOM     # note: R1: 9.87 x 8.2 m, school, label CLASSROOM (142 rooms)",
)  # fmt: skip
BOUNDARY_CHOSEN = register(
    "I442", Severity.INFO, "boundary chosen by the tool",
    "Reports the boundary chosen for a spec without a `boundary` section: the rooms' target "
    "area at 60 % fill, 1.6 times as wide as high, every room fitting (docs/sizes.md).",
    "Nothing is wrong: it says which boundary the layout is placed in. `layoutdsl fmt "
    "--fill-sizes` writes it into the spec; a `boundary` section of your own overrides it.",
    "rooms\nR1 R CLASSROOM\n# no boundary section: note: boundary 13.5 x 8.5 m chosen",
)  # fmt: skip

_FIRST = Span(1, 1, 1, 2)


def needs_resolving(spec: Spec) -> bool:
    """Does the spec leave anything to the tool (a room's sizes, the boundary)?"""
    return spec.boundary is None or any(room.sizeless and not room.has_sizes for room in spec.rooms)


def resolve_spec(spec: Spec, model: SizeModel | None = None) -> tuple[Spec, list[Diagnostic]]:
    """The spec with sizes and boundary filled in, and notes saying where they came from."""
    if not needs_resolving(spec):
        return spec, []
    diagnostics: list[Diagnostic] = []
    pending = [room for room in spec.rooms if room.sizeless and not room.has_sizes]
    if pending:
        kind = spec.settings.kind
        try:
            model = model if model is not None else load_model()
            model.kind(kind)
        except (OSError, ModelError) as error:
            span = spec.settings.spans.get("kind") if spec.settings.spans else None
            return spec, [Diagnostic(
                UNKNOWN_KIND, str(error), spec.path, span or pending[0].span or _FIRST,
                label="no size model for this kind", help="set `kind school` or `kind office` in `settings`",
            )]  # fmt: skip
        doors: Counter[str] = Counter()
        for adjacency in spec.adjacencies:
            doors[adjacency.a] += 1
            doors[adjacency.b] += 1
        notes = []
        rooms = []
        for room in spec.rooms:
            if room.sizeless and not room.has_sizes:
                rtype = room.rtype or model.label_type(kind, room.label)
                size = model.room_sizes(kind, rtype, room.label, doors=doors[room.id])
                room = replace(room, **_fields(size), rtype=rtype, sizes_from=size.source)
                notes.append(
                    f"{room.id} ({rtype} {room.label}): {format_number(size.target_w)} x "
                    f"{format_number(size.target_h)} m, from {size.source}"
                )
            rooms.append(room)
        spec = replace(spec, rooms=tuple(rooms))
        count = len(pending)
        diagnostics.append(Diagnostic(
            SIZES_FROM_MODEL,
            f"{count} room{'s' if count != 1 else ''} take{'s' if count == 1 else ''} "
            f"{'their' if count != 1 else 'its'} sizes from the {kind} size model",
            spec.path, pending[0].span or _FIRST, Severity.INFO, label="sizes from the model",
            help="`layoutdsl fmt --fill-sizes` writes these sizes into the spec",
            notes=tuple(notes),
        ))  # fmt: skip
    if spec.boundary is None:
        try:
            w, h = choose_boundary(spec.rooms, spec.arms, contains=placed_points(spec))
        except ValueError:
            return spec, diagnostics  # no rooms (E017 says so) or broken sizes (the checks say so)
        spec = replace(spec, boundary=Boundary(w, h, chosen=True))
        area = sum(room.target_w * room.target_h for room in spec.rooms) + sum(a.target_w * a.target_h for a in spec.arms)
        diagnostics.append(Diagnostic(
            BOUNDARY_CHOSEN, f"no `boundary` section: the boundary is {format_number(w)} x {format_number(h)} m",
            spec.path, spec.rooms[0].span or _FIRST, Severity.INFO, label="boundary chosen for these rooms",
            help="add a `boundary` section with a `w h` line to choose it yourself",
            notes=(f"the rooms' target area is {area:.1f} m²; the boundary holds it at {FILL:.0%} fill, "
                   f"{ASPECT:g} times as wide as high, every room fitting",),
        ))  # fmt: skip
    return spec, diagnostics


def placed_points(spec: Spec) -> list[tuple[float, float]]:
    """The points a spec places in the boundary's frame: positions, both points of each
    connection, the far corner of each hint. A chosen boundary must contain them."""
    points = [(p.x, p.y) for p in spec.positions]
    for c in spec.connections:
        points += [(c.x1, c.y1), (c.x2, c.y2)]
    points += [(h.x + h.w, h.y + h.h) for h in spec.hints]
    return points


def _fields(size) -> dict[str, float]:
    names = ("min_w", "max_w", "target_w", "min_h", "max_h", "target_h", "min_ar", "max_ar")
    return dict(zip(names, size.as_tuple()))
