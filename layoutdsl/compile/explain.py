"""Why there is no layout: E9xx diagnostics (and W906, variants that repeat one another), and a
deletion filter for infeasible specs.

When SCIP proves a spec infeasible, we look for a small set of spec lines whose constraints
conflict: each line that constrains the geometry (an adjacency, a position, a connection, a
cluster, an obstacle, an `onB` flag, a room's size bounds) is a group; a deletion filter
drops one group at a time and re-solves a feasibility-only model (objective dropped, short
limit). A group whose removal leaves the spec infeasible is not needed for the conflict and
stays dropped; one whose removal makes it feasible is part of the conflict. Only proven
infeasibility drops a group, so the lines reported always conflict; a re-solve that runs
out of time keeps its group, which can only make the set larger, never wrong.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace

import networkx as nx

from layoutdsl.compile.graph import corridor_skeleton, rings
from layoutdsl.syntax.ast import ARM_SUFFIX, Room, Spec
from layoutdsl.diagnostics import Diagnostic, Severity, register
from layoutdsl.diagnostics.source import Span

E901 = register(
    "E901",
    Severity.ERROR,
    "conflicting-constraints",
    "Marks each spec line of a set of constraints that no layout can satisfy together; "
    "the set is small: without any one of these lines a layout exists (as far as the "
    "solver could tell within its limit).",
    "The compiler proved that no layout meets all hard constraints, so it wrote nothing. "
    "The conflict usually involves only a few lines, and changing any one of them (a larger "
    "maximum size, a position moved, an adjacency removed) removes it.",
    "rooms\nA 2 3 2.5 2 3 2.5 1 1.5 R OFFICE\nB 2 3 2.5 2 3 2.5 1 1.5 R OFFICE\n\n"
    "boundary\n20 10\n\nadjacencies\nA B 0.9 e\n\npositions\nA 1 1\nB 18 8\n"
    "# A and B must touch, but their positions are 17 m apart and each is at most 3 m wide",
)
E902 = register(
    "E902",
    Severity.ERROR,
    "no-layout-in-time",
    "Reports that compile found no layout before it stopped: the generator's work limits ran "
    "out (its rounds of arrangements, the same on every machine), or the time limit (or a "
    "node or solution limit) stopped the search. The message says which.",
    "The spec may well be feasible, but no layout was found, so nothing was written. Larger "
    "specs, tight boundaries, narrow size ranges and cycles of adjacent rooms make the first "
    "layout hard to find. When the work limits ran out, a longer time limit changes nothing; "
    "another seed draws other arrangements.",
    "settings\ntime_limit 0.5\n# a 40-room spec with a boundary barely larger than the rooms",
)
E903 = register(
    "E903",
    Severity.ERROR,
    "verification-failed",
    "Reports a solved layout that the independent verifier rejected, with its violations.",
    "A layout that breaks a hard constraint of the spec is never written: it would give the "
    "simulation a building the spec did not ask for. This points at a solver tolerance or a "
    "bug in layoutdsl; please report it with the spec.",
    "# any spec; the verifier found two rooms 0.19 m apart with walldim 0.2",
)
E904 = register(
    "E904",
    Severity.ERROR,
    "infeasible-spec",
    "Reports that the solver proved the spec infeasible when no smaller set of conflicting "
    "lines could be isolated within the time limit.",
    "No layout satisfies all hard constraints, so nothing was written.",
    "rooms\nA 5 6 5.5 5 6 5.5 1 1.2 R HALL\nB 5 6 5.5 5 6 5.5 1 1.2 R HALL\n\n"
    "boundary\n10.5 6\n# two rooms at least 5 m wide and 0.2 m of wall do not fit in 10.5 m",
)

E905 = register(
    "E905",
    Severity.ERROR,
    "strategy-without-l-rooms",
    "Reports a compile of a spec with L-shaped rooms (an `arms` section) under a strategy "
    "that places rectangles only: `thesis` (the thesis' model as written).",
    "Those strategies solve the thesis' model, in which every room is one rectangle; they "
    "would drop the rooms' arms. The generator (strategy `auto`) places L-rooms.",
    "arms\nC0 1.5 2.2 1.8 6 9 8 1 20\n# compiled with --strategy thesis",
)

W906 = register(
    "W906",
    Severity.WARNING,
    "variants-not-distinct",
    "Reports a `--variants N` compile of new arrangements in which fewer than N variants "
    "differ by at least 0.3 from every variant before them (the arrangement difference: the "
    "share of room pairs whose relative position differs, best of the 8 rotations and "
    "mirrors). Layouts of the other seeds tried, in seed order, fill the missing places and "
    "are written too.",
    "Those variants are much the same building, so an experiment run on them samples fewer "
    "environments than it counts. In a long, narrow boundary the corridors must run along it "
    "and meet their rooms in much the same order whatever the seed.",
    "boundary\n73.425 19.8\n# office_324-Elm-Furn-Plan imported without hints (36 rooms), "
    "compiled with --variants 5",
)

E908 = register(
    "E908",
    Severity.ERROR,
    "rectangles-cannot-draw",
    "Reports four rooms joined pairwise by doors (a K4) none of which may be L-shaped: no four "
    "rectangles pairwise share a wall of positive length.",
    "Three rectangles can meet pairwise only around a point, and the fourth would have to "
    "touch all three, which no rectangle can. One L-shaped room (an `arms` line, e.g. for a "
    "corridor) wraps around two of the others and makes the four drawable.",
    "adjacencies\nC0 C1 0.9 i\nC0 C2 0.9 i\nC0 C3 0.9 i\nC1 C2 0.9 i\nC1 C3 0.9 i\n"
    "C2 C3 0.9 i\n# four corridors joined pairwise; none has an arm",
)

E912 = register(
    "E912",
    Severity.ERROR,
    "rectangles-cannot-keep-it-open",
    "Reports a room graph that no drawing with its room shapes realises, found from the graph "
    "alone before any search: three rooms joined pairwise (all rectangles) that would have to "
    "enclose other rooms, or rooms that must open to the outside (`onB`) that the doors round "
    "them shut in. Names the fewest such threes and rooms that conflict, at the first "
    "adjacency line among them, and in a note the rooms whose doors decide it (the branch "
    "rooms of a Kuratowski subgraph of the test's graph, as E215 names them for a non-planar "
    "one).",
    "Three rectangles joined pairwise share walls only around a point, so they enclose "
    "nothing; and every room that must open outside touches the one outside. When the room "
    "graph has no planar drawing that keeps both (`layoutdsl.check.rectangles` tests it: every "
    "real plan of the development corpus passes), no sizes help, and the search would run to "
    "its limit. Compile first gives a corridor-like room of the threes an L when that is "
    "enough, and says so on the terminal; E912 is for the graphs no such L saves. The way out "
    "is an `arms` line for another room of the threes, a door fewer, or `onB` dropped from one "
    "of the rooms named.",
    "adjacencies\nC0 C1 0.9 i\nC1 C2 0.9 i\nC2 C3 0.9 i\nC3 C0 0.9 i\nC0 E0 0.9 e\nC2 E0 0.9 e\n"
    "C1 E1 0.9 e\nC3 E1 0.9 e\n# E0 and E1 onB: the ring of corridors and the two entrances\n"
    "# that cross it leave one of them inside in every drawing",
)

I912 = register(
    "I912",
    Severity.INFO,
    "corridor-bent-not-placed",
    "Accompanies E902 when compile gave a corridor-like room an L so that the room graph could "
    "be drawn at all (three rooms joined pairwise, all rectangles, would otherwise have had to "
    "enclose rooms or shut an entrance in), and the generator still found no layout: names "
    "the threes, the rooms that must open outside and the L-rooms among the threes.",
    "With that L the graph has drawings, but few: the L must wrap the rooms the threes would "
    "have enclosed, and the generator's work limits ran out before it reached one. Another "
    "`--seed` draws other arrangements; an `arms` line for another room of the threes gives the "
    "search other shapes; a door fewer among the threes, or `onB` dropped from a room named, "
    "lets rectangles draw it. Where no L is enough, compile says so before any search (E912).",
    "# compile: C3 drawn as L-shaped rooms (rooms C0 C1 C3 and C1 C2 C3 are joined pairwise and\n"
    "#   E0, E2 must open to the outside: rectangles alone cannot draw them)\n"
    "# error[E902]: no layout found within the generator's work limits (8 rounds, ...)\n"
    "# info[I912]: rooms C0 C1 C3 and C1 C2 C3 are joined pairwise and E0, E2 must open to the "
    "outside: with C3 L-shaped they may be drawn, and the generator's arrangements did not reach it",
)


LONG_BOUNDARY = 3.0
"""A boundary at least this many times as long as it is wide is called long in W906's help.
Measured (bench/results/outline.txt): the two real plans of 3.7-3.8:1 differ from their
original by 0.18-0.30 in their own box, at 0.32-0.35 median in a 2:1 box of the same area.
office_324-Elm-Furn-Plan's `--variants 5`: in its 73.4 x 19.8 m boundary 0.17-0.26 apart and
0.21-0.25 from the original; in 54 x 27 m, 0.34-0.42 apart and 0.31-0.46 from the original,
with room area 0.77-0.81 of the original's (0.75-0.83 in its own boundary)."""


def variants_not_distinct(spec: Spec, close: list[int], asked: int, apart: float) -> Diagnostic:
    """W906: the new-arrangement variants numbered `close` (1-based, of `asked`) lie within
    `apart` (the arrangement difference variants are kept at) of an earlier one."""
    help_text = ("try another `--seed`, or a larger boundary: rooms in cycles of doors and a tight "
                 "boundary leave few arrangements")
    label = "the boundary every variant fills"
    boundary = spec.boundary
    if boundary is not None and min(boundary.w, boundary.h) > 0:
        aspect = max(boundary.w, boundary.h) / min(boundary.w, boundary.h)
        label = f"a {boundary.w:g} x {boundary.h:g} m boundary ({aspect:.1f}:1)"
        if aspect >= LONG_BOUNDARY:
            # the same area at 2:1, its long side where the spec has it, rounded up to 0.1 m
            long_side = math.ceil(math.sqrt(2 * boundary.w * boundary.h) * 10) / 10
            short_side = math.ceil(long_side * 5) / 10
            w, h = (long_side, short_side) if boundary.w >= boundary.h else (short_side, long_side)
            help_text = (f"a boundary of the same area at 2:1 (`{w:g} {h:g}` in `boundary`) leaves room "
                         "for other arrangements, of a building of another shape")
    return Diagnostic(
        code=W906,
        message=(f"{_numbered('variant', close)} of {asked} {'is' if len(close) == 1 else 'are'} "
                 f"within {apart:g} of an earlier variant: no arrangement farther from them was found"),
        filename=spec.path,
        span=_first_line_span(spec),
        severity=Severity.WARNING,
        label=label,
        help=help_text,
    )


def _numbered(noun: str, numbers: list[int]) -> str:
    """'variant 3', 'variants 2 and 5', 'variants 2, 3 and 5'."""
    if len(numbers) == 1:
        return f"{noun} {numbers[0]}"
    return f"{noun}s " + ", ".join(str(n) for n in numbers[:-1]) + f" and {numbers[-1]}"


_FALLBACK_SPAN = Span(1, 1, 1, 2)


def strategy_without_l_rooms(spec: Spec, strategy: str) -> Diagnostic:
    """E905: the strategy cannot place the spec's L-shaped rooms."""
    arm = spec.arms[0]
    return Diagnostic(
        code=E905,
        message=f"strategy `{strategy}` places rectangles only; room `{arm.room}` is L-shaped",
        filename=spec.path,
        span=_span(arm.span),
        label="an L-shaped room",
        help="compile with `--strategy auto` (the default): its construction places L-shaped rooms",
    )


def _span(node_span: Span | None) -> Span:
    return node_span if node_span is not None else _FALLBACK_SPAN


def _first_line_span(spec: Spec) -> Span:
    if spec.boundary is not None and spec.boundary.span is not None:
        return spec.boundary.span
    return _FALLBACK_SPAN


def no_layout_in_time(spec: Spec, options, status: str = "time_limit", *,
                      exhausted: tuple[int, int] | None = None, searched: bool = False) -> Diagnostic:
    """E902: no layout; says what stopped compile and what to try.

    `exhausted`: (rounds, moves) of a generator whose work limits ran out (not the clock);
    `searched`: SCIP then searched the whole model alone and stopped at `status`. Such a
    generator would find the same nothing with any time limit, so the message says so and
    the help leaves `--time-limit` out (unless SCIP's search after it was cut off).
    """
    limit, longer = _stopping_limit(options, status)
    if exhausted is not None:
        rounds, moves = exhausted
        work = f"the generator's work limits ({rounds} round{'s' if rounds != 1 else ''}, {moves:,} moves)"
        message = (f"no layout found within {work}, nor by the solver alone within {limit}" if searched
                   else f"no layout found within {work}")
    else:
        message = f"no layout found within {limit}"
    grows = _boundary_grows(spec, options)
    return Diagnostic(
        code=E902,
        message=message,
        filename=spec.path,
        span=_first_line_span(spec),
        label="no layout for this boundary found",
        # another seed first: the construction draws its arrangements from it, and on the
        # largest real plan (school_stjoseph, 105 rooms) 2 of seeds 0-7 find nothing in 60 s
        # while the other 6 construct in 16-30 s (bench/results/generation-renamed.txt)
        help=_alternatives(["another `--seed` (each draws other arrangements to construct)"]
                           + ([] if exhausted is not None and not searched else [longer])
                           + ([] if grows else ["a larger boundary"])
                           + ["wider size ranges (a larger variance when importing)"]
                           + ([] if grows else ["`--grow-boundary`"])
                           + (["rectangular rooms (`layoutdsl import --rectangular-only`)"]
                              if _arms_from_source(spec) else [])),
    )


def _stopping_limit(options, status: str) -> tuple[str, str]:
    """(the limit that stopped a search, in words; the flag that raises it, as advice)."""
    if status == "node_limit" and options.node_limit is not None:
        return f"the node limit of {options.node_limit}", "a larger node limit (`--node-limit`)"
    if status == "solution_limit" and options.solution_limit is not None:
        return f"the solution limit of {options.solution_limit}", "a larger solution limit (`--solution-limit`)"
    return f"the time limit of {options.time_limit:g} s", "a longer limit (`--time-limit`)"


def _arms_from_source(spec: Spec) -> bool:
    """Does the spec's own text give L-rooms (an `arms` line, as an import writes)? The Ls
    compile makes itself (a K4's corridor, a corridor turned to reach a door) have no line,
    and `import --rectangular-only` would not take them away."""
    return any(arm.span is not None for arm in spec.arms)


def _alternatives(things: list[str]) -> str:
    """'try a, b, or c'."""
    return "try " + (things[0] if len(things) == 1 else ", ".join(things[:-1]) + ", or " + things[-1])


def _boundary_grows(spec: Spec, options=None) -> bool:
    """The boundary is drawn round the building already: the tool chose it (a spec without
    one) or the compile may grow it (`--grow-boundary`). Advice to enlarge it, or to pass
    `--grow-boundary`, would then change nothing."""
    chosen = spec.boundary is not None and spec.boundary.chosen
    return chosen or bool(getattr(options, "grow_boundary", False))


I909 = register(
    "I909",
    Severity.INFO,
    "doors-left-unmet",
    "Accompanies E902 when the generator found no layout: names the doors its closest "
    "arrangement left unmet, worst first, at the adjacency line of the worst one, and the "
    "rooms that lay between the two rooms of each.",
    "They are where the room graph is hard to draw within the sizes and the boundary: rooms "
    "with more doors than their walls hold, cycles of rooms that cannot all close, rings of "
    "corridors that must close round the rooms hung inside them, entrances "
    "that must reach the outside, a long corridor between two rooms joined by a door (the "
    "door must reach round one of its ends). Wider size ranges for those rooms, a larger boundary, or "
    "another door of the cycle dropped make the search's task easier; another `--seed` "
    "draws other arrangements.",
    "# compile: no layout within the limit\n# note: in the closest arrangement found (12.4 m "
    "from a layout) these doors were unmet: C2-R14 5.3 m, C5-C6 3.8 m",
)

UNMET_SHOWN = 6
"""Doors an I909 note lists; the rest are counted."""


def _room_name(room_id: str) -> str:
    return room_id.removesuffix(ARM_SUFFIX) + (" (its arm)" if room_id.endswith(ARM_SUFFIX) else "")


def _door_name(a: str, b: str) -> str:
    """`A-B` for a door, `the L C0's arm and box` for the join of an L-room's two parts."""
    if a.removesuffix(ARM_SUFFIX) == b.removesuffix(ARM_SUFFIX):
        return f"the join of L-room {a.removesuffix(ARM_SUFFIX)}'s arm and box"
    return f"{_room_name(a)}-{_room_name(b)}"


def unmet_doors(spec: Spec, unmet: tuple[tuple[str, str, float], ...], rounds: int, moves: int,
                between: tuple[tuple[str, ...], ...] = (), options=None) -> Diagnostic:
    """I909: the doors the generator's closest arrangement left unmet (see I909's page);
    `between`, one per door of `unmet`: the rooms that lay between its two rooms there;
    `options` (the compile's): whether advice to enlarge the boundary would change anything."""
    a, b, _metres = unmet[0]
    span, label = _first_line_span(spec), "the door furthest from met"
    a, b = a.removesuffix(ARM_SUFFIX), b.removesuffix(ARM_SUFFIX)
    for adj in spec.adjacencies:
        if {adj.a, adj.b} == {a, b} and adj.span is not None:
            span = adj.span
            break
    if a == b:  # an L-room's arm and box: its room line
        label = "its arm and box do not join"
        for room in spec.rooms:
            if room.id == a and room.span is not None:
                span = room.span
    listed = ", ".join(f"{_door_name(x, y)} {metres:g} m" for x, y, metres in unmet[:UNMET_SHOWN])
    more = f" and {len(unmet) - UNMET_SHOWN} more" if len(unmet) > UNMET_SHOWN else ""
    total = sum(metres for _x, _y, metres in unmet)
    notes = [f"unmet (gap plus missing shared wall): {listed}{more}"]
    # the structure behind them: three rooms joined pairwise meet only around one point,
    # and a door in two such triangles has both ends of its wall pinned (measured on the
    # 80 room graphs of shared/graphs, bench/results/generation-graphs.txt: 7 of the 9 the
    # generator does not draw have two triangles of doors sharing a door, 21 of the 71 it draws)
    doors = spec.door_neighbours()
    for x, y, metres in unmet[:UNMET_SHOWN]:
        x, y = x.removesuffix(ARM_SUFFIX), y.removesuffix(ARM_SUFFIX)
        third = sorted(doors.get(x, set()) & doors.get(y, set()))
        if metres < 0.1 or not third or x == y:
            continue
        if len(third) == 1:
            notes.append(f"{x}-{y} closes a triangle of doors with {third[0]}: three rooms joined pairwise "
                         "can meet only around one point")
        else:
            notes.append(f"{x}-{y} closes triangles of doors with {' and '.join(third)}: both ends of the "
                         f"wall {x} and {y} share are pinned where three rooms meet")
    notes += _ring_notes(spec, unmet[:UNMET_SHOWN])
    notes += _rooms_between_notes(spec, unmet[:UNMET_SHOWN], between)
    return Diagnostic(
        code=I909,
        message=f"the generator's closest arrangement ({rounds} rounds, {moves:,} moves) left "
                f"{len(unmet)} door{'s' if len(unmet) != 1 else ''} unmet, {total:.1f} m in all",
        filename=spec.path,
        span=span,
        severity=Severity.INFO,
        label=label,
        notes=tuple(notes),
        help="these rooms are where the graph is hard to draw: wider size ranges for them, "
             + ("" if _boundary_grows(spec, options) else "a larger boundary or `--grow-boundary`, ")
             + "or another `--seed`",
    )


RINGS_HARD = 3
"""Rings of corridors from which a room graph is among those the generator draws least:
over six runs of the 80 room graphs of shared/graphs, those with at most 2 were drawn in 383
of 384 runs, with 3 in 43 of 60, with 4 or more in 10 of 36
(bench/experiments/results/corridor-cycles.txt)."""


def _ring_notes(spec: Spec, unmet: tuple[tuple[str, str, float], ...]) -> list[str]:
    """For each door of `unmet` between two corridor-like rooms that closes a ring of four
    corridors or more (a cycle of corridors and the doors between two of them; a ring of
    three is a triangle, which its own note names): the shortest such ring through it,
    since it must close round the rooms hung inside it. Then, when any unmet door lies on a
    ring and the corridors form RINGS_HARD independent rings or more, that the graph is
    among those the generator draws least."""
    skeleton = corridor_skeleton(spec)
    independent = rings(skeleton)
    notes = []
    on_a_ring = False
    for x, y, metres in unmet:
        x, y = x.removesuffix(ARM_SUFFIX), y.removesuffix(ARM_SUFFIX)
        if metres < 0.1 or x == y or not skeleton.has_edge(x, y):
            continue
        without = nx.restricted_view(skeleton, (), [(x, y)])
        if not nx.has_path(without, x, y):
            continue  # a bridge of the skeleton: on no ring
        on_a_ring = True
        # the shortest ring through the door that is not a triangle: a path from x to y
        # of three doors or more, with the rooms that close triangles with the door left out
        closing = set(without[x]) & set(without[y])
        try:
            ring = nx.shortest_path(nx.restricted_view(skeleton, closing, [(x, y)]), x, y)
        except nx.NetworkXNoPath:
            continue
        notes.append(f"{x}-{y} closes a ring of corridors ({', '.join(ring)}): the ring must close round "
                     "the rooms hung inside it")
    if on_a_ring and independent >= RINGS_HARD:
        notes.append(f"the corridors form {independent} independent rings (cycles of corridors joined by doors): room "
                     f"graphs with {RINGS_HARD} or more are the ones the generator draws least")
    return notes


def _rooms_between_notes(spec: Spec, unmet: tuple[tuple[str, str, float], ...],
                         between: tuple[tuple[str, ...], ...]) -> list[str]:
    """For each door of `unmet` with rooms between its two rooms in the closest arrangement:
    which rooms, and how long the one covering most of the gap is, since the door must reach
    round one of its ends (mostly a long corridor between two others joined by a door)."""
    from layoutdsl.layout.geometry import RoomSizes

    rooms = {room.id: room for room in spec.rooms}
    arms = {arm.room: arm for arm in spec.arms}
    notes = []
    for (x, y, metres), lying in zip(unmet, between):
        ends = (x.removesuffix(ARM_SUFFIX), y.removesuffix(ARM_SUFFIX))
        if metres < 0.1 or not lying or ends[0] == ends[1]:
            continue
        names = [name for name in dict.fromkeys(room_id.removesuffix(ARM_SUFFIX) for room_id in lying)
                 if name not in ends]
        if not names:
            continue
        first = rooms.get(names[0])
        measure = ""
        if first is not None:
            arm = arms.get(first.id)
            measure = (f"is an L, its box {RoomSizes.of(first).target_long:.1f} m and its arm "
                       f"{max(arm.target_w, arm.target_h):.1f} m long" if arm is not None else
                       f"is {RoomSizes.of(first).target_long:.1f} m long")
        shown = ", ".join(names[:UNMET_SHOWN]) + (f" and {len(names) - UNMET_SHOWN} more"
                                                   if len(names) > UNMET_SHOWN else "")
        if len(names) == 1:
            line = f"{_door_name(x, y)}: {shown} lay between them, so the door must reach round one of its ends"
            line += f"; {names[0]} {measure}" if measure else ""
        else:
            line = f"{_door_name(x, y)}: {shown} lay between them, so the door must reach round them"
            line += f"; {names[0]}, covering most of the gap, {measure}" if measure else ""
        notes.append(line)
    return notes


I911 = register(
    "I911",
    Severity.INFO,
    "four-joined-pairwise-not-placed",
    "Accompanies E902 when the generator found no layout for a room graph with four rooms "
    "joined pairwise (a K4) one of which is L-shaped: names the four and their L-rooms, at "
    "the first of their adjacency lines.",
    "Four rooms joined pairwise draw only one way: three meet around a point and an L wraps "
    "two of them, its arm reaching the third's far side. With corridors round them, few "
    "arrangements of the whole building have that shape, and the generator's work limits "
    "ran out before it reached one. Another `--seed` draws other arrangements; an `arms` "
    "line for a second of the four gives the search more shapes that fit; removing one of "
    "their six adjacencies makes them drawable with rectangles.",
    "# compile: C0 drawn as an L-shaped room (four rooms joined pairwise ...)\n"
    "# error[E902]: no layout found within the generator's work limits (8 rounds, ...)\n"
    "# info[I911]: rooms C0, C1, C2, C4 are joined pairwise: with C0 L-shaped they draw only as "
    "three around a point and C0 wrapping two of them, and the generator's arrangements did not "
    "reach it",
)


I910 = register(
    "I910",
    Severity.INFO,
    "closest-arrangement-outside",
    "Accompanies E902 when the generator found no layout and its closest arrangement left a "
    "room that must open to the outside (`onB`) inside the building, or stuck out of the "
    "boundary the spec gives: names those rooms, worst first, at the first one's `onB`, or "
    "the overhang at the boundary line, and how much of the boundary the rooms fill.",
    "A new arrangement of the rooms needs space a packed original may not have had: walls "
    "between rooms that were not neighbours, and voids where rooms do not line up. A "
    "boundary the rooms fill almost entirely (an imported office often fills 90 % of its "
    "bounding box) leaves no arrangement but the original's, and an entrance that must reach "
    "the outside through such a boundary is the first thing to give. `--grow-boundary` lets "
    "the boundary grow (compile reports by how much); `import --keep-arrangement` keeps the "
    "original arrangement.",
    "# compile: no layout within the limit\n# note: the closest arrangement stuck out of the "
    "boundary by 3.1 m along x; the rooms' target area fills 95 % of the boundary",
)


def outside_shortfall(spec: Spec, away: tuple[tuple[str, float], ...], overflow: tuple[float, float],
                      rounds: int, moves: int) -> Diagnostic:
    """I910: what kept the generator's closest arrangement from the outside (see I910's page)."""
    parts, notes = [], []
    span, label = _first_line_span(spec), "the rooms do not fit this boundary"
    rooms = {room.id: room for room in spec.rooms}
    if away:
        parts.append(f"left {len(away)} room{'s' if len(away) != 1 else ''} that must open to the outside "
                     "(onB) inside the building")
        notes.append("inside (metres from the outside): " + ", ".join(
            f"{_room_name(room_id)} {metres:g} m" for room_id, metres in away[:UNMET_SHOWN])
            + (f" and {len(away) - UNMET_SHOWN} more" if len(away) > UNMET_SHOWN else ""))
        first = rooms.get(away[0][0].removesuffix(ARM_SUFFIX))
        if first is not None and first.span is not None:
            span, label = first.spans.get("on_boundary", first.span), "must open to the outside"
    stuck_out = overflow[0] > 0 or overflow[1] > 0
    if stuck_out:
        along = " and ".join(f"{metres:g} m along {axis}" for axis, metres in zip("xy", overflow) if metres > 0)
        parts.append(f"stuck out of the boundary by {along}")
    boundary = spec.boundary
    if stuck_out and boundary is not None and boundary.w * boundary.h > 0:
        # why it stuck out: a boundary the rooms all but fill has room for one arrangement
        target = sum(room.target_w * room.target_h for room in spec.rooms)
        notes.append(f"the rooms' target area fills {100 * target / (boundary.w * boundary.h):.0f} % of the "
                     f"{boundary.w:g} x {boundary.h:g} boundary; a new arrangement needs walls and voids "
                     "an original packing may not have")
    return Diagnostic(
        code=I910,
        message=f"the generator's closest arrangement ({rounds} rounds, {moves:,} moves) " + " and ".join(parts),
        filename=spec.path,
        span=span,
        severity=Severity.INFO,
        label=label,
        notes=tuple(notes),
        help=("`--grow-boundary` lets the boundary grow (compile reports by how much); for an imported "
              "plan, `layoutdsl import --keep-arrangement` keeps the original's arrangement"
              if stuck_out else
              "a room that opens to the outside needs a wall free of doors: fewer doors, wider size "
              "ranges for it, or `onB` dropped; another `--seed` draws other arrangements"),
    )


def verification_failed(spec: Spec, violations) -> Diagnostic:
    """E903: the solved layout broke hard constraints; lists the violations."""
    notes = tuple(v.message for v in violations[:20])
    if len(violations) > 20:
        notes += (f"... and {len(violations) - 20} more",)
    return Diagnostic(
        code=E903,
        message=f"the solved layout failed verification ({len(violations)} violation"
        f"{'s' if len(violations) != 1 else ''}); nothing was written",
        filename=spec.path,
        span=_first_line_span(spec),
        label="layout for this spec",
        help=("the arrangement's relations allow neither a wall nor a usable space there; another "
              "`--seed` gives another arrangement" if all(v.rule == "sliver" for v in violations)
              else "this is a bug or a solver tolerance problem in layoutdsl; please report it with the spec"),
        notes=notes,
    )


def infeasible_without_explanation(spec: Spec, *, searched: bool = False) -> Diagnostic:
    """E904: proven infeasible, but no small conflicting set was isolated (or none was sought)."""
    if searched:
        hint = "a longer `--time-limit` gives the compiler time to isolate the conflicting lines"
    else:
        hint = "run without `--no-explain` to find the conflicting lines"
    return Diagnostic(
        code=E904,
        message="no layout satisfies every hard constraint of this spec",
        filename=spec.path,
        span=_first_line_span(spec),
        label="the rooms do not fit this boundary with these constraints",
        help=f"try a larger boundary or wider size ranges; {hint}",
    )


# ----- groups: one spec line each, and how to drop it -----

@dataclass(frozen=True, slots=True)
class Group:
    """One spec line that constrains the geometry, and the spec without its constraint."""

    kind: str
    """'adjacency', 'position', 'connection', 'cluster', 'obstacle', 'onB', 'size'."""
    key: object
    span: Span | None
    rooms: tuple[str, ...]
    describe: str


def constraint_groups(spec: Spec) -> list[Group]:
    """Every droppable constraint line of the spec, in a fixed order."""
    groups: list[Group] = []
    for index, adj in enumerate(spec.adjacencies):
        need = adj.door / spec.settings.door_utilization
        groups.append(Group("adjacency", index, adj.span, (adj.a, adj.b),
                            f"rooms `{adj.a}` and `{adj.b}` must share {need:g} m of wall"))
    for index, pos in enumerate(spec.positions):
        groups.append(Group("position", index, pos.span, (pos.room,),
                            f"room `{pos.room}` must cover the point ({pos.x:g}, {pos.y:g})"))
    for index, con in enumerate(spec.connections):
        groups.append(Group("connection", index, con.span, (con.room,),
                            f"room `{con.room}` must cover ({con.x1:g}, {con.y1:g}) and ({con.x2:g}, {con.y2:g})"))
    for index, cl in enumerate(spec.clusters):
        members = tuple(m.room for m in cl.members)
        groups.append(Group("cluster", index, cl.span, members,
                            f"cluster `{cl.id}` keeps {', '.join(f'`{m}`' for m in members)} in place"))
    if spec.boundary is not None:
        for index, ob in enumerate(spec.boundary.obstacles):
            groups.append(Group("obstacle", index, ob.span, (),
                                f"obstacle `{ob.id}` blocks {ob.w:g} x {ob.h:g} m at ({ob.x:g}, {ob.y:g})"))
    for room in spec.rooms:
        if room.on_boundary:
            span = room.spans.get("on_boundary", room.span)
            groups.append(Group("onB", room.id, span, (room.id,),
                                f"room `{room.id}` must touch the boundary"))
    for room in spec.rooms:
        groups.append(Group("size", room.id, room.span, (room.id,), _size_text(room)))
    return groups


def _size_text(room: Room) -> str:
    text = (f"room `{room.id}` is between {room.min_w:g} x {room.min_h:g} and "
            f"{room.max_w:g} x {room.max_h:g} m")
    if not room.is_corridor:
        text += f", aspect ratio {room.min_ar:g} to {room.max_ar:g}"
    return text


def _relaxed_room(room: Room, spec: Spec) -> Room:
    """The room with its size bounds and aspect ratio dropped (any size inside the boundary)."""
    assert spec.boundary is not None
    largest = max(spec.boundary.w, spec.boundary.h)
    return replace(room, min_w=0.0, min_h=0.0, max_w=largest, max_h=largest,
                   target_w=min(room.target_w, largest), target_h=min(room.target_h, largest),
                   rtype="C")  # corridors carry no aspect-ratio constraint (5.6)


def spec_without(spec: Spec, dropped: set[tuple[str, object]]) -> Spec:
    """The spec with the constraints of the dropped groups removed."""
    def keep(kind: str, key: object) -> bool:
        return (kind, key) not in dropped

    rooms = []
    for room in spec.rooms:
        if not keep("size", room.id):
            room = _relaxed_room(room, spec)
        if not keep("onB", room.id):
            room = replace(room, on_boundary=False)
        rooms.append(room)
    boundary = spec.boundary
    if boundary is not None:
        boundary = replace(boundary, obstacles=tuple(
            ob for i, ob in enumerate(boundary.obstacles) if keep("obstacle", i)))
    return replace(
        spec,
        rooms=tuple(rooms),
        boundary=boundary,
        adjacencies=tuple(a for i, a in enumerate(spec.adjacencies) if keep("adjacency", i)),
        positions=tuple(p for i, p in enumerate(spec.positions) if keep("position", i)),
        connections=tuple(c for i, c in enumerate(spec.connections) if keep("connection", i)),
        clusters=tuple(c for i, c in enumerate(spec.clusters) if keep("cluster", i)),
    )


FeasibilityTest = Callable[[Spec, float], "bool | None"]
"""test(spec, seconds) -> True feasible, False proven infeasible, None unknown (time out)."""


def scip_feasibility(spec: Spec, seconds: float, *, seed: int = 0) -> bool | None:
    """Feasibility-only SCIP solve (objective dropped, stop at the first layout)."""
    from layoutdsl.model import build_model
    from layoutdsl.solve import SolveOptions, solve

    model = build_model(spec)
    outcome = solve(model, SolveOptions(time_limit=seconds, seed=seed, emphasis="feasibility", quiet=True),
                    feasibility_only=True)
    if outcome.has_solution:
        return True
    if outcome.status == "infeasible":
        return False
    return None


def feasibility(spec: Spec, seconds: float, *, seed: int = 0) -> bool | None:
    """SCIP for a third of the time (it proves most conflicts infeasible in presolve), then the
    generator (layoutdsl.compile.generator) for the rest, since SCIP alone often finds no
    layout of ten rooms or more in seconds even when one exists."""
    began = time.monotonic()
    result = scip_feasibility(spec, seconds / 3, seed=seed)
    if result is not None:
        return result
    from layoutdsl.compile.generator import generate

    left = seconds - (time.monotonic() - began)
    if left <= 0.1:
        return None
    generated = generate(spec, seed=seed, deadline=time.monotonic() + left)
    rects, spec = generated.rects, generated.spec
    if rects is None:
        return None
    from layoutdsl.layout.geometry import layout_from_rects
    from layoutdsl.layout.verify import verify

    # only a layout the independent verifier accepts proves feasibility
    return True if not verify(spec, layout_from_rects(spec, rects)) else None


def conflicting_groups(spec: Spec, *, deadline: float, test: FeasibilityTest | None = None,
                       per_test_seconds: float = 3.0) -> list[Group] | None:
    """A small set of groups that conflict (deletion filter), or None if out of time.

    Assumes `spec` is infeasible. Groups are tried in order: lines first, then room sizes,
    so a conflict is blamed on the lines a person wrote rather than on size bounds when both
    would explain it.
    """
    test = test or feasibility
    groups = constraint_groups(spec)
    dropped: set[tuple[str, object]] = set()
    kept: list[Group] = []
    for group in groups:
        left = deadline - time.monotonic()
        if left <= 0.2:
            return None
        trial = dropped | {(group.kind, group.key)}
        result = test(spec_without(spec, trial), min(per_test_seconds, left))
        if result is False:
            dropped = trial  # still infeasible without it: not needed for the conflict
        else:
            kept.append(group)
    return kept


def explain_infeasibility(spec: Spec, options, *, test: FeasibilityTest | None = None) -> list[Diagnostic]:
    """E901 per conflicting line (deletion filter within options.time_limit), else one E904."""
    budget = max(5.0, options.time_limit)
    deadline = time.monotonic() + budget
    groups = conflicting_groups(spec, deadline=deadline, test=test)
    if not groups:
        return [infeasible_without_explanation(spec, searched=True)]
    assert spec.boundary is not None
    setting = (f"inside the {spec.boundary.w:g} x {spec.boundary.h:g} m boundary, rooms "
               f"{spec.settings.walldim:g} m (one wall) apart")
    others = {g: [o for o in groups if o is not g] for g in groups}
    diagnostics = []
    for group in groups:
        partners = "; ".join(o.describe for o in others[group][:4])
        if len(others[group]) > 4:
            partners += f"; and {len(others[group]) - 4} more"
        diagnostics.append(Diagnostic(
            code=E901,
            message=f"{group.describe}, which conflicts with {len(others[group])} other line"
            f"{'s' if len(others[group]) != 1 else ''}",
            filename=spec.path,
            span=_span(group.span),
            label="part of a conflict",
            help=_help_for(group),
            notes=((f"conflicts with: {partners}",) if partners else ()) + (setting,),
        ))
    return diagnostics


def _help_for(group: Group) -> str:
    return {
        "adjacency": "remove this adjacency or move the rooms' positions closer together",
        "position": "move this point, or drop it so the room can move",
        "connection": "move these points, or drop the connection",
        "cluster": "enlarge `cluster_margin` or move the cluster's points",
        "obstacle": "move or shrink the obstacle",
        "onB": "drop `onB` from this room",
        "size": "widen this room's size bounds or aspect-ratio range",
    }[group.kind]
