"""Benchmark: where the core-and-satellites annealer's runs stand as they go, which of them
repair, and what a checkpoint would cut (layoutdsl.compile.satellites: CHECKPOINT_SHARE with
REACH_M, SETTLED_SHARE).

For each plan of FOLDER (default ../shared/floorplans beside the repo) that the satellites
split, import it without hints and make runs of kernel seeds FIRST..FIRST+N-1, two at a time
as compile makes them, with the checkpoint off (each run goes on to SETTLED_SHARE of its moves
with the satellites). Each run that ends within REACH_M of a layout is then repaired as compile
repairs an annealed geometry of a split plan (construct._repair with its round limits), one at
a time. Per run, one row: its end (metres from a layout), seconds, its best at 5, 40, 50 and
60 % of its moves with the satellites (satellites.PROGRESS_MARKS), whether it repaired, and
where the committed checkpoint and each `--rule` (on top of it) would have stopped it.

A rule is a checkpoint relative to the run itself, `SHARE:OF_START` (stop at SHARE of the moves
with the satellites when the best is more than OF_START times the best at 5 %), several joined
by `+`. Per plan and rule, a summary: how many repaired runs it would have stopped, and the
share of the moves with the satellites the runs that did not repair make with it. Runs are
fixed by their seed, so a run cut at a checkpoint is the same run up to there: the rows say
exactly what a rule changes. Seconds depend on the machine and its load.

    python bench/checkpoints.py [FOLDER] [--first 1000] [--runs 40] [--only PATTERN]
                                [--rule 0.4:0.25+0.5:0.12] [--out FILE]
"""

from __future__ import annotations

import argparse
import math
import sys
import threading
import time
from pathlib import Path

import numpy as np

from plans import DEFAULT_FOLDER, ONLY_HELP, plan_files

MARKS = {"5%": 0, "40%": 7, "50%": 9, "60%": 11}
"""The progress marks shown (indices into a run's progress, one every 5 %)."""
REPAIR_SECONDS = 12.5
"""Most a repair may take (compile's are shorter: each round of an annealed geometry is capped)."""


def parse_rule(text: str) -> list[tuple[float, float, float]]:
    """'0.4:0.25+0.5:0.12' -> [(0.4, inf, 0.25), (0.5, inf, 0.12)]: (share, metres, share of
    the best at 5 %)."""
    checks = []
    for part in text.split("+"):
        share, of_start = part.split(":")
        checks.append((float(share), math.inf, float(of_start)))
    return sorted(checks)


def stopped_at(progress: np.ndarray, checkpoints) -> float | None:
    """The share of the moves with the satellites at which `checkpoints` ((share, metres,
    share of the best at 5 %), in order) would stop a run with this progress, or None."""
    for share, reach, of_start in checkpoints:
        best = progress[int(round(share * len(progress))) - 1]
        if np.isnan(best):
            return None  # the run met every door before
        if best > reach or best > of_start * progress[0]:
            return share
    return None


def trace_plan(spec, first: int, runs: int) -> list[dict]:
    """Runs of kernel seeds first..first+runs-1, two at a time, the checkpoint off: per run
    its geometry, end, seconds and progress."""
    from layoutdsl.compile import lshape, satellites

    split = satellites.Satellites.of(lshape.seeds_spec(spec))
    saved = satellites.REACH_M
    satellites.REACH_M = math.inf  # the kernel's checkpoint reads it when a run starts
    todo, rows, lock = list(range(first, first + runs)), [], threading.Lock()

    def work() -> None:
        while True:
            with lock:
                if not todo:
                    return
                seed = todo.pop(0)
            progress = np.full(satellites.PROGRESS_MARKS, np.nan)
            began = time.monotonic()
            result = split.chain(seed, np.zeros(1, dtype=np.int64), progress)
            geometry, end = split.geometry(result)
            row = {"seed": seed, "end": end, "seconds": time.monotonic() - began, "progress": progress,
                   "geometry": geometry}
            with lock:
                rows.append(row)

    try:
        threads = [threading.Thread(target=work) for _ in range(2)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
    finally:
        satellites.REACH_M = saved
    return sorted(rows, key=lambda row: row["seed"])


def repaired(spec, geometry, seed: int) -> bool:
    """Whether `geometry` repairs as compile repairs an annealed geometry of a split plan whose
    runs take every core (construct.ANNEALED_ROUNDS rounds of ANNEALED_ROUND_SECONDS)."""
    import random

    from layoutdsl.compile import construct, lshape

    if spec.arms:
        geometry = lshape.seed_arms(spec, geometry, random.Random(seed), hints=False)
        problem = construct.boxed_problem(spec, geometry)
    else:
        problem = construct._Problem.of(spec)
    rects = construct._repair(problem, geometry, time.monotonic() + REPAIR_SECONDS, 0,
                              max_stalls=construct.MAX_STALLS, max_rounds=construct.ANNEALED_ROUNDS,
                              round_seconds=construct.ANNEALED_ROUND_SECONDS)
    return rects is not None


def report(plan: str, rows: list[dict], rules: dict[str, list]) -> list[str]:
    from layoutdsl.compile import satellites

    settled = satellites.SETTLED_SHARE
    committed = [(satellites.CHECKPOINT_SHARE, satellites.REACH_M, math.inf)]
    lines = [f"# {plan}: {len(rows)} runs, the checkpoint off; 'repaired': repaired as compile repairs "
             f"(runs ending beyond REACH_M = {satellites.REACH_M:g} m are not tried)"]
    names = ["committed", *rules]
    lines.append("  seed     end      s  " + "  ".join(f"{mark:>6}" for mark in MARKS) + "  repaired  "
                 + "  ".join(f"{name:>12}" for name in names))
    # a rule is scored on top of the committed checkpoint, as compile would run it
    checks = {"committed": committed, **{name: sorted(committed + rule) for name, rule in rules.items()}}
    lost = {name: 0 for name in names}
    share = {name: 0.0 for name in names}
    good = 0
    for row in rows:
        marks = row["progress"]
        stops = {name: stopped_at(marks, checks[name]) for name in names}
        cells = "  ".join(f"{marks[i]:6.2f}" for i in MARKS.values())
        lines.append(f"  {row['seed']:4d}  {row['end']:6.2f}  {row['seconds']:5.1f}  {cells}  "
                     f"{'yes' if row['repaired'] else 'no':>8}  "
                     + "  ".join(f"{'-' if stops[n] is None else f'{stops[n]:.0%}':>12}" for n in names))
        if row["repaired"]:
            good += 1
            for name in names:
                lost[name] += stops[name] is not None
        else:
            for name in names:
                share[name] += settled if stops[name] is None else stops[name]
    bad = len(rows) - good
    lines.append(f"  repaired: {good} of {len(rows)}")
    for name in names:
        made = f"{share[name] / bad:.3f}" if bad else "-"
        lines.append(f"  {name}: stops {lost[name]} of the {good} repaired runs; the runs that did not repair make "
                     f"{made} of their moves with the satellites")
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", nargs="?", default=str(DEFAULT_FOLDER))
    parser.add_argument("--first", type=int, default=1000, help="the first kernel seed")
    parser.add_argument("--runs", type=int, default=40, help="runs a plan")
    parser.add_argument("--only", help=ONLY_HELP)
    parser.add_argument("--rule", action="append", default=[], help="a relative checkpoint rule to score, "
                        "e.g. 0.4:0.25+0.5:0.12 (repeatable)")
    parser.add_argument("--out", help="also write the table here")
    args = parser.parse_args(argv)

    from layoutdsl.compile import lshape, satellites
    from layoutdsl.importer import import_building

    rules = {rule: parse_rule(rule) for rule in args.rule}
    lines = []
    for path in plan_files(args.folder, args.only):
        spec, _ = import_building(path)
        if spec is None or satellites.Satellites.of(lshape.seeds_spec(spec)) is None:
            continue
        rows = trace_plan(spec, args.first, args.runs)
        for row in rows:
            row["repaired"] = row["end"] <= satellites.REACH_M and repaired(spec, row["geometry"], row["seed"])
        block = report(path.stem, rows, rules)
        print("\n".join(block), flush=True)
        lines += block
    if args.out:
        Path(args.out).write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
