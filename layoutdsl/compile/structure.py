"""What cannot be drawn: room graphs no arrangement of the spec's room shapes realises.

Checked before the generator runs, from the room graph alone (rooms as nodes, doors as
edges). A non-planar graph never gets here: the checks before compile reject it (E215,
layoutdsl.check, naming the rooms of a Kuratowski subgraph). What is left is what the
spec's room shapes cannot draw:

- four rooms joined pairwise (a K4) none of which is L-shaped (E908): no four rectangles
  pairwise share a wall of positive length (three meet pairwise only around a point, and
  the fourth cannot touch all three), while one L-room wrapping two of the others can.

A K4 with a corridor-like room (type C: corridors, halls, lobbies) is drawn instead: that
room gets an arm (`with_l_rooms`), an L that wraps two of the others (shapes.py): the
longest such room, since its legs must reach round the two it wraps.

- three rooms joined pairwise, all rectangles, that would have to enclose other rooms, and
  rooms that must open to the outside (onB) that the doors round them shut in (E912):
  three rectangles meet pairwise only around a point, so such a triangle is a face of every
  drawing, and when no planar embedding of the room graph keeps every one a face with the
  onB rooms round one outside, no sizes draw it (layoutdsl.check.rectangles, a test on the
  graph alone). Compile first gives a corridor-like room of those triangles an L when that
  is enough (`with_l_rooms`, the longest first): on the 80 synthetic school graphs two need
  one (cml_new_256 and cml_synth_121, whose unmet door had been put down to rings of
  corridors), and no real plan does.

The generator also turns corridors: of each door between two corridor-like rooms that its
best arrangement still leaves unmet, one gets an arm, the same L (shapes.py), for the rounds
that follow.
"""

from __future__ import annotations

from itertools import combinations

import networkx as nx

from layoutdsl.check.rectangles import Enclosure, drawable, enclosure, rectangle_triangles
from layoutdsl.compile.explain import E908, E912, I911, I912
from layoutdsl.compile.graph import room_graph
from layoutdsl.compile.shapes import with_arms, with_corridor_arms
from layoutdsl.layout.geometry import RoomSizes
from layoutdsl.diagnostics import Diagnostic, Severity
from layoutdsl.diagnostics.source import Span
from layoutdsl.syntax.ast import Spec

_FALLBACK_SPAN = Span(1, 1, 1, 2)


def with_l_rooms(spec: Spec) -> tuple[Spec, list[str]]:
    """The spec with one corridor-like room of every four rooms joined pairwise (and none
    L-shaped yet) made an L, and the rooms made so; rooms of type C only, the one with the
    longest target side first (then the most doors, then spec order). The L has to wrap two
    of the others: a long corridor's legs reach round them where a hall's do not (a hall
    with more doors than three corridors, made the L, found no layout for two seeds of
    four; the longest corridor, four of four). Then, when the rectangles left still cannot
    be drawn with the onB rooms outside (`enclosed`), the first corridor-like room in the
    same order whose L lets them be (`bent_for`)."""
    armed = {arm.room for arm in spec.arms}
    spec, made = with_corridor_arms(spec, rectangle_k4s(room_graph(spec), armed), longest=True)
    bent = bent_for(spec)
    if bent is not None:
        spec, made = with_arms(spec, [bent]), made + [bent]
    return spec, made


def why_l_rooms(spec: Spec, made: list[str]) -> str:
    """Why `with_l_rooms` made the rooms `made` of `spec` (the spec it was given) L-shaped,
    for the terminal."""
    armed = {arm.room for arm in spec.arms}
    in_fours = {room for four in rectangle_k4s(room_graph(spec), armed) for room in four}
    reasons = []
    if in_fours & set(made):
        reasons.append("four rooms joined pairwise cannot all be rectangles")
    k4_made = [room for room in made if room in in_fours]
    reason = enclosed(with_arms(spec, k4_made)) if set(made) - in_fours else None
    if reason is not None:
        reasons.append(f"{enclosure_text(reason)}: rectangles alone cannot draw them")
    return "; ".join(reasons)


def enclosed(spec: Spec, l_rooms: set[str] | None = None) -> Enclosure | None:
    """Why the spec's rectangles (every room but `l_rooms`, by default those with an arm)
    cannot be drawn with its onB rooms open to the outside; None when
    layoutdsl.check.rectangles finds no reason."""
    return enclosure(*_rectangle_test(spec, l_rooms))


def bent_for(spec: Spec) -> str | None:
    """The corridor-like room (not L-shaped yet) whose L lets the spec be drawn (`enclosed`
    finds no reason then), the longest target side first, then the most doors, then spec
    order; None when the spec needs none or no single L is enough. Only a room of a triangle
    of rectangles can be one (an L elsewhere leaves every conflicting triangle as it was),
    and each is tried with the plain test: the conflict itself is named once, by E912."""
    graph, rectangles, outside = _rectangle_test(spec)
    if drawable(graph, rectangles, outside):
        return None
    armed = {arm.room for arm in spec.arms}
    order = {room.id: index for index, room in enumerate(spec.rooms)}
    in_triangles = {room for triangle in rectangle_triangles(graph, rectangles) for room in triangle}
    candidates = sorted((room for room in spec.rooms if room.rtype == "C" and room.id not in armed
                         and room.id in in_triangles),
                        key=lambda room: (-RoomSizes.of(room).target_long, -graph.degree(room.id), order[room.id]))
    for room in candidates:
        if drawable(graph, [r for r in rectangles if r != room.id], outside):
            return room.id
    return None


def _rectangle_test(spec: Spec, l_rooms: set[str] | None = None) -> tuple[nx.Graph, list[str], list[str]]:
    """(room graph, its rectangles: every room but `l_rooms`, by default those with an arm,
    its onB rooms): what layoutdsl.check.rectangles tests."""
    if l_rooms is None:
        l_rooms = {arm.room for arm in spec.arms}
    rectangles = [room.id for room in spec.rooms if room.id not in l_rooms]
    return room_graph(spec), rectangles, [room.id for room in spec.rooms if room.on_boundary]


def undrawable(spec: Spec) -> list[Diagnostic]:
    """An E908 diagnostic for every four rooms joined pairwise that must all be rectangles;
    else an E912 when the rectangles cannot be drawn with the onB rooms outside (`enclosed`,
    after `with_l_rooms` gave what Ls it could); empty when the room graph may be drawable."""
    l_rooms = {arm.room for arm in spec.arms}
    k4s = [_k4_diagnostic(spec, group) for group in rectangle_k4s(room_graph(spec), l_rooms)]
    if k4s:
        return k4s
    reason = enclosed(spec)
    return [_enclosed_diagnostic(spec, reason)] if reason is not None else []


def rectangle_k4s(graph: nx.Graph, l_rooms: set[str]) -> list[tuple[str, ...]]:
    """Every four rooms joined pairwise none of which may be L-shaped (node order of the
    graph): cliques of four or more give each of their four-room subsets."""
    order = {node: i for i, node in enumerate(graph.nodes)}
    found: set[tuple[str, ...]] = set()
    for clique in nx.find_cliques(graph):
        if len(clique) < 4:
            continue
        for four in combinations(sorted(clique, key=order.__getitem__), 4):
            if not l_rooms & set(four):
                found.add(four)
    return sorted(found, key=lambda four: [order[r] for r in four])


def not_placed(spec: Spec) -> list[Diagnostic]:
    """An I911 note for every four rooms joined pairwise with an L among them: said when the
    generator found no layout for such a graph (E908 is for four that must be rectangles)."""
    l_rooms = {arm.room for arm in spec.arms}
    fours = [four for four in rectangle_k4s(room_graph(spec), set()) if l_rooms & set(four)]
    notes = [_not_placed_diagnostic(spec, four, l_rooms) for four in fours]
    # the Ls outside those fours, given by compile (`bent_for`, or a corridor the generator
    # turned) or by the spec: where rectangles alone could not draw the graph, the reason
    in_fours = {room for four in fours for room in four}
    reason = enclosed(spec, l_rooms & in_fours)
    if reason is not None and reason.triangles:
        bent = [room.id for room in spec.rooms if room.id in l_rooms - in_fours
                and any(room.id in triangle for triangle in reason.triangles)]
        if bent:
            notes.append(_bent_not_placed_diagnostic(spec, reason, bent))
    return notes


def enclosure_text(reason: Enclosure) -> str:
    """'rooms C0 C1 C3 and C1 C2 C3 are joined pairwise and E0, E2 must open to the outside'."""
    parts = []
    if reason.triangles:
        threes = " and ".join(" ".join(triangle) for triangle in reason.triangles)
        parts.append(f"rooms {threes} are joined pairwise")
    if reason.outside:
        parts.append(f"{', '.join(reason.outside)} must open to the outside")
    return " and ".join(parts)


def _enclosed_rooms(reason: Enclosure) -> list[str]:
    seen: dict[str, None] = {}
    for triangle in reason.triangles:
        seen.update(dict.fromkeys(triangle))
    seen.update(dict.fromkeys(reason.outside))
    return list(seen)


def _enclosed_diagnostic(spec: Spec, reason: Enclosure) -> Diagnostic:
    if reason.triangles:
        why = ("three rectangles joined pairwise meet only around a point, and no drawing keeps "
               "each three so" + (" with those rooms outside" if reason.outside else ""))
        corridors = sorted({room for triangle in reason.triangles for room in triangle})
        help_text = (f"give one of {', '.join(corridors)} an L (an `arms` line), remove a door among them"
                     + (f", or drop `onB` from one of {', '.join(reason.outside)}" if reason.outside else ""))
    else:
        why = "no arrangement of the doors leaves them all on the outside (a cycle of doors shuts one in)"
        help_text = (f"drop `onB` from one of {', '.join(reason.outside)}, or remove a door among the rooms "
                     "in the note")
    return Diagnostic(
        code=E912,
        message=f"{enclosure_text(reason)}: {why}",
        filename=spec.path, span=_adjacency_span(spec, _enclosed_rooms(reason)),
        label="no drawing with these shapes", help=help_text, notes=_trap_note(reason))


def _trap_note(reason: Enclosure) -> tuple[str, ...]:
    """Which rooms' doors decide it (layoutdsl.check.rectangles names them as E215 names a
    non-planar graph's)."""
    if not reason.rooms:
        return ()
    enclose = "a triangle of rectangles would have to enclose rooms"
    shut_in = f"one of {', '.join(reason.outside)} is shut in"
    shut = (f"{enclose} or {shut_in}" if reason.triangles and reason.outside
            else enclose if reason.triangles else shut_in)
    return (f"the doors among {', '.join(reason.rooms)} decide it: in every planar drawing of them {shut}",)


def _bent_not_placed_diagnostic(spec: Spec, reason: Enclosure, bent: list[str]) -> Diagnostic:
    return Diagnostic(
        code=I912,
        message=f"{enclosure_text(reason)}: with {' and '.join(bent)} L-shaped they may be drawn, and the "
                "generator's arrangements did not reach it",
        filename=spec.path, span=_adjacency_span(spec, _enclosed_rooms(reason)), severity=Severity.INFO,
        label="rectangles alone cannot draw these", notes=_trap_note(reason),
        help="another `--seed`; an `arms` line for another room of the threes; or a door fewer among them")


def _k4_diagnostic(spec: Spec, four: tuple[str, ...]) -> Diagnostic:
    return Diagnostic(
        code=E908,
        message=f"rooms {', '.join(four)} are joined pairwise: four rectangles cannot all share walls",
        filename=spec.path, span=_adjacency_span(spec, list(four)),
        label="four rooms joined pairwise",
        help=f"give one of them an L shape (an `arms` line, e.g. `{four[0]} ...` for a corridor), "
             "or remove one of their six adjacencies")


def _not_placed_diagnostic(spec: Spec, four: tuple[str, ...], l_rooms: set[str]) -> Diagnostic:
    ls = [room for room in four if room in l_rooms]
    named = " and ".join(ls)
    return Diagnostic(
        code=I911,
        message=f"rooms {', '.join(four)} are joined pairwise: with {named} L-shaped they draw only as "
                f"three around a point and {'an L' if len(ls) > 1 else named} wrapping two of them, "
                "and the generator's arrangements did not reach it",
        filename=spec.path, span=_adjacency_span(spec, list(four)), severity=Severity.INFO,
        label="four rooms joined pairwise",
        help="another `--seed`; an `arms` line for a second of the four; or one of their six "
             "adjacencies removed (then rectangles draw them)")


def _adjacency_span(spec: Spec, rooms: list[str]) -> Span:
    """The first adjacency line between two of the rooms, else the first room's line."""
    wanted = set(rooms)
    for adj in spec.adjacencies:
        if adj.a in wanted and adj.b in wanted and getattr(adj, "span", None) is not None:
            return adj.span
    for room in spec.rooms:
        if room.id in wanted and getattr(room, "span", None) is not None:
            return room.span
    return _FALLBACK_SPAN
