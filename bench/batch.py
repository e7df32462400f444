"""Benchmark: issue 12's acceptance for `layoutdsl batch`, through the command itself.

On the building XML plans in FOLDER (default ../shared/floorplans beside the repo), N variants
each, in one run:

1. the batch with 1 worker and with 2 workers: wall time, buildings per minute, speed-up;
2. the same batch on a local Dask cluster of 2 workers: every building compared with the
   2-worker pool's, byte for byte, apart from the timing fields (the manifest's `seconds`,
   the layout JSON's `solve.seconds` and `solve.first_feasible_seconds`);
3. a batch whose driver is SIGKILLed once half its buildings are logged, then run again: the
   second run must make exactly the rest, and the manifest list every building once;
4. seconds per building by plan size (mean, spread) from the 1-worker run, the figures for
   sizing a cluster (README, "Running a batch on a cluster").

    python bench/batch.py [FOLDER] [--plans N] [--variants 4] [--node-limit 20]
                          [--time-limit 300] [--skip-dask] [--skip-kill] [--out FILE]

`--plans N` takes the N smallest plans (by space count), for a quick run on a busy machine.
Wall times are only meaningful on an otherwise idle machine.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from plans import DEFAULT_FOLDER, plan_files

REPO = Path(__file__).resolve().parents[1]
SIZE_BUCKETS = ((1, 10), (11, 20), (21, 30), (31, 45), (46, 60), (61, 200))


def space_count(path: Path) -> int:
    """Spaces of a building XML plan (the `<space id=` elements), without parsing it."""
    return len(re.findall(r"<space\s+id=", path.read_text(encoding="utf-8", errors="replace")))


def batch_command(inputs: list[Path], outdir: Path, args, *extra: str) -> list[str]:
    return [sys.executable, "-m", "layoutdsl", "batch", *map(str, inputs), "-o", str(outdir),
            "--variants", str(args.variants), "--node-limit", str(args.node_limit),
            "--time-limit", str(args.time_limit), *extra]  # no -q: the summary line is read back


def environment() -> dict[str, str]:
    return dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in (str(REPO), os.environ.get("PYTHONPATH")) if p))


def timed_batch(command: list[str]) -> tuple[float, str]:
    began = time.monotonic()
    result = subprocess.run(command, env=environment(), capture_output=True, text=True)
    seconds = time.monotonic() - began
    if result.returncode not in (0, 3):
        raise RuntimeError(f"batch failed (exit {result.returncode}): {result.stderr.strip()}")
    return seconds, result.stdout


def manifest(outdir: Path) -> dict[str, dict]:
    lines = (outdir / "manifest.jsonl").read_text().splitlines()
    records = [json.loads(line) for line in lines]
    return {record["building"]: record for record in records}


def log_records(outdir: Path) -> list[dict]:
    lines = (outdir / ".batch" / "records.jsonl").read_text().splitlines()
    return [json.loads(line) for line in lines if line.strip()]


def log_buildings(outdir: Path) -> list[str]:
    return [record["building"] for record in log_records(outdir)]


def comparable(outdir: Path, record: dict) -> tuple:
    """A building without its timing fields: manifest fields and file bytes."""
    fields = {k: v for k, v in record.items() if k not in ("seconds", "sha256")}
    files = {}
    for name in record["files"]:
        data = (outdir / name).read_bytes()
        if name.endswith(".layout.json"):
            layout = json.loads(data)
            if layout.get("solve"):
                layout["solve"].pop("seconds", None)
                layout["solve"].pop("first_feasible_seconds", None)
            data = json.dumps(layout, sort_keys=True).encode()
        files[name] = data
    return json.dumps(fields, sort_keys=True), files


def compare(first: Path, second: Path) -> tuple[int, list[str]]:
    """(buildings compared, those that differ) between two batch folders."""
    a, b = manifest(first), manifest(second)
    differ = []
    for building in sorted(set(a) | set(b)):
        if building not in a or building not in b:
            differ.append(f"{building} (missing)")
        elif a[building]["status"] != b[building]["status"]:
            differ.append(f"{building} (status {a[building]['status']} vs {b[building]['status']})")
        elif a[building]["status"] == "done" and comparable(first, a[building]) != comparable(second, b[building]):
            differ.append(building)
    return len(set(a) | set(b)), differ


def kill_halfway(command: list[str], outdir: Path, total: int) -> int:
    """Start the batch, SIGKILL the driver once half the buildings are logged; the count logged."""
    driver = subprocess.Popen(command, env=environment(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    log = outdir / ".batch" / "records.jsonl"
    while driver.poll() is None:
        if log.exists() and log.read_text().count("\n") >= total // 2:
            break
        time.sleep(0.2)
    driver.send_signal(signal.SIGKILL)
    driver.wait()
    return len(log_buildings(outdir)) if log.exists() else 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", nargs="?", type=Path, default=DEFAULT_FOLDER)
    parser.add_argument("--plans", type=int, help="only the N smallest plans")
    parser.add_argument("--variants", type=int, default=4)
    parser.add_argument("--node-limit", type=int, default=20)
    parser.add_argument("--time-limit", type=float, default=300.0)
    parser.add_argument("--skip-dask", action="store_true")
    parser.add_argument("--skip-kill", action="store_true")
    parser.add_argument("--out", type=Path, help="also write the report to this file")
    args = parser.parse_args(argv)

    plans = sorted(plan_files(args.folder), key=lambda p: (space_count(p), p.name))
    if args.plans:
        plans = plans[: args.plans]
    rooms = {p.stem: space_count(p) for p in plans}
    total = len(plans) * args.variants
    lines = [f"layoutdsl batch benchmark: {len(plans)} plans x {args.variants} variants = {total} buildings, "
             f"node limit {args.node_limit}, time limit {args.time_limit:g} s, {os.cpu_count()} cores",
             f"plans: {', '.join(p.stem for p in plans)}", ""]

    def say(text: str = "") -> None:
        lines.append(text)
        print(text, flush=True)

    for line in lines[:-1]:
        print(line, flush=True)
    work = Path(tempfile.mkdtemp(prefix="layoutdsl-bench-batch-"))
    runs = {}
    say(f"{'run':<24} {'wall s':>8} {'bldg/min':>9} {'done':>5} {'failed':>6}")
    for name, extra in (("pool, 1 worker", ("--workers", "1")), ("pool, 2 workers", ("--workers", "2")),
                        ("dask local, 2 workers", ("--engine", "dask", "--workers", "2"))):
        if name.startswith("dask") and args.skip_dask:
            continue
        outdir = work / name.replace(",", "").replace(" ", "-")
        seconds, _ = timed_batch(batch_command(plans, outdir, args, *extra))
        records = manifest(outdir)
        done = sum(r["status"] == "done" for r in records.values())
        runs[name] = (outdir, seconds, records)
        say(f"{name:<24} {seconds:8.1f} {60 * len(records) / seconds:9.2f} {done:5d} {len(records) - done:6d}")
    speedup = runs["pool, 1 worker"][1] / runs["pool, 2 workers"][1]
    say(f"speed-up 2 workers vs 1: {speedup:.2f}x (acceptance: >= 1.8x on an idle 2-core machine)")

    failed = [(b, r["reason"]) for r in [runs["pool, 2 workers"][2]] for b, r in r.items() if r["status"] != "done"]
    say(f"every building verified or recorded with its reason: {total - len(failed)} verified, {len(failed)} failed")
    for building, reason in failed:
        say(f"  failed {building}: {reason}")
    compared, differ = compare(runs["pool, 1 worker"][0], runs["pool, 2 workers"][0])
    say(f"pool 1 worker == pool 2 workers (minus timing): {compared - len(differ)} of {compared} identical"
        + (f"; differ: {', '.join(differ)}" if differ else ""))
    if "dask local, 2 workers" in runs:
        compared, differ = compare(runs["pool, 2 workers"][0], runs["dask local, 2 workers"][0])
        say(f"dask == pool (minus timing): {compared - len(differ)} of {compared} identical"
            + (f"; differ: {', '.join(differ)}" if differ else ""))

    if not args.skip_kill:
        outdir = work / "killed"
        command = batch_command(plans, outdir, args, "--workers", "2")
        logged = kill_halfway(command, outdir, total)
        _, stdout = timed_batch(command)
        final = (outdir / "manifest.jsonl").read_text().splitlines()
        names = [json.loads(line)["building"] for line in final]
        statuses: dict[str, list[str]] = {}
        for record in log_records(outdir):
            statuses.setdefault(record["building"], []).append(record["status"])
        # a building is made twice when anything follows a done record of it
        made_twice = sorted(b for b, s in statuses.items() if "done" in s[:-1])
        say(f"SIGKILL of the driver after {logged} of {total} logged; re-run: "
            f"{stdout.splitlines()[0].split(': ', 1)[-1] if stdout else '?'}")
        say(f"  manifest lines {len(final)}, distinct buildings {len(set(names))}, expected {total}; "
            f"done buildings made twice: {len(made_twice)}")

    say("")
    say("seconds per building by plan size (pool, 1 worker: one building at a time)")
    say(f"{'spaces':<10} {'plans':>5} {'bldgs':>6} {'mean s':>8} {'stdev s':>8} {'min s':>7} {'max s':>7}")
    records = runs["pool, 1 worker"][2]
    for low, high in SIZE_BUCKETS:
        chosen = [r for r in records.values() if r["status"] == "done" and low <= rooms[r["building"].rsplit("-v", 1)[0]] <= high]
        if not chosen:
            continue
        seconds = [r["seconds"] for r in chosen]
        spread = statistics.stdev(seconds) if len(seconds) > 1 else 0.0
        plan_count = len({r["building"].rsplit("-v", 1)[0] for r in chosen})
        say(f"{f'{low}-{high}':<10} {plan_count:5d} {len(chosen):6d} {statistics.mean(seconds):8.1f} "
            f"{spread:8.1f} {min(seconds):7.1f} {max(seconds):7.1f}")
    # variants only help a dataset when they differ: count distinct room geometries per plan
    geometries: dict[str, set[str]] = {}
    outdir = runs["pool, 1 worker"][0]
    for r in records.values():
        if r["status"] == "done":
            layout_file = next(name for name in r["files"] if name.endswith(".layout.json"))
            rooms_only = json.dumps(json.loads((outdir / layout_file).read_text())["rooms"], sort_keys=True)
            geometries.setdefault(r["building"].rsplit("-v", 1)[0], set()).add(rooms_only)
    alike = sorted(plan for plan, shapes in geometries.items() if len(shapes) < args.variants)
    say(f"plans whose {args.variants} variants are not all different: {len(alike)} of {len(geometries)}"
        + (f" ({', '.join(alike)})" if alike else ""))
    stops = {}
    for r in records.values():
        stops[r["solve_status"]] = stops.get(r["solve_status"], 0) + 1
    say(f"solve stopped by: {', '.join(f'{k} {v}' for k, v in sorted(stops.items(), key=str))}")
    say(f"outputs kept in {work}")
    if args.out:
        args.out.write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
