"""Benchmark: new buildings generated from real plans' room graphs alone (issue 11's acceptance).

For each building XML file in FOLDER (default ../shared/floorplans beside the repo): import it
WITHOUT hints (the default), compile at default settings, and print one row:

    plan, rooms, cycles, verified, seconds to the first verified layout, total seconds,
    arrangement difference from the original (layoutdsl.layout.difference), generated /
    original room area, fill (room area / bounding box of the rooms) and the original's fill

and a summary line (verified count, median / max first-layout seconds, how many meet area
+-15 % and fill >= 0.8 x the original's). `--seeds N` compiles each plan at seeds SEED..SEED+N-1
(a row each, the plan's name followed by its seed) and adds a line a plan: how many verified,
and the median and max first layout over its seeds. One seed's time says little: the same
code took 12.7 s and 28.0 s for office_OfficePlan's seed 0 in two runs
(bench/results/anneal-align.txt). `--throughput PLAN` instead runs `compile --variants
25` on one plan (a >= 50-room one for the acceptance) with `--workers` processes and reports
how many variants it kept within `--minutes` of wall clock (each verified and at least 0.3
from every earlier one), when it had all 25, and their differences.

Every solve runs in its own forked process with a hard timeout, like bench/bench.py. Timings
depend on the machine and its load; say so when quoting them.

    python bench/generation.py [FOLDER] [--time-limit 60] [--only PATTERN] [--seed 0]
                               [--seeds 1] [--json] [--out FILE]
    python bench/generation.py --throughput school_wilbraham [--minutes 1] [--workers 2]
    python bench/generation.py --variants 5 --only Sabadell3,Neulengbach1,wilbraham
    python bench/generation.py --only stjoseph --seeds 8 --renamed

`--grow-boundary` compiles each plan with `compile --grow-boundary`: the original's outline
only guides the packing and the boundary is drawn round it; a `grown` column gives the area
of the boundary the layout was drawn in over the outline's (1.00: not grown).

`--renamed` compiles each plan with its rooms renamed and its lines shuffled (renamed()):
whether the arrangement owes anything to the names and order an import takes from the
original drawing.

Every layout row also carries the realism measures of issue 40 (layoutdsl.layout.realism):
entrances open to the outside (open/all), enclosed voids as a share of room area (and the
original's), rooms with an outside wall (with/all) and slivers.

`--graphs DIR` compiles the room graphs of DIR (the adjacency-matrix CSVs of
../shared/graphs; read by layoutdsl.importer.graphs, sized by layoutdsl.sizes.spec_from_graph
with the typical sizes of `--kind`, the boundary chosen by the tool), one row a graph: rooms,
cycles, whether it holds four pairwise joined rooms (K4), verified, first layout and total
seconds, room area / the rooms' target area, and the realism columns; then a summary line.

    python bench/generation.py --graphs ../shared/graphs [--time-limit 60] [--only PATTERN] [--seeds N]

With `--seeds N` each graph is compiled at seeds SEED..SEED+N-1, as plans are: on the hard
graphs one seed draws a graph and the next does not, so a change to the generator is judged
on several seeds a graph, not one.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

from layoutdsl.devtools.isolation import run_isolated
from plans import DEFAULT_FOLDER, ONLY_HELP, plan_files

GRACE_SECONDS = 30.0
"""A solve gets this long past its time limit before its process is killed."""

AREA_TOLERANCE = 0.15
FILL_RATIO = 0.8


def fill(rects) -> float:
    """Room area over the area of the rooms' bounding box; rects are (x, y, w, h)."""
    rects = list(rects)
    x0 = min(r[0] for r in rects)
    y0 = min(r[1] for r in rects)
    x1 = max(r[0] + r[2] for r in rects)
    y1 = max(r[1] + r[3] for r in rects)
    return sum(r[2] * r[3] for r in rects) / max((x1 - x0) * (y1 - y0), 1e-9)


def import_original(path: Path, hints: bool = False):
    """(spec without hints (with them: `import --keep-arrangement`), original room area,
    original fill, original centres)."""
    from layoutdsl.evaluate.difference import building_centres
    from layoutdsl.importer import import_building, read_building
    from layoutdsl.importer.convert import ImportOptions, original_room_area

    spec, diagnostics = import_building(path, ImportOptions(hints=hints))
    if spec is None:
        raise ValueError("import failed: " + "; ".join(d.message for d in diagnostics if d.is_error))
    building, _ = read_building(path)
    area = original_room_area(building)
    # the imported boundary is the original rooms' bounding box
    original_fill = area / max(spec.boundary.w * spec.boundary.h, 1e-9)
    return spec, area, original_fill, building_centres(building)


def original_void_share(path: Path) -> float:
    """The original plan's enclosed voids as a share of its room area."""
    from layoutdsl.importer.building import realism_of_building
    from layoutdsl.evaluate.topology import room_ids
    from layoutdsl.importer import read_building

    building, _ = read_building(path)
    return round(realism_of_building(building, room_ids(building)).void_share, 4)


def compiled_spec(spec, layout):
    """(the spec compile verified the layout against, the rooms compile made L-shaped): a
    graph with four rooms joined pairwise has one of them made an L (compile.structure), and
    a corridor the generator turned a corner has its arm in the layout."""
    from layoutdsl.compile.shapes import with_arms
    from layoutdsl.compile.structure import with_l_rooms

    reference, made_l = with_l_rooms(spec)
    armed = {arm.room for arm in reference.arms}
    turned = [room.id for room in layout.rooms if len(room.parts) > 1 and room.id not in armed]
    return with_arms(reference, turned), made_l + turned


def _layout_row(spec, layout, area, original_fill, centres) -> dict:
    from layoutdsl.layout.difference import difference, layout_centres
    from layoutdsl.layout.verify import drawn_boundary, verify

    # a boundary the tool chose, or one --grow-boundary grew, as the layout was drawn in
    spec, _made = compiled_spec(drawn_boundary(spec, layout), layout)

    # every rectangle of every room: an L-room's arm too
    rects = [(p.x, p.y, p.w, p.h) for r in layout.rooms for p in r.parts]
    generated = sum(r.area for r in layout.rooms)
    return {
        "verified": not verify(spec, layout),
        "difference": round(difference(layout_centres(layout), centres), 4),
        "area_ratio": round(generated / area, 4) if area > 0 else None,
        "fill": round(fill(rects), 4),
        "original_fill": round(original_fill, 4),
        **realism_columns(layout),
    }


def _warm_up() -> dict:
    """Compile a small bundled spec once, so whatever the generator compiles on first use
    (numba kernels, cached to disk) is compiled before any plan is timed: a plan's
    first-layout time is then what a user gets from the second compile on, not the
    install's one-off compile."""
    from layoutdsl.api import lint_source, read_source
    from layoutdsl.compile import compile_spec
    from layoutdsl.solve import SolveOptions

    spec_path = Path(__file__).resolve().parents[1] / "specs" / "school_cycle.lay"
    spec, _ = lint_source(read_source(str(spec_path)))
    result = compile_spec(spec, SolveOptions(time_limit=60, quiet=True), explain_infeasible=False)
    return {"warmed": result.layout is not None}


def cycle_rank(graph) -> int:
    """Independent cycles of a room graph: edges - nodes + connected components."""
    import networkx as nx

    return graph.number_of_edges() - graph.number_of_nodes() + nx.number_connected_components(graph)


def spec_graph(spec):
    """The room graph of a spec (rooms and adjacencies)."""
    import networkx as nx

    graph = nx.Graph()
    graph.add_nodes_from(room.id for room in spec.rooms)
    graph.add_edges_from((adj.a, adj.b) for adj in spec.adjacencies)
    return graph


def has_k4(graph) -> bool:
    """Whether four rooms are pairwise joined (a K4 subgraph), which no four rectangles draw."""
    import networkx as nx

    return any(len(clique) >= 4 for clique in nx.find_cliques(graph))


def realism_columns(layout) -> dict:
    """The realism measures of a layout as row fields (layoutdsl.layout.realism)."""
    from layoutdsl.layout.realism import measure_layout

    realism = measure_layout(layout)
    return {
        "entrances": f"{len(realism.open_entrances)}/{len(realism.entrances)}",
        "entrances_all_open": not realism.enclosed_entrances,
        "void_share": round(realism.void_share, 4),
        "outside_wall": f"{len(realism.rooms_with_outside_wall)}/{len(realism.outside_length)}",
        "slivers": len(realism.slivers or ()),
    }


def renamed(spec, centres: dict, seed: int):
    """`spec` with its rooms renamed (each name to another of the same first letter) and its
    rooms, arms and adjacencies in another order, all drawn from `seed`, and the original's
    centres under the new names. A generator that read the original through its names or
    lines (an imported plan's follow its drawing) would score lower than on the spec as
    imported; one that reads only the graph, the sizes and the boundary scores alike."""
    import random
    from dataclasses import replace

    if spec.positions or spec.connections or spec.clusters or spec.hints:
        raise ValueError("renamed: only for specs of rooms, arms and adjacencies")
    draw = random.Random(seed)
    by_letter: dict[str, list[str]] = {}
    for room in spec.rooms:
        by_letter.setdefault(room.id[0], []).append(room.id)
    new_name = {}
    for names in by_letter.values():
        others = list(names)
        draw.shuffle(others)
        new_name.update(zip(names, others))

    def shuffled(items):
        items = list(items)
        draw.shuffle(items)
        return tuple(items)

    spec = replace(
        spec,
        rooms=shuffled(replace(room, id=new_name[room.id]) for room in spec.rooms),
        arms=shuffled(replace(arm, room=new_name[arm.room]) for arm in spec.arms),
        adjacencies=shuffled(replace(adj, a=new_name[adj.a], b=new_name[adj.b]) for adj in spec.adjacencies))
    return spec, {new_name.get(room_id, room_id): centre for room_id, centre in centres.items()}


RENAME_SEED = 100
"""--renamed draws plan seed S's names and order from RENAME_SEED + S."""


def _compile_plan(path: str, time_limit: float, seed: int, rename: bool = False, search: bool = True,
                  hints: bool = False, grow_boundary: bool = False) -> dict:
    from layoutdsl.compile import compile_spec
    from layoutdsl.solve import SolveOptions

    spec, area, original_fill, centres = import_original(Path(path), hints)
    if rename:
        spec, centres = renamed(spec, centres, RENAME_SEED + seed)
    row = {"rooms": len(spec.rooms), "cycles": cycle_rank(spec_graph(spec)),
           "original_void_share": original_void_share(Path(path))}
    began = time.monotonic()
    result = compile_spec(spec, SolveOptions(time_limit=time_limit, seed=seed, quiet=True, search=search,
                                             grow_boundary=grow_boundary), explain_infeasible=False)
    row["seconds"] = round(time.monotonic() - began, 3)
    row["status"] = result.status
    if result.layout is not None:
        row["first"] = result.layout.solve.first_feasible_seconds if result.layout.solve else None
        if grow_boundary:
            # the boundary the layout was drawn in against the original's outline: 1.00 not grown
            grown = result.layout.solve.grown_boundary if result.layout.solve else None
            row["grown"] = round(grown[0] * grown[1] / (spec.boundary.w * spec.boundary.h), 3) if grown else 1.0
        row.update(_layout_row(spec, result.layout, area, original_fill, centres))
    else:
        row["verified"] = False
    return row


WARM_SECONDS = 120.0
"""Most the warm-up (_warm_up) may take."""


def isolated(function, *args, limit: float) -> dict:
    """function(*args) in a process group of its own, killed if it overruns `limit` + GRACE_SECONDS."""
    return run_isolated(function, *args, limit=limit + GRACE_SECONDS)


COLUMNS = (
    ("plan", 44, "{}"), ("rooms", 5, "{}"), ("cycles", 6, "{}"), ("verified", 8, "{}"),
    ("first", 7, "{:.2f}"), ("seconds", 7, "{:.1f}"), ("difference", 6, "{:.3f}"),
    ("area_ratio", 6, "{:.3f}"), ("fill", 6, "{:.3f}"), ("original_fill", 8, "{:.3f}"),
    ("entrances", 7, "{}"), ("void_share", 6, "{:.3f}"), ("original_void_share", 6, "{:.3f}"),
    ("outside_wall", 8, "{}"), ("slivers", 7, "{}"),
)
GROWN_COLUMN = ("grown", 6, "{:.2f}")
"""--grow-boundary: the area of the boundary the layout was drawn in over the outline's."""

HEADERS = {"first": "first s", "seconds": "total s", "difference": "diff", "area_ratio": "area",
           "original_fill": "orig fill", "entrances": "entr", "void_share": "void",
           "original_void_share": "o void", "outside_wall": "outside"}

GRAPH_COLUMNS = (
    ("plan", 22, "{}"), ("rooms", 5, "{}"), ("cycles", 6, "{}"), ("k4", 3, "{}"), ("verified", 8, "{}"),
    ("first", 7, "{:.2f}"), ("seconds", 7, "{:.1f}"), ("area_ratio", 6, "{:.3f}"),
    ("entrances", 7, "{}"), ("void_share", 6, "{:.3f}"), ("outside_wall", 8, "{}"), ("slivers", 7, "{}"),
    ("reason", 0, "{}"),
)


def format_row(row: dict, columns=COLUMNS) -> str:
    cells = []
    for key, width, fmt in columns:
        value = row.get(key)
        if key in ("verified", "k4"):
            text = "yes" if value else "no"
        else:
            text = "-" if value is None else fmt.format(value)
        cells.append(text.ljust(width) if key == "plan" else text.rjust(width))
    line = " ".join(cells)
    if row.get("error"):
        line += f"\n    {row['error']}"
    return line


def header(columns=COLUMNS) -> str:
    return " ".join(
        HEADERS.get(key, key).ljust(width) if key in ("plan", "reason") else HEADERS.get(key, key).rjust(width)
        for key, width, _ in columns
    )


def meets(row: dict) -> tuple[bool, bool]:
    """(area within +-15 % of the original, fill >= 0.8 x the original's)."""
    area = row.get("area_ratio")
    fill_ok = (row.get("fill") is not None and row.get("original_fill")
               and row["fill"] >= FILL_RATIO * row["original_fill"])
    return (area is not None and abs(area - 1) <= AREA_TOLERANCE, bool(fill_ok))


def first_layouts(rows: list[dict]) -> str:
    """How many rows verified, and the median and max of their first-layout seconds."""
    verified = [row for row in rows if row.get("verified")]
    firsts = [row["first"] for row in verified if row.get("first") is not None]
    median = f"{statistics.median(firsts):.2f}" if firsts else "-"
    worst = f"{max(firsts):.2f}" if firsts else "-"
    return f"verified {len(verified)}/{len(rows)}; first layout median {median} s, max {worst} s"


def realism_summary(rows: list[dict]) -> str:
    """Over the verified rows: entrances open, layouts with every entrance open, voids."""
    verified = [row for row in rows if row.get("verified") and row.get("entrances")]
    opened = total = 0
    for row in verified:
        a, b = row["entrances"].split("/")
        opened, total = opened + int(a), total + int(b)
    voids = [row["void_share"] for row in verified]
    within = sum(row["void_share"] <= row["original_void_share"] + 0.02 for row in verified
                 if row.get("original_void_share") is not None)
    text = (f"entrances open {opened}/{total}, layouts with every entrance open "
            f"{sum(row['entrances_all_open'] for row in verified)}/{len(verified)}; void share median "
            f"{statistics.median(voids) if voids else 0:.3f}, max {max(voids, default=0):.3f}")
    if any(row.get("original_void_share") is not None for row in verified):
        text += f", within original + 2 points: {within}/{len(verified)}"
    if any(row.get("area_ratio") is not None for row in verified):
        # issue 40's line: room area within 10 % of the original's
        area_ok = sum(abs(row["area_ratio"] - 1) <= 0.10 for row in verified if row.get("area_ratio") is not None)
        text += f"; area within +-10 %: {area_ok}/{len(verified)}"
    return text + f"; layouts with slivers {sum(row['slivers'] > 0 for row in verified)}"


def summary(rows: list[dict]) -> str:
    verified = [row for row in rows if row.get("verified")]
    area_ok = sum(meets(row)[0] for row in verified)
    fill_ok = sum(meets(row)[1] for row in verified)
    diff_ok = sum((row.get("difference") or 0) >= 0.3 for row in verified)
    return (f"{first_layouts(rows)}; difference >= 0.3: {diff_ok}; area within +-15 %: {area_ok}; "
            f"fill >= 0.8 x original: {fill_ok}\n{realism_summary(rows)}")


def _compile_graph(path: str, time_limit: float, seed: int, kind: str, search: bool = True) -> dict:
    """Read a room graph, size it (the size model's typical sizes, boundary chosen), compile."""
    from layoutdsl.api import lint_source
    from layoutdsl.compile import compile_spec
    from layoutdsl.diagnostics import has_errors
    from layoutdsl.diagnostics.source import Source
    from layoutdsl.importer.graphs import read_graph
    from layoutdsl.sizes import spec_from_graph
    from layoutdsl.solve import SolveOptions
    from layoutdsl.syntax.format import format_spec

    from dataclasses import replace

    graph, diagnostics = read_graph(path)
    if graph is None or has_errors(diagnostics):
        return {"verified": False, "reason": "unreadable: " + "; ".join(d.message for d in diagnostics)}
    row = {"rooms": graph.number_of_nodes(), "cycles": cycle_rank(graph), "k4": has_k4(graph)}
    spec = spec_from_graph(graph, kind=kind, name=Path(path).stem)
    # the spec as `layoutdsl import x.csv` writes it, read back and checked as compile reads
    # it: without a boundary section, so the tool chooses the boundary and may fit it to the
    # layout (written in, it would be a limit the user set)
    checked, diagnostics = lint_source(Source(Path(path).stem + ".lay", format_spec(replace(spec, boundary=None))))
    if checked is None or has_errors(diagnostics):
        row.update(verified=False, reason="spec: " + "; ".join(f"{d.code} {d.message}" for d in diagnostics
                                                               if d.is_error))
        return row
    target = sum(room.target_w * room.target_h for room in checked.rooms)
    began = time.monotonic()
    result = compile_spec(checked, SolveOptions(time_limit=time_limit, seed=seed, quiet=True, search=search),
                          explain_infeasible=True)
    row["seconds"] = round(time.monotonic() - began, 3)
    row["status"] = result.status
    if result.layout is None:
        row["verified"] = False
        row["reason"] = "; ".join(f"{d.code} {d.message}" for d in result.diagnostics)[:300]
        return row
    from layoutdsl.layout.verify import drawn_boundary, verify

    layout = result.layout
    reference, made_l = compiled_spec(checked, layout)
    row["l_rooms"] = ",".join(made_l)
    if (layout.width, layout.height) != (checked.boundary.w, checked.boundary.h):
        # the tool fitted the boundary it chose to the layout (or grew it): the row says so
        row["boundary"] = f"{checked.boundary.w:g}x{checked.boundary.h:g} -> {layout.width:g}x{layout.height:g}"
    row["verified"] = not verify(drawn_boundary(reference, layout), layout)
    row["first"] = layout.solve.first_feasible_seconds if layout.solve else None
    row["area_ratio"] = round(sum(r.area for r in layout.rooms) / target, 4) if target else None
    row["wall_clock_limited"] = bool(getattr(layout.solve, "wall_clock_limited", False))
    row.update(realism_columns(layout))
    return row


THROUGHPUT_VARIANTS = 25
"""Variants the throughput run asks for: more than the acceptance's 20 a minute, so the
count within the minute is not capped by the request."""


def throughput(path: Path, minutes: float, workers: int, time_limit: float,
               n: int = THROUGHPUT_VARIANTS) -> dict:
    """`compile --variants N` as a user runs it (compile_variants: new arrangements, each kept
    only at >= 0.3 from every earlier one, `workers` processes), timed: how many variants
    were kept within `minutes` of wall clock, and when all N were."""
    from itertools import combinations

    from layoutdsl.compile.variants import compile_variants
    from layoutdsl.layout.difference import layout_centres, pairwise_differences
    from layoutdsl.solve import SolveOptions

    spec, area, original_fill, centres = import_original(path)
    kept_at: list[float] = []
    began = time.monotonic()
    result = compile_variants(spec, n, seed=0, options=SolveOptions(time_limit=time_limit, quiet=True),
                              workers=workers, progress=lambda _line: kept_at.append(time.monotonic() - began))
    elapsed = time.monotonic() - began
    found = [layout for layout in result.layouts if layout is not None]
    rows = [_layout_row(spec, layout, area, original_fill, centres) for layout in found]
    in_time = [index for index, at in enumerate(kept_at) if at <= 60 * minutes]
    apart = pairwise_differences([layout_centres(layout) for layout in found])
    pairs = [apart[pair] for pair in combinations(in_time, 2)]
    return {
        "plan": path.stem,
        "workers": workers,
        "variants_asked": n,
        "found": len(found),
        "verified": sum(row["verified"] for row in rows),
        "kept_within_minutes": len(in_time),
        "minutes": minutes,
        "per_minute": round(len(in_time) / minutes, 2),
        "seconds_to_all": round(elapsed, 1),
        "seeds_used": max((s for s in result.seeds if s is not None), default=None),
        "kept_at_seconds": [round(at, 1) for at in kept_at],
        "pairwise_min": round(min(pairs), 4) if pairs else None,
        "pairwise_median": round(statistics.median(pairs), 4) if pairs else None,
        "pairwise_below_0.3": sum(value < 0.3 for value in pairs),
        "pairs": len(pairs),
        "differences_from_original": [rows[index]["difference"] for index in in_time],
        "area_ratios": [rows[index]["area_ratio"] for index in in_time],
    }


def _variants_of_plan(path: str, n: int, seed: int, time_limit: float, workers: int) -> dict:
    """compile --variants N of one plan (graph source): per variant its difference from the
    original, area and fill; pairwise differences."""
    from layoutdsl.solve import SolveOptions
    from layoutdsl.compile.variants import compile_variants
    from layoutdsl.layout.difference import layout_centres, pairwise_differences

    spec, area, original_fill, centres = import_original(Path(path))
    began = time.monotonic()
    result = compile_variants(spec, n, seed=seed, workers=workers,
                              options=SolveOptions(time_limit=time_limit, quiet=True))
    rows = []
    for index, layout in enumerate(result.layouts, start=1):
        row = {"variant": index}
        if layout is not None:
            row.update(_layout_row(spec, layout, area, original_fill, centres))
        rows.append(row)
    found = [layout_centres(layout) for layout in result.layouts if layout is not None]
    pairs = sorted(pairwise_differences(found).values())
    return {"rooms": len(spec.rooms), "seconds": round(time.monotonic() - began, 2),
            "original_void_share": original_void_share(Path(path)),
            "variants": rows, "pairwise_min": round(pairs[0], 4) if pairs else None,
            "pairwise_median": round(statistics.median(pairs), 4) if pairs else None,
            "pairwise": [round(v, 4) for v in pairs]}


def format_variants(plan: str, result: dict) -> str:
    lines = [f"{plan} ({result.get('rooms')} rooms, {result.get('seconds')} s): pairwise min "
             f"{result.get('pairwise_min')}, median {result.get('pairwise_median')}"]
    for row in result.get("variants", []):
        if not row.get("verified"):
            lines.append(f"  variant {row['variant']}: no layout")
            continue
        area_ok, fill_ok = meets(row)
        lines.append(f"  variant {row['variant']}: difference {row['difference']:.3f}, area "
                     f"{row['area_ratio']:.3f}{'' if area_ok else ' (outside +-15 %)'}, fill "
                     f"{row['fill']:.3f} vs original {row['original_fill']:.3f}"
                     f"{'' if fill_ok else ' (below 0.8 x)'}; entrances open {row['entrances']}, voids "
                     f"{row['void_share']:.3f} (original {result.get('original_void_share')}), outside walls "
                     f"{row['outside_wall']}, slivers {row['slivers']}")
    if result.get("error"):
        lines.append(f"  {result['error']}")
    return "\n".join(lines)


def over_seeds(stem: str, args, emit, columns, compile_seed, suffix: str = "") -> list[dict]:
    """The rows of one plan or graph at seeds args.seed .. args.seed + args.seeds - 1, each
    emitted as it comes (named `STEM sN` when there are several seeds, then `suffix`),
    followed by a line for the plan over its seeds; `compile_seed(seed)` gives a row's
    columns."""
    rows = []
    for seed in range(args.seed, args.seed + max(1, args.seeds)):
        row = {"plan": (stem if args.seeds <= 1 else f"{stem} s{seed}") + suffix}
        row.update(compile_seed(seed))
        rows.append(row)
        emit(json.dumps(row) if args.json else format_row(row, columns))
    if args.seeds > 1 and not args.json:
        emit(f"  {stem}: {first_layouts(rows)}")
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", nargs="?", type=Path, default=DEFAULT_FOLDER,
                        help="folder of building XML files (default ../shared/floorplans)")
    parser.add_argument("--time-limit", type=float, default=60.0, help="seconds per compile (default 60)")
    parser.add_argument("--only", metavar="PATTERN", help=ONLY_HELP)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--seeds", type=int, default=1, metavar="N",
                        help="compile each plan at seeds SEED..SEED+N-1 (default 1)")
    parser.add_argument("--throughput", metavar="PLAN", help="variants-per-minute run on this plan instead")
    parser.add_argument("--minutes", type=float, default=1.0,
                        help="throughput: variants kept within this many minutes count (default 1)")
    parser.add_argument("--workers", type=int, default=2, help="variant processes (default 2)")
    parser.add_argument("--variants", type=int, metavar="N",
                        help="compile N graph variants of each plan (--only) instead of one layout")
    parser.add_argument("--renamed", action="store_true",
                        help="rename each plan's rooms and shuffle its lines first (see renamed())")
    parser.add_argument("--graphs", type=Path, metavar="DIR",
                        help="compile the room graphs (*.csv, *.json, *.graphml) of DIR instead of the plans")
    parser.add_argument("--kind", default="school", help="--graphs: the size model's building kind (default school)")
    parser.add_argument("--first-layout", action="store_true",
                        help="stop each compile at its polished first layout (no search after it), so a run "
                             "measures success and time to a verified layout, not a minute of search")
    parser.add_argument("--keep-arrangement", action="store_true",
                        help="plans: import each with its original arrangement as hints "
                             "(`layoutdsl import --keep-arrangement`)")
    parser.add_argument("--grow-boundary", action="store_true",
                        help="plans: compile with `--grow-boundary` (the outline a guide; a `grown` column gives "
                             "the boundary's area over the outline's)")
    parser.add_argument("--json", action="store_true", help="print JSON rows instead of the table")
    parser.add_argument("--out", type=Path, help="also write the table (or JSON) to this file")
    args = parser.parse_args(argv)

    lines: list[str] = []

    def emit(text: str) -> None:
        print(text, flush=True)
        lines.append(text)

    # every mode times compiles: none should pay a one-off compile of the generator's kernels
    isolated(_warm_up, limit=WARM_SECONDS)
    if args.graphs:
        from fnmatch import fnmatch

        files = sorted(p for p in args.graphs.iterdir() if p.suffix in (".csv", ".json", ".graphml"))
        if args.only:
            patterns = args.only.split(",")
            files = [p for p in files if any(fnmatch(p.name, f"*{pat}*") for pat in patterns)]
        rows = []
        if not args.json:
            emit(header(GRAPH_COLUMNS))
        for path in files:
            rows += over_seeds(path.stem, args, emit, GRAPH_COLUMNS, lambda seed: isolated(
                _compile_graph, str(path), args.time_limit, seed, args.kind, not args.first_layout,
                limit=args.time_limit))
        if not args.json:
            emit(f"{first_layouts(rows)}\n{realism_summary(rows)}")
    elif args.variants:
        variant_rows = []
        for path in plan_files(args.folder, args.only):
            result = isolated(_variants_of_plan, str(path), args.variants, args.seed,
                              args.time_limit, args.workers, limit=args.time_limit * args.variants)
            emit(json.dumps({"plan": path.stem, **result}) if args.json
                 else format_variants(path.stem, result))
            variant_rows += [{**row, "original_void_share": result.get("original_void_share")}
                             for row in result.get("variants", [])]
        if not args.json:
            emit(realism_summary(variant_rows))
    elif args.throughput:
        matches = plan_files(args.folder, args.throughput)
        if not matches:
            print(f"no plan matching `{args.throughput}` in {args.folder}", file=sys.stderr)
            return 2
        result = throughput(matches[0], args.minutes, args.workers, args.time_limit)
        emit(json.dumps(result, indent=2) if args.json else "\n".join(
            f"{key:28} {value}" for key, value in result.items()))
    else:
        rows = []
        columns = COLUMNS + ((GROWN_COLUMN,) if args.grow_boundary else ())
        if not args.json:
            emit(header(columns))
        for path in plan_files(args.folder, args.only):
            rows += over_seeds(path.stem, args, emit, columns, lambda seed: isolated(
                _compile_plan, str(path), args.time_limit, seed, args.renamed, not args.first_layout,
                args.keep_arrangement, args.grow_boundary, limit=args.time_limit),
                suffix=" renamed" if args.renamed else "")
        if not args.json:
            emit(summary(rows))
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
