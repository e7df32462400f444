"""Benchmark: annealing a large plan in stages instead of whole (issue 11, a measured dead end).

school_stjoseph_scatholichighschool (105 rooms, 26 independent cycles) is the one real plan
the construction never builds from its room graph: whole-plan annealing runs end 6-90 m from
a layout. Its cycles all lie in the graph's 2-core (54 rooms); the other 51 rooms (59 with
the L-rooms' arms) hang off it in trees, most of them single rooms. Multilevel floorplanners
(clustering, then refining) suggest annealing a smaller problem first and then the whole plan
from its result. This prints, for
seeds 0..N-1 of each mode, the first stage's violation and the whole plan's after the second:

    whole     the whole plan from a random sequence pair (what compile does today)
    core      the 2-core alone from a random sequence pair; then each hanging room is put
              in the sequence pair beside the room it hangs off (a random side), in
              breadth-first order, and the whole plan is annealed from there as compile
              anneals from a given geometry (layoutdsl.compile.anneal.FROM_GEOMETRY_*)
    contract  each hanging tree of two rooms or more replaced by one room of its total area
              (aspect ratio 1-3) with the tree's door; the trees' rooms are then put in the
              sequence pair at that room's place and beside their parents, as for `core`

A second stage runs only from a first stage within --stage-max metres of a layout. After the
table, the doors left unmet (over 0.05 m) by the whole-plan runs, most frequent first: where
the annealer falls short.

It drives the annealer's chains directly (layoutdsl.compile.anneal._Arrays): staging is
not in the construction, because it did not pay (bench/results/anneal-stages.txt).

    python bench/anneal_stages.py [XML] [--seeds 4] [--modes whole,core,contract] [--out FILE]
"""

from __future__ import annotations

import argparse
import collections
import math
import random
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace
from pathlib import Path

import networkx as nx
import numpy as np

from plans import DEFAULT_FOLDER

DEFAULT_PLAN = DEFAULT_FOLDER / "school_stjoseph_scatholichighschool.xml"


class Stages:
    """One plan's spec as the annealer sees it (its L-rooms' arms drawn as rooms), and the
    smaller specs of the first stages."""

    def __init__(self, spec):
        from layoutdsl.compile import anneal, lshape
        from layoutdsl.compile.generate import drawn_sides, room_graph

        self.drawn = lshape.seeds_spec(spec)
        self.graph = room_graph(self.drawn)
        self.core = set(nx.k_core(self.graph, 2))
        self.sides = drawn_sides(self.drawn)
        self.whole = anneal._Arrays.of(self.drawn)
        self.index = {room_id: i for i, room_id in enumerate(self.whole.ids)}
        self.cancel = np.zeros(1, dtype=np.int64)
        self.pieces: dict[str, str] = {}
        """stand-in room of a contracted tree -> the tree's room next to the 2-core"""
        self.contracted = anneal._Arrays.of(self._contracted_spec())
        self.core_only = anneal._Arrays.of(self.drawn.restricted_to(self.core, "core"))

    def _contracted_spec(self):
        rooms = {room.id: room for room in self.drawn.rooms}
        hanging = self.graph.subgraph(set(self.graph) - self.core)
        keep, stand_ins, doors = set(self.core), [], []
        for k, piece in enumerate(sorted(nx.connected_components(hanging), key=sorted)):
            joins = [(r, n) for r in sorted(piece) for n in self.graph[r] if n in self.core]
            if len(piece) == 1 or len(joins) != 1:
                keep |= piece  # a single room, or a room with no door at all
                continue
            (first, root), = joins
            area = sum(self.sides[r][0] * self.sides[r][1] for r in piece)
            side = math.sqrt(area)
            stand_in = f"tree{k}"
            self.pieces[stand_in] = first
            stand_ins.append(replace(rooms[first], id=stand_in, min_w=side / math.sqrt(3),
                                     max_w=side * math.sqrt(3), target_w=side * 1.2,
                                     min_h=side / math.sqrt(3), max_h=side * math.sqrt(3),
                                     target_h=side / 1.2, min_ar=1.0, max_ar=3.0, rtype="R",
                                     on_boundary=False))
            door = next(a for a in self.drawn.adjacencies if {a.a, a.b} == {first, root})
            doors.append(replace(door, a=root, b=stand_in))
        sub = self.drawn.restricted_to(keep, "contracted")
        return replace(sub, rooms=sub.rooms + tuple(stand_ins), adjacencies=sub.adjacencies + tuple(doors))

    def first_stage(self, arrays, seed: int):
        began = time.monotonic()
        return arrays.chain(1000 + seed, self.cancel, None), time.monotonic() - began

    def expanded(self, arrays, result, seed: int):
        """The whole plan's state: the first stage's sequence pair with each stand-in as its
        tree's first room, and every room not yet in it beside the room it hangs off."""
        p, q, turned, long_side, short_side, _ = result
        whole = self.whole
        rng = random.Random(seed)
        new_turned = np.zeros(len(whole.ids), dtype=np.bool_)
        new_long, new_short = whole.long_side.copy(), whole.short_side.copy()
        name = [self.pieces.get(room_id, room_id) for room_id in arrays.ids]
        for k, room_id in enumerate(arrays.ids):
            i = self.index[name[k]]
            new_turned[i] = turned[k]
            if room_id not in self.pieces:
                new_long[i], new_short[i] = long_side[k], short_side[k]
        seq_p = [self.index[name[k]] for k in p]
        seq_q = [self.index[name[k]] for k in q]
        placed = {whole.ids[i] for i in seq_p}
        todo = [room_id for room_id in whole.ids if room_id not in placed]
        while todo:
            ready = [r for r in todo if any(n in placed for n in self.graph[r])]
            if not ready:  # rooms without doors: anywhere
                ready = todo[:1]
            for room_id in ready:
                todo.remove(room_id)
                i = self.index[room_id]
                new_turned[i] = rng.random() < 0.5
                parents = sorted(n for n in self.graph[room_id] if n in placed)
                placed.add(room_id)
                if not parents:
                    seq_p.insert(rng.randrange(len(seq_p) + 1), i)
                    seq_q.insert(rng.randrange(len(seq_q) + 1), i)
                    continue
                anchor = self.index[parents[0]]
                side = rng.randrange(4)  # as layoutdsl.compile.anneal's move beside a neighbour
                seq_p.insert(seq_p.index(anchor) + (side in (0, 3)), i)
                seq_q.insert(seq_q.index(anchor) + (side in (0, 2)), i)
        return (np.array(seq_p, dtype=np.int64), np.array(seq_q, dtype=np.int64), new_turned,
                new_long, new_short)

    def second_stage(self, state, seed: int):
        began = time.monotonic()
        return self.whole.chain_from(2000 + seed, self.cancel, state), time.monotonic() - began

    def unmet(self, result) -> list[tuple[float, str, str]]:
        """(metres, room, room) of each door the packing leaves unmet, measured on its
        rectangles: the gap across the nearer axis plus the missing shared wall."""
        geometry, _ = self.whole.geometry(result)
        whole, out = self.whole, []
        for k in range(len(whole.edge_a)):
            a, b = whole.ids[whole.edge_a[k]], whole.ids[whole.edge_b[k]]
            ax, ay, aw, ah = geometry[a]
            bx, by, bw, bh = geometry[b]
            gap_x = max(bx - ax - aw, ax - bx - bw) - whole.wall
            gap_y = max(by - ay - ah, ay - by - bh) - whole.wall
            wall_y = min(ay + ah, by + bh) - max(ay, by)
            wall_x = min(ax + aw, bx + bw) - max(ax, bx)
            missing = min(abs(gap_x) + max(0.0, whole.need[k] - wall_y),
                          abs(gap_y) + max(0.0, whole.need[k] - wall_x))
            if missing > 0.05:
                out.append((float(missing), a, b))
        return sorted(out, reverse=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("plan", nargs="?", default=str(DEFAULT_PLAN))
    parser.add_argument("--seeds", type=int, default=4)
    parser.add_argument("--modes", default="whole,core,contract")
    parser.add_argument("--stage-max", type=float, default=3.0,
                        help="metres from a layout below which a first stage goes on (default 3)")
    parser.add_argument("--out", help="also write the table to this file")
    args = parser.parse_args(argv)
    from layoutdsl.importer import import_building

    spec, diagnostics = import_building(Path(args.plan))
    if spec is None:
        print("import failed: " + "; ".join(d.message for d in diagnostics if d.is_error), file=sys.stderr)
        return 2
    stages = Stages(spec)
    lines = [f"plan {Path(args.plan).stem}: {len(stages.whole.ids)} rooms drawn (arms included), "
             f"2-core {len(stages.core)}, contracted {len(stages.contracted.ids)}; "
             f"second stage from first stages within {args.stage_max} m",
             f"{'mode':9s} {'seed':>4s} {'rooms':>5s} {'stage 1 m':>9s} {'s':>5s} {'whole m':>8s} {'s':>5s}"]
    print(*lines, sep="\n", flush=True)
    unmet: collections.Counter = collections.Counter()
    first_of = {"whole": stages.whole, "core": stages.core_only, "contract": stages.contracted}
    for mode in args.modes.split(","):
        arrays = first_of[mode]
        # two chains side by side, as compile runs them
        with ThreadPoolExecutor(2) as pool:
            firsts = list(pool.map(lambda seed: (seed, *stages.first_stage(arrays, seed)), range(args.seeds)))
        for seed, result, seconds in firsts:
            cells = f"{mode:9s} {seed:4d} {len(arrays.ids):5d} {result[5]:9.2f} {seconds:5.1f}"
            if mode == "whole":
                unmet.update((a, b) for _, a, b in stages.unmet(result))
                line = cells + f" {result[5]:8.2f} {'':>5s}"
            elif result[5] <= args.stage_max:
                second, seconds = stages.second_stage(stages.expanded(arrays, result, seed), seed)
                line = cells + f" {second[5]:8.2f} {seconds:5.1f}"
            else:
                line = cells + f" {'-':>8s} {'':>5s}"
            lines.append(line)
            print(line, flush=True)
    if unmet:
        lines.append("doors left unmet by the whole-plan runs (runs): "
                     + ", ".join(f"{a}-{b} ({n})" for (a, b), n in unmet.most_common(12)))
        print(lines[-1])
    if args.out:
        Path(args.out).write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
