"""`layoutdsl evaluate ORIGINAL.xml GENERATED.xml... -o REPORT_DIR`: the realism report.

Reads every plan with the project's XML reader; an unreadable plan is a located diagnostic
on stderr (exit 1), never a traceback. The report files are written all or nothing.
"""

from __future__ import annotations

import argparse
import sys
import time

from layoutdsl.diagnostics import exitcodes
from layoutdsl.cli.argtypes import non_negative_float, positive_float
from layoutdsl.diagnostics import has_errors
from layoutdsl.evaluate.explore import ExploreSettings
from layoutdsl.evaluate.plan import EvaluateOptions


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register the `evaluate` subcommand."""
    defaults = EvaluateOptions()
    parser = subparsers.add_parser(
        "evaluate",
        help="compare generated plans with their original (topology, areas, paths, exploration)",
        description=(
            "Measure how much generated building plans behave like the real one they come "
            "from (the thesis, §6.4-6.5): room graph, areas and room sizes, path lengths between "
            "entrances, and the effort of a simulated frontier exploration. Writes "
            "report.json, report.md and PNG plots into REPORT_DIR."
        ),
        epilog=exitcodes.EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("original", metavar="ORIGINAL.xml", help="the real plan (building XML)")
    parser.add_argument("generated", nargs="+", metavar="GENERATED.xml", help="generated plans (building XML)")
    parser.add_argument("-o", "--output", required=True, metavar="REPORT_DIR", help="directory for the report")
    parser.add_argument(
        "--robot-radius", type=non_negative_float, default=defaults.robot_radius_m, metavar="M",
        help=f"robot radius the walls are inflated by (default {defaults.robot_radius_m} m)",
    )  # fmt: skip
    parser.add_argument(
        "--resolution", type=positive_float, default=defaults.resolution_m, metavar="M",
        help=f"occupancy grid cell size for the paths (default {defaults.resolution_m} m)",
    )  # fmt: skip
    parser.add_argument(
        "--explore-resolution", type=positive_float, default=defaults.explore_resolution_m, metavar="M",
        help=(
            "cell size of the exploration grid, a whole multiple of --resolution "
            f"(default {defaults.explore_resolution_m} m)"
        ),
    )  # fmt: skip
    parser.add_argument("--seed", type=int, default=defaults.seed, help="seed of the exploration (initial heading)")
    parser.add_argument(
        "--start-room", default=None, metavar="ID",
        help="room the exploration starts in, the same in every plan (default: the first entrance, E0)",
    )  # fmt: skip
    parser.add_argument("-q", "--quiet", action="store_true", help="print no progress on stderr")
    parser.set_defaults(run=run)
    return parser


def _read_plans(paths: list[str]):
    from layoutdsl.importer import read_building
    from layoutdsl.diagnostics.render import render_full
    from layoutdsl.diagnostics.source import Source

    buildings, diagnostics, sources = [], [], {}
    for path in paths:
        building, found = read_building(path)
        diagnostics.extend(found)
        if found:
            try:
                with open(path, encoding="utf-8", errors="replace") as handle:
                    sources[path] = Source(path, handle.read())
            except OSError:
                pass
        buildings.append(building)
    if diagnostics:
        sys.stderr.write(render_full(diagnostics, sources))
    return buildings, diagnostics


def run(args: argparse.Namespace) -> int:
    """Evaluate the plans and write the report; exit 1 when a plan cannot be read."""
    from layoutdsl.evaluate.report import evaluate, map_check_warnings, write_report

    files = [args.original, *args.generated]
    buildings, diagnostics = _read_plans(files)
    if has_errors(diagnostics) or any(b is None for b in buildings):
        return exitcodes.SPEC_ERRORS
    if args.explore_resolution < args.resolution:
        args.explore_resolution = args.resolution
    options = EvaluateOptions(
        robot_radius_m=args.robot_radius,
        resolution_m=args.resolution,
        explore_resolution_m=args.explore_resolution,
        seed=args.seed,
        start_room=args.start_room,
        explore=ExploreSettings(),
    )
    if args.start_room is not None:
        from layoutdsl.evaluate.topology import room_ids

        known = set(room_ids(buildings[0]).values())
        if args.start_room not in known:
            print(
                f"layoutdsl evaluate: start room `{args.start_room}` is not a room of {args.original}",
                file=sys.stderr,
            )
            return exitcodes.USAGE
    started = time.monotonic()
    try:
        report = evaluate(buildings[0], buildings[1:], files, options)
    except (ValueError, MemoryError) as error:
        print(f"layoutdsl evaluate: cannot evaluate: {error}", file=sys.stderr)
        return exitcodes.USAGE
    for line in map_check_warnings(report):
        print(f"warning: {line}", file=sys.stderr)
    try:
        written = write_report(report, args.output)
    except OSError as error:
        print(f"layoutdsl evaluate: cannot write {args.output}: {error.strerror or error}", file=sys.stderr)
        return exitcodes.USAGE
    if not args.quiet:
        elapsed = time.monotonic() - started
        print(f"wrote {len(written)} files to {args.output} in {elapsed:.1f} s", file=sys.stderr)
    return exitcodes.OK
