"""Rectangular duals of room graphs: a regular edge labeling found by SCIP, then sized.

Tried for issue 40 as the generator's first stage (Koźmiński & Kinnen 1985, Kant & He 1997:
a plane triangulation with four poles and no separating triangle has a rectangular dual,
read off a regular edge labeling). The steps, each measured by `main` below:

1. embed the room graph with one vertex OUT joined to every entrance (networkx), clearing
   each triangle of doors of what hangs inside it; rooms with one door go back into their
   corridor's face on the outside;
2. triangulate by ears (chords that close no separating triangle; chords to OUT first),
   with a filler cell where a room would get more neighbours than its doors + SPARE_CONTACTS;
3. replace OUT by four poles; find a labeling with a feasibility MIP written from the
   definition (transition rule per corner, one block per label), with soft capacities:
   the rooms along each side of a room must fit along it, each turned either way;
4. tile (LP): every labelled edge a shared wall, the outline a rectangle (found for every
   labeling);
5. size (LP): each room within its bounds, doors shared walls, the labeling's other
   relations kept with gaps allowed, rooms that come to overlap related as in the tiling.

Measured on the 80 room graphs of ../shared/graphs, 3 seeds each (the command below;
bench/experiments/results/rectangular-dual.txt): steps 1-4 give a tiling in 218 of 240
tries, mostly in well under a second, and the tiling meets every door (the 4 graphs with
four rooms joined pairwise have none, as they must not). Sized within bounds: 14 of 240.
Step 5 fails because a labeling fixes whole rows and columns (a corridor with a door at each end spans whatever stack of rooms the labeling
put beside it), and the rooms' upper and lower bounds together cannot meet that; the
labeling's local capacities do not see it. Handing the tiling to the generator's sizing
stage (solve.relations.repair) or to the annealer as its first state did not help either
(cml_new_130: no sizing in 20 s; the annealer took as long as from a spring embedding).
What would: searching over labelings with the sizes in the loop, which is the floorplanning
problem the annealer already searches.

    PYTHONPATH=bench .venv/bin/python bench/experiments/rectangular_dual.py ../shared/graphs
"""

from __future__ import annotations

import math
import random
import sys
import time
from collections.abc import Hashable, Mapping, Sequence
from pathlib import Path

import networkx as nx

from layoutdsl.layout.geometry import Rect, RoomSizes
from layoutdsl.solve.quiet import native_output_silenced
from layoutdsl.syntax.ast import Spec

LABELS = ("N", "E", "S", "W")
"""A vertex's view of an edge, clockwise: red out, blue out, red in, blue in."""

LABELING_NODES = 2000
"""Branch-and-bound nodes the labeling MIP may use (measured: the root suffices)."""


OVERFILL_WEIGHT = 100.0
"""Objective per metre a labeling overfills a room's wall (the draw adds at most 1 an edge)."""


def _quiet_model(name: str, seed: int, seconds: float, nodes: int):
    from pyscipopt import Model

    model = Model(name)
    model.hideOutput()
    model.setParam("display/verblevel", 0)
    model.setParam("limits/time", max(0.05, seconds))
    model.setParam("limits/nodes", max(1, nodes))
    model.setParam("randomization/randomseedshift", seed % 2**31)
    model.setParam("parallel/maxnthreads", 1)
    return model


def _add(model, constraint) -> bool:
    """Add a constraint; one between constants (two pole edges) is checked instead. False:
    it does not hold, so no labeling does."""
    if isinstance(constraint, bool):
        return constraint
    model.addCons(constraint)
    return True


def regular_edge_labeling(
    rotation: Mapping[Hashable, Sequence[Hashable]], poles: tuple[Hashable, Hashable, Hashable, Hashable],
    seed: int, seconds: float = 30.0, nodes: int = LABELING_NODES,
    sides: Mapping[Hashable, tuple[float, float]] | None = None,
    footprints: Mapping[tuple[Hashable, Hashable], float] | None = None, overhang: float = 0.0,
) -> tuple[dict[tuple[Hashable, Hashable], str], dict[Hashable, bool]] | None:
    """({(tail, head): 'red' | 'blue'} for every edge with an inner endpoint, {vertex: its
    long side lies along x} for the vertices in `sides`), or None when SCIP finds no
    labeling within its limits. `rotation`: each inner vertex's neighbours in clockwise
    order (poles included); `poles`: (N, E, S, W).

    `sides[v]` = (longest, shortest) side v may have, `footprints[(v, u)]` = the length of
    v's wall that u takes at least, (turned short side on, long side on): the neighbours on
    each side of v must fit along
    it (its two end ones may stick out by `overhang`), with v turned either way. This keeps
    a labeling from hanging ten classrooms off one side of a short corridor."""
    north, east, south, west = poles
    pole_set = set(poles)
    inner = [v for v in rotation if v not in pole_set]
    order = {v: i for i, v in enumerate(inner)}
    model = _quiet_model("labeling", seed, seconds, nodes)
    draw = random.Random(f"labeling:{seed}")
    # per inner edge {u, v} (u before v in `order`): its four labels from u's side
    edge_vars: dict[tuple[Hashable, Hashable], dict[str, object]] = {}
    objective = 0
    for u in inner:
        for v in rotation[u]:
            if v in pole_set or order[v] < order[u]:
                continue
            labels = {a: model.addVar(vtype="B", name=f"l_{order[u]}_{order[v]}_{a}") for a in LABELS}
            model.addCons(sum(labels.values()) == 1)
            edge_vars[(u, v)] = labels
            for a in LABELS:
                objective += draw.random() * labels[a]
    opposite = {"N": "S", "S": "N", "E": "W", "W": "E"}

    def seen(v, u):
        """v's view of the edge to u: a dict label -> expression (0/1)."""
        if u in pole_set:
            fixed = {north: "N", east: "E", south: "S", west: "W"}[u]
            return {a: (1 if a == fixed else 0) for a in LABELS}
        if (v, u) in edge_vars:
            return edge_vars[(v, u)]
        labels = edge_vars[(u, v)]
        return {a: labels[opposite[a]] for a in LABELS}

    previous = {"N": "W", "E": "N", "S": "E", "W": "S"}
    for v in inner:
        around = [seen(v, u) for u in rotation[v]]
        d = len(around)
        for a in LABELS:
            if not _add(model, sum(around[i][a] for i in range(d)) >= 1):
                return None
            starts = []
            for i in range(d):
                here, before = around[i], around[i - 1]
                # clockwise, a label follows itself or the one before it in LABELS' cycle
                if not _add(model, here[a] <= before[a] + before[previous[a]]):
                    return None
                start = model.addVar(vtype="C", lb=0.0, ub=1.0, name=f"s_{order[v]}_{i}_{a}")
                model.addCons(start >= here[a] - before[a])
                starts.append(start)
            # ... and each label is one block: the four blocks go round once
            model.addCons(sum(starts) <= 1)
    long_x: dict[Hashable, object] = {}
    overfill: list = []
    for v in (sides or {}):
        if v in order:
            long_x[v] = model.addVar(vtype="B", name=f"o_{order[v]}")
    for v, (longest, shortest) in (sides or {}).items():
        if v not in order:
            continue
        # (neighbour, its footprint on v's wall turned short side on, long side on)
        beside = [(u, *footprints[(v, u)]) for u in rotation[v]
                  if footprints is not None and (v, u) in footprints and u in long_x]
        if not beside:
            continue
        turned = long_x[v]
        for a in LABELS:
            along_x = a in ("N", "S")  # rooms above and below v sit along its width
            room_on_side = (longest * turned + shortest * (1 - turned)) if along_x else \
                (shortest * turned + longest * (1 - turned))
            used = 0
            for u, short_on, long_on in beside:
                on_side = seen(v, u)[a]
                if isinstance(on_side, int):
                    continue
                # u shows v its long side when it lies along v's side: z = on_side and that
                lengthwise = model.addVar(lb=0.0, ub=1.0, name=f"z_{order[v]}_{order[u]}_{a}")
                model.addCons(lengthwise >= on_side + (long_x[u] if along_x else 1 - long_x[u]) - 1)
                used += short_on * on_side + (long_on - short_on) * lengthwise
            if isinstance(used, (int, float)):
                continue
            # soft: a labeling that overfills a wall still beats none (the sizing may
            # find room), but every metre of it costs more than any choice of the draw
            excess = model.addVar(lb=0.0, name=f"excess_{order[v]}_{a}")
            model.addCons(used <= room_on_side + overhang + excess)
            overfill.append(excess)
    model.setObjective(objective + OVERFILL_WEIGHT * sum(overfill), "minimize")
    with native_output_silenced():
        model.optimize()
    if model.getNSols() == 0:
        return None
    solution = model.getBestSol()
    orientation = {v: solution[var] > 0.5 for v, var in long_x.items()}
    labeling: dict[tuple[Hashable, Hashable], str] = {}
    for (u, v), labels in edge_vars.items():
        chosen = max(LABELS, key=lambda a: solution[labels[a]])
        # u's view: N = u -> v red, E = u -> v blue, S = v -> u red, W = v -> u blue
        if chosen == "N":
            labeling[(u, v)] = "red"
        elif chosen == "E":
            labeling[(u, v)] = "blue"
        elif chosen == "S":
            labeling[(v, u)] = "red"
        else:
            labeling[(v, u)] = "blue"
    for v in inner:
        for u in rotation[v]:
            if u == north:
                labeling[(v, u)] = "red"
            elif u == south:
                labeling[(u, v)] = "red"
            elif u == east:
                labeling[(v, u)] = "blue"
            elif u == west:
                labeling[(u, v)] = "blue"
    return labeling, orientation


def tiling(
    vertices: Sequence[Hashable], labeling: Mapping[tuple[Hashable, Hashable], str],
    poles: tuple[Hashable, Hashable, Hashable, Hashable], targets: Mapping[Hashable, tuple[float, float]],
    overlap: Mapping[frozenset, float], wall: float, collapse: frozenset = frozenset(),
    outline: tuple[float, float] | None = None, seed: int = 0, seconds: float = 30.0,
    lower: Mapping[Hashable, tuple[float, float]] | None = None,
) -> dict[Hashable, tuple[float, float, float, float]] | None:
    """(x, y, w, h) of every vertex realising `labeling` as a tiling of a rectangle, one wall
    between rooms, each side pulled to its target (w, h) in `targets`; vertices in
    `collapse` (fillers) are pulled to nothing. `overlap[{u, v}]`: the shared wall an edge
    needs; `outline`: (width, height) the tiling may not exceed; `lower[v]`: the least
    (w, h) of v (a room squeezed below its least size in the tiling would leave its
    neighbours relations that no size within bounds meets). None when SCIP finds no solution (the labeling is not regular)."""
    north, east, south, west = poles
    pole_set = set(poles)
    model = _quiet_model("tiling", seed, seconds, 1)
    index = {v: i for i, v in enumerate(vertices)}
    x, y, w, h = {}, {}, {}, {}
    width = model.addVar(lb=0.0, name="width")
    height = model.addVar(lb=0.0, name="height")
    if outline is not None:
        model.addCons(width <= outline[0])
        model.addCons(height <= outline[1])
    objective = 0
    for v in vertices:
        i = index[v]
        x[v] = model.addVar(lb=0.0, name=f"x{i}")
        y[v] = model.addVar(lb=0.0, name=f"y{i}")
        least = (lower or {}).get(v, (0.0, 0.0))
        w[v] = model.addVar(lb=least[0], name=f"w{i}")
        h[v] = model.addVar(lb=least[1], name=f"h{i}")
        model.addCons(x[v] + w[v] <= width)
        model.addCons(y[v] + h[v] <= height)
        if v in collapse:
            objective += 0.5 * (w[v] + h[v])
            continue
        for side, target in ((w[v], targets[v][0]), (h[v], targets[v][1])):
            over = model.addVar(lb=0.0, name=f"o{i}")
            under = model.addVar(lb=0.0, name=f"u{i}")
            model.addCons(side - target == over - under)
            # a side too short costs more than one too long: stretched rooms fill a tiling
            objective += over + 2.0 * under
    for (u, v), colour in labeling.items():
        if u in pole_set and v in pole_set:
            continue
        # the outline is a rectangle: the rooms along it reach it
        if u == west:
            model.addCons(x[v] == 0)
        elif v == east:
            model.addCons(x[u] + w[u] == width)
        elif u == south:
            model.addCons(y[v] == 0)
        elif v == north:
            model.addCons(y[u] + h[u] == height)
        if west == u or v == east or u == south or v == north:
            continue
        need = overlap.get(frozenset((u, v)), 0.0)
        if colour == "blue":
            model.addCons(x[u] + w[u] + wall == x[v])
            model.addCons(y[u] + h[u] - y[v] >= need)
            model.addCons(y[v] + h[v] - y[u] >= need)
            model.addCons(h[u] >= need)
            model.addCons(h[v] >= need)
        else:
            model.addCons(y[u] + h[u] + wall == y[v])
            model.addCons(x[u] + w[u] - x[v] >= need)
            model.addCons(x[v] + w[v] - x[u] >= need)
            model.addCons(w[u] >= need)
            model.addCons(w[v] >= need)
    return _solved(model, objective, vertices, (x, y, w, h))


def _solved(model, objective, vertices, boxes):
    """(x, y, w, h) of each vertex at the LP's optimum, or None without a solution."""
    model.setObjective(objective, "minimize")
    with native_output_silenced():
        model.optimize()
    if model.getNSols() == 0:
        return None
    solution = model.getBestSol()
    x, y, w, h = boxes
    return {v: (solution[x[v]], solution[y[v]], solution[w[v]], solution[h[v]]) for v in vertices}


LAZY_ROUNDS = 12
"""Rounds of the sized drawing's relation loop (measured: 1-4 suffice)."""


def sized_drawing(
    vertices: Sequence[Hashable], labeling: Mapping[tuple[Hashable, Hashable], str],
    poles: tuple[Hashable, Hashable, Hashable, Hashable], doors: Mapping[frozenset, float],
    targets: Mapping[Hashable, tuple[float, float]],
    bounds: Mapping[Hashable, tuple[float, float, float, float]], tiled: Mapping[Hashable, tuple],
    wall: float, outline: tuple[float, float] | None = None, seed: int = 0, seconds: float = 30.0,
) -> dict[Hashable, tuple[float, float, float, float]] | None:
    """(x, y, w, h) of the rooms (the vertices in `bounds`) within their bounds, realising the
    labeling's relations: the two rooms of a door share a wall at least `doors[{u, v}]` long,
    every other labelled pair keeps its side of the other (u left of, or below, v) with a
    gap the objective closes where the sizes allow. Fillers (vertices without bounds) carry
    relations only. Rooms no relation keeps apart that come to overlap get the relation of
    `tiled` (the labeling's rectangular tiling), and the LP is solved again. None: no such
    drawing (the sizes do not fit this labeling)."""
    pole_set = set(poles)
    rooms = [v for v in vertices if v in bounds]
    kept: list[tuple[Hashable, Hashable, str]] = []
    for (u, v), colour in labeling.items():
        if u in pole_set or v in pole_set:
            continue
        kept.append((u, v, "left" if colour == "blue" else "below"))
    for _round in range(LAZY_ROUNDS):
        drawn = _drawing(vertices, kept, doors, targets, bounds, wall, outline, seed, seconds)
        if drawn is None:
            return None
        added = 0
        for i, a in enumerate(rooms):
            ax, ay, aw, ah = drawn[a]
            for b in rooms[i + 1:]:
                bx, by, bw, bh = drawn[b]
                if min(ax + aw, bx + bw) - max(ax, bx) > -wall + 1e-6 and \
                        min(ay + ah, by + bh) - max(ay, by) > -wall + 1e-6:
                    kept.append(_relation(a, b, tiled))
                    added += 1
        if not added:
            return {v: drawn[v] for v in rooms}
    return None


def _relation(a, b, tiled) -> tuple[Hashable, Hashable, str]:
    """The side a lies of b in the tiling: along the axis they are further apart on."""
    ax, ay, aw, ah = tiled[a]
    bx, by, bw, bh = tiled[b]
    sep_x = max(bx - (ax + aw), ax - (bx + bw))
    sep_y = max(by - (ay + ah), ay - (by + bh))
    if sep_x >= sep_y:
        return (a, b, "left") if ax < bx else (b, a, "left")
    return (a, b, "below") if ay < by else (b, a, "below")


def _drawing(vertices, kept, doors, targets, bounds, wall, outline, seed, seconds):
    model = _quiet_model("sized drawing", seed, seconds, 1)
    index = {v: i for i, v in enumerate(vertices)}
    x, y, w, h = {}, {}, {}, {}
    width = model.addVar(lb=0.0, name="width")
    height = model.addVar(lb=0.0, name="height")
    if outline is not None:
        model.addCons(width <= outline[0])
        model.addCons(height <= outline[1])
    objective = COMPACTNESS * (width + height)
    for v in vertices:
        i = index[v]
        x[v] = model.addVar(lb=0.0, name=f"x{i}")
        y[v] = model.addVar(lb=0.0, name=f"y{i}")
        if v in bounds:
            w_lo, w_hi, h_lo, h_hi = bounds[v]
            w[v] = model.addVar(lb=w_lo, ub=w_hi, name=f"w{i}")
            h[v] = model.addVar(lb=h_lo, ub=h_hi, name=f"h{i}")
            for side, target in ((w[v], targets[v][0]), (h[v], targets[v][1])):
                over = model.addVar(lb=0.0, name=f"o{i}")
                under = model.addVar(lb=0.0, name=f"u{i}")
                model.addCons(side - target == over - under)
                objective += over + under
        else:
            w[v] = model.addVar(lb=0.0, name=f"w{i}")
            h[v] = model.addVar(lb=0.0, name=f"h{i}")
        model.addCons(x[v] + w[v] <= width)
        model.addCons(y[v] + h[v] <= height)
    seen = set()
    for u, v, relation in kept:
        if (u, v, relation) in seen:
            continue
        seen.add((u, v, relation))
        along, size, across, span = (x, w, y, h) if relation == "left" else (y, h, x, w)
        need = doors.get(frozenset((u, v)))
        gap = wall if (u in bounds and v in bounds) else 0.0
        if need is None:
            model.addCons(along[u] + size[u] + gap <= along[v])
            if u in bounds and v in bounds:
                # a wall between rooms rather than a sliver of space: gaps cost
                slack = model.addVar(lb=0.0, name=f"g{index[u]}_{index[v]}")
                model.addCons(along[v] - along[u] - size[u] - gap <= slack)
                objective += GAP_WEIGHT * slack
        else:
            model.addCons(along[u] + size[u] + gap == along[v])
            model.addCons(across[u] + span[u] - across[v] >= need)
            model.addCons(across[v] + span[v] - across[u] >= need)
    return _solved(model, objective, vertices, (x, y, w, h))


COMPACTNESS = 0.05
"""Objective per metre of the drawing's width and height."""

GAP_WEIGHT = 0.2
"""Objective per metre between two neighbours of the labeling that share no door."""


from collections.abc import Hashable


from layoutdsl.layout.geometry import Rect
from layoutdsl.layout.geometry import RoomSizes
from layoutdsl.syntax.ast import Spec

OUT = ("outside",)
"""The vertex that stands for the outside while the graph is embedded and triangulated."""

SPARE_CONTACTS = 2
"""Neighbours beyond its doors a room may get from the triangulation's chords; the rest of
its faces are closed by fillers, which the sizing may shrink away."""

HUB_DOORS = 3
"""Doors from which a room is a hub whose walls the triangulation spares (_chord_rank)."""

POLES = (("pole", "N"), ("pole", "E"), ("pole", "S"), ("pole", "W"))

MAX_FILLERS_PER_ROOM = 1.0
"""Fillers (empty cells) a triangulation may add per room before the dual is given up."""

NON_DOOR_OVERLAP = 0.5
"""Metres two rooms that touch in the dual but share no door overlap in the tiling: enough
that the sizing stage reads them as neighbours across one wall, not corner to corner."""


class _Plane:
    """A plane graph as a rotation system: each vertex's neighbours in clockwise order.
    Faces are traced by next(u -> v) = (v, the neighbour after u clockwise round v)."""

    def __init__(self, rotation: dict[Hashable, list[Hashable]]):
        self.rotation = rotation
        self.adjacent = {v: set(ns) for v, ns in rotation.items()}

    def after(self, v, u):
        ring = self.rotation[v]
        return ring[(ring.index(u) + 1) % len(ring)]

    def faces(self) -> list[list[Hashable]]:
        seen: set[tuple[Hashable, Hashable]] = set()
        faces = []
        for u in self.rotation:
            for v in self.rotation[u]:
                if (u, v) in seen:
                    continue
                walk = []
                a, b = u, v
                while (a, b) not in seen:
                    seen.add((a, b))
                    walk.append(a)
                    a, b = b, self.after(b, a)
                faces.append(walk)
        return faces

    def face_at(self, v, u) -> list[Hashable]:
        """The face that holds the corner of v right after neighbour u (clockwise)."""
        walk = [u]
        a, b = v, self.after(v, u)
        start = (u, v)
        a, b = u, v
        walk = []
        while True:
            walk.append(a)
            a, b = b, self.after(b, a)
            if (a, b) == start:
                return walk

    def insert(self, v, new, after_neighbour) -> None:
        """`new` into v's ring right after `after_neighbour` (into the face at that corner)."""
        ring = self.rotation[v]
        ring.insert(ring.index(after_neighbour) + 1, new)
        self.adjacent[v].add(new)

    def add_chord(self, face: list[Hashable], i: int, j: int) -> None:
        """An edge from face corner i to corner j, drawn inside the face."""
        k = len(face)
        a, c = face[i], face[j]
        self.insert(a, c, face[(i - 1) % k])
        self.insert(c, a, face[(j - 1) % k])

    def add_filler(self, face: list[Hashable], corners: list[int], filler: Hashable) -> None:
        k = len(face)
        for i in corners:
            self.insert(face[i], filler, face[(i - 1) % k])
        self.rotation[filler] = [face[i] for i in reversed(corners)]
        self.adjacent[filler] = set(self.rotation[filler])


def _ear_allowed(plane: _Plane, face: list[Hashable], i: int) -> bool:
    """Whether the chord face[i-1] - face[i+1] closes a face without a separating triangle."""
    k = len(face)
    a, b, c = face[(i - 1) % k], face[i], face[(i + 1) % k]
    if a == c or c in plane.adjacent[a]:
        return False
    allowed = {b}
    if k == 4:
        allowed.add(face[(i + 2) % k])
    return not ((plane.adjacent[a] & plane.adjacent[c]) - allowed)


def _filler_corners(plane: _Plane, face: list[Hashable]) -> list[int]:
    """Corners of a face a filler may join without closing a separating triangle: distinct
    rooms, no two of them neighbours unless they follow each other on the face."""
    chosen: list[int] = []
    k = len(face)
    for i, v in enumerate(face):
        if any(face[j] == v for j in chosen):
            continue
        # consecutive on the face: i - 1, or 0 for the last corner (the face is a cycle)
        if all(face[j] not in plane.adjacent[v] or j == i - 1 or (j == 0 and i == k - 1) for j in chosen):
            chosen.append(i)
    return chosen


def _chord_rank(a: Hashable, c: Hashable, hubs: frozenset) -> int:
    """Which chords a triangulation adds first. Every chord becomes a shared wall, and the
    walls of a hub (a room with three doors or more: corridors, halls) are for its doors:
    chords from the outside to a room first (more rooms with an outside wall, as in real
    buildings), then between two rooms, then to a hub, last from the outside to a hub
    (an outside wall takes a whole side of it)."""
    outside = OUT in (a, c)
    hub = a in hubs or c in hubs
    return (0 if outside else 1) if not hub else (3 if outside else 2)


def _load(plane: _Plane, v: Hashable) -> int:
    return 0 if v == OUT else len(plane.rotation[v])


def _triangulate(plane: _Plane, rng: random.Random, max_fillers: int,
                 hubs: frozenset = frozenset(), capacity: dict | None = None) -> list[Hashable] | None:
    """Close every face of `plane` into triangles (module docstring, step 2). The fillers
    added, or None when that took more than `max_fillers`."""
    fillers: list[Hashable] = []
    capacity = capacity or {}
    while True:
        open_faces = [f for f in plane.faces() if len(f) > 3]
        if not open_faces:
            return fillers
        face = open_faces[rng.randrange(len(open_faces))]
        k = len(face)
        corners = list(range(k))
        rng.shuffle(corners)
        # a fan from one room would give it more neighbours than its walls hold: among
        # chords of a rank, those between rooms with fewer neighbours first
        corners.sort(key=lambda i: (_chord_rank(face[(i - 1) % k], face[(i + 1) % k], hubs),
                                    _load(plane, face[(i - 1) % k]) + _load(plane, face[(i + 1) % k])))
        allowed = [i for i in corners if _ear_allowed(plane, face, i)]
        # a chord is a shared wall: one that would give a room more neighbours than its
        # walls hold (capacity) is left for a filler, an empty cell, instead
        roomy = [i for i in allowed
                 if all(_load(plane, v) < capacity.get(v, math.inf)
                        for v in (face[(i - 1) % k], face[(i + 1) % k]))]
        chosen = _filler_corners(plane, face) if not roomy else []
        if roomy or (allowed and (len(chosen) < 3 or len(fillers) >= max_fillers)):
            i = (roomy or allowed)[0]
            plane.add_chord(face, (i - 1) % k, (i + 1) % k)
            continue
        if len(chosen) < 3 or len(fillers) >= max_fillers:
            return None
        filler = ("filler", len(fillers))
        plane.add_filler(face, chosen, filler)
        fillers.append(filler)


def _separating_triangles(plane: _Plane) -> bool:
    graph = nx.Graph((u, v) for u in plane.rotation for v in plane.rotation[u])
    triangles = sum(nx.triangles(graph).values()) // 3
    return triangles != len(plane.faces())


def _with_poles(plane: _Plane, rng: random.Random) -> dict[Hashable, list[Hashable]] | None:
    """The rotation with OUT replaced by the four poles (step 3), or None when OUT has fewer
    than four neighbours."""
    ring = plane.rotation[OUT]
    d = len(ring)
    if d < 4:
        return None
    first = rng.randrange(d)
    cuts = sorted({(first + round(k * d / 4 + rng.uniform(-0.3, 0.3) * d / 4)) % d for k in range(4)})
    if len(cuts) < 4:
        cuts = sorted((first + k * d // 4) % d for k in range(4))
    if len(set(cuts)) < 4:
        return None
    # OUT's clockwise ring walks the building's outline anticlockwise seen from inside:
    # its arcs are N, W, S, E in that order
    arc_poles = (POLES[0], POLES[3], POLES[2], POLES[1])
    # each of OUT's neighbours: the poles of the arcs it lies on, in OUT's ring order (a
    # corner: the arc that ends at it, then the one that starts at it)
    arcs_of: dict[Hashable, list[Hashable]] = {v: [] for v in ring}
    for k in range(4):
        start, end = cuts[k], cuts[(k + 1) % 4]
        i = (start + 1) % d
        while i != end:
            arcs_of[ring[i]].append(arc_poles[k])
            i = (i + 1) % d
        arcs_of[ring[start]].append(arc_poles[k])  # starts at this corner
        arcs_of[ring[end]].insert(0, arc_poles[k])  # ends at that one
    position = {v: i for i, v in enumerate(ring)}
    rotation = {v: list(ns) for v, ns in plane.rotation.items() if v != OUT}
    for v in ring:
        around = rotation[v]
        at = around.index(OUT)
        poles = arcs_of[v]
        if len(poles) == 2 and around[at - 1] != ring[(position[v] - 1) % d]:
            # clockwise round v, OUT's neighbour before OUT is on the arc that starts here
            poles = poles[::-1]
        around[at:at + 1] = poles
    return rotation


EMBEDDING_ATTEMPTS = 8
"""Embeddings of a room graph's core tried (each networkx's, on a reshuffled graph) for one
in which every triangle of doors can be cleared to a face."""


def _side(plane: _Plane, triangle: tuple) -> dict[Hashable, set[Hashable]]:
    """For each corner v of the triangle, its neighbours on one side of the triangle (the
    side the corners' rings turn into after the previous corner, consistently round it)."""
    a, b, c = triangle
    sides = {}
    for v, previous, following in ((a, b, c), (b, c, a), (c, a, b)):
        ring = plane.rotation[v]
        i = ring.index(previous)
        arc = set()
        j = (i + 1) % len(ring)
        while ring[j] != following:
            arc.add(ring[j])
            j = (j + 1) % len(ring)
        sides[v] = arc
    return sides


def _triangles_cleared(plane: _Plane, triangles: list[tuple], rng: random.Random) -> bool:
    """Make every triangle of doors a face where the rooms inside it hang off one corner:
    they move, with the angle they take at that corner, to its other side (OUT's side).
    False when a triangle encloses rooms joined to two of its corners."""
    for _step in range(4 * len(triangles) + 1):
        faces = {frozenset(f) for f in plane.faces() if len(f) == 3}
        bad = [t for t in triangles if frozenset(t) not in faces]
        if not bad:
            return True
        triangle = bad[0]
        corners = set(triangle)
        rest = nx.Graph((u, v) for u in plane.rotation for v in plane.rotation[u]
                        if u not in corners and v not in corners)
        rest.add_nodes_from(v for v in plane.rotation if v not in corners)
        side = _side(plane, triangle)
        out_side = None
        components = list(nx.connected_components(rest))
        placed = []
        for component in components:
            on_side = {v for v in triangle if side[v] & component}
            off_side = {v for v in triangle if (set(plane.rotation[v]) - side[v] - corners) & component}
            placed.append((component, on_side, off_side))
            if OUT in component:
                out_side = bool(on_side)
        for component, on_side, off_side in placed:
            inside = on_side if out_side is False else off_side
            if not inside or OUT in component:
                continue
            attached = {v for v in triangle if set(plane.rotation[v]) & component}
            if len(attached) > 1:
                return False
            (v,) = attached
            ring = plane.rotation[v]
            block = [u for u in ring if u in component]
            plane.rotation[v] = ring = [u for u in ring if u not in component]
            keep = side[v] if out_side else set(ring) - side[v] - corners
            angles = [u for u in ring if u in keep or u in corners]
            lengths = [len(plane.face_at(v, u)) for u in angles]
            longest = max(lengths)
            choices = [u for u, n in zip(angles, lengths) if n == longest and n > 3] or angles
            at = ring.index(choices[rng.randrange(len(choices))]) + 1
            ring[at:at] = block
    return False


def _embedded(graph: nx.Graph, rng: random.Random) -> _Plane | None:
    """A plane embedding of the graph (None: not planar) in which the trees hanging off it
    lie in faces that are not triangles: networkx embeds the graph's core (what is left
    when rooms with one neighbour are peeled off, OUT kept), in a seeded order; each peeled
    room then goes back into an angle of its neighbour on the longest face there, so that
    no room ends up inside a triangle of doors (which would leave it no rectangular dual)."""
    core = graph.copy()
    peeled: list[tuple[Hashable, Hashable]] = []  # (room, the neighbour it hangs off)
    leaves = [v for v in core if core.degree(v) <= 1 and v != OUT]
    while leaves:
        v = leaves.pop()
        if v not in core or v == OUT or core.degree(v) > 1:
            continue
        neighbours = list(core.neighbors(v))
        core.remove_node(v)
        if neighbours:
            peeled.append((v, neighbours[0]))
            if core.degree(neighbours[0]) <= 1:
                leaves.append(neighbours[0])
    nodes = list(core.nodes)
    rng.shuffle(nodes)
    edges = list(core.edges)
    rng.shuffle(edges)
    shuffled = nx.Graph()
    shuffled.add_nodes_from(nodes)
    shuffled.add_edges_from(edges)
    triangles = [tuple(c) for c in nx.enumerate_all_cliques(core) if len(c) == 3 and OUT not in c]
    for _attempt in range(EMBEDDING_ATTEMPTS):
        planar, embedding = nx.check_planarity(shuffled)
        if not planar:
            return None
        plane = _Plane({v: list(embedding.neighbors_cw_order(v)) for v in embedding.nodes})
        if _triangles_cleared(plane, triangles, rng):
            break
        rng.shuffle(nodes)
        rng.shuffle(edges)
        shuffled = nx.Graph()
        shuffled.add_nodes_from(nodes)
        shuffled.add_edges_from(edges)
    else:
        return None
    for room, parent in reversed(peeled):
        plane.rotation.setdefault(parent, [])
        plane.adjacent.setdefault(parent, set())
        ring = plane.rotation[parent]
        if ring:
            # onto the outside where the parent has a corner there (a room hanging off a
            # corridor gets its outside wall, as in real buildings), else the longest face
            faces = [plane.face_at(parent, x) for x in ring]
            scores = [(OUT in face, len(face)) for face in faces]
            best = max(scores)
            choices = [x for x, score in zip(ring, scores) if score == best]
            plane.insert(parent, room, choices[rng.randrange(len(choices))])
        else:
            ring.append(room)
            plane.adjacent[parent].add(room)
        plane.rotation[room] = [parent]
        plane.adjacent[room] = {parent}
    return plane


def plane_triangulation(graph: nx.Graph, outside: list[Hashable], seed: int,
                        capacity: dict[Hashable, int] | None = None,
                        ) -> tuple[dict[Hashable, list[Hashable]], list[Hashable]] | None:
    """(clockwise rotation of every room and filler, poles included; the fillers) of the
    room graph completed to a graph with a rectangular dual, or None (module docstring).
    `capacity[room]`: neighbours its walls hold, beyond which fillers take the chords."""
    rng = random.Random(f"dual:{seed}")
    rooms = list(graph.nodes)
    outside = [v for v in outside if v in graph]
    if not outside:
        outside = [rooms[rng.randrange(len(rooms))]]
    edges = [tuple(e) for e in graph.edges] + [(OUT, v) for v in outside]
    while True:
        augmented = nx.Graph()
        augmented.add_nodes_from(rooms + [OUT])
        augmented.add_edges_from(edges)
        plane = _embedded(augmented, rng)
        if plane is not None:
            break
        # not every onB room fits round one outside: the last ones are left to the sizing
        if len(outside) <= 1:
            return None
        edges.remove((OUT, outside.pop()))
    hubs = frozenset(v for v in graph if graph.degree(v) >= HUB_DOORS)
    fillers = _triangulate(plane, rng, int(MAX_FILLERS_PER_ROOM * len(rooms)) + 2, hubs, capacity)
    if fillers is None or _separating_triangles(plane):
        return None
    rotation = _with_poles(plane, rng)
    if rotation is None:
        return None
    return rotation, fillers


def dual_geometry(spec: Spec, sides: dict[str, tuple[float, float]], seed: int,
                  outline: tuple[float, float] | None = None, seconds: float = 30.0,
                  tiled_only: bool = False) -> dict[str, Rect] | None:
    """A tiling of the spec's rooms in which every door is a shared wall (module
    docstring), with each room near its drawn (long, short) sides, within `outline` (width,
    height) when given; None when the room graph has no rectangular dual this way."""
    if spec.arms or len(spec.rooms) < 2:
        return None
    graph = nx.Graph()
    graph.add_nodes_from(room.id for room in spec.rooms)
    graph.add_edges_from((adj.a, adj.b) for adj in spec.adjacencies if adj.a != adj.b)
    if not nx.is_connected(graph):
        return None
    outside = [room.id for room in spec.rooms if room.on_boundary]
    sizes = {room.id: RoomSizes.of(room) for room in spec.rooms}
    capacity = {v: graph.degree(v) + SPARE_CONTACTS for v in graph.nodes}
    completed = plane_triangulation(graph, outside, seed, capacity)
    if completed is None:
        return None
    rotation, fillers = completed
    utilization = spec.settings.door_utilization
    wall = spec.settings.walldim
    # every room beside v takes at least its narrowest side of v's wall (a door's room at
    # least the door): pairs without a door only touch in the dual, but the sizing keeps
    # them in the row the dual puts them in
    footprints = {}
    for v in graph.nodes:
        for u in rotation[v]:
            if u in graph:
                footprints[(v, u)] = (sizes[u].lo_short + wall, sizes[u].lo_long + wall)
    for adj in spec.adjacencies:
        for v, u in ((adj.a, adj.b), (adj.b, adj.a)):
            door = adj.door / utilization
            footprints[(v, u)] = (max(door, sizes[u].lo_short) + wall, max(door, sizes[u].lo_long) + wall)
    overhang = 2 * max((s.lo_short for s in sizes.values()), default=0.0)
    found = regular_edge_labeling(rotation, POLES, seed, seconds=seconds,
                                  sides={v: (s.hi_long, s.hi_short) for v, s in sizes.items()},
                                  footprints=footprints, overhang=overhang)
    if found is None:
        return None
    labeling, long_x = found
    overlap = {}
    for u in rotation:
        for v in rotation[u]:
            overlap[frozenset((u, v))] = NON_DOOR_OVERLAP if u in graph and v in graph else 0.0
    for adj in spec.adjacencies:
        overlap[frozenset((adj.a, adj.b))] = max(NON_DOOR_OVERLAP, adj.door / utilization)
    targets = {}
    for v in rotation:
        if v in POLES:
            continue
        if v not in sides:
            targets[v] = (0.0, 0.0)
            continue
        long_side, short_side = sides[v]
        if v in long_x:
            wide = long_x[v]
        else:
            # the long side runs along the longer row of neighbours: rooms above and below
            # make it wide, rooms left and right of it tall
            stacked = sum(1 for (a, b), colour in labeling.items() if colour == "red" and v in (a, b))
            beside = sum(1 for (a, b), colour in labeling.items() if colour == "blue" and v in (a, b))
            wide = stacked >= beside
        targets[v] = (long_side, short_side) if wide else (short_side, long_side)
    vertices = [v for v in rotation if v not in POLES]
    placed = tiling(vertices, labeling, POLES, targets, overlap, spec.settings.walldim,
                    collapse=frozenset(fillers), seed=seed, seconds=seconds)
    if placed is None:
        return None
    if tiled_only:
        return {v: placed[v] for v in graph.nodes}
    bounds = {}
    for v in graph.nodes:
        wide = targets[v][0] >= targets[v][1]
        s = sizes[v]
        bounds[v] = ((s.lo_long, s.hi_long, s.lo_short, s.hi_short) if wide
                     else (s.lo_short, s.hi_short, s.lo_long, s.hi_long))
    doors = {frozenset((adj.a, adj.b)): adj.door / utilization for adj in spec.adjacencies}
    return sized_drawing(vertices, labeling, POLES, doors, targets, bounds, placed, spec.settings.walldim,
                         outline=outline, seed=seed, seconds=seconds)


def _spec_of(path: Path) -> Spec:
    from dataclasses import replace

    from layoutdsl.api import lint_source
    from layoutdsl.diagnostics.source import Source
    from layoutdsl.importer.graphs import read_graph
    from layoutdsl.sizes import spec_from_graph
    from layoutdsl.syntax.format import format_spec

    graph, _diagnostics = read_graph(str(path))
    spec = spec_from_graph(graph, kind="school", name=path.stem)
    checked, _diagnostics = lint_source(Source(path.stem + ".lay", format_spec(replace(spec, boundary=None))))
    return checked


def main(folder: str, seeds: int = 3) -> None:
    from layoutdsl.compile import initial

    print(f"{'graph':22s} {'rooms':>5s} {'dual':>5s} {'sized':>5s} {'s/try':>6s}")
    totals = [0, 0, 0]
    for path in sorted(Path(folder).glob("*.csv")):
        spec = _spec_of(path)
        sides = initial.drawn_sides(spec, (spec.boundary.w, spec.boundary.h), shrink=1.0)
        tiled = sized = 0
        began = time.monotonic()
        for seed in range(seeds):
            if dual_geometry(spec, sides, seed, tiled_only=True) is not None:
                tiled += 1
            if dual_geometry(spec, sides, seed) is not None:
                sized += 1
        totals[0] += seeds
        totals[1] += tiled
        totals[2] += sized
        print(f"{path.stem:22s} {len(spec.rooms):5d} {tiled:5d} {sized:5d} {(time.monotonic() - began) / seeds:6.2f}",
              flush=True)
    print(f"tries {totals[0]}: tiled {totals[1]}, sized within bounds {totals[2]}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "../shared/graphs")
