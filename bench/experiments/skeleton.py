"""Benchmark: how much of a plan's difference from the original its corridors decide.

The difference (layoutdsl.layout.difference) counts the room pairs whose relation (which
side of one room's centre the other lies, along the axis where they differ most) is not the
original's, minimised over the 8 rotations and mirrors. Rooms hang off corridors, so a
building whose corridors are where the original has them can differ from it only in where
each room sits along its corridor. For each plan this prints:

- compiled: the difference of seed S's first verified layout from the original (compile at
  default settings but without the search for better layouts after it, which mostly resizes
  rooms: bench/results/generation-60s.txt's column `diff`, the same seed after 60 s, is within
  0.04 of this one on all 24 plans), the difference of its corridors alone (rooms of type C, the thesis'
  connective spaces; `-` for a plan with fewer than 3), and its room area over the
  original's (the first layout's: the search raises it, by 0.08 on office_324-Elm-Furn-Plan
  at seed 0, so it is not the figure the acceptance's +-15 % is about);
- corridors kept: N random buildings with the original's corridors where they are and every
  other room at a random one of the places of the rooms that share its parent (the corridor
  it has a door to with the most doors, else the neighbour with the most), mirrored across
  the parent at random; overlaps ignored. Median and largest difference from the original:
  how far a building with the original's corridors gets without aiming at it.

A plan whose corridors-kept largest is under 0.3 reaches 0.3 by moving its corridors, or by
an arrangement of its rooms along them that random draws do not make.

    python bench/skeleton.py [FOLDER] [--only PATTERN] [--seed 0] [--seeds 1] [--draws 200]
                             [--time-limit 60] [--out FILE]
"""

from __future__ import annotations

import argparse
import random
import statistics
import sys

from generation import import_original, isolated
from plans import DEFAULT_FOLDER, ONLY_HELP, plan_files

def parents(spec) -> dict[str, str]:
    """Each non-corridor room with a door: the room it hangs off (its corridor neighbour with
    the most doors, else its neighbour with the most; ties by id)."""
    from layoutdsl.compile.generate import room_graph

    graph = room_graph(spec)
    corridor = {room.id: room.is_corridor for room in spec.rooms}
    chosen = {}
    for room in graph:
        if corridor[room] or not graph[room]:
            continue
        candidates = [n for n in graph[room] if corridor[n]] or list(graph[room])
        chosen[room] = max(candidates, key=lambda n: (graph.degree(n), n))
    return chosen


def corridors_kept(spec, centres: dict, draws: int, seed: int) -> list[float]:
    """Differences from the original of `draws` buildings with its corridors in place and the
    other rooms shuffled among their parent's rooms' places, each mirrored across the parent
    at random (see the module's docstring), sorted."""
    from layoutdsl.layout.difference import difference

    draw = random.Random(seed)
    children: dict[str, list[str]] = {}
    for room, parent in sorted(parents(spec).items()):
        children.setdefault(parent, []).append(room)
    values = []
    for _ in range(draws):
        moved = dict(centres)
        for parent, rooms in children.items():
            px, py = centres[parent]
            places = [centres[room] for room in rooms]
            draw.shuffle(places)
            for room, (x, y) in zip(rooms, places):
                moved[room] = (2 * px - x if draw.random() < 0.5 else x, 2 * py - y if draw.random() < 0.5 else y)
        values.append(difference(moved, centres))
    return sorted(values)


def _compiled(spec, area: float, centres: dict, seed: int, time_limit: float) -> dict:
    """Seed `seed`'s first verified layout of the imported plan (import_original's spec, room
    area and centres; the forked process inherits them): its difference from the original,
    its corridors' alone, and its room area over the original's."""
    from layoutdsl.compile import compile_spec
    from layoutdsl.layout.difference import difference, layout_centres
    from layoutdsl.layout.verify import verify
    from layoutdsl.solve import SolveOptions

    result = compile_spec(spec, SolveOptions(time_limit=time_limit, seed=seed, quiet=True, search=False),
                          explain_infeasible=False)
    if result.layout is None or verify(spec, result.layout):
        return {"verified": False}
    placed = layout_centres(result.layout)
    corridors = [room.id for room in spec.rooms if room.is_corridor]
    row = {"verified": True, "difference": difference(placed, centres), "corridors": len(corridors),
           "area_ratio": sum(room.area for room in result.layout.rooms) / area}
    if len(corridors) >= 3:
        row["corridor_difference"] = difference({c: placed[c] for c in corridors}, {c: centres[c] for c in corridors})
    return row


def _number(value) -> str:
    return "-" if value is None else f"{value:.3f}"


def format_row(plan: str, rooms: int, aspect: float, seed: int, row: dict, kept: list[float]) -> str:
    """One line of the table: a compiled row (_compiled's) beside the plan's corridors-kept draws."""
    compiled = row.get("difference") if row.get("verified") else None
    return (f"{plan[:36]:36} {rooms:5d} {aspect:6.1f} {seed:4d} {_number(compiled):>8}"
            f" {_number(row.get('corridor_difference')):>9} {_number(row.get('area_ratio')):>5}"
            f" {statistics.median(kept):11.3f} {kept[-1]:8.3f}")


HEADER = (f"{'plan':36} {'rooms':>5} {'aspect':>6} {'seed':>4} {'compiled':>8} {'corridors':>9} {'area':>5}"
          f" {'kept median':>11} {'kept max':>8}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", nargs="?", default=str(DEFAULT_FOLDER))
    parser.add_argument("--only", help=ONLY_HELP)
    parser.add_argument("--seed", type=int, default=0, help="the first seed compiled")
    parser.add_argument("--seeds", type=int, default=1, help="seeds compiled a plan: SEED..SEED+N-1")
    parser.add_argument("--draws", type=int, default=200, help="random corridors-kept buildings a plan")
    parser.add_argument("--time-limit", type=float, default=60.0)
    parser.add_argument("--out", help="also write the table to this file, a row at a time")
    args = parser.parse_args(argv)

    # each row goes to --out as it comes: a run of several minutes a plan keeps what it has done
    out = open(args.out, "w") if args.out else None

    def emit(line: str) -> None:
        print(line, flush=True)
        if out is not None:
            out.write(line + "\n")
            out.flush()

    emit(HEADER)
    for path in plan_files(args.folder, args.only):
        spec, area, _, centres = import_original(path)
        kept = corridors_kept(spec, centres, args.draws, seed=0)
        aspect = max(spec.boundary.w, spec.boundary.h) / min(spec.boundary.w, spec.boundary.h)
        for seed in range(args.seed, args.seed + args.seeds):
            row = isolated(_compiled, spec, area, centres, seed, args.time_limit, limit=args.time_limit)
            emit(format_row(path.stem, len(spec.rooms), aspect, seed, row, kept))
    if out is not None:
        out.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
