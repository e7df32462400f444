"""Benchmark: how far the building's outline lets a new arrangement differ from the original.

An imported spec's boundary is the original plan's bounding box (the thesis, §5.3). For
each plan, this draws N greedy placements of its room graph
(layoutdsl.compile.generate.generate_geometry, seeds 0..N-1: the seed geometries compile
repairs into its layouts) inside that boundary and inside boundaries of the same area with
other aspect ratios, and prints the arrangement difference of each placement from the
original (layoutdsl.layout.difference: room-pair relations, minimised over the 8
rotations and mirrors) as min / median / max over the seeds.

A long, narrow outline fixes the order of the rooms along it: a corridor chain that must run
along the long side meets its rooms in the original's order (or its mirror image), whatever
the seed. This bench shows how much of a plan's low difference is that. The placements are
seed geometries, not compiled layouts; for a plan without cycles the repair keeps their
relations (office_324-Elm-Furn-Plan: 0.20-0.26 over seeds 0-5 compiled, 0.20-0.26 here).

    python bench/outline.py [FOLDER] [--only PATTERN] [--seeds 20] [--aspects 2,1] [--out FILE]
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import random
import statistics
import sys
from pathlib import Path

from plans import DEFAULT_FOLDER, ONLY_HELP, plan_files


def _with_aspect(spec, aspect: float | None):
    """The spec with its boundary's area kept and its width / height set to `aspect`
    (None: the original boundary)."""
    if aspect is None:
        return spec
    area = spec.boundary.w * spec.boundary.h
    width = math.sqrt(area * aspect)
    return dataclasses.replace(spec, boundary=dataclasses.replace(spec.boundary, w=width, h=area / width))


def differences(spec, original: dict[str, tuple[float, float]], seeds: int, aspect: float | None) -> list[float]:
    """Each seed's greedy placement of `spec` (its boundary reshaped to `aspect`) scored
    against the original plan's room centres."""
    from layoutdsl.compile.generate import generate_geometry
    from layoutdsl.layout.difference import difference

    spec = _with_aspect(spec, aspect)
    result = []
    for seed in range(seeds):
        geometry = generate_geometry(spec, random.Random(seed))
        # an L-room's arm is drawn as a rectangle of its own: the room's centre is its box's
        centres = {room_id: (x + w / 2, y + h / 2) for room_id, (x, y, w, h) in geometry.items()
                   if room_id in original}
        result.append(difference(centres, original))
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", nargs="?", type=Path, default=DEFAULT_FOLDER)
    parser.add_argument("--only", metavar="PATTERN", help=ONLY_HELP)
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--aspects", default="2,1",
                        help="width/height ratios of the same-area boundaries tried besides the original")
    parser.add_argument("--out", type=Path, help="also write the table to this file")
    args = parser.parse_args(argv)
    aspects = [None] + [float(a) for a in args.aspects.split(",") if a]
    lines: list[str] = []

    def emit(text: str) -> None:
        print(text, flush=True)
        lines.append(text)

    heading = "".join(f"{'original' if a is None else f'aspect {a:g}':>20}" for a in aspects)
    emit(f"{'plan':34} {'rooms':>5} {'W x H':>12} {'aspect':>6}{heading}")
    emit(f"{'':34} {'':>5} {'':>12} {'':>6}" + f"{'min / med / max':>20}" * len(aspects))
    from layoutdsl.evaluate.difference import building_centres
    from layoutdsl.importer import import_building, read_building

    for path in plan_files(args.folder, args.only):
        spec, _ = import_building(path)
        if spec is None:
            emit(f"{path.stem:34} import failed")
            continue
        original = building_centres(read_building(path)[0])
        w, h = spec.boundary.w, spec.boundary.h
        cells = []
        for aspect in aspects:
            found = differences(spec, original, args.seeds, aspect)
            cells.append(f"{min(found):.2f} / {statistics.median(found):.2f} / {max(found):.2f}")
        emit(f"{path.stem[:34]:34} {len(spec.rooms):>5} {f'{w:.0f} x {h:.0f}':>12} {max(w, h) / min(w, h):>6.1f}"
             + "".join(f"{c:>20}" for c in cells))
    if args.out:
        args.out.write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
