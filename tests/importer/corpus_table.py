"""Measure the importer over the real plans: a markdown table for notes and reports.

Not a test (pytest does not collect it). Usage, from the repository root:

    .venv/bin/python tests/importer/corpus_table.py                 # import only (~1 s)
    .venv/bin/python tests/importer/corpus_table.py --compile 60    # also compile, 60 s each

Columns: spaces in the XML, rooms and adjacencies in the spec, portal-graph components,
import time (median of 3 runs, read + convert), the importer's warnings, the original room
area, and with --compile whether `layoutdsl compile` wrote a verified layout within the
limit (it stops at the first verified layout: `--solution-limit 1`), and after how long.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter
from dataclasses import replace
from pathlib import Path

import networkx as nx

from layoutdsl.emit.atomic import write_text_atomic
from layoutdsl.syntax.format import format_spec
from layoutdsl.importer import import_building, original_room_area, read_building

CORPUS = Path(__file__).resolve().parents[2] / ".." / "shared" / "floorplans"


def _components(spec) -> int:
    graph = nx.Graph()
    graph.add_nodes_from(spec.room_ids)
    graph.add_edges_from((a.a, a.b) for a in spec.adjacencies)
    return nx.number_connected_components(graph)


def _compile(spec_path: Path, limit: float) -> str:
    with tempfile.TemporaryDirectory() as out:
        started = time.perf_counter()
        result = subprocess.run(
            [sys.executable, "-m", "layoutdsl", "compile", str(spec_path), "-o", out,
             "--time-limit", str(limit), "--solution-limit", "1", "--emit", "xml", "-q"],
            capture_output=True, text=True, timeout=limit + 120,
        )  # fmt: skip
        elapsed = time.perf_counter() - started
    return f"yes ({elapsed:.0f} s)" if result.returncode == 0 else f"no (exit {result.returncode}, {elapsed:.0f} s)"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--compile", type=float, metavar="S", help="also compile each spec with this time limit")
    parser.add_argument("plans", nargs="*", type=Path, help="plans to measure (default: the whole corpus)")
    args = parser.parse_args()
    plans = args.plans or sorted(CORPUS.glob("*.xml"), key=lambda p: p.stat().st_size)

    header = "| plan | spaces | rooms | adjacencies | components | import ms | warnings | area m² |"
    rule = "|---|---|---|---|---|---|---|---|"
    if args.compile:
        header += f" layout in {args.compile:g} s |"
        rule += "---|"
    print(header)
    print(rule)
    with tempfile.TemporaryDirectory() as work:
        for plan in plans:
            times = []
            for _ in range(3):
                started = time.perf_counter()
                spec, diagnostics = import_building(plan)
                times.append((time.perf_counter() - started) * 1000)
            building, _ = read_building(plan)
            if spec is None:
                print(f"| {plan.stem} | - | - | - | - | - | {len(diagnostics)} errors | - |")
                continue
            warnings = Counter(d.code for d in diagnostics)
            row = (
                f"| {plan.stem} | {len(building.spaces)} | {len(spec.rooms)} | {len(spec.adjacencies)} "
                f"| {_components(spec)} | {statistics.median(times):.0f} "
                f"| {', '.join(f'{n}x {c}' for c, n in sorted(warnings.items())) or '-'} "
                f"| {original_room_area(building):.0f} |"
            )
            if args.compile:
                spec_path = Path(work) / f"{plan.stem}.lay"
                write_text_atomic(spec_path, format_spec(replace(spec, path=str(spec_path))))
                row += f" {_compile(spec_path, args.compile)} |"
            print(row, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
