"""Benchmark: what realism costs when the buildings are really new (issue 11's acceptance).

For each plan: import it twice (the default, no hints; and --keep-arrangement), compile five
variants of each (`--variants 5`: new arrangements from the room graph; `--variants 5
--variants-from hints`: perturbed original boxes), emit them as building XML, and run
`layoutdsl evaluate` on the original against each set. Prints one row per plan and source:

    variants found, arrangement difference from the original (mean, min), room area / the
    original's, mean |relative deviation| of the entrance-to-entrance path lengths, the
    same for the mean over the variants of each pair's path (the thesis' measure, §6.4, and
    issue 40's: the deviation of the mean, averaged over the pairs), and the exploration
    effort per m² of room area (distance to the coverage target / room area) against the
    original's.

Everything goes through the command line, as a user would run it; the reports stay in
--work (default: a temporary folder) for a closer look.

    python bench/realism.py [--plans school_Sabadell3,school_Neulengbach1,school_wilbraham]
                            [--variants 5] [--sources graph,hints] [--work DIR] [--out FILE]
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from plans import DEFAULT_FOLDER

PLANS = "school_Sabadell3,school_Neulengbach1,school_wilbraham"


def layoutdsl(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "layoutdsl", *args, "-q"], check=False,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def run_source(plan: Path, work: Path, source: str, variants: int) -> dict:
    """Compile the variants of one source and evaluate them; the report's figures."""
    spec = work / f"{plan.stem}-{source}.lay"
    import_flags = ["--keep-arrangement"] if source == "hints" else []
    layoutdsl("import", str(plan), "-o", str(spec), *import_flags)
    out = work / f"{plan.stem}-{source}"
    layoutdsl("compile", str(spec), "-o", str(out), "--variants", str(variants),
              "--variants-from", source, "--emit", "xml")
    xmls = sorted(out.glob("*.xml"))
    row = {"plan": plan.stem, "source": source, "found": len(xmls)}
    if not xmls:
        return row
    report_dir = work / f"{plan.stem}-{source}-report"
    layoutdsl("evaluate", str(plan), *map(str, xmls), "-o", str(report_dir))
    report = json.loads((report_dir / "report.json").read_text())
    original = report["original"]
    generated = report["generated"]
    deviation = [g["deviation"] for g in generated]
    deviations = [abs(v) for d in deviation for v in d["paths"].values() if v is not None]
    # the report's per-pair deviation of the mean path over the variants, in size
    of_means = [abs(p["relative_deviation_of_mean"]) for p in report["path_pairs"]
                if p["relative_deviation_of_mean"] is not None]
    explore = [g["exploration"].get("distance_per_m2") for g in generated]
    explore = [v for v in explore if v is not None]
    row.update(
        difference_mean=statistics.fmean(d["arrangement_difference"] for d in deviation),
        difference_min=min(d["arrangement_difference"] for d in deviation),
        area=statistics.fmean(1 + d["room_area"] for d in deviation),
        path_dev=statistics.fmean(deviations) if deviations else None,
        path_mean_dev=statistics.fmean(of_means) if of_means else None,
        pairs=len(report["path_pairs"]),
        unreachable=sum(p["generated_unreachable"] for p in report["path_pairs"]),
        explore=statistics.fmean(explore) if explore else None,
        explore_original=original["exploration"].get("distance_per_m2"),
    )
    return row


def _fmt(value, digits=3) -> str:
    return "-" if value is None else f"{value:.{digits}f}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--plans", default=PLANS, help="comma-separated plan names (file stems)")
    parser.add_argument("--folder", type=Path, default=DEFAULT_FOLDER)
    parser.add_argument("--variants", type=int, default=5)
    parser.add_argument("--sources", default="graph,hints",
                        help="comma-separated variant sources: graph (new arrangements), hints")
    parser.add_argument("--work", type=Path, help="keep the compiled plans and reports here")
    parser.add_argument("--out", type=Path, help="also write the table to this file")
    args = parser.parse_args(argv)
    work = args.work or Path(tempfile.mkdtemp(prefix="layoutdsl-realism-"))
    work.mkdir(parents=True, exist_ok=True)
    header = (f"{'plan':30s} {'source':6s} {'found':>5s} {'diff':>6s} {'min':>6s} {'area':>6s} "
              f"{'path|d|':>8s} {'mean|d|':>8s} {'pairs':>5s} {'unreach':>7s} {'expl/m2':>8s} {'orig':>7s}")
    lines = [header]
    print(header, flush=True)
    for name in args.plans.split(","):
        plan = args.folder / f"{name}.xml"
        for source in args.sources.split(","):
            r = run_source(plan, work, source, args.variants)
            line = (f"{r['plan']:30s} {source:6s} {r['found']:5d} {_fmt(r.get('difference_mean'))[:6]:>6s} "
                    f"{_fmt(r.get('difference_min'))[:6]:>6s} {_fmt(r.get('area'))[:6]:>6s} "
                    f"{_fmt(r.get('path_dev')):>8s} {_fmt(r.get('path_mean_dev')):>8s} {r.get('pairs', 0):5d} "
                    f"{r.get('unreachable', 0):7d} "
                    f"{_fmt(r.get('explore')):>8s} {_fmt(r.get('explore_original')):>7s}")
            lines.append(line)
            print(line, flush=True)
    lines.append("diff: arrangement difference from the original (mean, min); area: room area / the "
                 "original's; path|d|: mean |relative deviation| of entrance-to-entrance paths; "
                 "mean|d|: |relative deviation| of each pair's mean path over the variants, averaged "
                 "over the pairs (the thesis' measure); pairs: entrance pairs; "
                 "expl/m2: exploration distance to the coverage target per m² of room area "
                 f"(mean of the variants; orig: the original's). Work folder: {work}")
    print(lines[-1])
    if args.out:
        args.out.write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
