"""Benchmark: which room graphs the generator fails on, by the cycles among their corridors.

A graph's corridors (rooms of type C: corridors, halls, lobbies as `layoutdsl.sizes`
types them) and the doors between two of them form the corridor graph; its independent
cycles (edges - nodes + components) are rings of corridors, each of which has to close
round rooms or a courtyard. For each graph of FOLDER (the adjacency-matrix CSVs of
../shared/graphs) this prints its rooms, corridors, corridor cycles and cycles, and its
first-layout seconds in each run of the result tables given (`-`: not drawn); then, per
number of corridor cycles, how many runs drew the graph. With `--plans FOLDER` (building
XML files, imported by default) it prints each plan's corridor cycles too.

A result table is a `bench/generation.py --graphs` table (its rows start with the graph's
name); a file with several tables (bench/results/generation-graphs.txt keeps older runs
below newer ones) gives one run per table, the first `--tables` of them.

    PYTHONPATH=. python bench/experiments/corridor_cycles.py ../shared/graphs RESULTS... [--tables N]
                                                             [--plans ../shared/floorplans]
"""

from __future__ import annotations

import argparse
import statistics
from pathlib import Path

from layoutdsl.compile.graph import corridor_skeleton, rings, room_graph
from layoutdsl.importer import import_building
from layoutdsl.importer.convert import ImportOptions
from layoutdsl.importer.graphs import read_graph
from layoutdsl.sizes import spec_from_graph


def runs_of(path: Path, tables: int) -> list[dict[str, float | None]]:
    """Each table of a result file as {graph: first-layout seconds, or None when not drawn}."""
    runs: list[dict[str, float | None]] = []
    for line in path.read_text().splitlines():
        fields = line.split()
        if fields[:1] == ["plan"]:
            runs.append({})
            continue
        if runs and len(fields) > 5 and fields[0].startswith("cml") and fields[4] in ("yes", "no"):
            runs[-1][fields[0]] = float(fields[5]) if fields[4] == "yes" else None
    return [run for run in runs if run][:tables]


def corridor_cycles(spec) -> int:
    """Independent cycles of the spec's corridors and the doors between two of them."""
    return rings(corridor_skeleton(spec))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", type=Path)
    parser.add_argument("results", type=Path, nargs="+")
    parser.add_argument("--tables", type=int, default=2, help="tables read from each result file (default 2)")
    parser.add_argument("--plans", type=Path, help="a folder of building XML files: their corridor cycles too")
    args = parser.parse_args()
    runs = [run for path in args.results for run in runs_of(path, args.tables)]
    rows = []
    for path in sorted(args.folder.glob("*.csv")):
        graph_in, _diagnostics = read_graph(path)
        spec = spec_from_graph(graph_in, kind="school", name=path.stem)
        n_corridors = sum(room.is_corridor for room in spec.rooms)
        rows.append((corridor_cycles(spec), rings(room_graph(spec)), path.stem, len(spec.rooms), n_corridors,
                     [run.get(path.stem) for run in runs]))
    print(f"{'graph':16s} {'rooms':>5s} {'corr':>4s} {'c.cyc':>5s} {'cycles':>6s}  first layout, s (one column a run)")
    for c_cycles, cycles, name, n_rooms, n_corridors, times in sorted(rows):
        cells = " ".join(f"{t:7.2f}" if t is not None else f"{'-':>7s}" for t in times)
        print(f"{name:16s} {n_rooms:5d} {n_corridors:4d} {c_cycles:5d} {cycles:6d}  {cells}")
    print()
    print("corridor cycles  graphs  drawn (runs)  median s  max s  over 20 s")
    groups: dict[int, list[list[float | None]]] = {}
    for c_cycles, _cycles, _name, _rooms, _corridors, times in rows:
        groups.setdefault(min(c_cycles, 4), []).append(times)
    for c_cycles, group in sorted(groups.items()):
        drawn = [t for times in group for t in times if t is not None]
        total = sum(len(times) for times in group)
        label = ">= 4" if c_cycles == 4 else str(c_cycles)
        median = f"{statistics.median(drawn):8.2f}" if drawn else f"{'-':>8s}"
        worst = f"{max(drawn):6.2f}" if drawn else f"{'-':>6s}"
        print(f"{label:>15s}  {len(group):6d}  {len(drawn):5d}/{total:<6d}  {median}  {worst}  {sum(t > 20 for t in drawn):9d}")
    if args.plans is not None:
        print()
        print(f"{'plan':40s} {'rooms':>5s} {'corr':>4s} {'c.cyc':>5s}")
        for path in sorted(args.plans.glob("*.xml")):
            spec, _diagnostics = import_building(path, ImportOptions())
            if spec is not None:
                n_corridors = sum(room.is_corridor for room in spec.rooms)
                print(f"{path.stem:40s} {len(spec.rooms):5d} {n_corridors:4d} {corridor_cycles(spec):5d}")


if __name__ == "__main__":
    main()
