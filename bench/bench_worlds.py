"""Benchmark: the 3D worlds (issue 13's acceptance): emit time, and MuJoCo's laser against the map.

Table 1, for each layout: rooms, wall boxes, and the seconds to render every 3D format
(mjcf, sdf, gltf) in memory, best and median of REPEATS runs, plus the per-format split.
The acceptance is < 2 s for a 100-room layout.

Table 2 (needs mujoco): the robot's 271 rangefinders in real MuJoCo against ray casts on
the occupancy grid, at the start pose, three room centres and a pose looking through a
door, with the tests' agreement rule (tests/emit/test_mjcf.py): how many readings lie
within one cell plus the wall rounding, the median and largest difference among those,
and how many only agree as grazing rays (both hit points on the other model's walls).

    python bench/bench_worlds.py [--repeats 5] [--out FILE]

Layouts: the bundled specs' planted layouts, a compiled 55-room real office plan and a
compiled 105-room real school plan (tests/fixtures/layouts), and a synthetic 106-room school.
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "tests" / "emit"), str(ROOT)]

from _emit_support import planted_layouts, school_layout  # noqa: E402

from layoutdsl.emit import WORLD_3D_FORMATS, render_outputs  # noqa: E402
from layoutdsl.emit.walls import wall_geometry  # noqa: E402
from layoutdsl.layout import Layout  # noqa: E402

FIXTURES = ROOT / "tests" / "fixtures" / "layouts"


def layouts() -> dict[str, Layout]:
    found = dict(planted_layouts())
    for path in sorted(FIXTURES.glob("*.layout.json")):
        layout = Layout.from_json(path.read_text())
        found[layout.name] = layout
    found["synthetic_school_106"] = school_layout()
    return found


def timing_rows(named: dict[str, Layout], repeats: int) -> list[str]:
    rows = [f"{'layout':36} {'rooms':>5} {'boxes':>5} {'best s':>7} {'median s':>8}   per format (best s)"]
    for name, layout in named.items():
        totals = []
        split = {fmt: [] for fmt in WORLD_3D_FORMATS}
        for _ in range(repeats):
            began = time.perf_counter()
            render_outputs(layout, "plan", WORLD_3D_FORMATS)
            totals.append(time.perf_counter() - began)
            for fmt in WORLD_3D_FORMATS:
                began = time.perf_counter()
                render_outputs(layout, "plan", [fmt])
                split[fmt].append(time.perf_counter() - began)
        per = "  ".join(f"{fmt} {min(times):.3f}" for fmt, times in split.items())
        boxes = len(wall_geometry(layout).boxes)
        rows.append(f"{name:36} {len(layout.rooms):5d} {boxes:5d} {min(totals):7.3f} {statistics.median(totals):8.3f}   {per}")
    return rows


def agreement_rows(named: dict[str, Layout]) -> list[str]:
    try:
        import mujoco
        import test_mjcf as check
    except ImportError:
        return ["(mujoco is not installed: pip install 'layoutdsl[sim]')"]
    from layoutdsl.emit.raster import rasterize_layout

    rows = [f"{'layout':36} {'poses':>5} {'rays':>6} {'within':>6} {'grazing':>7} {'median m':>8} {'max m':>6}"]
    for name, layout in named.items():
        grid = rasterize_layout(layout)
        model, data = check._load(layout)
        mujoco.mj_resetData(model, data)
        for _ in range(check.SETTLE_STEPS):
            mujoco.mj_step(model, data)
        stats = [check._compare(layout, model, data, grid)]
        poses = [*check._poses(layout), check._door_pose(layout, grid)[:3]]
        for x, y, yaw in poses:
            check._place(model, data, x, y, yaw)
            stats.append(check._compare(layout, model, data, grid))
        rays = sum(s["rays"] for s in stats)
        within = sum(s["within"] for s in stats)
        median = statistics.median(s["median"] for s in stats)
        largest = max(s["max_within"] for s in stats)
        rows.append(f"{name:36} {len(stats):5d} {rays:6d} {within:6d} {rays - within:7d} {median:8.4f} {largest:6.3f}")
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--out", type=Path, help="also write the tables to this file")
    args = parser.parse_args(argv)
    named = layouts()
    machine = f"{platform.python_implementation()} {platform.python_version()}, {os.cpu_count()} cores"
    lines = [f"3D worlds: seconds to render mjcf + sdf + gltf in memory ({machine}; best of {args.repeats})",
             *timing_rows(named, args.repeats), ""]
    lines += ["MuJoCo rangefinders vs ray casts on the occupancy grid (0.05 m cells)", *agreement_rows(named)]
    text = "\n".join(lines) + "\n"
    print(text, end="")
    if args.out:
        args.out.write_text(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
