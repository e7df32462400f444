"""Do the real originals' occupancy maps realise their portal graphs? (the realism report's map check)

For each building XML file in FOLDER (default ../shared/floorplans beside the repo): rasterize
it as `evaluate` does (the thesis' map preparation, §6.3.6), then check and repair the map
against the plan's portal graph (`layoutdsl.evaluate.portals`). One row per plan: portals the
rasterization left closed, joins without a portal, what the repair opened / walled off, and
whether the map realises the graph before and after. Runs unattended:

    python bench/map_check.py [FOLDER] [--resolution 0.05]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from plans import DEFAULT_FOLDER, plan_files


def main() -> int:
    from layoutdsl.evaluate.grid import room_cells
    from layoutdsl.evaluate.portals import realise_portal_graph
    from layoutdsl.evaluate.topology import room_graph, room_ids
    from layoutdsl.importer import read_building
    from layoutdsl.emit.raster import rasterize_building

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", nargs="?", type=Path, default=DEFAULT_FOLDER)
    parser.add_argument("--resolution", type=float, default=0.05)
    args = parser.parse_args()
    files = plan_files(args.folder)
    print(f"{'plan':38s} {'rooms':>5s} {'closed':>6s} {'joins':>5s} {'opened':>6s} {'walled':>6s} "
          f"{'before':>6s} {'after':>5s} {'s':>5s}  left as it is")
    before = after = 0
    still: list[str] = []
    for path in files:
        building, _ = read_building(path)
        if building is None:
            print(f"{path.stem:38s} unreadable")
            continue
        began = time.monotonic()
        grid = rasterize_building(building, args.resolution)
        cells = room_cells(building, grid, room_ids(building))
        pairs = {tuple(sorted(edge)) for edge in room_graph(building).edges}
        _, check = realise_portal_graph(grid.occupied, cells.labels, cells.ids, pairs, args.resolution,
                                        building.real_distance_m)
        before += check.realised_before
        after += check.realised
        if not check.realised:
            still.append(path.stem)
        left = "; ".join(check.warnings()) or "-"
        print(f"{path.stem:38s} {len(building.spaces):5d} {len(check.missing_before):6d} {len(check.extra_before):5d} "
              f"{len(check.opened):6d} {len(check.closed):6d} {'yes' if check.realised_before else 'no':>6s} "
              f"{'yes' if check.realised else 'no':>5s} {time.monotonic() - began:5.1f}  {left}")
    print(f"\nmaps realising their portal graph: {before} of {len(files)} as rasterized, {after} of {len(files)} "
          f"after the repair" + (f"; still not: {', '.join(still)}" if still else ""))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
