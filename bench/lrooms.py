"""L-shaped rooms (issue 14) on the real plans: fitting, compile time, realism.

    python bench/lrooms.py fit                 # how many spaces become L-rooms, how well they fit
    python bench/lrooms.py compile [--only a,b] [--seeds N] [--first] [--keep-arrangement]
                                               # compile with L-rooms and rectangular-only
    python bench/lrooms.py realism [--only a,b] [--variants 5]
                                               # the thesis' experiment (§6.5.3), both ways

The plans are read from ../shared/floorplans (or --plans). Each table is printed and, with
--out, written to a file (bench/results/lrooms-*.txt). Timings are wall-clock seconds on
the machine the table was made on; the header says how many cores it had.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from dataclasses import replace
from pathlib import Path

from layoutdsl.importer import ImportOptions
from layoutdsl.importer.convert import FIT_GAIN, convert
from layoutdsl.importer.lshape import fit_l
from layoutdsl.importer.reader import read_building
from plans import DEFAULT_FOLDER, ONLY_HELP, plan_files

ACCEPTANCE = ("school_scuolasconosciuta2", "school_stjoseph_scatholichighschool", "school_Neulengbach1")


def _building(path: Path):
    building, diagnostics = read_building(str(path))
    if building is None:
        raise SystemExit(f"{path}: {diagnostics[0].message}")
    return building


def fit_table(paths: list[Path], thresholds=(0.7, 0.8, 0.9)) -> list[str]:
    """Per plan: spaces, spaces below each threshold, L-rooms made, and the area mismatch
    (in one shape and not the other, share of the polygons' area) of box vs L."""
    lines = [
        f"# L fitting over {len(paths)} plans (FIT_GAIN {FIT_GAIN}); "
        "'<t' spaces with polygon/bbox area below t; 'L@t' L-rooms imported at threshold t",
        f"{'plan':40} {'spaces':>6} " + " ".join(f"{'<' + str(t):>5} {'L@' + str(t):>6}" for t in thresholds)
        + f" {'box mism.':>9} {'L mism.':>8}",
    ]
    totals = [0] * (1 + 2 * len(thresholds))
    for path in paths:
        building = _building(path)
        counts = [len(building.spaces)]
        for threshold in thresholds:
            below = sum(1 for s in building.spaces if s.rectangularization_ratio ** 2 < threshold)
            spec, _ = convert(building, ImportOptions(l_threshold=threshold))
            counts += [below, len(spec.arms)]
        spec, _ = convert(building, ImportOptions())
        armed = {arm.room for arm in spec.arms}
        ids = building.spec_room_ids()
        box_m, l_m = [], []
        for space in building.spaces:
            if ids[space.id] in armed:
                fit = fit_l([(p.x, p.y) for p in space.polygon])
                box_m.append(fit.box_mismatch)
                l_m.append(fit.mismatch)
        totals = [a + b for a, b in zip(totals, counts)]
        mism = (f"{statistics.mean(box_m):9.3f} {statistics.mean(l_m):8.3f}" if box_m else f"{'-':>9} {'-':>8}")
        lines.append(f"{path.stem:40} {counts[0]:6} " + " ".join(
            f"{counts[1 + 2 * i]:5} {counts[2 + 2 * i]:6}" for i in range(len(thresholds))) + " " + mism)
    lines.append(f"{'total':40} {totals[0]:6} " + " ".join(
        f"{totals[1 + 2 * i]:5} {totals[2 + 2 * i]:6}" for i in range(len(thresholds))))
    return lines


def _compile(spec, seed: int, time_limit: float, search: bool = True):
    from layoutdsl.compile import compile_spec
    from layoutdsl.layout.verify import verify
    from layoutdsl.solve import SolveOptions

    options = SolveOptions(time_limit=time_limit, seed=seed, quiet=True, search=search)
    began = time.monotonic()
    result = compile_spec(spec, options)
    seconds = time.monotonic() - began
    ok = result.layout is not None and not verify(spec, result.layout)
    return result, seconds, ok


def _graph_exact(spec, layout) -> bool:
    """Every adjacency of the spec is a portal of the layout and no portal is extra."""
    wanted = {frozenset((a.a, a.b)) for a in spec.adjacencies}
    have = {frozenset((p.a, p.b)) for p in layout.portals}
    return wanted == have


def compile_table(paths: list[Path], seeds: int, time_limit: float, search: bool,
                  hints: bool = False) -> list[str]:
    """Per plan and seed: compile time and verdict with L-rooms and rectangular-only (with
    `hints`, both imported with the original arrangement as hints, --keep-arrangement)."""
    rule = ("SCIP searches until the gap or the limit" if search else
            "no search: the first verified layout polished with its relations fixed (the variants' rule)")
    # both modes compile under the same rule
    lines = [
        f"# compile with L-rooms vs rectangular-only, time limit {time_limit:g} s, seeds 0..{seeds - 1}, "
        f"{os.cpu_count()} cores shared with other work (timings inflated by contention)",
        f"# both modes: {rule}" + ("; imported with --keep-arrangement (hints)" if hints else ""),
        "# L s / rect s: the whole compile with L-rooms / rectangular-only; rect first: seconds to "
        "the first verified rectangular layout; graph: the L layout's portals are exactly the "
        "spec's adjacencies; ratio = L s / rect s",
        f"{'plan':40} {'L':>3} {'seed':>4} {'L s':>7} {'L ok':>5} {'graph':>5} {'rect first':>10} {'rect s':>7} "
        f"{'rect ok':>7} {'ratio':>6}",
    ]
    totals = []
    for path in paths:
        building = _building(path)
        spec_l, _ = convert(building, ImportOptions(hints=hints))
        spec_r, _ = convert(building, ImportOptions(rectangular_only=True, hints=hints))
        spec_l = replace(spec_l, name=path.stem)
        spec_r = replace(spec_r, name=path.stem)
        for seed in range(seeds):
            result_l, seconds_l, ok_l = _compile(spec_l, seed, time_limit, search)
            result_r, seconds_r, ok_r = _compile(spec_r, seed, time_limit, search)
            graph = _graph_exact(spec_l, result_l.layout) if ok_l else False
            first_r = result_r.layout.solve.first_feasible_seconds if ok_r else None
            ratio = f"{seconds_l / max(seconds_r, 1e-9):6.2f}" if ok_r and ok_l else f"{'-':>6}"
            first_text = f"{first_r:10.2f}" if first_r is not None else f"{'-':>10}"
            lines.append(
                f"{path.stem:40} {len(spec_l.arms):3} {seed:4} {seconds_l:7.2f} {str(ok_l):>5} {str(graph):>5} "
                f"{first_text} {seconds_r:7.2f} {str(ok_r):>7} {ratio}"
            )
            print(lines[-1], flush=True)
            totals.append((seconds_l, seconds_r, ok_l, ok_r, graph))
    ok = [t for t in totals if t[2] and t[3]]
    if ok:
        lines.append(f"# verified: L {sum(t[2] for t in totals)}/{len(totals)}, graph exact "
                     f"{sum(t[4] for t in totals)}/{len(totals)}, rect {sum(t[3] for t in totals)}/{len(totals)}; "
                     f"median L s {statistics.median(t[0] for t in ok):.2f}, median rect s "
                     f"{statistics.median(t[1] for t in ok):.2f}, total L / total rect "
                     f"{sum(t[0] for t in ok) / sum(t[1] for t in ok):.2f}")
    return lines


def realism_table(paths: list[Path], variants: int, time_limit: float, workdir: Path) -> list[str]:
    """The thesis' experiment (§6.5.3) with and without L-rooms: per plan and mode, the
    exploration effort per m² and the entrance path lengths of the variants against the
    original's, through `layoutdsl evaluate` on the written building XMLs."""
    import subprocess

    lines = [
        f"# realism, {variants} variants per plan and mode, time limit {time_limit:g} s each; "
        "explore = exploration effort per m² (original | generated mean), paths = mean entrance "
        "path length in m (original | generated mean)",
        f"{'plan':34} {'mode':6} {'ok':>3} {'explore/m2 orig':>15} {'gen':>7} {'paths orig':>10} {'gen':>7}",
        "# explore/m2: exploration distance per m² of reachable free space (m/m²); paths: the "
        "mean over entrance pairs; |path dev|: mean |generated mean - original| / original",
    ]
    python = sys.executable
    for path in paths:
        for mode, extra in (("L", []), ("rect", ["--rectangular-only"])):
            folder = workdir / f"{path.stem}-{mode}"
            folder.mkdir(parents=True, exist_ok=True)
            spec_path = folder / f"{path.stem}.lay"
            subprocess.run([python, "-m", "layoutdsl", "import", str(path), "-o", str(spec_path), "-q", *extra],
                           check=True, capture_output=True)
            generated = []
            for seed in range(variants):
                out = folder / f"v{seed}"
                done = subprocess.run([python, "-m", "layoutdsl", "compile", str(spec_path), "-o", str(out), "-q",
                                       "--seed", str(seed), "--time-limit", str(time_limit)],
                                      capture_output=True, text=True)
                xml = out / f"{path.stem}.xml"
                if done.returncode == 0 and xml.exists():
                    generated.append(xml)
            if not generated:
                lines.append(f"{path.stem:34} {mode:6} {0:3} (no variant compiled)")
                print(lines[-1], flush=True)
                continue
            report_dir = folder / "report"
            done = subprocess.run([python, "-m", "layoutdsl", "evaluate", str(path), *map(str, generated),
                                   "-o", str(report_dir), "-q"], capture_output=True, text=True)
            lines.append(f"{path.stem:34} {mode:6} {len(generated):3} " + _summarise(report_dir, done))
            print(lines[-1], flush=True)
    return lines


def _summarise(report_dir: Path, done) -> str:
    import json

    reports = [report_dir / "report.json"] if (report_dir / "report.json").exists() else []
    if done.returncode != 0 or not reports:
        return f"(evaluate failed: {done.stderr.strip().splitlines()[-1] if done.stderr.strip() else done.returncode})"
    data = json.loads(reports[0].read_text())
    return _format_report(data)


def _format_report(data) -> str:
    """Exploration effort per m² and entrance path lengths, original | generated mean, and
    the mean absolute relative deviation of the paths."""
    original = data["original"]
    generated = [g for g in data["generated"] if g.get("exploration", {}).get("ran")]
    explore_o = original["exploration"]["distance_per_m2"]
    explore_g = statistics.mean(g["exploration"]["distance_per_m2"] for g in generated) if generated else float("nan")
    pairs = [p for p in data["path_pairs"] if p.get("generated_mean_m") is not None]
    paths_o = statistics.mean(p["original_m"] for p in pairs) if pairs else float("nan")
    paths_g = statistics.mean(p["generated_mean_m"] for p in pairs) if pairs else float("nan")
    deviation = statistics.mean(abs(p["relative_deviation_of_mean"]) for p in pairs) if pairs else float("nan")
    return (f"{explore_o:15.3f} {explore_g:7.3f} {paths_o:10.1f} {paths_g:7.1f}  "
            f"|path dev| {100 * deviation:5.1f} %  explore dev {100 * (explore_g / explore_o - 1):+6.1f} %")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("what", choices=("fit", "compile", "realism"))
    parser.add_argument("--plans", type=Path, default=DEFAULT_FOLDER)
    parser.add_argument("--only", help=ONLY_HELP + " (compile: the acceptance three)")
    parser.add_argument("--seeds", type=int, default=1)
    parser.add_argument("--variants", type=int, default=5)
    parser.add_argument("--time-limit", type=float, default=60.0)
    parser.add_argument("--first", action="store_true",
                        help="compile: stop at the first verified layout, polished (both modes)")
    parser.add_argument("--keep-arrangement", action="store_true",
                        help="compile: import with the original arrangement as hints (both modes)")
    parser.add_argument("--workdir", type=Path, default=Path("/tmp") / "lrooms-bench")
    parser.add_argument("--out", type=Path, help="also write the table to this file")
    args = parser.parse_args(argv)
    if not args.plans.is_dir():
        print(f"no plans at {args.plans}", file=sys.stderr)
        return 2
    if args.what == "fit":
        lines = fit_table(plan_files(args.plans, args.only))
    elif args.what == "compile":
        lines = compile_table(plan_files(args.plans, args.only or ",".join(ACCEPTANCE)), args.seeds, args.time_limit,
                              not args.first, args.keep_arrangement)
    else:
        lines = realism_table(plan_files(args.plans, args.only), args.variants, args.time_limit, args.workdir)
    text = "\n".join(lines) + "\n"
    print(text)
    if args.out:
        args.out.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
