"""Benchmark: does a spec and a seed give the same layout on an idle and on a loaded machine?

For each building XML file in FOLDER (default ../shared/floorplans beside the repo), imported
as `layoutdsl import` does by default, and each seed of `--seeds`: run

    layoutdsl compile PLAN.lay -o DIR --variants 1 --seed S -q --emit xml

once as the machine is (phase "idle"), then once more while LOAD busy-loop processes (default
2: both cores of the 2-core machine) run beside it (phase "loaded"; this script starts them
and stops them). The two runs' files are compared: the layout JSON with its timing fields left
out (solve.seconds, solve.first_feasible_seconds), every other file byte for byte. One row per
plan and seed: exit code and seconds of each phase, whether the files are identical, and if
not, what differs (the rooms that moved, or the fields). The summary line counts identical
pairs. The runs go through the command line in fresh processes (`python -m layoutdsl`), so
PYTHONPATH picks the code measured.

    python bench/reproducible.py [FOLDER] [--only PATTERN] [--seeds 0,1] [--time-limit 60]
                                 [--load 2] [--out FILE]

"idle" means whatever else the machine runs: on a shared machine say what that was. The load
average at the start of each phase is printed in the header.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from plans import DEFAULT_FOLDER, ONLY_HELP, plan_files

TIMING_FIELDS = ("seconds", "first_feasible_seconds")
"""Fields of the layout JSON's `solve` that are wall-clock measurements."""

BUSY_LOOP = "while True: pass"


def import_plan(path: Path, folder: Path) -> Path:
    spec = folder / (path.stem + ".lay")
    done = subprocess.run([sys.executable, "-m", "layoutdsl", "import", str(path), "-o", str(spec), "-q"],
                          capture_output=True, text=True, cwd=folder)
    if done.returncode not in (0,) or not spec.exists():
        raise RuntimeError(f"import {path.name} failed: {done.stderr.strip()[:300]}")
    return spec


def compile_once(spec: Path, outdir: Path, seed: int, time_limit: float) -> dict:
    began = time.monotonic()
    done = subprocess.run(
        [sys.executable, "-m", "layoutdsl", "compile", str(spec), "-o", str(outdir), "--variants", "1",
         "--seed", str(seed), "-q", "--emit", "xml", "--time-limit", str(time_limit)],
        capture_output=True, text=True, timeout=time_limit * 3 + 120,
        cwd=outdir.parent)  # not the repository: `-m` would put its checkout before PYTHONPATH
    return {"rc": done.returncode, "seconds": round(time.monotonic() - began, 1),
            "stderr": done.stderr.strip()[-300:]}


def layout_content(path: Path) -> dict:
    """The layout JSON without its timing fields."""
    data = json.loads(path.read_text())
    solve = data.get("solve") or {}
    for key in TIMING_FIELDS:
        solve.pop(key, None)
    return data


def compare(a: Path, b: Path) -> tuple[bool, str]:
    """(identical, what differs) between two output folders."""
    files_a = sorted(p.name for p in a.iterdir()) if a.exists() else []
    files_b = sorted(p.name for p in b.iterdir()) if b.exists() else []
    if files_a != files_b:
        return False, f"files differ: {files_a} vs {files_b}"
    notes = []
    for name in files_a:
        pa, pb = a / name, b / name
        if name.endswith(".layout.json"):
            ca, cb = layout_content(pa), layout_content(pb)
            if ca == cb:
                continue
            rooms_a = {r["id"]: r for r in ca.get("rooms", [])}
            rooms_b = {r["id"]: r for r in cb.get("rooms", [])}
            moved = [rid for rid in rooms_a if rooms_a[rid] != rooms_b.get(rid)]
            fields = [k for k in ca if ca.get(k) != cb.get(k)]
            solve = [k for k in (ca.get("solve") or {}) if (ca.get("solve") or {}).get(k) != (cb.get("solve") or {}).get(k)]
            notes.append(f"{name}: {len(moved)}/{len(rooms_a)} rooms differ; fields {fields}"
                         + (f", solve {solve}" if solve else ""))
        elif pa.read_bytes() != pb.read_bytes():
            notes.append(f"{name} differs")
    # a JSON that matches makes its other files (drawn from it) a consequence, not a cause
    json_notes = [n for n in notes if ".layout.json" in n]
    return not notes, "; ".join(json_notes or notes)


def load_average() -> str:
    try:
        return " ".join(f"{v:.1f}" for v in os.getloadavg())
    except OSError:
        return "?"


class BusyLoad:
    """`count` processes spinning on a core each, started and stopped by this script."""

    def __init__(self, count: int):
        self.processes = [subprocess.Popen([sys.executable, "-c", BUSY_LOOP]) for _ in range(count)]

    def stop(self) -> None:
        for process in self.processes:
            process.send_signal(signal.SIGTERM)
        for process in self.processes:
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", nargs="?", type=Path, default=DEFAULT_FOLDER,
                        help="folder of building XML files (default ../shared/floorplans)")
    parser.add_argument("--only", metavar="PATTERN", help=ONLY_HELP)
    parser.add_argument("--seeds", default="0,1", help="comma-separated seeds (default 0,1)")
    parser.add_argument("--time-limit", type=float, default=60.0, help="seconds per compile (default 60)")
    parser.add_argument("--load", type=int, default=2, help="busy-loop processes in the loaded phase (default 2)")
    parser.add_argument("--out", type=Path, help="also write the table to this file")
    args = parser.parse_args(argv)
    seeds = [int(s) for s in args.seeds.split(",") if s.strip()]
    plans = plan_files(args.folder, args.only)
    lines: list[str] = []

    def emit(text: str) -> None:
        print(text, flush=True)
        lines.append(text)

    with tempfile.TemporaryDirectory(prefix="layoutdsl-reproducible-") as tmp:
        work = Path(tmp)
        specs = {path.stem: import_plan(path, work) for path in plans}
        runs: dict[str, dict[tuple[str, int], dict]] = {"idle": {}, "loaded": {}}
        for phase in ("idle", "loaded"):
            emit(f"# phase {phase}: load average {load_average()} at the start"
                 + (f", {args.load} busy-loop processes beside it" if phase == "loaded" else ""))
            load = BusyLoad(args.load) if phase == "loaded" else None
            try:
                for name, spec in specs.items():
                    for seed in seeds:
                        outdir = work / phase / f"{name}-s{seed}"
                        outdir.parent.mkdir(parents=True, exist_ok=True)
                        runs[phase][(name, seed)] = compile_once(spec, outdir, seed, args.time_limit)
                        print(f"  {phase} {name} seed {seed}: rc {runs[phase][(name, seed)]['rc']}, "
                              f"{runs[phase][(name, seed)]['seconds']} s", file=sys.stderr, flush=True)
            finally:
                if load is not None:
                    load.stop()
        emit(f"# code: {subprocess.run([sys.executable, '-c', 'import layoutdsl; print(layoutdsl.__file__)'], capture_output=True, text=True, cwd=work).stdout.strip()}")
        emit(f"{'plan':44} {'seed':>4} {'idle rc':>7} {'idle s':>7} {'load rc':>7} {'load s':>7} {'same':>5}  differs")
        same = neither = 0
        for name in specs:
            for seed in seeds:
                idle, loaded = runs["idle"][(name, seed)], runs["loaded"][(name, seed)]
                identical, note = compare(work / "idle" / f"{name}-s{seed}", work / "loaded" / f"{name}-s{seed}")
                identical = identical and idle["rc"] == loaded["rc"]
                if identical and idle["rc"] != 0:
                    neither += 1
                    note = note or "no layout in either run"
                same += identical
                emit(f"{name:44} {seed:>4} {idle['rc']:>7} {idle['seconds']:>7} {loaded['rc']:>7} "
                     f"{loaded['seconds']:>7} {'yes' if identical else 'NO':>5}  {note}")
        emit(f"identical {same}/{len(specs) * len(seeds)} ({neither} of them without a layout in both runs; "
             f"layout JSON apart from solve.seconds and solve.first_feasible_seconds; other files byte for byte)")
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
