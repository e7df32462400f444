"""Benchmark: the sequence-pair annealer (layoutdsl.compile.anneal) on real plans' room graphs.

For each building XML file in FOLDER (default ../shared/floorplans beside the repo): import it
without hints (the default, with its L-rooms' arms drawn as rooms of their own, as the
construction draws them), anneal seeds 0..N-1 and print one row a plan:

    plan, rooms (with arms), doors, each seed's violation in metres (extent past the boundary,
    each door's gap and missing wall) and seconds, and how many seeds reached 0

A violation of 0 is a packing in which every door's rooms touch across one wall along the
door's wall, inside the boundary: a seed geometry whose first repair LP is already a layout.
The annealer runs its chains on all cores, so run nothing beside it; timings depend on the
machine (the first row includes numba's compile unless its cache is warm).

`--kernel satellites` anneals with the core-and-satellites annealer
(layoutdsl.compile.satellites) instead, on the plans it splits (the others are left out), and
adds how many seeds ended within 6 m of a layout (the repair's reach,
construct.ANNEAL_REPAIR_M).

    python bench/anneal.py [FOLDER] [--seeds 2] [--only PATTERN] [--kernel satellites] [--out FILE]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from plans import DEFAULT_FOLDER, ONLY_HELP, plan_files


def _row(path: Path, seeds: int, kernel: str) -> str | None:
    from layoutdsl.compile import lshape
    from layoutdsl.compile.anneal import anneal_geometry
    from layoutdsl.compile.construct import ANNEAL_REPAIR_M
    from layoutdsl.compile.satellites import Satellites, satellites_geometry
    from layoutdsl.importer import import_building

    spec, diagnostics = import_building(path)
    if spec is None:
        return f"{path.stem:36s} import failed: " + "; ".join(d.message for d in diagnostics if d.is_error)
    drawn = lshape.seeds_spec(spec)
    if kernel == "satellites" and Satellites.of(drawn) is None:
        return None
    anneal = satellites_geometry if kernel == "satellites" else anneal_geometry
    cells, zero, near = [], 0, 0
    for seed in range(seeds):
        began = time.monotonic()
        _, violation = anneal(drawn, seed)
        cells.append(f"{violation:8.2f} {time.monotonic() - began:5.1f}s")
        zero += violation <= 1e-9
        near += violation <= ANNEAL_REPAIR_M
    tail = f"  {zero:4d}" + (f"  {near:4d}" if kernel == "satellites" else "")
    return f"{path.stem:36s} {len(drawn.rooms):5d} {len(drawn.adjacencies):5d}  " + "  ".join(cells) + tail


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", nargs="?", default=str(DEFAULT_FOLDER))
    parser.add_argument("--seeds", type=int, default=2)
    parser.add_argument("--only", help=ONLY_HELP)
    parser.add_argument("--kernel", choices=("sequence-pair", "satellites"), default="sequence-pair")
    parser.add_argument("--out", help="also write the table to this file")
    args = parser.parse_args(argv)
    from layoutdsl.compile.construct import ANNEAL_REPAIR_M

    paths = plan_files(args.folder, args.only)
    if not paths:
        print(f"no building XML files in {args.folder}", file=sys.stderr)
        return 2
    seed_heads = "  ".join(f"seed {s}: viol m, time" for s in range(args.seeds))
    near = f"  <={ANNEAL_REPAIR_M:g}m" if args.kernel == "satellites" else ""
    lines = [f"{'plan':36s} {'rooms':>5s} {'doors':>5s}  {seed_heads}  zero{near}"]
    print(lines[0], flush=True)
    for path in paths:
        row = _row(path, args.seeds, args.kernel)
        if row is not None:
            lines.append(row)
            print(lines[-1], flush=True)
    if args.out:
        Path(args.out).write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
